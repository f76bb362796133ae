//! Straight Cartesian lines: positions on the segment, slerp orientation, IK tracking.

use kinegen::trajectory::{
    slerp, track, CartesianLine, Profile, Quintic, TrajectoryError, Trapezoid,
};
use nalgebra::{Isometry3, Point3, Translation3, UnitQuaternion, Vector3};
use proptest::prelude::*;

fn pose() -> impl Strategy<Value = Isometry3<f64>> {
    (
        proptest::array::uniform3(-1.0..1.0_f64),
        proptest::array::uniform3(-3.2..3.2_f64),
    )
        .prop_map(|(p, r)| Isometry3::new(Vector3::from(p), Vector3::from(r)))
}

fn unit_s(duration: f64) -> Quintic {
    Quintic::new([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], duration).unwrap()
}

proptest! {
    #[test]
    fn sampled_positions_lie_on_the_segment(a in pose(), b in pose(), rate in 50.0..1000.0_f64) {
        let line = CartesianLine::new(a, b, unit_s(1.5)).unwrap();
        let (p0, p1) = (a.translation.vector, b.translation.vector);
        let d = p1 - p0;
        let len = d.norm();
        let mut prev_s = 0.0;
        for (t, x) in line.sample(rate).unwrap() {
            let p = x.translation.vector;
            // Distance from the line and position along it.
            let along = if len > 0.0 { (p - p0).dot(&d) / (len * len) } else { 0.0 };
            let off = (p - p0 - d * along).norm();
            prop_assert!(off <= 1e-12, "t = {t}: {off} off the line");
            prop_assert!((-1e-12..=1.0 + 1e-12).contains(&along), "t = {t}: s = {along}");
            // Quintic 0 → 1 rest-to-rest is monotone: never goes back along the line.
            prop_assert!(along >= prev_s - 1e-12);
            prev_s = along;
            prop_assert!((x.rotation.coords.norm() - 1.0).abs() <= 1e-12);
        }
    }

    #[test]
    fn endpoints_and_slerp(a in pose(), b in pose(), s in 0.0..1.0_f64) {
        let line = CartesianLine::new(a, b, unit_s(2.0)).unwrap();
        prop_assert_eq!(line.pose(0.0), a);
        prop_assert_eq!(line.pose(line.duration()), b);
        prop_assert_eq!(line.sample(500.0).unwrap().last().unwrap().1, b);
        let (q0, q1) = (a.rotation, b.rotation);
        prop_assert!(slerp(&q0, &q1, 0.0).angle_to(&q0) <= 1e-7);
        prop_assert!(slerp(&q0, &q1, 1.0).angle_to(&q1) <= 1e-7);
        // Constant axis, angle proportional to s: the shortest arc, travelled uniformly.
        let q = slerp(&q0, &q1, s);
        prop_assert!((q.coords.norm() - 1.0).abs() <= 1e-12);
        let theta = q0.angle_to(&q1);
        prop_assume!(theta < std::f64::consts::PI - 1e-6); // the half-turn's arc is ambiguous
        prop_assert!((q0.angle_to(&q) - s * theta).abs() <= 1e-7, "{} vs {}", q0.angle_to(&q), s * theta);
        prop_assert!((q.angle_to(&q1) - (1.0 - s) * theta).abs() <= 1e-7);
    }

    #[test]
    fn twist_matches_numerical_derivative(a in pose(), b in pose(), t in 0.05..1.95_f64) {
        let line = CartesianLine::new(a, b, unit_s(2.0)).unwrap();
        prop_assume!(a.rotation.angle_to(&b.rotation) < std::f64::consts::PI - 1e-3);
        let h = 1e-6;
        let (xm, xp) = (line.pose(t - h), line.pose(t + h));
        let v = (xp.translation.vector - xm.translation.vector) / (2.0 * h);
        // ω from the rotation that takes the earlier sample to the later (world frame).
        let w = (xp.rotation * xm.rotation.inverse()).scaled_axis() / (2.0 * h);
        let tw = line.twist(t);
        for i in 0..3 {
            prop_assert!((v[i] - tw[i]).abs() <= 1e-6, "v{i}: {} vs {}", v[i], tw[i]);
            prop_assert!((w[i] - tw[3 + i]).abs() <= 1e-6, "w{i}: {} vs {}", w[i], tw[3 + i]);
        }
    }

    #[test]
    fn limits_bound_tool_speeds(a in pose(), b in pose()) {
        let (v_max, a_max, w_max, al_max) = (0.25, 1.0, 1.0, 3.0);
        let line = CartesianLine::with_limits(a, b, v_max, a_max, w_max, al_max).unwrap();
        for k in 0..=1000 {
            let t = line.duration() * k as f64 / 1000.0;
            let tw = line.twist(t);
            let acc = line.twist_rate(t);
            let norm = |x: &[f64]| x.iter().map(|c| c * c).sum::<f64>().sqrt();
            prop_assert!(norm(&tw[..3]) <= v_max * (1.0 + 1e-9));
            prop_assert!(norm(&tw[3..]) <= w_max * (1.0 + 1e-9));
            prop_assert!(norm(&acc[..3]) <= a_max * (1.0 + 1e-9));
            prop_assert!(norm(&acc[3..]) <= al_max * (1.0 + 1e-9));
        }
        prop_assert_eq!(line.pose(line.duration()), b);
    }
}

#[test]
fn lecture_line_at_500_hz() {
    // P1 = [0.3, −0.2, 0.4, π/2, 0, 0] → P2 = [0.5, 0.1, 0.2, π/2, 0, 0] (the lecture's
    // example, RPY), trapezoid at 0.1 m/s and 0.5 m/s².
    let rot = UnitQuaternion::from_euler_angles(std::f64::consts::FRAC_PI_2, 0.0, 0.0);
    let a = Isometry3::from_parts(Translation3::new(0.3, -0.2, 0.4), rot);
    let b = Isometry3::from_parts(Translation3::new(0.5, 0.1, 0.2), rot);
    let line = CartesianLine::with_limits(a, b, 0.1, 0.5, 1.0, 1.0).unwrap();
    let len = (0.2_f64 * 0.2 + 0.3 * 0.3 + 0.2 * 0.2).sqrt();
    assert!((line.length() - len).abs() < 1e-15);
    assert_eq!(line.angle(), 0.0);
    // T = L/v + v/a.
    assert!((line.duration() - (len / 0.1 + 0.1 / 0.5)).abs() < 1e-12);
    let n = line.sample(500.0).unwrap().count();
    assert_eq!(n, (line.duration() * 500.0).ceil() as usize + 1);
    let mid = line.pose(0.5 * line.duration());
    let centre = Point3::new(0.4, -0.05, 0.3);
    assert!((mid.translation.vector - centre.coords).norm() < 1e-12);
    assert!(mid.rotation.angle_to(&rot) < 1e-12);
}

#[test]
fn tracking_threads_the_seed_and_stops_at_the_first_error() {
    let a = Isometry3::translation(0.0, 0.0, 0.0);
    let b = Isometry3::translation(1.0, 0.0, 0.0);
    let line = CartesianLine::new(a, b, Trapezoid::new(0.0, 1.0, 1.0, 2.0).unwrap()).unwrap();
    // A stand-in "IK": q = [x, number of calls]; it checks the seed is its last answer.
    let mut expected_seed = [10.0, 0.0];
    let steps: Vec<_> = line
        .track(100.0, [10.0, 0.0], |target, seed: &[f64; 2]| {
            assert_eq!(*seed, expected_seed);
            let q = [target.translation.x, seed[1] + 1.0];
            expected_seed = q;
            if target.translation.x > 0.5 {
                Err("out of reach")
            } else {
                Ok(q)
            }
        })
        .unwrap()
        .collect();
    let last = steps.last().unwrap();
    assert_eq!(*last, Err("out of reach"));
    assert!(steps[..steps.len() - 1].iter().all(|s| s.is_ok()));
    let n_ok = steps.len() - 1;
    assert_eq!(steps[n_ok - 1].as_ref().unwrap().1[1], n_ok as f64);

    // `track` on any pose iterator, e.g. a hand-made list.
    let poses = [(0.0, a), (1.0, b)];
    let qs: Vec<_> = track(poses.into_iter(), [0.0], |x, _| {
        Ok::<_, ()>([x.translation.x])
    })
    .collect();
    assert_eq!(qs, vec![Ok((0.0, [0.0])), Ok((1.0, [1.0]))]);
}

#[test]
fn bad_lines_are_errors() {
    let a = Isometry3::translation(0.0, 0.0, 0.0);
    let b = Isometry3::translation(1.0, 0.0, 0.0);
    // s must run from 0 to 1.
    let wrong = Trapezoid::new(0.0, 2.0, 1.0, 1.0).unwrap();
    assert!(matches!(
        CartesianLine::new(a, b, wrong),
        Err(TrajectoryError::NotNormalized { .. })
    ));
    let nan = Isometry3::translation(f64::NAN, 0.0, 0.0);
    assert!(matches!(
        CartesianLine::new(a, nan, unit_s(1.0)),
        Err(TrajectoryError::NotFinite { .. })
    ));
    assert!(matches!(
        CartesianLine::with_limits(a, b, 0.0, 1.0, 1.0, 1.0),
        Err(TrajectoryError::InvalidLimit { .. })
    ));
    // Same pose: a zero-duration line that stays put.
    let still = CartesianLine::with_limits(a, a, 1.0, 1.0, 1.0, 1.0).unwrap();
    assert_eq!(still.duration(), 0.0);
    assert_eq!(
        still.sample(500.0).unwrap().collect::<Vec<_>>(),
        vec![(0.0, a)]
    );
    // Pure rotation: limited by the angular limits only.
    let turned = Isometry3::new(Vector3::zeros(), Vector3::new(0.0, 0.0, 1.0));
    let spin = CartesianLine::with_limits(a, turned, 1.0, 1.0, 0.5, 2.0).unwrap();
    assert!((spin.duration() - (1.0 / 0.5 + 0.5 / 2.0)).abs() < 1e-12);
    assert!(spin.profile().duration() > 0.0);
}
