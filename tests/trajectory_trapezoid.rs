//! Trapezoidal / triangular velocity profiles: boundary conditions, limits, feasibility.

use kinegen::trajectory::{Profile, Stretch, TrajectoryError, Trapezoid};
use proptest::prelude::*;
#[path = "../kinegen-core/tests/common/fixed_seed.rs"]
mod fixed_seed;
use fixed_seed::fixed_seed;

/// Relative slack for "within the limit": profiles derive v and a from the timing, so a
/// limit can be exceeded by a few ulps, never more.
const LIMIT_TOL: f64 = 1e-12;

fn pos() -> impl Strategy<Value = f64> {
    -10.0..10.0_f64
}
fn vel_limit() -> impl Strategy<Value = f64> {
    0.01..10.0_f64
}
fn acc_limit() -> impl Strategy<Value = f64> {
    0.01..100.0_f64
}

/// Dense times over [0, T]: a 2000-point grid plus both sides of the phase switches.
fn probe_times(p: &Trapezoid) -> impl Iterator<Item = f64> + '_ {
    let t = p.duration();
    let switches = [p.accel_time(), t - p.accel_time()];
    let grid = (0..=2000).map(move |k| t * k as f64 / 2000.0);
    let near = switches
        .into_iter()
        .flat_map(|s| [s - 1e-9, s, s + 1e-9])
        .filter(move |s| (0.0..=t).contains(s));
    grid.chain(near)
}

fn assert_within_limits(p: &Trapezoid, v_max: f64, a_max: f64) {
    for t in probe_times(p) {
        let (v, a) = (p.velocity(t), p.acceleration(t));
        assert!(
            v.abs() <= v_max * (1.0 + LIMIT_TOL),
            "|v({t})| = {} > {v_max}",
            v.abs()
        );
        assert!(
            a.abs() <= a_max * (1.0 + LIMIT_TOL),
            "|a({t})| = {} > {a_max}",
            a.abs()
        );
    }
}

fn assert_boundaries(p: &Trapezoid, q0: f64, q1: f64) {
    let t = p.duration();
    assert_eq!(p.position(0.0), q0);
    assert_eq!(p.position(t), q1);
    assert_eq!(p.velocity(0.0), 0.0);
    assert_eq!(p.velocity(t), 0.0);
    // Accelerating away from q0 at the start, braking into q1 at the end.
    let dir = (q1 - q0).signum();
    assert_eq!(p.acceleration(0.0), dir * p.peak_acceleration());
    assert_eq!(p.acceleration(t), -dir * p.peak_acceleration());
    // Clamped outside [0, T].
    assert_eq!(p.position(-1.0), q0);
    assert_eq!(p.position(t + 1.0), q1);
    assert_eq!(p.velocity(t + 1.0), 0.0);
}

/// Central differences of position match velocity (and of velocity match acceleration
/// away from the jumps of the acceleration).
fn assert_derivatives(p: &Trapezoid) {
    let h = 1e-6;
    let t_end = p.duration();
    let scale = 1.0 + p.peak_acceleration() + p.peak_velocity();
    for k in 1..200 {
        let t = t_end * k as f64 / 200.0;
        let fd = (p.position(t + h) - p.position(t - h)) / (2.0 * h);
        // O(h·a) where the acceleration jumps, rounding of 1e-16·|q|/h elsewhere.
        assert!(
            (fd - p.velocity(t)).abs() <= 1e-6 * scale + 1e-8,
            "t = {t}: {fd} vs {}",
            p.velocity(t)
        );
        let near_switch = [p.accel_time(), t_end - p.accel_time()]
            .iter()
            .any(|s| (t - s).abs() < 2.0 * h);
        if !near_switch {
            let fd = (p.velocity(t + h) - p.velocity(t - h)) / (2.0 * h);
            assert!((fd - p.acceleration(t)).abs() <= 1e-6 * scale + 1e-8);
        }
    }
}

proptest! {
    #![proptest_config(fixed_seed(256))]

    #[test]
    fn fastest_profile_meets_boundaries_and_limits(
        q0 in pos(), q1 in pos(), v_max in vel_limit(), a_max in acc_limit()
    ) {
        prop_assume!(q0 != q1);
        let p = Trapezoid::new(q0, q1, v_max, a_max).unwrap();
        assert_boundaries(&p, q0, q1);
        assert_within_limits(&p, v_max, a_max);
        assert_derivatives(&p);
        let d = (q1 - q0).abs();
        // Minimum time: full acceleration, and either full velocity or a triangle.
        prop_assert!((p.peak_acceleration() - a_max).abs() <= 1e-9 * a_max);
        if d * a_max < v_max * v_max {
            prop_assert!(p.is_triangular());
            prop_assert!((p.duration() - 2.0 * (d / a_max).sqrt()).abs() <= 1e-12 * p.duration());
            prop_assert!((p.peak_velocity() - (d * a_max).sqrt()).abs() <= 1e-9 * v_max);
            prop_assert!(p.peak_velocity() < v_max);
        } else {
            prop_assert!((p.peak_velocity() - v_max).abs() <= 1e-9 * v_max);
            prop_assert!((p.duration() - (d / v_max + v_max / a_max)).abs() <= 1e-12 * p.duration());
        }
    }

    #[test]
    fn velocity_and_time(q0 in pos(), q1 in pos(), v_max in vel_limit(), k in 1.0001..5.0_f64) {
        // T chosen so that |Δ| < v_max·T by the factor k.
        let d = (q1 - q0).abs();
        prop_assume!(d > 1e-6);
        let t = k * d / v_max;
        let p = Trapezoid::with_velocity_and_time(q0, q1, v_max, t).unwrap();
        prop_assert_eq!(p.duration(), t);
        assert_boundaries(&p, q0, q1);
        assert_within_limits(&p, v_max, f64::INFINITY);
        assert_derivatives(&p);
        if k <= 2.0 {
            // v_max is reachable: cruise exactly at it.
            prop_assert!((p.peak_velocity() - v_max).abs() <= 1e-9 * v_max);
        } else {
            // Triangular fallback with the lower peak 2|Δ|/T.
            prop_assert!(p.is_triangular());
            prop_assert!((p.peak_velocity() - 2.0 * d / t).abs() <= 1e-9 * v_max);
        }
    }

    #[test]
    fn velocity_and_time_infeasible(q0 in pos(), q1 in pos(), v_max in vel_limit(), k in 0.01..1.0_f64) {
        let d = (q1 - q0).abs();
        prop_assume!(d > 1e-6);
        let t = k * d / v_max; // |Δ| ≥ v_max·T
        let r = Trapezoid::with_velocity_and_time(q0, q1, v_max, t);
        prop_assert!(matches!(r, Err(TrajectoryError::VelocityTooLow { .. })), "{:?}", r);
    }

    #[test]
    fn acceleration_and_time(q0 in pos(), q1 in pos(), a_max in acc_limit(), k in 1.0..5.0_f64) {
        let d = (q1 - q0).abs();
        prop_assume!(d > 1e-6);
        let t = k * (4.0 * d / a_max).sqrt(); // 4|Δ| ≤ a_max·T²
        let p = Trapezoid::with_acceleration_and_time(q0, q1, a_max, t).unwrap();
        prop_assert_eq!(p.duration(), t);
        assert_boundaries(&p, q0, q1);
        assert_within_limits(&p, f64::INFINITY, a_max);
        assert_derivatives(&p);
        prop_assert!((p.peak_acceleration() - a_max).abs() <= 1e-9 * a_max);
    }

    #[test]
    fn acceleration_and_time_infeasible(q0 in pos(), q1 in pos(), a_max in acc_limit(), k in 0.01..0.999_f64) {
        let d = (q1 - q0).abs();
        prop_assume!(d > 1e-6);
        let t = k * (4.0 * d / a_max).sqrt(); // 4|Δ| > a_max·T²
        let r = Trapezoid::with_acceleration_and_time(q0, q1, a_max, t);
        prop_assert!(matches!(r, Err(TrajectoryError::AccelerationTooLow { .. })), "{:?}", r);
    }

    #[test]
    fn negative_displacement_mirrors_positive(d in 0.001..10.0_f64, v_max in vel_limit(), a_max in acc_limit()) {
        // From 0, so ±d are exact mirrors and so must be the profiles, bit for bit.
        // (Negative moves from other starts are covered by the tests above, whose random
        // goals lie below the start half of the time.)
        let up = Trapezoid::new(0.0, d, v_max, a_max).unwrap();
        let down = Trapezoid::new(0.0, -d, v_max, a_max).unwrap();
        prop_assert_eq!(up.duration(), down.duration());
        for k in 0..=100 {
            let t = up.duration() * k as f64 / 100.0;
            prop_assert_eq!(up.position(t), -down.position(t));
            prop_assert_eq!(up.velocity(t), -down.velocity(t));
            prop_assert_eq!(up.acceleration(t), -down.acceleration(t));
        }
    }

    #[test]
    fn stretched_keeps_limits_and_duration(
        q0 in pos(), q1 in pos(), v_max in vel_limit(), a_max in acc_limit(), k in 1.0..4.0_f64,
        keep_velocity in any::<bool>()
    ) {
        let fastest = Trapezoid::new(q0, q1, v_max, a_max).unwrap();
        prop_assume!(fastest.duration() > 0.0);
        let t = k * fastest.duration();
        let stretch = if keep_velocity { Stretch::KeepVelocity } else { Stretch::KeepAcceleration };
        let p = Trapezoid::stretched(q0, q1, v_max, a_max, t, stretch).unwrap();
        prop_assert_eq!(p.duration(), t);
        assert_boundaries(&p, q0, q1);
        assert_within_limits(&p, v_max, a_max);
    }

    #[test]
    fn samples_cover_the_motion(q0 in pos(), q1 in pos(), rate in 1.0..2000.0_f64) {
        let p = Trapezoid::new(q0, q1, 2.0, 5.0).unwrap();
        let samples = p.sample(rate).unwrap();
        let expected = samples.size_hint().0;
        let mut n = 0;
        let mut prev: Option<f64> = None;
        let mut last = (f64::NAN, f64::NAN, f64::NAN, f64::NAN);
        for s in samples {
            let (t, q, v, a) = s;
            prop_assert_eq!((q, v, a), (p.position(t), p.velocity(t), p.acceleration(t)));
            match prev {
                None => prop_assert_eq!(t, 0.0),
                Some(tp) => {
                    prop_assert!(t > tp);
                    prop_assert!(t - tp <= 1.0 / rate * (1.0 + 1e-9));
                }
            }
            prev = Some(t);
            last = s;
            n += 1;
        }
        prop_assert_eq!(n, expected);
        prop_assert_eq!(last.0, p.duration());
        prop_assert_eq!(last.1, q1);
    }
}

#[test]
fn triangular_fallback_example() {
    // 0.1 rad at v_max = 1, a_max = 1: v_max²/a_max = 1 > 0.1, so a triangle:
    // t_a = √0.1, T = 2√0.1, peak √0.1 < 1.
    let p = Trapezoid::new(0.0, 0.1, 1.0, 1.0).unwrap();
    assert!(p.is_triangular());
    assert_eq!(p.cruise_time(), 0.0);
    assert!((p.duration() - 2.0 * 0.1_f64.sqrt()).abs() < 1e-15);
    assert!((p.peak_velocity() - 0.1_f64.sqrt()).abs() < 1e-15);
    assert!((p.velocity(p.duration() / 2.0) - 0.1_f64.sqrt()).abs() < 1e-15);
}

#[test]
fn lecture_example() {
    // t_a = v/a = 0.5, T = Δ/v + t_a = 2 + 0.5, cruise 1.5 s.
    let p = Trapezoid::new(1.0, 3.0, 1.0, 2.0).unwrap();
    assert!((p.accel_time() - 0.5).abs() < 1e-15);
    assert!((p.duration() - 2.5).abs() < 1e-15);
    assert!((p.cruise_time() - 1.5).abs() < 1e-15);
    // Midway through the first blend: ½·a·t² = 0.0625.
    assert!((p.position(0.25) - 1.0625).abs() < 1e-15);
    // During the cruise: ½·a·t_a² + v·(t − t_a) = 0.25 + 0.5.
    assert!((p.position(1.0) - 1.75).abs() < 1e-15);
    // In the final blend, 0.25 s before the end: q1 − ½·a·0.25².
    assert!((p.position(2.25) - (3.0 - 0.0625)).abs() < 1e-15);
}

#[test]
fn zero_displacement() {
    let p = Trapezoid::new(0.7, 0.7, 1.0, 1.0).unwrap();
    assert_eq!(p.duration(), 0.0);
    assert_eq!(p.position(0.3), 0.7);
    assert_eq!(p.velocity(0.3), 0.0);
    assert_eq!(
        p.sample(500.0).unwrap().collect::<Vec<_>>(),
        vec![(0.0, 0.7, 0.0, 0.0)]
    );
    let held = Trapezoid::with_velocity_and_time(0.7, 0.7, 1.0, 2.0).unwrap();
    assert_eq!(held.duration(), 2.0);
    assert_eq!(held.position(1.0), 0.7);
}

#[test]
fn bad_inputs_are_errors() {
    use TrajectoryError::*;
    for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        assert!(matches!(
            Trapezoid::new(0.0, 1.0, bad, 1.0),
            Err(InvalidLimit { what: "v_max", .. })
        ));
        assert!(matches!(
            Trapezoid::new(0.0, 1.0, 1.0, bad),
            Err(InvalidLimit { what: "a_max", .. })
        ));
        assert!(matches!(
            Trapezoid::with_velocity_and_time(0.0, 1.0, 1.0, bad),
            Err(InvalidDuration { .. })
        ));
        assert!(matches!(
            Trapezoid::with_acceleration_and_time(0.0, 1.0, 1.0, bad),
            Err(InvalidDuration { .. })
        ));
    }
    assert!(matches!(
        Trapezoid::new(f64::NAN, 1.0, 1.0, 1.0),
        Err(NotFinite { .. })
    ));
    assert!(matches!(
        Trapezoid::new(0.0, f64::INFINITY, 1.0, 1.0),
        Err(NotFinite { .. })
    ));
    // Finite inputs whose difference overflows, or whose duration does.
    assert!(matches!(
        Trapezoid::new(-1e308, 1e308, 1.0, 1.0),
        Err(Overflow)
    ));
    assert!(matches!(
        Trapezoid::new(0.0, 1e300, 1e-300, 1.0),
        Err(Overflow)
    ));
    // Exactly |Δ| = v_max·T needs infinite acceleration.
    assert!(matches!(
        Trapezoid::with_velocity_and_time(0.0, 2.0, 1.0, 2.0),
        Err(VelocityTooLow { .. })
    ));
    // A shorter duration than the fastest profile.
    let fastest = Trapezoid::new(0.0, 1.0, 1.0, 1.0).unwrap().duration();
    assert!(
        Trapezoid::stretched(0.0, 1.0, 1.0, 1.0, 0.9 * fastest, Stretch::KeepAcceleration).is_err()
    );
    for rate in [0.0, -5.0, f64::NAN, f64::INFINITY] {
        let p = Trapezoid::new(0.0, 1.0, 1.0, 1.0).unwrap();
        assert!(matches!(p.sample(rate), Err(InvalidRate { .. })));
    }
    // NaN time never leaks into the output.
    let p = Trapezoid::new(0.0, 1.0, 1.0, 1.0).unwrap();
    assert_eq!(p.position(f64::NAN), 0.0);
}

#[test]
fn errors_explain_themselves() {
    let e = Trapezoid::with_velocity_and_time(0.0, 3.0, 1.0, 2.0).unwrap_err();
    assert_eq!(
        e.to_string(),
        "distance 3 cannot be covered in 2 s at v_max = 1 (needs distance < v_max·T = 2)"
    );
    let e = Trapezoid::with_acceleration_and_time(0.0, 3.0, 1.0, 2.0).unwrap_err();
    assert!(e.to_string().contains("4·distance ≤ a_max·T² = 4"), "{e}");
    let e = Trapezoid::new(0.0, 1.0, -2.0, 1.0).unwrap_err();
    assert_eq!(e.to_string(), "v_max must be finite and positive, got -2");
}

#[test]
fn sample_count_at_500_hz() {
    // T = 2.5 s at 500 Hz: t = 0, 0.002, …, 2.5 → 1251 samples, the last exactly at T.
    let p = Trapezoid::new(1.0, 3.0, 1.0, 2.0).unwrap();
    let v: Vec<_> = p.sample(500.0).unwrap().collect();
    assert_eq!(v.len(), 1251);
    assert_eq!(v[1].0, 0.002);
    assert_eq!(v.last().unwrap().0, p.duration());
}
