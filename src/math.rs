//! The math the generated code calls, in one place so generated code never names a libm.
//!
//! [`sin_cos`] and [`sin_cos_f32`] are inlined fdlibm (one shared argument reduction,
//! branch-free quadrant selection), the same with and without `std`: the trig of a joint
//! angle is most of the run time of closed-form kinematics, and the platform's
//! `f64::sin_cos` was the slower choice (numbers in BENCHMARKS.md). [`sin_cos_n`] is
//! [`sin_cos`] of several angles at once, two per SIMD register, which generated `f64`
//! code calls once per function. The rest is the
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
        fdlibm::quadrant(n, fdlibm::k_sin(y0, y1), fdlibm::k_cos(y0, y1))
    }
}

/// `(sin x, cos x)` of `N` angles at once, lane by lane bit for bit the same as
/// [`sin_cos`], two lanes side by side in an SSE2 register on x86_64 (explicit
/// intrinsics: SSE2 is part of x86_64's baseline), two lanes of straight-line code each
/// elsewhere (soft-float targets such as thumbv7em compute the same bits).
///
/// One straight-line path for every lane: the first round of fdlibm's reduction (the one
/// [`sin_cos`] does), its kernels, the quadrant picked with bit masks, and for each lane
/// whether that was enough. A single branch, taken when *any* lane is tiny but not zero
/// (0 < |x| < 2⁻²⁷·√2), huge (|x| ≥ 2²⁰·π/2), ±∞, NaN, or one fdlibm
/// reduces a second time (|x − n·π/2| < 2⁻¹⁶ of |x| rounded down to a power of 2: near a
/// multiple of π/2, or any |x| beyond about 2¹⁶·π/4 ≈ 5·10⁴), sends those lanes, and only
/// those, through [`sin_cos`]. (Joints at exactly 0 or ±π/2 are common — home poses,
/// snapped configurations, the stretched arm an unreachable IK pose gives — and taking
/// every lane through [`sin_cos`] for one of them cost a UR5 `fk` about 500
/// instructions.) For uniform angles in [−2π, 2π] a lane needs that one time in 2·10⁴, a
/// call of six lanes one time in 4000. Generated f64 code calls this once per function
/// with all its joint angles.
///
/// Doing fdlibm's second and third rounds for every lane instead also works if each
/// round's rounding error is carried (fdlibm's later rounds restart from the previous
/// round's rounded remainder, exact only where it runs them, when that remainder
/// cancels), and is a little more accurate, but it was 1.4× slower for six angles (48 ns
/// against 34 ns in criterion, both compiler-vectorised; six scalar calls 60 ns) and not
/// bit-identical to [`sin_cos`].
///
/// ```
/// let ([s1, s2], [c1, c2]) = kinegen::math::sin_cos_n([1.0, -2.0]);
/// assert_eq!((s1, c1), kinegen::math::sin_cos(1.0));
/// assert_eq!((s2, c2), kinegen::math::sin_cos(-2.0));
/// ```
#[inline(always)]
pub fn sin_cos_n<const N: usize>(x: [f64; N]) -> ([f64; N], [f64; N]) {
    #[cfg(all(target_arch = "x86", not(target_feature = "sse2")))]
    {
        sin_cos_each(x)
    }
    #[cfg(not(all(target_arch = "x86", not(target_feature = "sse2"))))]
    {
        let (mut s, mut c) = ([0.0; N], [0.0; N]);
        // `|`, not `if`: no branch per lane. Bit `min(i, 63)`: lane i needs `sin_cos`.
        let mut slow = 0u64;
        // Lanes in pairs, the last one twice if N is odd. A loop over pairs stays a loop
        // (not unrolled), so the first four pairs are spelled out: constant indices, the
        // ones past N fold away. (A closure here was not inlined.)
        slow |= sin_cos_pair(&x, &mut s, &mut c, 0);
        slow |= sin_cos_pair(&x, &mut s, &mut c, 2);
        slow |= sin_cos_pair(&x, &mut s, &mut c, 4);
        slow |= sin_cos_pair(&x, &mut s, &mut c, 6);
        for i in (8..N).step_by(2) {
            slow |= sin_cos_pair(&x, &mut s, &mut c, i);
        }
        if slow != 0 {
            sin_cos_lanes(&x, &mut s, &mut c, slow);
        }
        (s, c)
    }
}

/// Lanes `i` and `i + 1` of [`sin_cos_n`]'s fast path (lane `i` twice if it is the last
/// one, nothing if `i ≥ N`), and the lanes it does not hold for: bit `min(lane, 63)`.
#[cfg(not(all(target_arch = "x86", not(target_feature = "sse2"))))]
#[inline(always)]
fn sin_cos_pair<const N: usize>(x: &[f64; N], s: &mut [f64; N], c: &mut [f64; N], i: usize) -> u64 {
    if i >= N {
        return 0;
    }
    let j = if i + 1 < N { i + 1 } else { i };
    #[cfg(target_arch = "x86_64")]
    let (sp, cp, slow) = fdlibm::sse2::sin_cos_2([x[i], x[j]]);
    #[cfg(not(target_arch = "x86_64"))]
    let (sp, cp, slow) = sin_cos_2_portable([x[i], x[j]]);
    (s[i], c[i], s[j], c[j]) = (sp[0], cp[0], sp[1], cp[1]);
    let slow = slow as u64;
    ((slow & 1) << i.min(63)) | ((slow >> 1) << j.min(63))
}

/// [`sin_cos_n`] four lanes at a time in AVX2 registers, for a caller that has checked
/// the CPU (`is_x86_feature_detected!("avx2")`) and runs in code built for AVX2 (a
/// `#[target_feature(enable = "avx2")]` function, where this inlines): the same bits
/// lane by lane as [`sin_cos`] and [`sin_cos_n`], twice the lanes an instruction.
///
/// # Safety
/// The CPU must have AVX2.
///
/// ```
/// # #[cfg(all(target_arch = "x86_64", feature = "std"))]
/// if std::is_x86_feature_detected!("avx2") {
///     let x = [1.0, -2.0, 0.5, 3.0, 0.0];
///     // SAFETY: the CPU has AVX2 (checked just above).
///     let (s, c) = unsafe { kinegen::math::sin_cos_n_avx2(x) };
///     assert_eq!((s, c), kinegen::math::sin_cos_n(x));
/// }
/// ```
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
#[inline]
pub unsafe fn sin_cos_n_avx2<const N: usize>(x: [f64; N]) -> ([f64; N], [f64; N]) {
    let (mut s, mut c) = ([0.0; N], [0.0; N]);
    let mut slow = 0u64;
    for i in (0..N).step_by(4) {
        // A short last group repeats its last lane in the spare ones.
        let lane = |l: usize| x[(i + l).min(N - 1)];
        // SAFETY: the caller's contract: the CPU has AVX2.
        let (sq, cq, sl) = unsafe { fdlibm::avx2::sin_cos_4([lane(0), lane(1), lane(2), lane(3)]) };
        for l in 0..4.min(N - i) {
            (s[i + l], c[i + l]) = (sq[l], cq[l]);
            slow |= u64::from((sl >> l) & 1) << (i + l).min(63);
        }
    }
    if slow != 0 {
        sin_cos_lanes(&x, &mut s, &mut c, slow);
    }
    (s, c)
}

/// Two lanes of [`sin_cos_n`]'s fast path in plain Rust: each lane the fast path of
/// [`sin_cos`], and the lanes it does not hold for (bit 0: lane 0, bit 1: lane 1). (On
/// x86_64 LLVM's SLP vectoriser packed
/// this into SSE2 registers well for N = 6 angles alone, but inside a generated Jacobian
/// it paired the lanes differently and the UR5 Jacobian became slower than with scalar
/// calls; hence the intrinsics there.)
#[cfg(not(all(target_arch = "x86", not(target_feature = "sse2"))))]
#[cfg_attr(all(target_arch = "x86_64", not(test)), allow(dead_code))]
#[inline(always)]
fn sin_cos_2_portable(x: [f64; 2]) -> ([f64; 2], [f64; 2], u32) {
    let (mut s, mut c, mut slow) = ([0.0; 2], [0.0; 2], 0);
    for k in 0..2 {
        let (n, y0, y1, exact) = fdlibm::rem_pio2_first(x[k]);
        slow |= (!exact as u32) << k;
        (s[k], c[k]) = fdlibm::quadrant(n, fdlibm::k_sin(y0, y1), fdlibm::k_cos(y0, y1));
    }
    (s, c, slow)
}

/// The lanes of [`sin_cos_n`] its fast path does not hold for (bit `min(i, 63)` of
/// `slow`: lane i, all lanes from 63 on for bit 63) through [`sin_cos`]: the rare path,
/// out of line so the inlined fast path stays small.
#[cfg(not(all(target_arch = "x86", not(target_feature = "sse2"))))]
#[cold]
#[inline(never)]
fn sin_cos_lanes<const N: usize>(x: &[f64; N], s: &mut [f64; N], c: &mut [f64; N], slow: u64) {
    for i in 0..N {
        if slow & (1 << i.min(63)) != 0 {
            (s[i], c[i]) = sin_cos(x[i]);
        }
    }
}

/// [`sin_cos`] lane by lane: [`sin_cos_n`] on x86 without SSE2 (x87's excess precision
/// breaks the fast path's rounding trick).
#[cfg(all(target_arch = "x86", not(target_feature = "sse2")))]
fn sin_cos_each<const N: usize>(x: [f64; N]) -> ([f64; N], [f64; N]) {
    let (mut s, mut c) = ([0.0; N], [0.0; N]);
    for i in 0..N {
        (s[i], c[i]) = sin_cos(x[i]);
    }
    (s, c)
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

    /// The first round of [`rem_pio2_medium`] for any `x`, and whether it is the whole of
    /// `rem_pio2_medium(x)` and `x` is in [`sin_cos`]'s fast path (2⁻²⁷·√2 ≤ |x| <
    /// 2²⁰·π/2, or ±0): no branch. fdlibm's test for a second round, `ex − ey > 16` on the
    /// biased exponents of `x` and `y0`, is here `|y0| < 2^(ex − 1023) · 2⁻¹⁶`, the
    /// power of 2 being `|x|` with its mantissa cleared (exact, and false for NaN).
    #[cfg_attr(all(target_arch = "x86_64", not(test)), allow(dead_code))]
    #[inline(always)]
    pub fn rem_pio2_first(x: f64) -> (u64, f64, f64, bool) {
        let t = x * INV_PIO2 + TO_INT;
        let f_n = t - TO_INT;
        let n = t.to_bits();
        let r = x - f_n * PIO2_1;
        let w = f_n * PIO2_1T;
        let y0 = r - w;
        let abs = |v: f64| f64::from_bits(v.to_bits() & ABS);
        let ax = abs(x);
        let power = f64::from_bits(x.to_bits() & EXPONENT);
        // `&` on comparisons, not `&&` (nor `Range::contains`, which is `&&`): no branch.
        #[allow(clippy::manual_range_contains)]
        // (±0 too: the kernels give exactly `(±0, 1)` for it, as `sin_cos` does.)
        let exact =
            ((ax >= FAST_MIN) | (ax == 0.0)) & (ax < FAST_END) & (abs(y0) >= power * CANCEL);
        (n, y0, (r - y0) - w, exact)
    }

    /// The fast path of `sin_cos`, 2⁻²⁷·√2 ≤ |x| < 2²⁰·π/2: bits 0x3e46a09e_00000000 and
    /// 0x413921fb_00000000.
    const FAST_MIN: f64 = 1.0536709282860102e-8;
    const FAST_END: f64 = 1647099.0;
    /// `|y0| < 2^(ex − 1023) · CANCEL` is fdlibm's `ex − ey > 16`.
    const CANCEL: f64 = 1.0 / 65536.0;
    const ABS: u64 = !(1 << 63);
    const EXPONENT: u64 = 0x7ff0_0000_0000_0000;

    /// Two lanes in one SSE2 register: [`rem_pio2_first`], [`k_sin`], [`k_cos`] and
    /// [`quadrant`], the same operations in the same order (so the same bits), as
    /// intrinsics, which LLVM keeps as vector code wherever the call is inlined.
    #[cfg(target_arch = "x86_64")]
    pub mod sse2 {
        use super::*;
        use core::arch::x86_64::*;

        #[inline(always)]
        pub fn sin_cos_2(x: [f64; 2]) -> ([f64; 2], [f64; 2], u32) {
            // SAFETY: SSE2 is part of the x86_64 baseline; the pointers are those of
            // local arrays of two f64.
            unsafe {
                let k = |v: f64| _mm_set1_pd(v);
                let x = _mm_loadu_pd(x.as_ptr());
                // rem_pio2_first
                let t = _mm_add_pd(_mm_mul_pd(x, k(INV_PIO2)), k(TO_INT));
                let f_n = _mm_sub_pd(t, k(TO_INT));
                let n = _mm_castpd_si128(t);
                let r = _mm_sub_pd(x, _mm_mul_pd(f_n, k(PIO2_1)));
                let w = _mm_mul_pd(f_n, k(PIO2_1T));
                let y0 = _mm_sub_pd(r, w);
                let y1 = _mm_sub_pd(_mm_sub_pd(r, y0), w);
                let bits = |b: u64| _mm_castsi128_pd(_mm_set1_epi64x(b as i64));
                let ax = _mm_and_pd(x, bits(ABS));
                let power = _mm_and_pd(x, bits(EXPONENT));
                let exact = _mm_and_pd(
                    _mm_and_pd(
                        _mm_or_pd(_mm_cmpge_pd(ax, k(FAST_MIN)), _mm_cmpeq_pd(ax, k(0.0))),
                        _mm_cmplt_pd(ax, k(FAST_END)),
                    ),
                    _mm_cmpge_pd(_mm_and_pd(y0, bits(ABS)), _mm_mul_pd(power, k(CANCEL))),
                );
                let slow = !_mm_movemask_pd(exact) as u32 & 0b11;
                // k_sin(y0, y1)
                let z = _mm_mul_pd(y0, y0);
                let w = _mm_mul_pd(z, z);
                let r = _mm_add_pd(
                    _mm_add_pd(
                        k(S2),
                        _mm_mul_pd(z, _mm_add_pd(k(S3), _mm_mul_pd(z, k(S4)))),
                    ),
                    _mm_mul_pd(_mm_mul_pd(z, w), _mm_add_pd(k(S5), _mm_mul_pd(z, k(S6)))),
                );
                let v = _mm_mul_pd(z, y0);
                let inner = _mm_sub_pd(
                    _mm_mul_pd(z, _mm_sub_pd(_mm_mul_pd(k(0.5), y1), _mm_mul_pd(v, r))),
                    y1,
                );
                let s = _mm_sub_pd(y0, _mm_sub_pd(inner, _mm_mul_pd(v, k(S1))));
                // k_cos(y0, y1)
                let r = _mm_add_pd(
                    _mm_mul_pd(
                        z,
                        _mm_add_pd(
                            k(C1),
                            _mm_mul_pd(z, _mm_add_pd(k(C2), _mm_mul_pd(z, k(C3)))),
                        ),
                    ),
                    _mm_mul_pd(
                        _mm_mul_pd(w, w),
                        _mm_add_pd(
                            k(C4),
                            _mm_mul_pd(z, _mm_add_pd(k(C5), _mm_mul_pd(z, k(C6)))),
                        ),
                    ),
                );
                let hz = _mm_mul_pd(k(0.5), z);
                let w = _mm_sub_pd(k(1.0), hz);
                let c = _mm_add_pd(
                    w,
                    _mm_add_pd(
                        _mm_sub_pd(_mm_sub_pd(k(1.0), w), hz),
                        _mm_sub_pd(_mm_mul_pd(z, r), _mm_mul_pd(y0, y1)),
                    ),
                );
                // quadrant
                let (s, c) = (_mm_castpd_si128(s), _mm_castpd_si128(c));
                let (one, two) = (_mm_set1_epi64x(1), _mm_set1_epi64x(2));
                let swap = _mm_sub_epi64(_mm_setzero_si128(), _mm_and_si128(n, one));
                let a = _mm_or_si128(_mm_andnot_si128(swap, s), _mm_and_si128(swap, c));
                let b = _mm_or_si128(_mm_andnot_si128(swap, c), _mm_and_si128(swap, s));
                let sign_a = _mm_slli_epi64(_mm_and_si128(n, two), 62);
                let sign_b = _mm_slli_epi64(_mm_and_si128(_mm_add_epi64(n, one), two), 62);
                let (mut so, mut co) = ([0.0; 2], [0.0; 2]);
                _mm_storeu_pd(so.as_mut_ptr(), _mm_castsi128_pd(_mm_xor_si128(a, sign_a)));
                _mm_storeu_pd(co.as_mut_ptr(), _mm_castsi128_pd(_mm_xor_si128(b, sign_b)));
                (so, co, slow)
            }
        }
    }

    /// Four lanes in one AVX2 register: [`sse2::sin_cos_2`]'s operations in the same
    /// order on `__m256d` (so the same bits: no fused multiply-add, no other rounding).
    /// A transcription, not one body shared with the SSE2 pair: written once over each
    /// module's lane functions, the PUMA 560's `ik`, which inlines the SSE2 pair, took
    /// 2 % more instructions (97.3 M against 95.2 M for 20 000 calls, callgrind). The
    /// tests hold both to [`super::sin_cos`] bit for bit.
    #[cfg(target_arch = "x86_64")]
    pub mod avx2 {
        use super::*;
        use core::arch::x86_64::*;

        /// # Safety
        /// The CPU must have AVX2.
        #[target_feature(enable = "avx2")]
        #[inline]
        pub unsafe fn sin_cos_4(x: [f64; 4]) -> ([f64; 4], [f64; 4], u32) {
            let k = |v: f64| _mm256_set1_pd(v);
            // SAFETY: the pointer is that of a local array of four f64.
            let x = unsafe { _mm256_loadu_pd(x.as_ptr()) };
            // rem_pio2_first
            let t = _mm256_add_pd(_mm256_mul_pd(x, k(INV_PIO2)), k(TO_INT));
            let f_n = _mm256_sub_pd(t, k(TO_INT));
            let n = _mm256_castpd_si256(t);
            let r = _mm256_sub_pd(x, _mm256_mul_pd(f_n, k(PIO2_1)));
            let w = _mm256_mul_pd(f_n, k(PIO2_1T));
            let y0 = _mm256_sub_pd(r, w);
            let y1 = _mm256_sub_pd(_mm256_sub_pd(r, y0), w);
            let bits = |b: u64| _mm256_castsi256_pd(_mm256_set1_epi64x(b as i64));
            let ax = _mm256_and_pd(x, bits(ABS));
            let power = _mm256_and_pd(x, bits(EXPONENT));
            // Ordered comparisons, false for NaN, as SSE2's `cmpge`/`cmpeq`/`cmplt`.
            let exact = _mm256_and_pd(
                _mm256_and_pd(
                    _mm256_or_pd(
                        _mm256_cmp_pd::<_CMP_GE_OQ>(ax, k(FAST_MIN)),
                        _mm256_cmp_pd::<_CMP_EQ_OQ>(ax, k(0.0)),
                    ),
                    _mm256_cmp_pd::<_CMP_LT_OQ>(ax, k(FAST_END)),
                ),
                _mm256_cmp_pd::<_CMP_GE_OQ>(
                    _mm256_and_pd(y0, bits(ABS)),
                    _mm256_mul_pd(power, k(CANCEL)),
                ),
            );
            let slow = !_mm256_movemask_pd(exact) as u32 & 0b1111;
            // k_sin(y0, y1)
            let z = _mm256_mul_pd(y0, y0);
            let w = _mm256_mul_pd(z, z);
            let r = _mm256_add_pd(
                _mm256_add_pd(
                    k(S2),
                    _mm256_mul_pd(z, _mm256_add_pd(k(S3), _mm256_mul_pd(z, k(S4)))),
                ),
                _mm256_mul_pd(
                    _mm256_mul_pd(z, w),
                    _mm256_add_pd(k(S5), _mm256_mul_pd(z, k(S6))),
                ),
            );
            let v = _mm256_mul_pd(z, y0);
            let inner = _mm256_sub_pd(
                _mm256_mul_pd(
                    z,
                    _mm256_sub_pd(_mm256_mul_pd(k(0.5), y1), _mm256_mul_pd(v, r)),
                ),
                y1,
            );
            let s = _mm256_sub_pd(y0, _mm256_sub_pd(inner, _mm256_mul_pd(v, k(S1))));
            // k_cos(y0, y1)
            let r = _mm256_add_pd(
                _mm256_mul_pd(
                    z,
                    _mm256_add_pd(
                        k(C1),
                        _mm256_mul_pd(z, _mm256_add_pd(k(C2), _mm256_mul_pd(z, k(C3)))),
                    ),
                ),
                _mm256_mul_pd(
                    _mm256_mul_pd(w, w),
                    _mm256_add_pd(
                        k(C4),
                        _mm256_mul_pd(z, _mm256_add_pd(k(C5), _mm256_mul_pd(z, k(C6)))),
                    ),
                ),
            );
            let hz = _mm256_mul_pd(k(0.5), z);
            let w = _mm256_sub_pd(k(1.0), hz);
            let c = _mm256_add_pd(
                w,
                _mm256_add_pd(
                    _mm256_sub_pd(_mm256_sub_pd(k(1.0), w), hz),
                    _mm256_sub_pd(_mm256_mul_pd(z, r), _mm256_mul_pd(y0, y1)),
                ),
            );
            // quadrant
            let (s, c) = (_mm256_castpd_si256(s), _mm256_castpd_si256(c));
            let (one, two) = (_mm256_set1_epi64x(1), _mm256_set1_epi64x(2));
            let swap = _mm256_sub_epi64(_mm256_setzero_si256(), _mm256_and_si256(n, one));
            let a = _mm256_or_si256(_mm256_andnot_si256(swap, s), _mm256_and_si256(swap, c));
            let b = _mm256_or_si256(_mm256_andnot_si256(swap, c), _mm256_and_si256(swap, s));
            let sign_a = _mm256_slli_epi64::<62>(_mm256_and_si256(n, two));
            let sign_b = _mm256_slli_epi64::<62>(_mm256_and_si256(_mm256_add_epi64(n, one), two));
            let (mut so, mut co) = ([0.0; 4], [0.0; 4]);
            // SAFETY: the pointers are those of local arrays of four f64.
            unsafe {
                _mm256_storeu_pd(
                    so.as_mut_ptr(),
                    _mm256_castsi256_pd(_mm256_xor_si256(a, sign_a)),
                );
                _mm256_storeu_pd(
                    co.as_mut_ptr(),
                    _mm256_castsi256_pd(_mm256_xor_si256(b, sign_b)),
                );
            }
            (so, co, slow)
        }
    }

    /// `(sin x, cos x)` from the kernels' `(sin y, cos y)` and the quadrant `n` mod 4 of
    /// `x = n·π/2 + y`: `(s, c)`, `(c, −s)`, `(−s, −c)`, `(−c, s)`. Bit masks, not `if`:
    /// the quadrant of a joint angle is unpredictable, a mispredicted branch costs more
    /// than the whole selection (and masks work lane-wise in SIMD registers).
    #[inline(always)]
    pub fn quadrant(n: u64, s: f64, c: f64) -> (f64, f64) {
        let (s, c) = (s.to_bits(), c.to_bits());
        let swap = (n & 1).wrapping_neg();
        let (a, b) = ((s & !swap) | (c & swap), (c & !swap) | (s & swap));
        (
            f64::from_bits(a ^ ((n & 2) << 62)),
            f64::from_bits(b ^ ((n.wrapping_add(1) & 2) << 62)),
        )
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

/// fdlibm's `atan` polynomial (`aT`, in `x²`; its bit patterns): within 1 ulp for
/// `|x| ≤ 7/16`.
const ATAN_POLY: [f64; 11] = [
    f64::from_bits(0x3FD5_5555_5555_550D), // 3.33333333333329318e-01
    f64::from_bits(0xBFC9_9999_9998_EBC4), // -1.99999999998764832e-01
    f64::from_bits(0x3FC2_4924_9200_83FF), // 1.42857142725034664e-01
    f64::from_bits(0xBFBC_71C6_FE23_1671), // -1.11111104054623558e-01
    f64::from_bits(0x3FB7_45CD_C54C_206E), // 9.09088713343650656e-02
    f64::from_bits(0xBFB3_B0F2_AF74_9A6D), // -7.69187620504482999e-02
    f64::from_bits(0x3FB1_0D66_A0D0_3D51), // 6.66107313738753121e-02
    f64::from_bits(0xBFAD_DE2D_52DE_FD9A), // -5.83357013379057349e-02
    f64::from_bits(0x3FA9_7B4B_2476_0DEB), // 4.97687799461593236e-02
    f64::from_bits(0xBFA2_B444_2C6A_6C2F), // -3.65315727442169155e-02
    f64::from_bits(0x3F90_AD3A_E322_DA11), // 1.62858201153657824e-02
];

/// `atan2(y, x)` in a few selects instead of branches, for the closed-form IK (whose
/// cost was half `atan2`: every joint angle is one): `t = min(|x|, |y|) / max(…)` and,
/// above `tan(π/8)`, `(t − 1) / (t + 1)` with `π/4` added back — one division either way —
/// then fdlibm's polynomial (valid to `7/16 > tan(π/8)`, evaluated by Estrin's scheme),
/// then the octant restored with `π/2` and `π` split into high and low parts. Measured
/// within 1.3 ulp of glibc's `atan2` over 2 million pairs (`tests/math_atan2.rs`), about
/// twice as fast.
/// Zeros, infinities and NaN go to the full `atan2`, so their signed results are
/// IEEE's. With the `small-ik` feature it is the full `atan2` for every input: the
/// special cases keep that one in the image anyway, and a second arctangent costs
/// 1.1 KB of a Cortex-M4F's flash.
#[inline]
pub fn fast_atan2(y: f64, x: f64) -> f64 {
    if cfg!(feature = "small-ik") {
        return atan2(y, x);
    }
    let (n, d, swap, special) = atan2_octant(y, x);
    if special {
        return atan2(y, x);
    }
    atan2_in_octant(y, x, n, d, swap)
}

/// [`fast_atan2`] of `L` pairs at once, lane by lane its bits: on x86_64 and aarch64 one
/// pass of straight-line code over the lanes (which the compiler keeps in vector
/// registers: two `atan2` for about 1.2 times the instructions of one on x86_64), then the
/// rare lanes with both zero, both infinite, or NaN through the full `atan2`; on other
/// targets one [`fast_atan2`] per lane.
///
/// ```
/// let [a, b] = kinegen::math::fast_atan2_n([1.0, -0.5], [0.3, -2.0]);
/// assert_eq!(a, kinegen::math::fast_atan2(1.0, 0.3));
/// assert_eq!(b, kinegen::math::fast_atan2(-0.5, -2.0));
/// ```
#[inline(always)]
pub fn fast_atan2_n<const L: usize>(y: [f64; L], x: [f64; L]) -> [f64; L] {
    let mut r = [0.0; L];
    // Lanes pay off with vector registers for f64; elsewhere (a Cortex-M's soft-float
    // doubles) they would only copy the polynomial into every caller: one call per lane
    // (and with `small-ik`, where `fast_atan2` is the full `atan2`).
    #[cfg(any(
        feature = "small-ik",
        not(any(target_arch = "x86_64", target_arch = "aarch64"))
    ))]
    for i in 0..L {
        r[i] = fast_atan2(y[i], x[i]);
    }
    #[cfg(all(
        not(feature = "small-ik"),
        any(target_arch = "x86_64", target_arch = "aarch64")
    ))]
    {
        for i in 0..L {
            let (n, d, swap, _) = atan2_octant(y[i], x[i]);
            r[i] = atan2_in_octant(y[i], x[i], n, d, swap);
        }
        // The special lanes are the NaN results: both zero (0/0), both infinite (∞/∞), a
        // NaN in. (One infinite gives u = 0 and the exact 0, ±π/2 or ±π of the full
        // `atan2`.) One comparison for all lanes, no branch per lane.
        if !all_finite(&r) {
            for i in 0..L {
                if atan2_octant(y[i], x[i]).3 {
                    r[i] = atan2(y[i], x[i]);
                }
            }
        }
    }
    r
}

/// [`fast_atan2`]'s reduction to the first octant: `(n, d) = (min, max)` of `|x|`, `|y|`,
/// whether they were swapped, and whether `(y, x)` is a special case (zeros, ∞, NaN)
/// whose result is the full `atan2`'s instead.
#[inline(always)]
fn atan2_octant(y: f64, x: f64) -> (f64, f64, bool, bool) {
    let (ax, ay) = (abs(x), abs(y));
    let swap = ay > ax;
    let (n, d) = if swap { (ax, ay) } else { (ay, ax) };
    // d = 0 (both zero), d = ∞ or NaN: the cases with IEEE's special results.
    let special = !((d > 0.0) & (d < f64::INFINITY)) | n.is_nan();
    (n, d, swap, special)
}

/// [`fast_atan2`] from [`atan2_octant`]'s reduction.
#[inline(always)]
fn atan2_in_octant(y: f64, x: f64, n: f64, d: f64, swap: bool) -> f64 {
    use core::f64::consts::{FRAC_PI_2, FRAC_PI_4, PI};
    const TAN_PI_8: f64 = 0.414_213_562_373_095;
    // π/4, π/2, π rounded, and what the rounding left off (fdlibm's atanlo, pi_lo).
    const PIO4: (f64, f64) = (FRAC_PI_4, f64::from_bits(0x3C81_A626_3314_5C07));
    const PIO2: (f64, f64) = (FRAC_PI_2, f64::from_bits(0x3C91_A626_3314_5C07));
    const PI_SPLIT: (f64, f64) = (PI, f64::from_bits(0x3CA1_A626_3314_5C07));
    let big = n > TAN_PI_8 * d;
    let (num, den) = if big { (n - d, n + d) } else { (n, d) };
    let u = num / den;
    let a = &ATAN_POLY;
    let (z, w) = (u * u, u * u * (u * u));
    let (w2, w4) = (w * w, w * w * (w * w));
    let s1 = z * ((a[0] + w * a[2]) + w2 * (a[4] + w * a[6]) + w4 * (a[8] + w * a[10]));
    let s2 = w * ((a[1] + w * a[3]) + w2 * (a[5] + w * a[7]) + w4 * a[9]);
    let (hi, lo) = if big { PIO4 } else { (0.0, 0.0) };
    let mut r = hi - ((u * (s1 + s2) - lo) - u);
    if swap {
        r = (PIO2.0 - r) + PIO2.1;
    }
    if x.is_sign_negative() {
        r = (PI_SPLIT.0 - r) + PI_SPLIT.1;
    }
    r.copysign(y)
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

/// Whether every `x` is finite, with one comparison and no branch per value: `0 · x` is
/// ±0 for a finite `x` and NaN otherwise, and a sum of zeros is exactly zero.
#[inline(always)]
pub(crate) fn all_finite<'a>(xs: impl IntoIterator<Item = &'a f64>) -> bool {
    xs.into_iter().fold(0.0, |sum, x| sum + 0.0 * x) == 0.0
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

/// `x % 2π` for `2π` = [`core::f64::consts::TAU`]: IEEE `fmod`, `x − n·TAU` with `n =
/// trunc(x / TAU)`, exactly (the result is representable); NaN for NaN and ±∞.
///
/// Long division of the significands, one exponent bit a step (musl's `fmod` with the
/// divisor fixed): a few dozen bytes, where the `%` of `core` links compiler-builtins'
/// general `fmod` (about 4 KB on a Cortex-M: a 128-bit reduction and a division). The
/// IK solvers' angle wrapping calls it only for angles beyond three half turns (a
/// caller's free value), so its loop — one step per binary order of magnitude of `x`
/// over 2π, at most about a thousand — costs nothing in the common case.
///
/// ```
/// use core::f64::consts::TAU;
/// for x in [7.0, -7.0, 1e6, -3.5e17, TAU, 2.0 * TAU] {
///     assert_eq!(kinegen::math::rem_tau(x).to_bits(), (x % TAU).to_bits());
/// }
/// ```
#[inline(never)]
pub fn rem_tau(x: f64) -> f64 {
    const SIGNIFICAND: u64 = (1 << 52) - 1;
    const ONE: u64 = 1 << 52;
    let (ux, uy) = (x.to_bits(), core::f64::consts::TAU.to_bits());
    let sign = ux & (1 << 63);
    let (mut ex, ey) = (((ux >> 52) & 0x7ff) as i64, ((uy >> 52) & 0x7ff) as i64);
    if ex == 0x7ff {
        return f64::NAN;
    }
    // |x| ≤ TAU: x itself, or a signed zero at |x| = TAU.
    if ux << 1 <= uy << 1 {
        return if ux << 1 == uy << 1 { 0.0 * x } else { x };
    }
    // Both are normal here (|x| > TAU).
    let (mut mx, my) = ((ux & SIGNIFICAND) | ONE, (uy & SIGNIFICAND) | ONE);
    // One step of the division per exponent bit, down to the divisor's exponent.
    loop {
        let d = mx.wrapping_sub(my);
        if d >> 63 == 0 {
            if d == 0 {
                return 0.0 * x;
            }
            mx = d;
        }
        if ex == ey {
            break;
        }
        mx <<= 1;
        ex -= 1;
    }
    while mx >> 52 == 0 {
        mx <<= 1;
        ex -= 1;
    }
    let bits = if ex > 0 {
        (mx - ONE) | ((ex as u64) << 52)
    } else {
        mx >> (1 - ex)
    };
    f64::from_bits(bits | sign)
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::rem_tau;
    use std::vec;

    /// Zeros take `sin_cos_n`'s fast path (a joint at exactly 0 is common), with
    /// `sin_cos`'s signed zero.
    #[cfg(not(all(target_arch = "x86", not(target_feature = "sse2"))))]
    #[test]
    fn zeros_are_fast_and_signed() {
        let (zs, zc) = super::sin_cos_n([0.0, -0.0]);
        assert_eq!(
            zs.map(f64::to_bits),
            [0.0f64.to_bits(), (-0.0f64).to_bits()]
        );
        assert_eq!(zc, [1.0, 1.0]);
        assert!(super::fdlibm::rem_pio2_first(0.0).3 && super::fdlibm::rem_pio2_first(-0.0).3);
        #[cfg(target_arch = "x86_64")]
        assert_eq!(super::fdlibm::sse2::sin_cos_2([0.0, -0.0]).2, 0);
    }

    /// The SSE2 pair is the portable pair bit for bit (the portable one runs on targets
    /// other than x86_64, the firmware's among them); both set the same fast-path flag.
    #[cfg(target_arch = "x86_64")]
    #[test]
    fn sse2_pair_is_the_portable_pair() {
        let mut state = 0x5eed_0021u64;
        let mut next = move || {
            state ^= state >> 12;
            state ^= state << 25;
            state ^= state >> 27;
            state.wrapping_mul(0x2545_f491_4f6c_dd1d)
        };
        let mut xs = vec![
            0.0,
            -0.0,
            1e-9,
            f64::MIN_POSITIVE,
            1.0536709282860102e-8,
            1647099.0,
            1.7e6,
            f64::MAX,
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ];
        for k in 1..2000 {
            let x0 = k as f64 * core::f64::consts::FRAC_PI_2;
            xs.extend([x0, -x0, f64::from_bits(x0.to_bits() + 1)]);
        }
        for _ in 0..100_000 {
            for _ in 0..2 {
                let unit = (next() >> 11) as f64 / (1u64 << 53) as f64;
                xs.push((2.0 * unit - 1.0) * [7.0, 1e3, 2e6][(next() % 3) as usize]);
            }
            // Random bit patterns: every exponent, NaNs and infinities too.
            xs.extend([f64::from_bits(next()), f64::from_bits(next())]);
        }
        let same = |a: f64, b: f64| a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan());
        let mut fast_pairs = 0;
        for p in xs.chunks_exact(2) {
            let x = [p[0], p[1]];
            let (s, c, slow) = super::fdlibm::sse2::sin_cos_2(x);
            let (ps, pc, pslow) = super::sin_cos_2_portable(x);
            assert_eq!(slow, pslow, "{x:?}");
            fast_pairs += (slow == 0) as usize;
            for k in (0..2).filter(|k| slow & (1 << k) == 0) {
                assert!(same(s[k], ps[k]) && same(c[k], pc[k]), "{x:?} lane {k}");
                assert_eq!((s[k], c[k]), super::sin_cos(x[k]), "{x:?} lane {k}");
            }
        }
        // The flag is not trivially false. Arguments of scale 7 and 1e3 are fast, those of
        // scale 2e6 are not (beyond 2²⁰·π/2, or |x| > 2¹⁶·|y0| where fdlibm reduces
        // twice): 4 in 9 pairs of ordinary arguments expected fast (measured 45,056).
        assert!(fast_pairs > 40_000, "{fast_pairs} fast pairs");
    }

    /// The AVX2 form is `sin_cos_n` (and so `sin_cos`) bit for bit, lane by lane, on the
    /// SSE2 pair's arguments: special values, multiples of π/2 and their neighbours,
    /// random angles and random bit patterns, in groups of 8 and of 5 (a short last
    /// group). Skipped on a CPU without AVX2.
    #[cfg(target_arch = "x86_64")]
    #[test]
    fn avx2_lanes_are_sin_cos_n() {
        if !std::is_x86_feature_detected!("avx2") {
            return;
        }
        let mut state = 0x0a5e_ed42u64;
        let mut next = move || {
            state ^= state >> 12;
            state ^= state << 25;
            state ^= state >> 27;
            state.wrapping_mul(0x2545_f491_4f6c_dd1d)
        };
        let mut xs = vec![
            0.0,
            -0.0,
            1e-9,
            f64::MIN_POSITIVE,
            1647099.0,
            f64::NAN,
            f64::INFINITY,
        ];
        for k in 1..2000 {
            let x0 = k as f64 * core::f64::consts::FRAC_PI_2;
            xs.extend([x0, -x0, f64::from_bits(x0.to_bits() + 1)]);
        }
        for _ in 0..100_000 {
            let unit = (next() >> 11) as f64 / (1u64 << 53) as f64;
            xs.push((2.0 * unit - 1.0) * [7.0, 1e3, 2e6][(next() % 3) as usize]);
            xs.push(f64::from_bits(next()));
        }
        let same = |a: f64, b: f64| a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan());
        let check = |x: &[f64], s: &[f64], c: &[f64]| {
            for (k, &xk) in x.iter().enumerate() {
                let (ws, wc) = super::sin_cos(xk);
                assert!(same(s[k], ws) && same(c[k], wc), "{x:?} lane {k}");
            }
        };
        for g in xs.chunks_exact(8) {
            let x: [f64; 8] = g.try_into().unwrap();
            // SAFETY: the CPU has AVX2 (checked above).
            let (s, c) = unsafe { super::sin_cos_n_avx2(x) };
            check(&x, &s, &c);
        }
        for g in xs.chunks_exact(5) {
            let x: [f64; 5] = g.try_into().unwrap();
            // SAFETY: as above.
            let (s, c) = unsafe { super::sin_cos_n_avx2(x) };
            check(&x, &s, &c);
        }
    }

    /// `rem_tau` is `%` by `TAU` to the bit: random magnitudes from 2π to 2¹⁰²³, both
    /// signs, the multiples of TAU and their neighbours, NaN and ±∞.
    #[test]
    fn rem_tau_is_fmod_by_tau_to_the_bit() {
        use core::f64::consts::TAU;
        let mut state = 0x2545_f491_4f6c_dd1d_u64;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state
        };
        let same = |x: f64| {
            let (a, b) = (rem_tau(x), x % TAU);
            assert!(
                a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan()),
                "{x:e}: {a:e} against {b:e}"
            );
        };
        for _ in 0..200_000 {
            // A random significand at a random exponent of 2π and above.
            let exponent = 1025 + next() % 1020;
            let bits = (exponent << 52) | (next() & ((1 << 52) - 1)) | (next() & (1 << 63));
            same(f64::from_bits(bits));
        }
        for k in 1..2000u32 {
            let m = f64::from(k) * TAU;
            for x in [m, -m, m.next_up(), m.next_down(), -m.next_up(), 1.5 * m] {
                same(x);
            }
        }
        for x in [
            f64::NAN,
            f64::INFINITY,
            -f64::INFINITY,
            0.0,
            -0.0,
            3.0,
            -TAU,
            TAU,
            f64::MAX,
            f64::MIN_POSITIVE,
        ] {
            same(x);
        }
    }
}
