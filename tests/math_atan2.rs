//! `kinegen::math::fast_atan2` (the closed-form IK's `atan2`) against `std`'s `atan2`:
//! seeded pairs over all quadrants and many magnitudes, the octant boundaries, and the
//! special values (zeros of both signs, infinities, NaN, subnormals).

use kinegen::ik::XorShift64;
use kinegen::math::fast_atan2;

/// Uniform in [−1, 1) from the runtime's seeded generator.
fn signed(rng: &mut XorShift64) -> f64 {
    2.0 * rng.next_f64() - 1.0
}

/// The bound: 1.27 ulp measured against glibc's `atan2` (itself within 1 ulp of the
/// correctly rounded value, as other platforms' are), plus room for another platform's.
const ULPS: f64 = 3.0;

/// Distance in units of the last place of the reference (of the larger of the two when
/// the reference is tiny).
fn ulps(got: f64, want: f64) -> f64 {
    let unit = f64::EPSILON * want.abs().max(f64::MIN_POSITIVE);
    (got - want).abs() / unit
}

#[test]
fn within_three_ulp_of_std_over_quadrants_and_magnitudes() {
    let mut rng = XorShift64::new(0x5eed_a7a2);
    let mut worst = 0.0_f64;
    for i in 0..2_000_000_i32 {
        // Magnitudes from 1e-12 to 1e12 on either argument, independently.
        let ey = i % 25 - 12;
        let ex = (i / 25) % 25 - 12;
        let y = signed(&mut rng) * 10f64.powi(ey);
        let x = signed(&mut rng) * 10f64.powi(ex);
        let got = fast_atan2(y, x);
        let want = y.atan2(x);
        let e = ulps(got, want);
        assert!(
            e <= ULPS,
            "atan2({y:e}, {x:e}) = {got:e}, std {want:e} ({e} ulp)"
        );
        worst = worst.max(e);
    }
    println!("largest difference from std: {worst} ulp");
}

#[test]
fn octant_boundaries_and_axes() {
    use std::f64::consts::PI;
    for k in 0..16 {
        let t = k as f64 * PI / 8.0;
        for dt in [-1e-12, -1e-15, 0.0, 1e-15, 1e-12] {
            let (y, x) = ((t + dt).sin(), (t + dt).cos());
            let (got, want) = (fast_atan2(y, x), y.atan2(x));
            assert!(ulps(got, want) <= ULPS, "{k}: {got} vs {want}");
        }
    }
    assert_eq!(fast_atan2(1.0, 1.0), std::f64::consts::FRAC_PI_4);
    assert_eq!(fast_atan2(1.0, 0.0), std::f64::consts::FRAC_PI_2);
    assert_eq!(fast_atan2(0.0, -1.0), PI);
}

#[test]
fn special_values_are_ieee() {
    let inf = f64::INFINITY;
    let cases = [
        (0.0, 0.0),
        (-0.0, 0.0),
        (0.0, -0.0),
        (-0.0, -0.0),
        (0.0, -1.0),
        (-0.0, -1.0),
        (-0.0, 1.0),
        (1.0, inf),
        (1.0, -inf),
        (inf, inf),
        (-inf, 2.0),
        (1e-320, 1.0),
        (1.0, 1e-320),
        (-1e-320, -1e-310),
    ];
    for (y, x) in cases {
        let (got, want) = (fast_atan2(y, x), y.atan2(x));
        assert!(
            got.to_bits() == want.to_bits() || ulps(got, want) <= ULPS,
            "atan2({y:e}, {x:e}) = {got:e}, std {want:e}"
        );
        assert_eq!(got.is_sign_negative(), want.is_sign_negative(), "{y} {x}");
    }
    assert!(fast_atan2(f64::NAN, 1.0).is_nan());
    assert!(fast_atan2(1.0, f64::NAN).is_nan());
}

/// `fast_atan2_n` gives each lane `fast_atan2`'s bits, whichever lanes beside it are
/// special (zeros, infinities, NaN, subnormals): the special lanes go through the full
/// `atan2` after one check for all lanes, and must neither leak into nor miss a lane.
#[test]
fn lanes_are_fast_atan2_lane_by_lane() {
    let inf = f64::INFINITY;
    let mut rng = XorShift64::new(0x1a2e5);
    let special = [
        (0.0, 0.0),
        (-0.0, -0.0),
        (0.0, -1.0),
        (1.0, inf),
        (inf, inf),
        (-inf, 2.0),
        (f64::NAN, 1.0),
        (1.0, f64::NAN),
        (1e-320, 1.0),
        (-1e-320, -1e-310),
        (1.0, -inf),
        (-1.0, -inf),
        (inf, -inf),
        (-inf, -inf),
        (-0.0, 0.0),
        (0.0, -0.0),
        (-2.0, 0.0),
        (f64::NAN, f64::NAN),
        (inf, f64::NAN),
        (f64::MAX, f64::MIN_POSITIVE),
    ];
    let same = |a: f64, b: f64| a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan());
    for round in 0..200 {
        let mut y = [0.0; 20];
        let mut x = [0.0; 20];
        for i in 0..20 {
            (y[i], x[i]) = (signed(&mut rng), signed(&mut rng));
        }
        // None, then one or two special lanes at varying places.
        if round > 0 {
            let k = round % special.len();
            (y[round % 20], x[round % 20]) = special[k];
            if round % 3 == 0 {
                (y[(round * 7) % 20], x[(round * 7) % 20]) = special[(k + 3) % special.len()];
            }
        }
        let lanes = kinegen::math::fast_atan2_n(y, x);
        let pair = kinegen::math::fast_atan2_n([y[0], y[1]], [x[0], x[1]]);
        for i in 0..20 {
            let want = fast_atan2(y[i], x[i]);
            assert!(
                same(lanes[i], want),
                "lane {i}: atan2({:e}, {:e}) = {:e}, not {want:e}",
                y[i],
                x[i],
                lanes[i]
            );
        }
        for i in 0..2 {
            assert!(same(pair[i], fast_atan2(y[i], x[i])), "pair lane {i}");
        }
    }
}
