//! `kinegen::math::sin_cos` (and `sin_cos_f32`) against `libm::sin`/`libm::cos` and the
//! platform's `f64::sin`/`f64::cos`: random arguments, the neighbourhoods of multiples of
//! π/2 where argument reduction cancels, the thresholds of the fast path, ±0, subnormals,
//! huge values, NaN and ±∞; the batched `sin_cos_n` the same way and against `sin_cos`.
//! Run with `--nocapture` to see the measured differences.

use kinegen::ik::XorShift64;
use kinegen::math::{sin_cos, sin_cos_f32, sin_cos_n};
use std::f64::consts::{FRAC_PI_2, PI};

/// Distance in ulps (signed zero counts as equal to zero).
fn ulps(a: f64, b: f64) -> u64 {
    let key = |x: f64| {
        let b = x.to_bits() as i64;
        if b < 0 {
            i64::MIN - b
        } else {
            b
        }
    };
    key(a).abs_diff(key(b))
}

fn ulps_f32(a: f32, b: f32) -> u32 {
    let key = |x: f32| {
        let b = x.to_bits() as i32;
        if b < 0 {
            i32::MIN - b
        } else {
            b
        }
    };
    key(a).abs_diff(key(b))
}

/// Worst differences of `sin_cos` from one reference over a set of arguments.
#[derive(Default, Debug)]
struct Worst {
    n: usize,
    abs: f64,
    abs_at: f64,
    ulps: u64,
    ulps_at: f64,
    bit_differences: usize,
}

impl Worst {
    fn add(&mut self, x: f64, got: f64, want: f64) {
        self.n += 1;
        let (d, u) = ((got - want).abs(), ulps(got, want));
        if d > self.abs {
            (self.abs, self.abs_at) = (d, x);
        }
        if u > self.ulps {
            (self.ulps, self.ulps_at) = (u, x);
        }
        if got.to_bits() != want.to_bits() {
            self.bit_differences += 1;
        }
    }
}

/// Compare on `xs`; assert ≤ 1 ulp and ≤ `max_abs` against both references.
fn compare(label: &str, xs: impl Iterator<Item = f64>, max_abs: f64) {
    let (mut libm_w, mut std_w) = (Worst::default(), Worst::default());
    for x in xs {
        let (s, c) = sin_cos(x);
        libm_w.add(x, s, libm::sin(x));
        libm_w.add(x, c, libm::cos(x));
        std_w.add(x, s, x.sin());
        std_w.add(x, c, x.cos());
    }
    println!("{label}: vs libm {libm_w:?}");
    println!("{label}: vs f64::sin/cos {std_w:?}");
    for (who, w) in [("libm", &libm_w), ("f64::sin/cos", &std_w)] {
        assert!(
            w.ulps <= 1,
            "{label}: {} ulps from {who} at x = {:e}",
            w.ulps,
            w.ulps_at
        );
        assert!(
            w.abs <= max_abs,
            "{label}: |Δ| = {:e} from {who} at x = {:e}",
            w.abs,
            w.abs_at
        );
    }
}

#[test]
fn random_arguments_in_four_pi() {
    let mut rng = XorShift64::new(0x5eed_0001);
    let xs = (0..1_000_000).map(|_| (2.0 * rng.next_f64() - 1.0) * 4.0 * PI);
    // One ulp of a number below 1 is at most 1.1e-16.
    compare("uniform [-4π, 4π]", xs, 1.2e-16);
}

#[test]
fn random_magnitudes_up_to_the_fast_path_bound() {
    // Log-uniform |x| in [1e-9, 1.6e6]: every quadrant count the fast path handles.
    let mut rng = XorShift64::new(0x5eed_0002);
    let xs = (0..300_000).map(|_| {
        let m = 10f64.powf(-9.0 + 15.2 * rng.next_f64());
        if rng.next_u64() & 1 == 0 {
            m
        } else {
            -m
        }
    });
    compare("log-uniform |x| ≤ 1.6e6", xs, 1.2e-16);
}

#[test]
fn near_multiples_of_half_pi() {
    // k·π/2 rounded to double and its neighbours: sin or cos is tiny there, and the
    // reduction needs its second and third rounds. Absolute error is what matters for
    // kinematics; ulps of a tiny result are checked too.
    let mut xs = Vec::new();
    for k in (1..=64i64).chain([1000, 12345, 99_999, 333_333, 666_667]) {
        let x0 = k as f64 * FRAC_PI_2;
        for dx in -3i64..=3 {
            let x = f64::from_bits((x0.to_bits() as i64 + dx) as u64);
            xs.push(x);
            xs.push(-x);
        }
    }
    compare("k·π/2 ± 3 ulps", xs.into_iter(), 1.2e-16);
}

/// |x| = 2⁻²⁷·√2 (tiny cut-off), 2²⁰·π/2 (fast-path bound) and π/4, ± a few ulps.
fn fast_path_edges() -> Vec<f64> {
    let mut xs = Vec::new();
    for edge in [
        f64::from_bits(0x3e46_a09e_0000_0000),
        f64::from_bits(0x4139_21fb_0000_0000),
        f64::from_bits(0x4139_21fb_5444_2d18),
        FRAC_PI_2 / 2.0,
    ] {
        for dx in -4i64..=4 {
            let x = f64::from_bits((edge.to_bits() as i64 + dx) as u64);
            xs.push(x);
            xs.push(-x);
        }
    }
    xs
}

#[test]
fn thresholds_of_the_fast_path() {
    let xs = fast_path_edges();
    compare("thresholds", xs.into_iter(), 1.2e-16);
}

#[test]
fn zero_tiny_and_subnormal_keep_the_sign() {
    for x in [
        0.0,
        -0.0,
        f64::MIN_POSITIVE,
        -f64::MIN_POSITIVE,
        5e-324,
        -5e-324,
        1e-300,
        -1e-20,
        1e-9,
    ] {
        let (s, c) = sin_cos(x);
        assert_eq!(s.to_bits(), libm::sin(x).to_bits(), "sin({x:e})");
        assert_eq!(c.to_bits(), libm::cos(x).to_bits(), "cos({x:e})");
    }
    assert!(sin_cos(-0.0).0.is_sign_negative());
}

#[test]
fn huge_values_match_libm_exactly() {
    // Beyond the fast path `sin_cos` is libm, bit for bit.
    for x in [1.7e6, 1e7, 1e10, 1e22, 1e300, f64::MAX, -1e15, -f64::MAX] {
        let (s, c) = sin_cos(x);
        assert_eq!(s.to_bits(), libm::sin(x).to_bits(), "sin({x:e})");
        assert_eq!(c.to_bits(), libm::cos(x).to_bits(), "cos({x:e})");
        assert!(
            ulps(s, x.sin()) <= 1 && ulps(c, x.cos()) <= 1,
            "{x:e} vs f64"
        );
    }
}

#[test]
fn reduction_constant_is_fdlibms() {
    // `sin_cos` takes 2/π from `core` (clippy prefers it); it must be fdlibm's `invpio2`.
    assert_eq!(std::f64::consts::FRAC_2_PI.to_bits(), 0x3fe4_5f30_6dc9_c883);
}

#[test]
fn nan_and_infinity_give_nan() {
    for x in [f64::NAN, -f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        let (s, c) = sin_cos(x);
        assert!(s.is_nan() && c.is_nan(), "sin_cos({x}) = ({s}, {c})");
        assert!(libm::sin(x).is_nan() && libm::cos(x).is_nan());
    }
}

#[test]
fn pythagoras_holds_to_rounding() {
    let mut rng = XorShift64::new(0x5eed_0003);
    for _ in 0..100_000 {
        let x = (2.0 * rng.next_f64() - 1.0) * 100.0;
        let (s, c) = sin_cos(x);
        assert!((s * s + c * c - 1.0).abs() <= 4.0 * f64::EPSILON, "x = {x}");
    }
}

#[test]
fn single_precision_against_libm_and_std() {
    let mut rng = XorShift64::new(0x5eed_0004);
    let mut xs: Vec<f32> = (0..500_000)
        .map(|_| ((2.0 * rng.next_f64() - 1.0) * 4.0 * PI) as f32)
        .collect();
    xs.extend((0..200_000).map(|_| {
        let m = 10f64.powf(-5.0 + 13.0 * rng.next_f64()) as f32;
        if rng.next_u64() & 1 == 0 {
            m
        } else {
            -m
        }
    }));
    for k in 1..=64 {
        let x0 = (k as f64 * FRAC_PI_2) as f32;
        for dx in -3i32..=3 {
            xs.push(f32::from_bits((x0.to_bits() as i32 + dx) as u32));
        }
    }
    xs.extend([0.0, -0.0, 1e-30, -1e-40, 2.4e-4, 1e9, f32::MAX, -f32::MAX]);
    let (mut worst_libm, mut worst_std, mut worst_abs) = (0u32, 0u32, 0f64);
    for &x in &xs {
        let (s, c) = sin_cos_f32(x);
        for (got, want, std_want, exact) in [
            (s, libm::sinf(x), x.sin(), (x as f64).sin()),
            (c, libm::cosf(x), x.cos(), (x as f64).cos()),
        ] {
            worst_libm = worst_libm.max(ulps_f32(got, want));
            worst_std = worst_std.max(ulps_f32(got, std_want));
            worst_abs = worst_abs.max((got as f64 - exact).abs());
            assert!(ulps_f32(got, want) <= 1, "f32 {x:e}: {got} vs libm {want}");
            assert!(
                ulps_f32(got, std_want) <= 1,
                "f32 {x:e}: {got} vs std {std_want}"
            );
            // Rounded once from a < 1-ulp double result: within an f32 ulp of the truth.
            assert!(
                (got as f64 - exact).abs() <= 6e-8,
                "f32 {x:e}: {got} vs {exact}"
            );
        }
    }
    println!(
        "f32 ({} arguments): max ulps vs libm {worst_libm}, vs std {worst_std}, max |Δ| vs f64 sin/cos {worst_abs:e}",
        xs.len()
    );
    assert!(sin_cos_f32(-0.0).0.is_sign_negative());
    for x in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY] {
        let (s, c) = sin_cos_f32(x);
        assert!(s.is_nan() && c.is_nan());
    }
}

/// Differences of `sin_cos_n` (lanes of `N`) from libm, from `f64::sin`/`cos` and from the
/// scalar `sin_cos` over `xs`; asserts ≤ 1 ulp and ≤ `max_abs` from each.
fn compare_batched<const N: usize>(label: &str, xs: impl Iterator<Item = f64>, max_abs: f64) {
    compare_batched_quietly::<N>(label, xs, max_abs, true)
}

/// [`compare_batched`], printing the differences only if `print`.
fn compare_batched_quietly<const N: usize>(
    label: &str,
    xs: impl Iterator<Item = f64>,
    max_abs: f64,
    print: bool,
) {
    let (mut libm_w, mut std_w, mut scalar_w) =
        (Worst::default(), Worst::default(), Worst::default());
    let mut check = |lanes: &[f64; N], len: usize| {
        let (s, c) = sin_cos_n(*lanes);
        for i in 0..len {
            let x = lanes[i];
            let (ss, sc) = sin_cos(x);
            libm_w.add(x, s[i], libm::sin(x));
            libm_w.add(x, c[i], libm::cos(x));
            std_w.add(x, s[i], x.sin());
            std_w.add(x, c[i], x.cos());
            scalar_w.add(x, s[i], ss);
            scalar_w.add(x, c[i], sc);
        }
    };
    let mut lanes = [1.0; N];
    let mut len = 0;
    for x in xs {
        lanes[len] = x;
        len += 1;
        if len == N {
            check(&lanes, N);
            len = 0;
        }
    }
    if len > 0 {
        // Unused lanes keep ordinary arguments from before: the fast path stays taken.
        check(&lanes, len);
    }
    if print {
        println!("{label} (sin_cos_n, {N} lanes): vs libm {libm_w:?}");
        println!("{label} (sin_cos_n, {N} lanes): vs f64::sin/cos {std_w:?}");
        println!("{label} (sin_cos_n, {N} lanes): vs sin_cos {scalar_w:?}");
    }
    // Each lane is `sin_cos` bit for bit: the same first reduction round, kernels and
    // quadrant selection, and `sin_cos` itself for every lane of a call in which one
    // lane needs more. (A reduction that loses a rounding error stays within the 1-ulp
    // bounds below but changes ~15 % of values; one missing fdlibm's later rounds, a few
    // hundred near multiples of π/2.)
    assert_eq!(
        scalar_w.bit_differences, 0,
        "{label}: sin_cos_n differs from sin_cos in {} of {} values (first {:e})",
        scalar_w.bit_differences, scalar_w.n, scalar_w.ulps_at
    );
    for (who, w) in [
        ("libm", &libm_w),
        ("f64::sin/cos", &std_w),
        ("sin_cos", &scalar_w),
    ] {
        assert!(
            w.ulps <= 1,
            "{label}: sin_cos_n {} ulps from {who} at x = {:e}",
            w.ulps,
            w.ulps_at
        );
        assert!(
            w.abs <= max_abs,
            "{label}: sin_cos_n |Δ| = {:e} from {who} at x = {:e}",
            w.abs,
            w.abs_at
        );
    }
}

/// Random arguments for the batched tests: 10⁷ by default, `KINEGEN_TRIG_SAMPLES` to
/// change it.
fn samples() -> usize {
    std::env::var("KINEGEN_TRIG_SAMPLES").map_or(10_000_000, |s| s.parse().unwrap())
}

#[test]
fn batched_random_arguments_in_two_pi() {
    let mut rng = XorShift64::new(0x5eed_0011);
    let xs = (0..samples()).map(|_| (2.0 * rng.next_f64() - 1.0) * 2.0 * PI);
    compare_batched::<6>("uniform [-2π, 2π]", xs, 1.2e-16);
}

#[test]
fn batched_random_arguments_up_to_1e5() {
    let mut rng = XorShift64::new(0x5eed_0012);
    let xs = (0..samples()).map(|_| (2.0 * rng.next_f64() - 1.0) * 1e5);
    compare_batched::<6>("uniform [-1e5, 1e5]", xs, 1.2e-16);
}

#[test]
fn batched_random_magnitudes_and_lane_counts() {
    // Log-uniform |x| in [1e-9, 1.6e6]: the fast path's whole range and its edges; lane
    // counts that fill SSE registers exactly and not.
    let xs = |seed| {
        let mut rng = XorShift64::new(seed);
        (0..300_000).map(move |_| {
            let m = 10f64.powf(-9.0 + 15.2 * rng.next_f64());
            if rng.next_u64() & 1 == 0 {
                m
            } else {
                -m
            }
        })
    };
    compare_batched::<1>("log-uniform |x| ≤ 1.6e6", xs(0x5eed_0013), 1.2e-16);
    compare_batched::<2>("log-uniform |x| ≤ 1.6e6", xs(0x5eed_0014), 1.2e-16);
    compare_batched::<5>("log-uniform |x| ≤ 1.6e6", xs(0x5eed_0015), 1.2e-16);
    compare_batched::<7>("log-uniform |x| ≤ 1.6e6", xs(0x5eed_0016), 1.2e-16);
}

#[test]
fn batched_near_every_multiple_of_half_pi() {
    // k·π/2 rounded to double and its neighbours for every k of the fast path (|x| below
    // 2²⁰·π/2): the arguments closest to multiples of π/2 there, where the first round of
    // the reduction cancels and `sin_cos_n` must leave the lane to `sin_cos`'s further
    // rounds. ±3 ulps for small k, ±1 beyond.
    let xs = (1..(1i64 << 20)).flat_map(|k| {
        let x0 = k as f64 * FRAC_PI_2;
        let d = if k <= 64 { 3 } else { 1 };
        (-d..=d).flat_map(move |dx| {
            let x = f64::from_bits((x0.to_bits() as i64 + dx) as u64);
            [x, -x]
        })
    });
    compare_batched::<6>("k·π/2 ± 1 ulp, all k < 2²⁰", xs, 1.2e-16);
}

#[test]
fn batched_thresholds_of_the_fast_path() {
    let xs = fast_path_edges();
    // One at a time beside ordinary lanes, and all lanes together.
    for &x in &xs {
        for lane in 0..6 {
            let mut lanes = [0.5, -1.0, 2.0, -3.0, 4.0, -5.0];
            lanes[lane] = x;
            compare_batched_quietly::<6>("thresholds", lanes.into_iter(), 1.2e-16, false);
        }
    }
    compare_batched::<6>("thresholds", xs.into_iter(), 1.2e-16);
}

#[test]
fn batched_special_lanes_are_scalar_sin_cos_exactly() {
    // A tiny, huge or non-finite lane goes through `sin_cos`, the others keep the fast
    // path: every lane bit for bit the scalar result, signed zeros and NaN included.
    let specials = [
        0.0,
        -0.0,
        5e-324,
        -f64::MIN_POSITIVE,
        1e-9,
        -1e-20,
        1.7e6,
        -1e22,
        f64::MAX,
        f64::NAN,
        f64::INFINITY,
        f64::NEG_INFINITY,
    ];
    for &special in &specials {
        for lane in 0..6 {
            let mut x = [0.5, -1.0, 2.0, -3.0, 4.0, -5.0];
            x[lane] = special;
            lanes_are_scalar_sin_cos(x);
        }
    }
    let (s, _) = sin_cos_n([-0.0, 0.0]);
    assert!(s[0].is_sign_negative() && s[1].is_sign_positive());
    let (s, c) = sin_cos_n([f64::NAN, 1.0, f64::INFINITY]);
    assert!(s[0].is_nan() && c[0].is_nan() && s[2].is_nan() && c[2].is_nan());
    assert_eq!((s[1], c[1]), sin_cos(1.0));
    assert_eq!(sin_cos_n::<0>([]), ([], []));
}

#[test]
fn batched_lanes_past_64_share_one_flag_and_stay_exact() {
    // Lanes from 63 on share the last bit of the slow-lane mask: a special lane there
    // sends all of them through `sin_cos`, which gives the fast path's bits anyway.
    for special in [0.0, FRAC_PI_2, f64::NAN, 1e22] {
        for lane in [0, 10, 62, 63, 64, 69] {
            let mut x = [0.0; 70];
            for (i, v) in x.iter_mut().enumerate() {
                *v = 0.37 * i as f64 - 11.0;
            }
            x[lane] = special;
            lanes_are_scalar_sin_cos(x);
        }
    }
}

/// Every lane of `sin_cos_n(x)` is `sin_cos` of it, bit for bit (signed zeros, NaN).
fn lanes_are_scalar_sin_cos<const N: usize>(x: [f64; N]) {
    let same = |a: f64, b: f64| a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan());
    let (s, c) = sin_cos_n(x);
    for i in 0..N {
        let (ss, sc) = sin_cos(x[i]);
        assert!(
            same(s[i], ss) && same(c[i], sc),
            "lane {i} of {x:?}: ({}, {}) vs sin_cos ({ss}, {sc})",
            s[i],
            c[i]
        );
    }
}
