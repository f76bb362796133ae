//! Straight Cartesian lines: positions on the segment, slerp orientation, IK tracking.

use kinegen::trajectory::{
    slerp, track, CartesianLine, Profile, Quintic, TrajectoryError, Trapezoid,
};
use nalgebra::{Isometry3, Point3, Translation3, UnitQuaternion, Vector3};
use proptest::prelude::*;
#[path = "../kinegen-core/tests/common/fixed_seed.rs"]
mod fixed_seed;
use fixed_seed::fixed_seed;

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
    #![proptest_config(fixed_seed(256))]

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
        // Central differences err by h²/6·|x⃛| ≤ 1e-12/6 · (length 3.5 m or angle π) · 60/T³
        // (the unit quintic's peak jerk) ≈ 5e-12, plus rounding ε·|x|/h ≈ 4e-10: 1e-6 is
        // the sum with a wide margin, in m/s and rad/s.
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

/// A straight line on the generated UR5, sampled at 500 Hz and tracked by the runtime's
/// IK seeded with the previous sample's solution: the tool stays on the line (position
/// and orientation at the sampled targets), joints move in small steps, and the arm
/// keeps its branch (the signs of the determinant's factors `sin q3`, `sin q5` and the
/// shoulder factor do not change).
#[test]
fn ur5_tracks_a_straight_line_with_ik_at_500_hz() {
    use kinegen::adapters::{fk_isometry, translation_of};
    use kinegen::ik::IkOptions;
    use kinegen_robots::Ur5;

    let ur5 = Ur5::default();
    let q0 = [0.3, -1.2, 1.4, -0.3, 1.1, 0.2];
    let a = fk_isometry(&ur5, &q0);
    // 0.25 m along a skew direction while turning 0.5 rad about a skew axis.
    let turn = UnitQuaternion::from_scaled_axis(Vector3::new(0.3, -0.2, 0.3).normalize() * 0.5);
    let b = Isometry3::from_parts(
        Translation3::from(a.translation.vector + Vector3::new(0.15, -0.1, 0.17)),
        turn * a.rotation,
    );
    let line = CartesianLine::with_limits(a, b, 0.25, 1.0, 1.0, 2.0).unwrap();
    let rate = 500.0;
    // 3 rad/s per joint at most: 6 mrad per 2 ms sample.
    let max_joint_step = 3.0 / rate;
    let (p0, d) = (
        a.translation.vector,
        b.translation.vector - a.translation.vector,
    );
    let mut prev = q0;
    let signs = |q: &[f64; 6]| ur5.singular_factors(q).map(|f| f.signum());
    let start_signs = signs(&q0);
    let (mut n, mut max_pos, mut max_line, mut max_ang, mut max_step) =
        (0, 0.0f64, 0.0f64, 0.0f64, 0.0f64);
    let mut max_iterations = 0;
    for step in line
        .track_ik(&ur5, rate, q0, &IkOptions::default(), max_joint_step)
        .unwrap()
    {
        let (t, sol) = step.unwrap_or_else(|e| panic!("{e}"));
        let target = line.pose(t);
        let pose = ur5.fk(&sol.q);
        let p = translation_of(&pose);
        max_pos = max_pos.max((p - target.translation.vector).norm());
        // Distance from the straight segment itself.
        let s = ((p - p0).dot(&d) / d.norm_squared()).clamp(0.0, 1.0);
        max_line = max_line.max((p - (p0 + d * s)).norm());
        max_ang = max_ang.max(
            fk_isometry(&ur5, &sol.q)
                .rotation
                .angle_to(&target.rotation),
        );
        for (a, b) in sol.q.iter().zip(prev.iter()) {
            max_step = max_step.max((a - b).abs());
        }
        assert_eq!(signs(&sol.q), start_signs, "branch changed at t = {t}");
        max_iterations = max_iterations.max(sol.iterations);
        prev = sol.q;
        n += 1;
    }
    assert_eq!(n, line.sample(rate).unwrap().count());
    println!(
        "UR5 line {:.3} m, {:.2} rad in {:.3} s at {rate} Hz: {n} IK solves (≤ {max_iterations} iterations each); \
         max position error {max_pos:.1e} m (distance from the line {max_line:.1e} m), max orientation error {max_ang:.1e} rad, \
         max joint step {max_step:.2e} rad",
        line.length(),
        line.angle(),
        line.duration()
    );
    assert!(max_pos <= 1e-9 && max_line <= 1e-9 && max_ang <= 2e-9);
    assert!(max_step <= max_joint_step);
    // The end pose is reached.
    let end = fk_isometry(&ur5, &prev);
    assert!((end.translation.vector - b.translation.vector).norm() <= 1e-9);
}

/// Tracking stops with a clear error, never NaN: a line leaving the workspace ends in
/// `IkTrackError::Ik` (out of reach), and a joint-step bound too tight for the motion in
/// `IkTrackError::Jump`.
#[test]
fn ik_tracking_reports_why_it_stopped() {
    use kinegen::adapters::fk_isometry;
    use kinegen::ik::{IkError, IkOptions};
    use kinegen::trajectory::IkTrackError;
    use kinegen_robots::Ur5;

    let ur5 = Ur5::default();
    let q0 = [0.3, -1.2, 1.4, -0.3, 1.1, 0.2];
    let a = fk_isometry(&ur5, &q0);
    let far = Translation3::new(2.0, 0.0, 0.0) * a;
    let line = CartesianLine::with_limits(a, far, 1.0, 4.0, 1.0, 2.0).unwrap();
    let steps: Vec<_> = line
        .track_ik(&ur5, 100.0, q0, &IkOptions::default(), f64::INFINITY)
        .unwrap()
        .collect();
    let (last, before) = steps.split_last().unwrap();
    assert!(
        before.iter().all(|s| s.is_ok()),
        "only the last sample fails"
    );
    match last {
        Err(IkTrackError::Ik { t, error }) => {
            assert!(*t > 0.0 && *t < line.duration());
            assert!(
                matches!(
                    error,
                    IkError::OutOfReach { .. }
                        | IkError::NotConverged { .. }
                        | IkError::Singular { .. }
                ),
                "{error:?}"
            );
            println!(
                "line out of the workspace stops at t = {t:.3} s: {}",
                last.unwrap_err()
            );
        }
        other => panic!("{other:?}"),
    }
    for s in before {
        let (_, sol) = s.as_ref().unwrap();
        assert!(sol.q.iter().all(|x| x.is_finite()));
    }
    // 1 µrad per sample is far less than this motion needs.
    let near = Translation3::new(0.1, 0.0, 0.0) * a;
    let line = CartesianLine::with_limits(a, near, 0.25, 1.0, 1.0, 2.0).unwrap();
    let mut it = line
        .track_ik(&ur5, 500.0, q0, &IkOptions::default(), 1e-6)
        .unwrap();
    assert!(
        it.next().unwrap().is_ok(),
        "the first sample is the start pose"
    );
    assert!(matches!(it.next().unwrap(), Err(IkTrackError::Jump { .. })));
    assert!(it.next().is_none());
    // Bad arguments.
    assert!(matches!(
        line.track_ik(&ur5, 500.0, q0, &IkOptions::default(), 0.0),
        Err(TrajectoryError::InvalidLimit { .. })
    ));
    assert!(matches!(
        line.track_ik(&ur5, 500.0, [f64::NAN; 6], &IkOptions::default(), 1.0),
        Err(TrajectoryError::NotFinite { .. })
    ));
}
