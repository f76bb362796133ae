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
