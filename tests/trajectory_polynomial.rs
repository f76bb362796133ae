//! Cubic and quintic polynomial trajectories.

use kinegen::trajectory::{Cubic, Profile, Quintic, TrajectoryError};
use proptest::prelude::*;
#[path = "../kinegen-core/tests/common/fixed_seed.rs"]
mod fixed_seed;
use fixed_seed::fixed_seed;

fn pos() -> impl Strategy<Value = f64> {
    -10.0..10.0_f64
}
fn vel() -> impl Strategy<Value = f64> {
    -5.0..5.0_f64
}
fn acc() -> impl Strategy<Value = f64> {
    -20.0..20.0_f64
}
fn dur() -> impl Strategy<Value = f64> {
    0.05..20.0_f64
}

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol
}

/// `d^k/dt^k Σ cᵢ tⁱ` evaluated term by term (independently of the crate's Horner).
fn poly(c: &[f64; 6], k: usize, t: f64) -> f64 {
    (k..6)
        .map(|i| {
            let falling: f64 = (0..k).map(|j| (i - j) as f64).product();
            falling * c[i] * t.powi((i - k) as i32)
        })
        .sum()
}

/// Central differences: q → q̇ → q̈ → q⃛ (polynomials are smooth, so everywhere).
/// Tolerance: truncation `h²/6·|f‴|` is ~1e-10 of the derivative's size over the profile
/// for `h = 1e-5·T` (the profile's own time scale), rounding ~1e-11; 1e-6 leaves room.
fn assert_derivatives<P: Profile>(p: &P) {
    let t_end = p.duration();
    let h = 1e-5 * t_end;
    let grid = |k: usize| t_end * k as f64 / 100.0;
    let size = |f: &dyn Fn(f64) -> f64| (0..=100).map(|k| f(grid(k)).abs()).fold(0.0, f64::max);
    let scales = [
        size(&|t| p.velocity(t)),
        size(&|t| p.acceleration(t)),
        size(&|t| p.jerk(t)),
    ];
    for k in 1..100 {
        let t = grid(k);
        let d = |f: &dyn Fn(f64) -> f64| (f(t + h) - f(t - h)) / (2.0 * h);
        let pairs: [(f64, f64); 3] = [
            (d(&|t| p.position(t)), p.velocity(t)),
            (d(&|t| p.velocity(t)), p.acceleration(t)),
            (d(&|t| p.acceleration(t)), p.jerk(t)),
        ];
        for (i, (fd, exact)) in pairs.into_iter().enumerate() {
            let tol = 1e-6 * scales[i] + 1e-9;
            assert!(
                close(fd, exact, tol),
                "derivative {i} at t = {t}: {fd} vs {exact}"
            );
        }
    }
}

proptest! {
    #![proptest_config(fixed_seed(256))]

    #[test]
    fn cubic_boundaries(q0 in pos(), q1 in pos(), v0 in vel(), v1 in vel(), t in dur()) {
        let c = Cubic::new(q0, q1, v0, v1, t).unwrap();
        let tol = 1e-12 * (1.0 + q0.abs() + q1.abs() + (v0.abs() + v1.abs()) * t);
        prop_assert_eq!(c.position(0.0), q0);
        prop_assert_eq!(c.velocity(0.0), v0);
        // Exact at T (the stored boundary values) ...
        prop_assert_eq!(c.position(t), q1);
        prop_assert_eq!(c.velocity(t), v1);
        // ... which the polynomial itself meets to rounding.
        let k = c.coefficients();
        prop_assert!(close(poly(&k, 0, t), q1, tol), "{} vs {q1}", poly(&k, 0, t));
        prop_assert!(close(poly(&k, 1, t), v1, tol / t), "{} vs {v1}", poly(&k, 1, t));
        prop_assert!(close(c.acceleration(t), poly(&k, 2, t), 0.0));
        prop_assert_eq!(c.jerk(0.0), c.jerk(t)); // constant third derivative
        assert_derivatives(&c);
    }

    #[test]
    fn quintic_boundaries(
        q0 in pos(), q1 in pos(), v0 in vel(), v1 in vel(), a0 in acc(), a1 in acc(), t in dur()
    ) {
        let q = Quintic::new([q0, v0, a0], [q1, v1, a1], t).unwrap();
        let scale = 1.0 + q0.abs() + q1.abs() + (v0.abs() + v1.abs()) * t + (a0.abs() + a1.abs()) * t * t;
        let tol = 1e-12 * scale;
        prop_assert_eq!(q.position(0.0), q0);
        prop_assert_eq!(q.velocity(0.0), v0);
        prop_assert_eq!(q.acceleration(0.0), a0);
        prop_assert_eq!((q.position(t), q.velocity(t), q.acceleration(t)), (q1, v1, a1));
        let k = q.coefficients();
        prop_assert!(close(poly(&k, 0, t), q1, tol), "{} vs {q1}", poly(&k, 0, t));
        prop_assert!(close(poly(&k, 1, t), v1, tol / t), "{} vs {v1}", poly(&k, 1, t));
        prop_assert!(close(poly(&k, 2, t), a1, tol / (t * t)), "{} vs {a1}", poly(&k, 2, t));
        assert_derivatives(&q);
    }

    #[test]
    fn rest_to_rest_within_limits(
        q0 in pos(), q1 in pos(), v_max in 0.01..10.0_f64, a_max in 0.01..100.0_f64
    ) {
        prop_assume!((q1 - q0).abs() > 1e-9);
        let c = Cubic::rest_to_rest(q0, q1, v_max, a_max).unwrap();
        let q = Quintic::rest_to_rest(q0, q1, v_max, a_max).unwrap();
        check_rest_to_rest(&c, v_max, a_max);
        check_rest_to_rest(&q, v_max, a_max);
    }
}

fn check_rest_to_rest<P: Profile>(p: &P, v_max: f64, a_max: f64) {
    let t_end = p.duration();
    let (mut peak_v, mut peak_a) = (0.0_f64, 0.0_f64);
    for k in 0..=4000 {
        let t = t_end * k as f64 / 4000.0;
        peak_v = peak_v.max(p.velocity(t).abs());
        peak_a = peak_a.max(p.acceleration(t).abs());
    }
    assert!(peak_v <= v_max * (1.0 + 1e-9), "{peak_v} > {v_max}");
    assert!(peak_a <= a_max * (1.0 + 1e-9), "{peak_a} > {a_max}");
    // Minimum time: one of the two limits is reached (to the sampling's resolution).
    let reached = (peak_v / v_max).max(peak_a / a_max);
    assert!(reached > 1.0 - 1e-5, "neither limit reached: {reached}");
    assert_eq!(p.velocity(0.0), 0.0);
    assert!(p.velocity(t_end).abs() <= 1e-12 * v_max);
}

#[test]
fn textbook_values() {
    // Rest-to-rest cubic 0 → 1 in 1 s: q = 3t² − 2t³.
    let c = Cubic::new(0.0, 1.0, 0.0, 0.0, 1.0).unwrap();
    assert_eq!(c.coefficients(), [0.0, 0.0, 3.0, -2.0, 0.0, 0.0]);
    assert_eq!(c.jerk(0.3), -12.0);
    // Rest-to-rest quintic 0 → 1 in 1 s: q = 10t³ − 15t⁴ + 6t⁵.
    let q = Quintic::new([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], 1.0).unwrap();
    assert_eq!(q.coefficients(), [0.0, 0.0, 0.0, 10.0, -15.0, 6.0]);
    assert_eq!(q.jerk(0.0), 60.0);
    assert!(close(q.position(0.5), 0.5, 1e-15));
}

#[test]
fn bad_inputs_are_errors() {
    use TrajectoryError::*;
    for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        assert!(matches!(
            Cubic::new(0.0, 1.0, 0.0, 0.0, bad),
            Err(InvalidDuration { .. })
        ));
        assert!(matches!(
            Quintic::new([0.0; 3], [1.0, 0.0, 0.0], bad),
            Err(InvalidDuration { .. })
        ));
        assert!(matches!(
            Cubic::rest_to_rest(0.0, 1.0, bad, 1.0),
            Err(InvalidLimit { .. })
        ));
    }
    assert!(matches!(
        Cubic::new(0.0, 1.0, f64::NAN, 0.0, 1.0),
        Err(NotFinite { .. })
    ));
    assert!(matches!(
        Quintic::new([0.0, 0.0, f64::INFINITY], [1.0, 0.0, 0.0], 1.0),
        Err(NotFinite { .. })
    ));
    // No motion: no duration follows from the limits.
    assert!(matches!(
        Quintic::rest_to_rest(1.0, 1.0, 1.0, 1.0),
        Err(InvalidDuration { .. })
    ));
    // Coefficients that overflow.
    assert!(matches!(
        Cubic::new(0.0, 1e300, 0.0, 0.0, 1e-10),
        Err(Overflow)
    ));
}
