//! Errors of the runtime's linear solves (inverse velocity kinematics, pseudo-inverses,
//! Cartesian control). IK and the analytical Jacobian have their own error types
//! ([`crate::ik::IkError`], [`crate::analytic::RepresentationSingularity`]) because they
//! carry different context.

use core::fmt;

/// Why a linear solve with a Jacobian failed.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum SolveError {
    /// The matrix is singular or numerically so: a pivot of the LU factorisation (or the
    /// smallest singular value, for the full-rank pseudo-inverse forms), relative to the
    /// largest entry of the matrix, fell below `tolerance`. Returned instead of inf/NaN.
    Singular {
        /// The offending relative pivot (or relative singular value); `0` for an exactly
        /// singular matrix.
        measure: f64,
        /// The relative tolerance it was compared with.
        tolerance: f64,
    },
    /// An input (matrix or vector) contained NaN or ±∞.
    NonFinite,
    /// The solve succeeded but the result overflowed to ±∞ (the matrix is so badly
    /// conditioned that the answer is not representable).
    Overflow,
}

impl fmt::Display for SolveError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SolveError::Singular { measure, tolerance } => write!(
                f,
                "singular Jacobian: relative pivot {measure:e} is below the tolerance {tolerance:e}"
            ),
            SolveError::NonFinite => f.write_str("input contains NaN or infinity"),
            SolveError::Overflow => {
                f.write_str("result overflowed: the Jacobian is too badly conditioned")
            }
        }
    }
}

#[cfg(feature = "std")]
impl std::error::Error for SolveError {}
