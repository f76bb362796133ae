//! The optional features (the suite turns `serde` and `mint` on through the root's
//! dev-dependency on itself; built without them, this file is empty):
//! - `serde`: IK solutions, trajectories and poses read back bit for bit; stored
//!   trajectories that break a constructor's invariant are refused; a solution set longer
//!   than its capacity is refused;
//! - `mint`: transforms to and from `mint` matrices, the same entries.
#![cfg(any(feature = "serde", feature = "mint"))]

use kinegen::ik::XorShift64;

kinegen::kinematics! {
    /// The UR5 of `robots/ur5.toml`, built here so that this file compiles alone.
    pub struct Ur5 = "robots/ur5.toml";
}

fn uniform(rng: &mut XorShift64, lo: f64, hi: f64) -> f64 {
    lo + (hi - lo) * rng.next_f64()
}

#[cfg(feature = "serde")]
mod serde_round_trips {
    use super::*;
    use kinegen::ik::{IkBranch, IkError, IkSolution, IkSolutions};
    use kinegen::nalgebra::{Isometry3, Vector3};
    use kinegen::trajectory::{
        CartesianLine, Cubic, Profile, Quintic, StopAtVias, Stretch, Synchronized, ThroughVias,
        TrajectoryError, Trapezoid,
    };
    use serde::{de::DeserializeOwned, Serialize};

    fn round_trip<T: Serialize + DeserializeOwned>(x: &T) -> T {
        let text = serde_json::to_string(x).expect("serializes");
        serde_json::from_str(&text).unwrap_or_else(|e| panic!("{text} does not read back: {e}"))
    }

    /// `PartialEq` on floats says `0.0 == -0.0`; a round trip must keep the bits.
    fn same_bits(a: &[f64], b: &[f64]) -> bool {
        a.len() == b.len() && a.iter().zip(b).all(|(x, y)| x.to_bits() == y.to_bits())
    }

    #[test]
    fn ik_solutions_read_back_bit_for_bit() {
        let robot = Ur5::default();
        let mut rng = XorShift64::new(30);
        let mut branches = 0;
        for i in 0..500 {
            let mut q: [f64; 6] = core::array::from_fn(|_| uniform(&mut rng, -3.1, 3.1));
            if i % 5 == 0 {
                q[4] = 0.0; // wrist singular: singular flags and least-squares residuals
            }
            let sols = robot.ik(&robot.fk(&q));
            let back = round_trip(&sols);
            assert_eq!(back.len(), sols.len());
            for (a, b) in sols.iter().zip(back.iter()) {
                assert_eq!(a, b);
                assert!(same_bits(&a.q, &b.q) && a.residual.to_bits() == b.residual.to_bits());
            }
            branches += sols.len();
        }
        assert!(branches >= 500 * 4, "{branches} branches");
    }

    #[test]
    fn a_solution_set_longer_than_its_capacity_is_refused() {
        let branch = IkBranch::<2> {
            q: [0.1, -0.2],
            exact: true,
            residual: 0.0,
            singular: 0,
            at_singularity: false,
            within_limits: true,
        };
        let three = serde_json::to_string(&[branch; 3]).unwrap();
        let ok: IkSolutions<2, 3> = serde_json::from_str(&three).unwrap();
        assert_eq!(ok.as_slice(), &[branch; 3]);
        let err = serde_json::from_str::<IkSolutions<2, 2>>(&three).unwrap_err();
        assert!(err.to_string().contains("at most 2"), "{err}");
        // A branch with the wrong number of joints is refused too.
        assert!(serde_json::from_str::<IkSolutions<3, 3>>(&three).is_err());
    }

    #[test]
    fn numerical_ik_results_and_errors_serialize() {
        let s = IkSolution::<2> {
            q: [0.5, -1.0],
            iterations: 7,
            residual: 1e-13,
            position_error: 1e-13,
            orientation_error: 0.0,
            attempts: 1,
        };
        assert_eq!(round_trip(&s), s);
        let e = IkError::<2>::InvalidInput("target is not finite");
        assert_eq!(
            serde_json::to_string(&e).unwrap(),
            r#"{"InvalidInput":"target is not finite"}"#
        );
        let e = TrajectoryError::InvalidDuration { value: -1.0 };
        assert_eq!(
            serde_json::to_string(&e).unwrap(),
            r#"{"InvalidDuration":{"value":-1.0}}"#
        );
    }

    /// Profiles from every constructor, random inputs: each reads back equal, bit for bit.
    #[test]
    fn trajectories_read_back_bit_for_bit() {
        let mut rng = XorShift64::new(31);
        let mut checked = 0;
        for _ in 0..2_000 {
            let (q0, q1) = (uniform(&mut rng, -3.0, 3.0), uniform(&mut rng, -3.0, 3.0));
            let (v, a) = (uniform(&mut rng, 0.1, 3.0), uniform(&mut rng, 0.1, 10.0));
            let fastest = Trapezoid::new(q0, q1, v, a).unwrap();
            let t = fastest.duration() * uniform(&mut rng, 1.0, 3.0);
            let mut trapezoids = vec![fastest, Trapezoid::at_rest(q0, t)];
            trapezoids.extend(Trapezoid::with_velocity_and_time(q0, q1, v, t).ok());
            trapezoids.extend(Trapezoid::with_acceleration_and_time(q0, q1, a, t).ok());
            for stretch in [Stretch::KeepAcceleration, Stretch::KeepVelocity] {
                trapezoids.push(Trapezoid::stretched(q0, q1, v, a, t, stretch).unwrap());
            }
            for p in trapezoids {
                let back = round_trip(&p);
                assert_eq!(back, p);
                assert_eq!(back.peak_velocity().to_bits(), p.peak_velocity().to_bits());
                assert_eq!(
                    back.peak_acceleration().to_bits(),
                    p.peak_acceleration().to_bits()
                );
                checked += 1;
            }
            let (v0, v1) = (uniform(&mut rng, -1.0, 1.0), uniform(&mut rng, -1.0, 1.0));
            for c in [
                Cubic::new(q0, q1, v0, v1, t).unwrap(),
                Cubic::rest_to_rest(q0, q1, v, a).unwrap(),
            ] {
                let back = round_trip(&c);
                assert_eq!(back, c);
                assert!(same_bits(&back.coefficients(), &c.coefficients()));
            }
            let (a0, a1) = (uniform(&mut rng, -2.0, 2.0), uniform(&mut rng, -2.0, 2.0));
            for p in [
                Quintic::new([q0, v0, a0], [q1, v1, a1], t).unwrap(),
                Quintic::rest_to_rest(q0, q1, v, a).unwrap(),
            ] {
                let back = round_trip(&p);
                assert_eq!(back, p);
                assert!(same_bits(&back.coefficients(), &p.coefficients()));
            }
            let q2 = uniform(&mut rng, -3.0, 3.0);
            let s = Synchronized::new(
                [q0, q1, q2],
                [q1, q2, q0],
                [v, 1.0, 2.0],
                [a, 2.0, 5.0],
                Stretch::KeepVelocity,
            )
            .unwrap();
            assert_eq!(round_trip(&s), s);
        }
        assert!(checked >= 2_000 * 5, "{checked}");
    }

    /// Paths through via points, every constructor, random points: equal bit for bit.
    #[test]
    fn via_point_paths_read_back_bit_for_bit() {
        let mut rng = XorShift64::new(33);
        for _ in 0..500 {
            let points: [f64; 5] = core::array::from_fn(|_| uniform(&mut rng, -3.0, 3.0));
            let mut times = [0.0; 5];
            for i in 1..5 {
                times[i] = times[i - 1] + uniform(&mut rng, 0.5, 4.0);
            }
            let (v, a) = (uniform(&mut rng, 1.0, 3.0), uniform(&mut rng, 2.0, 10.0));
            let mut stops = vec![StopAtVias::new(points, v, a).unwrap()];
            stops.extend(StopAtVias::with_times(points, times, v, a, Stretch::KeepVelocity).ok());
            let joints = [points, points.map(|p| -p)];
            let joints: [[f64; 2]; 5] = core::array::from_fn(|i| [joints[0][i], joints[1][i]]);
            stops.extend(
                StopAtVias::synchronized(joints, [v, 2.0], [a, 5.0], Stretch::KeepAcceleration)
                    .unwrap(),
            );
            for p in stops {
                assert_eq!(round_trip(&p), p);
            }
            let through = [
                ThroughVias::new(points, times).unwrap(),
                ThroughVias::with_limits(points, v, a).unwrap(),
            ];
            for p in through {
                let back = round_trip(&p);
                assert_eq!(back, p);
                assert!(same_bits(back.via_velocities(), p.via_velocities()));
            }
        }
    }

    #[test]
    fn a_cartesian_line_reads_back_with_its_poses() {
        let start = Isometry3::new(Vector3::new(0.4, -0.1, 0.3), Vector3::new(0.1, 0.2, -0.3));
        let end = Isometry3::new(Vector3::new(0.2, 0.3, 0.5), Vector3::new(-0.4, 0.1, 1.2));
        let line = CartesianLine::new(
            start,
            end,
            Quintic::rest_to_rest(0.0, 1.0, 0.5, 2.0).unwrap(),
        )
        .unwrap();
        let back = round_trip(&line);
        assert_eq!(back, line);
        for k in 0..=10 {
            let t = line.duration() * k as f64 / 10.0;
            assert_eq!(back.pose(t), line.pose(t));
        }
    }

    /// What a constructor refuses, a stored profile cannot smuggle in.
    #[test]
    fn stored_trajectories_that_break_an_invariant_are_refused() {
        let refused = [
            // blends longer than the duration
            r#"{"start":0.0,"goal":1.0,"accel_time":1.5,"duration":2.0}"#,
            r#"{"start":0.0,"goal":1.0,"accel_time":1.0,"duration":-2.0}"#,
            // a move in no time
            r#"{"start":0.0,"goal":1.0,"accel_time":0.0,"duration":1.0}"#,
            // JSON has no NaN: serde_json writes it as null, which is no number
            r#"{"start":null,"goal":1.0,"accel_time":0.5,"duration":2.0}"#,
            r#"{"start":1e308,"goal":-1e308,"accel_time":0.5,"duration":2.0}"#,
        ];
        for text in refused {
            assert!(
                serde_json::from_str::<Trapezoid>(text).is_err(),
                "{text} was read"
            );
        }
        let err = serde_json::from_str::<Trapezoid>(refused[0]).unwrap_err();
        assert!(
            err.to_string()
                .contains("its acceleration time does not fit"),
            "{err}"
        );
        assert!(serde_json::from_str::<Cubic>(
            r#"{"start":[0.0,0.0],"end":[1.0,0.0],"duration":0.0}"#
        )
        .is_err());
        assert!(serde_json::from_str::<Quintic>(
            r#"{"start":[0.0,0.0,0.0],"end":[1.0,0.0,0.0],"duration":-1.0}"#
        )
        .is_err());
        // Joints that do not finish together are not synchronised.
        let a = Trapezoid::new(0.0, 1.0, 1.0, 1.0).unwrap();
        let b = Trapezoid::new(0.0, 2.0, 1.0, 1.0).unwrap();
        let text = format!(
            r#"{{"joints":[{},{}]}}"#,
            serde_json::to_string(&a).unwrap(),
            serde_json::to_string(&b).unwrap()
        );
        let err = serde_json::from_str::<Synchronized<2>>(&text).unwrap_err();
        assert!(
            err.to_string()
                .contains("part 1 of the stored profile: its duration"),
            "{err}"
        );
        // Via-point paths whose segments do not join, or whose times do not fit them.
        let path = StopAtVias::new([0.0, 1.0, 3.0], 1.0, 2.0).unwrap();
        let text = serde_json::to_string(&path).unwrap();
        let moved = text.replacen(r#""goal":1.0"#, r#""goal":1.5"#, 1);
        let err = serde_json::from_str::<StopAtVias<3>>(&moved).unwrap_err();
        assert!(
            err.to_string()
                .contains("part 0 of the stored profile: its end"),
            "{err}"
        );
        // The second arrival 0.1 s later than its segment takes.
        let mut late: serde_json::Value = serde_json::from_str(&text).unwrap();
        let t1 = late["times"][1].as_f64().unwrap();
        late["times"][1] = (t1 + 0.1).into();
        let err = serde_json::from_value::<StopAtVias<3>>(late).unwrap_err();
        assert!(
            err.to_string()
                .contains("part 0 of the stored profile: its arrival time"),
            "{err}"
        );
        assert!(serde_json::from_str::<ThroughVias<3>>(
            r#"{"points":[0.0,1.0,2.0],"times":[0.0,2.0,1.0],"velocities":[0.0,0.5,0.0]}"#
        )
        .is_err());
        // A path parameter that does not run from 0 to 1.
        let line = CartesianLine::new(
            Isometry3::identity(),
            Isometry3::identity(),
            Trapezoid::new(0.0, 1.0, 1.0, 1.0).unwrap(),
        )
        .unwrap();
        let text = serde_json::to_string(&line)
            .unwrap()
            .replace(r#""goal":1.0"#, r#""goal":2.0"#);
        assert!(
            serde_json::from_str::<CartesianLine<Trapezoid>>(&text).is_err(),
            "{text}"
        );
    }
}

#[cfg(feature = "mint")]
mod mint_interop {
    use super::*;
    use kinegen::adapters::{pose_from_mint, pose_isometry, pose_to_mint, translation_of};

    #[test]
    fn poses_go_to_mint_and_back_unchanged() {
        let robot = Ur5::default();
        let mut rng = XorShift64::new(32);
        for _ in 0..1_000 {
            let q: [f64; 6] = core::array::from_fn(|_| uniform(&mut rng, -3.1, 3.1));
            let t = robot.fk(&q);
            let m = pose_to_mint(&t);
            // Column-major: column c holds row r's entry c.
            let columns = [m.x, m.y, m.z, m.w];
            for (c, column) in columns.iter().enumerate() {
                let column: [f64; 4] = (*column).into();
                for r in 0..4 {
                    assert_eq!(column[r].to_bits(), t[r][c].to_bits());
                }
            }
            assert_eq!(pose_from_mint(m), t);
            let p: mint::Vector3<f64> = translation_of(&t).into();
            assert_eq!([p.x, p.y, p.z], [t[0][3], t[1][3], t[2][3]]);
            let quat: mint::Quaternion<f64> = pose_isometry(&t).rotation.into();
            let norm =
                quat.s * quat.s + quat.v.x * quat.v.x + quat.v.y * quat.v.y + quat.v.z * quat.v.z;
            assert!((norm - 1.0).abs() < 1e-14);
        }
    }
}
