//! Why a trajectory could not be planned.

use core::fmt;

/// Why a trajectory request was refused.
///
/// Every constructor in [`crate::trajectory`] checks its inputs and returns one of these
/// instead of producing a profile that would divide by zero, overshoot a limit or
/// contain NaN. With `serde`, serialized for logs (not read back: it holds `&'static
/// str` names); it is also what reading back a trajectory that breaks its invariants
/// reports.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum TrajectoryError {
    /// An input that must be a finite number (a position, velocity, time, …) was NaN or ±∞.
    NotFinite {
        /// Which input.
        what: &'static str,
    },
    /// A limit (maximum velocity or acceleration) was zero, negative, NaN or infinite.
    InvalidLimit {
        /// Which limit.
        what: &'static str,
        /// The value given.
        value: f64,
    },
    /// A duration was zero, negative, NaN or infinite.
    InvalidDuration {
        /// The value given.
        value: f64,
    },
    /// `(v_max, T)`: the distance cannot be covered in `T` at speed `v_max`
    /// (a trapezoid needs `|Δ| < v_max·T`).
    VelocityTooLow {
        /// `|Δ|`.
        distance: f64,
        /// The maximum velocity given.
        v_max: f64,
        /// The duration given.
        duration: f64,
    },
    /// `(a_max, T)`: the distance cannot be covered in `T` with acceleration `a_max`
    /// (a trapezoid needs `4·|Δ| ≤ a_max·T²`).
    AccelerationTooLow {
        /// `|Δ|`.
        distance: f64,
        /// The maximum acceleration given.
        a_max: f64,
        /// The duration given.
        duration: f64,
    },
    /// A sample rate was zero, negative, NaN or infinite.
    InvalidRate {
        /// The value given, in Hz.
        rate_hz: f64,
    },
    /// A multi-segment path needs at least two points.
    TooFewPoints {
        /// How many points were given.
        count: usize,
    },
    /// Via-point times must start at 0 and increase strictly.
    TimesNotIncreasing {
        /// Index of the first time that is not larger than the one before it
        /// (0 if the first time is not 0).
        index: usize,
    },
    /// A scalar profile given to a Cartesian line does not go from `s = 0` to `s = 1`.
    NotNormalized {
        /// `s(0)`.
        start: f64,
        /// `s(T)`.
        end: f64,
    },
    /// A profile through given times would exceed a velocity or acceleration limit.
    LimitExceeded {
        /// `"velocity"` or `"acceleration"`.
        what: &'static str,
        /// Segment (0-based) where the peak occurs.
        segment: usize,
        /// The profile's peak `|q̇|` or `|q̈|` there.
        peak: f64,
        /// The limit given.
        limit: f64,
    },
    /// The inputs were valid but the result overflowed (e.g. an enormous distance at a
    /// tiny velocity gives an infinite duration).
    Overflow,
    /// A profile read back with the `serde` feature whose parts do not fit together: a
    /// trapezoid whose blends take more than its duration, a via-point path whose
    /// segment ends where the next does not start or arrives off its time, synchronised
    /// joints that do not share one duration.
    PartsDoNotFit {
        /// Which part: the segment's or joint's index (0 for a single profile).
        part: usize,
        /// What of it does not fit: `"end"`, `"arrival time"`, `"duration"` or
        /// `"acceleration time"`.
        what: &'static str,
    },
}

impl fmt::Display for TrajectoryError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Self::NotFinite { what } => write!(f, "{what} must be a finite number"),
            Self::InvalidLimit { what, value } => {
                write!(f, "{what} must be finite and positive, got {value}")
            }
            Self::InvalidDuration { value } => {
                write!(f, "duration must be finite and positive, got {value}")
            }
            Self::VelocityTooLow {
                distance,
                v_max,
                duration,
            } => write!(
                f,
                "distance {distance} cannot be covered in {duration} s at v_max = {v_max} \
                 (needs distance < v_max·T = {})",
                v_max * duration
            ),
            Self::AccelerationTooLow {
                distance,
                a_max,
                duration,
            } => write!(
                f,
                "distance {distance} cannot be covered in {duration} s with a_max = {a_max} \
                 (needs 4·distance ≤ a_max·T² = {})",
                a_max * duration * duration
            ),
            Self::InvalidRate { rate_hz } => {
                write!(
                    f,
                    "sample rate must be finite and positive, got {rate_hz} Hz"
                )
            }
            Self::TooFewPoints { count } => {
                write!(f, "a path needs at least 2 points, got {count}")
            }
            Self::TimesNotIncreasing { index } => write!(
                f,
                "via-point times must start at 0 and increase strictly (index {index})"
            ),
            Self::NotNormalized { start, end } => write!(
                f,
                "the path parameter must go from 0 to 1, this profile goes from {start} to {end}"
            ),
            Self::LimitExceeded {
                what,
                segment,
                peak,
                limit,
            } => write!(
                f,
                "segment {segment} reaches a peak {what} of {peak}, above the limit {limit}"
            ),
            Self::Overflow => write!(f, "the trajectory's numbers overflow f64"),
            Self::PartsDoNotFit { part, what } => {
                write!(
                    f,
                    "part {part} of the stored profile: its {what} does not fit the rest"
                )
            }
        }
    }
}

#[cfg(feature = "std")]
impl std::error::Error for TrajectoryError {}

/// `Ok(x)` if `x` is finite.
pub(crate) fn finite(x: f64, what: &'static str) -> Result<f64, TrajectoryError> {
    if x.is_finite() {
        Ok(x)
    } else {
        Err(TrajectoryError::NotFinite { what })
    }
}

/// `Ok(x)` if `x` is a usable limit: finite and strictly positive.
pub(crate) fn limit(x: f64, what: &'static str) -> Result<f64, TrajectoryError> {
    if x.is_finite() && x > 0.0 {
        Ok(x)
    } else {
        Err(TrajectoryError::InvalidLimit { what, value: x })
    }
}

/// `Ok(t)` if `t` is a usable duration: finite and strictly positive.
pub(crate) fn duration(t: f64) -> Result<f64, TrajectoryError> {
    if t.is_finite() && t > 0.0 {
        Ok(t)
    } else {
        Err(TrajectoryError::InvalidDuration { value: t })
    }
}
