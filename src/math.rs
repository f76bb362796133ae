//! The math the generated code calls: the platform's libm with `std`, the `libm`
//! crate without it. One place, so generated code never names either.

/// `(sin x, cos x)`.
#[inline(always)]
pub fn sin_cos(x: f64) -> (f64, f64) {
    #[cfg(feature = "std")]
    {
        x.sin_cos()
    }
    #[cfg(not(feature = "std"))]
    {
        (libm::sin(x), libm::cos(x))
    }
}

/// `(sin x, cos x)` in single precision.
#[inline(always)]
pub fn sin_cos_f32(x: f32) -> (f32, f32) {
    #[cfg(feature = "std")]
    {
        x.sin_cos()
    }
    #[cfg(not(feature = "std"))]
    {
        (libm::sinf(x), libm::cosf(x))
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

/// Determinant of a square matrix by LU decomposition with partial pivoting, on the
/// stack: the fallback when the closed form is over the engine's budget.
pub fn det_lu<const N: usize>(mut a: [[f64; N]; N]) -> f64 {
    let mut det = 1.0;
    for k in 0..N {
        let mut p = k;
        for r in k + 1..N {
            if abs(a[r][k]) > abs(a[p][k]) {
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
        for r in k + 1..N {
            let f = a[r][k] / a[k][k];
            for c in k..N {
                a[r][c] -= f * a[k][c];
            }
        }
    }
    det
}

/// Same as [`det_lu`] in single precision.
pub fn det_lu_f32<const N: usize>(mut a: [[f32; N]; N]) -> f32 {
    let mut det = 1.0;
    for k in 0..N {
        let mut p = k;
        for r in k + 1..N {
            if libm::fabsf(a[r][k]) > libm::fabsf(a[p][k]) {
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
        for r in k + 1..N {
            let f = a[r][k] / a[k][k];
            for c in k..N {
                a[r][c] -= f * a[k][c];
            }
        }
    }
    det
}
