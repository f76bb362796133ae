//! The math the generated code calls, in one place so generated code never names a libm.
//!
//! [`sin_cos`] and [`sin_cos_f32`] are inlined fdlibm (one shared argument reduction,
//! branch-free quadrant selection), the same with and without `std`: the trig of a joint
//! angle is most of the run time of closed-form kinematics, and the platform's
//! `f64::sin_cos` was the slower choice (numbers in BENCHMARKS.md). The rest is the
//! platform's libm with `std` and the `libm` crate without it.

/// `(sin x, cos x)`, as accurate as libm and faster than calling it twice.
///
/// One argument reduction shared by both results, then fdlibm's kernel polynomials (the
/// ones of `libm`'s `sin`, `cos` and `sincos`, error < 1 ulp), and the quadrant picked
/// without branches: inlined into generated code, six of these overlap in the pipeline.
/// The reduction is Cody–Waite with π/2 split in three 33-bit parts (fdlibm's
/// `__rem_pio2` "medium" case), exact enough for |x| < 2²⁰·π/2 ≈ 1.6·10⁶; beyond that,
/// and for NaN and ±∞ (which give NaN, as libm does), this calls `libm`. Results agree
/// with `libm::sin` / `libm::cos` to within an ulp (see `tests/math_sin_cos.rs` for the
/// measured differences); `sin(±0) = ±0`.
///
/// ```
/// let (s, c) = kinegen::math::sin_cos(1.0);
/// assert!((s - 1.0f64.sin()).abs() <= 1e-16 && (c - 1.0f64.cos()).abs() <= 1e-16);
/// ```
#[inline(always)]
pub fn sin_cos(x: f64) -> (f64, f64) {
    // x87 without SSE2 keeps excess precision and breaks the rounding trick below.
    #[cfg(all(target_arch = "x86", not(target_feature = "sse2")))]
    {
        (libm::sin(x), libm::cos(x))
    }
    #[cfg(not(all(target_arch = "x86", not(target_feature = "sse2"))))]
    {
        let ix = (x.to_bits() >> 32) as u32 & 0x7fff_ffff;
        if ix < 0x3e46_a09e {
            // |x| < 2⁻²⁷·√2: sin x = x, cos x = 1 in double (and keeps the sign of zero).
            return (x, 1.0);
        }
        if ix >= 0x4139_21fb {
            // |x| ≥ 2²⁰·π/2, ±∞, NaN: libm's full reduction (NaN in, NaN out).
            return (libm::sin(x), libm::cos(x));
        }
        let (n, y0, y1) = fdlibm::rem_pio2_medium(x, ix);
        let (s, c) = (
            fdlibm::k_sin(y0, y1).to_bits(),
            fdlibm::k_cos(y0, y1).to_bits(),
        );
        // Quadrant n mod 4: (s, c), (c, −s), (−s, −c), (−c, s). Bit masks, not `if`:
        // the quadrant of a joint angle is unpredictable, a mispredicted branch costs
        // more than the whole selection.
        let swap = (n & 1).wrapping_neg();
        let (a, b) = ((s & !swap) | (c & swap), (c & !swap) | (s & swap));
        (
            f64::from_bits(a ^ ((n & 2) << 62)),
            f64::from_bits(b ^ ((n.wrapping_add(1) & 2) << 62)),
        )
    }
}

/// `(sin x, cos x)` in single precision: the same scheme as [`sin_cos`] in double
/// arithmetic (fdlibm's `__rem_pio2f` medium case and its `__sindf`/`__cosdf` kernels),
/// rounded once to `f32`; libm for |x| ≥ 2²⁸·π/2, ±∞ and NaN.
///
/// ```
/// let (s, c) = kinegen::math::sin_cos_f32(1.0);
/// assert!((s - 1.0f32.sin()).abs() <= 1e-7 && (c - 1.0f32.cos()).abs() <= 1e-7);
/// ```
#[inline(always)]
pub fn sin_cos_f32(x: f32) -> (f32, f32) {
    #[cfg(all(target_arch = "x86", not(target_feature = "sse2")))]
    {
        (libm::sinf(x), libm::cosf(x))
    }
    #[cfg(not(all(target_arch = "x86", not(target_feature = "sse2"))))]
    {
        let ix = x.to_bits() & 0x7fff_ffff;
        if ix < 0x3980_0000 {
            // |x| < 2⁻¹²: sin x = x, cos x = 1 in single precision (and keeps ±0).
            return (x, 1.0);
        }
        if ix >= 0x4dc9_0fdb {
            return (libm::sinf(x), libm::cosf(x));
        }
        let (n, y) = fdlibm::rem_pio2f_medium(x);
        let (s, c) = (fdlibm::k_sinf(y).to_bits(), fdlibm::k_cosf(y).to_bits());
        let n = n as u32;
        let swap = (n & 1).wrapping_neg();
        let (a, b) = ((s & !swap) | (c & swap), (c & !swap) | (s & swap));
        (
            f32::from_bits(a ^ ((n & 2) << 30)),
            f32::from_bits(b ^ ((n.wrapping_add(1) & 2) << 30)),
        )
    }
}

/// The pieces of fdlibm (FreeBSD msun, as ported in the `libm` crate) that [`sin_cos`]
/// and [`sin_cos_f32`] inline. Constants and formulas are fdlibm's, unchanged.
///
/// Copyright (C) 1993 by Sun Microsystems, Inc. All rights reserved. Developed at
/// SunPro, a Sun Microsystems, Inc. business. Permission to use, copy, modify, and
/// distribute this software is freely granted, provided that this notice is preserved.
/// (Single-precision parts converted by Ian Lance Taylor, optimized by Bruce D. Evans.)
#[allow(clippy::excessive_precision, clippy::unreadable_literal)]
mod fdlibm {
    /// 1.5 / ε: adding and subtracting it rounds a double below 2⁵¹ to an integer.
    const TO_INT: f64 = 1.5 / f64::EPSILON;
    /// 2/π rounded to double: fdlibm's `invpio2`, 0x3FE45F30_6DC9C883.
    const INV_PIO2: f64 = core::f64::consts::FRAC_2_PI;
    /// π/2 in three 33-bit parts `PIO2_k` with the rests `PIO2_kT` (n·PIO2_k is exact for
    /// |n| < 2²⁰).
    const PIO2_1: f64 = 1.57079632673412561417e+00;
    const PIO2_1T: f64 = 6.07710050650619224932e-11;
    const PIO2_2: f64 = 6.07710050630396597660e-11;
    const PIO2_2T: f64 = 2.02226624879595063154e-21;
    const PIO2_3: f64 = 2.02226624871116645580e-21;
    const PIO2_3T: f64 = 8.47842766036889956997e-32;

    /// `x = n·π/2 + (y0 + y1)` with |y0 + y1| ≤ π/4 (about), for |x| < 2²⁰·π/2; `ix` is the
    /// high word of |x|. A second and third round only when the first cancels many bits
    /// (x near a multiple of π/2). Only `n mod 4` is meaningful in the returned `n`.
    #[inline(always)]
    pub fn rem_pio2_medium(x: f64, ix: u32) -> (u64, f64, f64) {
        let t = x * INV_PIO2 + TO_INT;
        let f_n = t - TO_INT;
        // t = 1.5·2⁵² + n: its low mantissa bits are n in two's complement, which saves
        // a (saturating) float-to-int conversion.
        let n = t.to_bits();
        let mut r = x - f_n * PIO2_1;
        let mut w = f_n * PIO2_1T;
        let mut y0 = r - w;
        let ex = (ix >> 20) as i32;
        let ey = (y0.to_bits() >> 52) as i32 & 0x7ff;
        if ex - ey > 16 {
            let t = r;
            w = f_n * PIO2_2;
            r = t - w;
            w = f_n * PIO2_2T - ((t - r) - w);
            y0 = r - w;
            let ey = (y0.to_bits() >> 52) as i32 & 0x7ff;
            if ex - ey > 49 {
                let t = r;
                w = f_n * PIO2_3;
                r = t - w;
                w = f_n * PIO2_3T - ((t - r) - w);
                y0 = r - w;
            }
        }
        (n, y0, (r - y0) - w)
    }

    const S1: f64 = -1.66666666666666324348e-01;
    const S2: f64 = 8.33333333332248946124e-03;
    const S3: f64 = -1.98412698298579493134e-04;
    const S4: f64 = 2.75573137070700676789e-06;
    const S5: f64 = -2.50507602534068634195e-08;
    const S6: f64 = 1.58969099521155010221e-10;

    /// sin(x + y) for |x + y| ≤ π/4, `y` the tail of `x` (fdlibm `__kernel_sin`, iy = 1).
    #[inline(always)]
    pub fn k_sin(x: f64, y: f64) -> f64 {
        let z = x * x;
        let w = z * z;
        let r = S2 + z * (S3 + z * S4) + z * w * (S5 + z * S6);
        let v = z * x;
        x - ((z * (0.5 * y - v * r) - y) - v * S1)
    }

    const C1: f64 = 4.16666666666666019037e-02;
    const C2: f64 = -1.38888888888741095749e-03;
    const C3: f64 = 2.48015872894767294178e-05;
    const C4: f64 = -2.75573143513906633035e-07;
    const C5: f64 = 2.08757232129817482790e-09;
    const C6: f64 = -1.13596475577881948265e-11;

    /// cos(x + y) for |x + y| ≤ π/4 (fdlibm `__kernel_cos`).
    #[inline(always)]
    pub fn k_cos(x: f64, y: f64) -> f64 {
        let z = x * x;
        let w = z * z;
        let r = z * (C1 + z * (C2 + z * C3)) + w * w * (C4 + z * (C5 + z * C6));
        let hz = 0.5 * z;
        let w = 1.0 - hz;
        w + (((1.0 - w) - hz) + (z * r - x * y))
    }

    /// π/2 in two parts for single precision: 25 + 53 bits suffice below 2²⁸·π/2.
    const PIO2F_1: f64 = 1.57079631090164184570e+00;
    const PIO2F_1T: f64 = 1.58932547735281966916e-08;

    /// `x = n·π/2 + y`, |y| ≤ π/4 (about), in double, for |x| < 2²⁸·π/2 (`n mod 4` only).
    #[inline(always)]
    pub fn rem_pio2f_medium(x: f32) -> (u64, f64) {
        let x = x as f64;
        let t = x * INV_PIO2 + TO_INT;
        let f_n = t - TO_INT;
        (t.to_bits(), x - f_n * PIO2F_1 - f_n * PIO2F_1T)
    }

    const SF1: f64 = -0.166666666416265235595;
    const SF2: f64 = 0.0083333293858894631756;
    const SF3: f64 = -0.000198393348360966317347;
    const SF4: f64 = 0.0000027183114939898219064;

    /// sin x rounded to f32, |x| ≤ π/4 (fdlibm `__kernel_sindf`).
    #[inline(always)]
    pub fn k_sinf(x: f64) -> f32 {
        let z = x * x;
        let w = z * z;
        let r = SF3 + z * SF4;
        let s = z * x;
        ((x + s * (SF1 + z * SF2)) + s * w * r) as f32
    }

    const CF0: f64 = -0.499999997251031003120;
    const CF1: f64 = 0.0416666233237390631894;
    const CF2: f64 = -0.00138867637746099294692;
    const CF3: f64 = 0.0000243904487962774090654;

    /// cos x rounded to f32, |x| ≤ π/4 (fdlibm `__kernel_cosdf`).
    #[inline(always)]
    pub fn k_cosf(x: f64) -> f32 {
        let z = x * x;
        let w = z * z;
        let r = CF2 + z * CF3;
        (((1.0 + z * CF0) + w * CF1) + (w * z) * r) as f32
    }
}

/// `√x`.
#[inline(always)]
pub fn sqrt(x: f64) -> f64 {
    #[cfg(feature = "std")]
    {
        x.sqrt()
    }
    #[cfg(not(feature = "std"))]
    {
        libm::sqrt(x)
    }
}

/// `atan2(y, x)`.
#[inline(always)]
pub fn atan2(y: f64, x: f64) -> f64 {
    #[cfg(feature = "std")]
    {
        y.atan2(x)
    }
    #[cfg(not(feature = "std"))]
    {
        libm::atan2(y, x)
    }
}

/// `acos(x)`.
#[inline(always)]
pub fn acos(x: f64) -> f64 {
    #[cfg(feature = "std")]
    {
        x.acos()
    }
    #[cfg(not(feature = "std"))]
    {
        libm::acos(x)
    }
}

/// `|x|` (core has it without std since Rust 1.85, but keep one spelling).
#[inline(always)]
pub fn abs(x: f64) -> f64 {
    libm::fabs(x)
}

/// One body for both precisions: LU with partial pivoting on a stack array.
macro_rules! det_lu_impl {
    ($(#[$doc:meta])* $name:ident, $t:ty, $fabs:path) => {
        $(#[$doc])*
        pub fn $name<const N: usize>(mut a: [[$t; N]; N]) -> $t {
            let mut det = 1.0;
            for k in 0..N {
                let mut p = k;
                for r in k + 1..N {
                    if $fabs(a[r][k]) > $fabs(a[p][k]) {
                        p = r;
                    }
                }
                if a[p][k] == 0.0 {
                    return 0.0;
                }
                if p != k {
                    a.swap(p, k);
                    det = -det;
                }
                det *= a[k][k];
                let (top, rest) = a.split_at_mut(k + 1);
                let pivot = &top[k];
                for row in rest {
                    let f = row[k] / pivot[k];
                    for (x, y) in row[k..].iter_mut().zip(&pivot[k..]) {
                        *x -= f * y;
                    }
                }
            }
            det
        }
    };
}

det_lu_impl!(
    /// Determinant of a square matrix by LU decomposition with partial pivoting, on the
    /// stack: the fallback when the closed form is over the engine's budget.
    det_lu,
    f64,
    libm::fabs
);
det_lu_impl!(
    /// Same as [`det_lu`] in single precision.
    det_lu_f32,
    f32,
    libm::fabsf
);
