//! Paths through via points: stopping at each, or passing with continuous velocity.

use kinegen::trajectory::{
    heuristic_via_velocities, Profile, StopAtVias, Stretch, ThroughVias, TrajectoryError,
};
use proptest::prelude::*;

const K: usize = 5;

fn points() -> impl Strategy<Value = [f64; K]> {
    proptest::array::uniform5(-5.0..5.0_f64)
}

/// Strictly increasing times from 0 built from positive gaps.
fn times() -> impl Strategy<Value = [f64; K]> {
    proptest::array::uniform4(0.1..3.0_f64).prop_map(|gaps| {
        let mut t = [0.0; K];
        for i in 1..K {
            t[i] = t[i - 1] + gaps[i - 1];
        }
        t
    })
}

proptest! {
    #[test]
    fn stop_at_vias(p in points(), v_max in 0.1..5.0_f64, a_max in 0.1..50.0_f64) {
        let path = StopAtVias::new(p, v_max, a_max).unwrap();
        let t = *path.arrival_times();
        prop_assert_eq!(t[0], 0.0);
        prop_assert_eq!(t[K - 1], path.duration());
        for i in 0..K {
            prop_assert_eq!(path.position(t[i]), p[i]);
            prop_assert_eq!(path.velocity(t[i]), 0.0);
        }
        for k in 0..=5000 {
            let tk = path.duration() * k as f64 / 5000.0;
            prop_assert!(path.velocity(tk).abs() <= v_max * (1.0 + 1e-12));
            prop_assert!(path.acceleration(tk).abs() <= a_max * (1.0 + 1e-12));
        }
    }

    #[test]
    fn through_vias_is_continuous(p in points(), t in times()) {
        let path = ThroughVias::new(p, t).unwrap();
        let v = *path.via_velocities();
        prop_assert_eq!(v, heuristic_via_velocities(&p, &t));
        prop_assert_eq!(v[0], 0.0);
        prop_assert_eq!(v[K - 1], 0.0);
        let scale = 1.0 + p.iter().map(|x| x.abs()).fold(0.0, f64::max);
        for i in 0..K {
            // Exactly the via point and via velocity at each join (right side) ...
            prop_assert_eq!(path.position(t[i]), p[i]);
            if i < K - 1 {
                prop_assert_eq!(path.velocity(t[i]), v[i]);
            }
            // ... and the segment that ends there arrives with the same values.
            if i > 0 {
                let seg = path.segment(i - 1).unwrap();
                let end = seg.duration();
                prop_assert!((seg.position(end) - p[i]).abs() <= 1e-12 * scale);
                prop_assert!((seg.velocity(end) - v[i]).abs() <= 1e-12 * scale / (t[i] - t[i - 1]));
            }
        }
        // Continuity seen through the whole profile: tiny steps across each join.
        let h = 1e-9;
        for &ti in &t[1..K - 1] {
            prop_assert!((path.position(ti + h) - path.position(ti - h)).abs() <= 1e-6 * scale);
            prop_assert!((path.velocity(ti + h) - path.velocity(ti - h)).abs() <= 1e-6 * scale);
        }
    }

    #[test]
    fn heuristic_velocity_rules(p in points(), t in times()) {
        let v = heuristic_via_velocities(&p, &t);
        for i in 1..K - 1 {
            let before = (p[i] - p[i - 1]) / (t[i] - t[i - 1]);
            let after = (p[i + 1] - p[i]) / (t[i + 1] - t[i]);
            if before * after > 0.0 {
                prop_assert_eq!(v[i], 0.5 * (before + after));
                // Between the two slopes, so the path does not overshoot either way.
                prop_assert!(v[i] >= before.min(after) && v[i] <= before.max(after));
            } else {
                prop_assert_eq!(v[i], 0.0);
            }
        }
    }

    #[test]
    fn synchronized_stops(
        pts in proptest::array::uniform4(proptest::array::uniform3(-2.0..2.0_f64)),
        keep_v in any::<bool>()
    ) {
        // Make consecutive points differ in joint 0 so no segment is empty.
        let mut pts = pts;
        for (i, p) in pts.iter_mut().enumerate() {
            p[0] = i as f64 * 0.5 + p[0] * 0.1;
        }
        let v_max = [1.0, 2.0, 0.5];
        let a_max = [4.0, 1.0, 2.0];
        let stretch = if keep_v { Stretch::KeepVelocity } else { Stretch::KeepAcceleration };
        let joints = StopAtVias::synchronized(pts, v_max, a_max, stretch).unwrap();
        let times = *joints[0].arrival_times();
        for (j, path) in joints.iter().enumerate() {
            prop_assert_eq!(*path.arrival_times(), times);
            for (i, &ti) in times.iter().enumerate() {
                prop_assert_eq!(path.position(ti), pts[i][j]);
                prop_assert_eq!(path.velocity(ti), 0.0);
            }
            for i in 0..3 {
                let seg = path.segment(i).unwrap();
                prop_assert!(seg.peak_velocity() <= v_max[j] * (1.0 + 1e-12));
                prop_assert!(seg.peak_acceleration() <= a_max[j] * (1.0 + 1e-12));
            }
        }
    }
}

/// Largest |q̇| and |q̈| over a dense sampling of the whole path.
fn sampled_peaks<P: Profile>(path: &P) -> (f64, f64) {
    let (mut v, mut a) = (0.0f64, 0.0f64);
    for k in 0..=5_000 {
        let t = path.duration() * k as f64 / 5_000.0;
        v = v.max(path.velocity(t).abs());
        a = a.max(path.acceleration(t).abs());
    }
    (v, a)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn through_vias_with_limits_respects_them(p in points(), v_max in 0.1..5.0_f64, a_max in 0.1..50.0_f64) {
        prop_assume!(p.windows(2).all(|w| (w[1] - w[0]).abs() > 1e-6));
        let path = ThroughVias::with_limits(p, v_max, a_max).unwrap();
        let t = *path.arrival_times();
        for i in 0..K {
            prop_assert_eq!(path.position(t[i]), p[i]);
        }
        let ((pv, _), (pa, _)) = path.peaks();
        let (sv, sa) = sampled_peaks(&path);
        // The exact peaks bound the sampled ones, and both are within the limits ...
        prop_assert!(sv <= pv * (1.0 + 1e-12) && sa <= pa * (1.0 + 1e-12));
        prop_assert!(pv <= v_max && pa <= a_max, "{pv} > {v_max} or {pa} > {a_max}");
        // ... and the tighter limit is reached: no slower than the scaling needs.
        prop_assert!((pv / v_max).max(pa / a_max) >= 1.0 - 1e-9);
        // Velocity stays continuous through the via points.
        for &ti in &t[1..K - 1] {
            prop_assert!((path.velocity(ti + 1e-9) - path.velocity(ti - 1e-9)).abs() <= 1e-6 * (1.0 + pa));
        }
    }

    #[test]
    fn through_vias_new_within_refuses_exactly_what_exceeds(p in points(), t in times(), v_max in 0.1..5.0_f64, a_max in 0.1..50.0_f64) {
        let free = ThroughVias::new(p, t).unwrap();
        let ((pv, _), (pa, _)) = free.peaks();
        let (sv, sa) = sampled_peaks(&free);
        prop_assert!(sv <= pv * (1.0 + 1e-12) + 1e-12 && sa <= pa * (1.0 + 1e-12) + 1e-12);
        // Sampling gets within 0.1% of the exact peak (dense grid, smooth cubics).
        prop_assert!(sv >= pv * (1.0 - 1e-3) - 1e-9, "{sv} vs {pv}");
        match ThroughVias::new_within(p, t, v_max, a_max) {
            Ok(path) => {
                prop_assert_eq!(path, free);
                prop_assert!(pv <= v_max && pa <= a_max);
            }
            Err(TrajectoryError::LimitExceeded { what, peak, limit, .. }) => {
                prop_assert!(peak > limit);
                prop_assert!(pv > v_max || pa > a_max);
                prop_assert!(what == "velocity" || what == "acceleration");
            }
            Err(e) => prop_assert!(false, "unexpected {e:?}"),
        }
    }
}

#[test]
fn through_vias_limit_errors() {
    // 2 rad in 1 s: the cubic peaks at 1.5·2/1 = 3 rad/s.
    let e = ThroughVias::new_within([0.0, 2.0], [0.0, 1.0], 2.0, 100.0).unwrap_err();
    assert_eq!(
        e,
        TrajectoryError::LimitExceeded {
            what: "velocity",
            segment: 0,
            peak: 3.0,
            limit: 2.0
        }
    );
    assert!(e.to_string().contains("above the limit"));
    // ... and 6·2/1² = 12 rad/s² at the ends.
    assert!(matches!(
        ThroughVias::new_within([0.0, 2.0], [0.0, 1.0], 10.0, 11.0),
        Err(TrajectoryError::LimitExceeded {
            what: "acceleration",
            ..
        })
    ));
    // Single segment, velocity-bound: T = 1.5·Δ/v_max exactly.
    let one = ThroughVias::with_limits([0.0, 2.0], 1.0, 100.0).unwrap();
    assert!((one.duration() - 3.0).abs() < 1e-9);
    assert!(matches!(
        ThroughVias::with_limits([0.0, 1.0, 1.0], 1.0, 1.0),
        Err(TrajectoryError::TimesNotIncreasing { index: 2 })
    ));
    assert!(matches!(
        ThroughVias::with_limits([0.0, 1.0], 0.0, 1.0),
        Err(TrajectoryError::InvalidLimit { .. })
    ));
    assert!(matches!(
        ThroughVias::new_within([0.0, 1.0], [0.0, 1.0], 1.0, f64::NAN),
        Err(TrajectoryError::InvalidLimit { .. })
    ));
}

#[test]
fn via_velocity_examples() {
    // Monotone: mean of slopes 1 and 2. Turning back: 0. Flat neighbour: 0.
    let v = heuristic_via_velocities(&[0.0, 1.0, 3.0, 1.0, 1.0], &[0.0, 1.0, 2.0, 3.0, 4.0]);
    assert_eq!(v, [0.0, 1.5, 0.0, 0.0, 0.0]);
}

#[test]
fn explicit_via_velocities() {
    let path =
        ThroughVias::with_velocities([0.0, 1.0, 2.0], [0.0, 1.0, 2.0], [0.0, 1.0, 0.5]).unwrap();
    assert_eq!(path.velocity(1.0), 1.0);
    assert!((path.velocity(2.0) - 0.5).abs() < 1e-12);
    assert!((path.segment(0).unwrap().velocity(1.0) - 1.0).abs() < 1e-12);
}

#[test]
fn bad_paths_are_errors() {
    use TrajectoryError::*;
    assert!(matches!(
        ThroughVias::new([1.0], [0.0]),
        Err(TooFewPoints { count: 1 })
    ));
    assert!(matches!(
        StopAtVias::new([1.0], 1.0, 1.0),
        Err(TooFewPoints { count: 1 })
    ));
    assert!(matches!(
        ThroughVias::new([0.0, 1.0, 2.0], [0.0, 1.0, 1.0]),
        Err(TimesNotIncreasing { index: 2 })
    ));
    assert!(matches!(
        ThroughVias::new([0.0, 1.0, 2.0], [0.5, 1.0, 2.0]),
        Err(TimesNotIncreasing { index: 0 })
    ));
    assert!(matches!(
        ThroughVias::new([0.0, f64::NAN], [0.0, 1.0]),
        Err(NotFinite { .. })
    ));
    assert!(matches!(
        ThroughVias::new([0.0, 1.0], [0.0, f64::INFINITY]),
        Err(NotFinite { .. })
    ));
    // A segment too short for the limits.
    assert!(
        StopAtVias::with_times([0.0, 10.0], [0.0, 1.0], 1.0, 1.0, Stretch::KeepAcceleration)
            .is_err()
    );
    // Two equal consecutive points in a synchronised path.
    assert!(matches!(
        StopAtVias::synchronized([[0.0], [0.0]], [1.0], [1.0], Stretch::KeepAcceleration),
        Err(TimesNotIncreasing { index: 1 })
    ));
}
