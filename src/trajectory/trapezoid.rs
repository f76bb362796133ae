//! Trapezoidal velocity profile (linear segment with parabolic blends), with the
//! triangular profile as its short-distance case.
//!
//! Accelerate at `a` for `t_a`, cruise at `v = a·t_a` for `T − 2·t_a`, decelerate at `a`
//! for `t_a`. The distance covered is `|Δ| = v·(T − t_a)`. When the distance is too
//! short to reach the cruise velocity (`|Δ| < v_max²/a_max`), the cruise phase vanishes
//! and the profile is a triangle with `t_a = T/2`.

use super::error::{self, TrajectoryError};
use super::profile::{clamp_time, Profile};
use crate::math;

/// Relative slack for the feasibility tests, so a duration computed by
/// [`Trapezoid::new`] can be handed back to the `(·, T)` constructors without being
/// refused for one rounding error. Requests infeasible by less than this are planned as
/// the limiting (triangular) case.
const FEASIBILITY_SLACK: f64 = 1e-12;

/// A trapezoidal (or triangular) velocity profile from `q0` to `q1`, at rest at both ends.
///
/// ```
/// use kinegen::trajectory::{Profile, Trapezoid};
/// // 1 rad at most 0.5 rad/s and 1 rad/s²: t_a = 0.5 s, T = 1/0.5 + 0.5 = 2.5 s.
/// let p = Trapezoid::new(0.0, 1.0, 0.5, 1.0)?;
/// assert!((p.duration() - 2.5).abs() < 1e-12);
/// assert!((p.velocity(1.0) - 0.5).abs() < 1e-12);
/// assert_eq!(p.position(p.duration()), 1.0);
/// # Ok::<(), kinegen::trajectory::TrajectoryError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(
        into = "super::stored::TrapezoidTiming",
        try_from = "super::stored::TrapezoidTiming"
    )
)]
pub struct Trapezoid {
    q0: f64,
    q1: f64,
    /// +1 or −1: direction of motion.
    sign: f64,
    /// Acceleration (and deceleration) time.
    t_a: f64,
    duration: f64,
    /// Peak (cruise) speed, ≥ 0.
    v: f64,
    /// Acceleration magnitude, ≥ 0.
    a: f64,
}

impl Trapezoid {
    /// The fastest profile under `v_max` and `a_max`: `t_a = v_max/a_max`,
    /// `T = |Δ|/v_max + t_a`; a triangle (`t_a = √(|Δ|/a_max)`, `T = 2·t_a`) when
    /// `|Δ| < v_max²/a_max`. A zero displacement gives a zero-duration profile.
    pub fn new(q0: f64, q1: f64, v_max: f64, a_max: f64) -> Result<Self, TrajectoryError> {
        let d = displacement(q0, q1)?;
        let v_max = error::limit(v_max, "v_max")?;
        let a_max = error::limit(a_max, "a_max")?;
        if d == 0.0 {
            return Ok(Self::at_rest(q0, 0.0));
        }
        let (t_a, duration) = if d * a_max < v_max * v_max {
            let t_a = math::sqrt(d / a_max);
            (t_a, 2.0 * t_a)
        } else {
            let t_a = v_max / a_max;
            (t_a, d / v_max + t_a)
        };
        Self::from_timing(q0, q1, t_a, duration)
    }

    /// Duration `T` given, cruising at `v_max`: `t_a = T − |Δ|/v_max`,
    /// `a = v_max/t_a`. If `v_max` is more than the distance needs (`v_max > 2|Δ|/T`),
    /// the profile is the triangle with peak `2|Δ|/T`, which stays below `v_max`.
    ///
    /// `Err` if `|Δ| ≥ v_max·T`: the distance cannot be covered (at equality only with
    /// infinite acceleration).
    pub fn with_velocity_and_time(
        q0: f64,
        q1: f64,
        v_max: f64,
        duration: f64,
    ) -> Result<Self, TrajectoryError> {
        let d = displacement(q0, q1)?;
        let v_max = error::limit(v_max, "v_max")?;
        let duration = error::duration(duration)?;
        if d == 0.0 {
            return Ok(Self::at_rest(q0, duration));
        }
        if d >= v_max * duration {
            return Err(TrajectoryError::VelocityTooLow {
                distance: d,
                v_max,
                duration,
            });
        }
        let t_a = (duration - d / v_max).min(0.5 * duration);
        if t_a <= 0.0 {
            // |Δ| is below v_max·T only by a rounding error.
            return Err(TrajectoryError::VelocityTooLow {
                distance: d,
                v_max,
                duration,
            });
        }
        Self::from_timing(q0, q1, t_a, duration)
    }

    /// Duration `T` given, accelerating at `a_max`: from `|Δ| = a·t_a·(T − t_a)`,
    /// `t_a = (T − √(T² − 4|Δ|/a_max))/2` (the root with `t_a ≤ T/2`; the other one
    /// would accelerate past the midpoint), cruise speed `a_max·t_a`.
    ///
    /// `Err` if `4|Δ| > a_max·T²`: even a triangle at `a_max` is too slow.
    pub fn with_acceleration_and_time(
        q0: f64,
        q1: f64,
        a_max: f64,
        duration: f64,
    ) -> Result<Self, TrajectoryError> {
        let d = displacement(q0, q1)?;
        let a_max = error::limit(a_max, "a_max")?;
        let duration = error::duration(duration)?;
        if d == 0.0 {
            return Ok(Self::at_rest(q0, duration));
        }
        let t2 = duration * duration;
        let disc = t2 - 4.0 * d / a_max;
        let t_a = if disc >= 0.0 {
            // 2c/(b + √disc) instead of (b − √disc)/2: no cancellation for short moves.
            2.0 * (d / a_max) / (duration + math::sqrt(disc))
        } else if disc >= -FEASIBILITY_SLACK * t2 {
            0.5 * duration
        } else {
            return Err(TrajectoryError::AccelerationTooLow {
                distance: d,
                a_max,
                duration,
            });
        };
        Self::from_timing(q0, q1, t_a, duration)
    }

    /// Duration `T` (at least the minimum time under the limits) with both limits kept,
    /// choosing as [`Stretch`] says. Used to synchronise joints and segments.
    pub fn stretched(
        q0: f64,
        q1: f64,
        v_max: f64,
        a_max: f64,
        duration: f64,
        stretch: Stretch,
    ) -> Result<Self, TrajectoryError> {
        let fastest = Self::new(q0, q1, v_max, a_max)?;
        let duration = error::duration(duration)?;
        if duration < fastest.duration * (1.0 - FEASIBILITY_SLACK) {
            // Report against the limit that makes it infeasible.
            let d = fastest.distance();
            return Err(if fastest.is_triangular() {
                TrajectoryError::AccelerationTooLow {
                    distance: d,
                    a_max,
                    duration,
                }
            } else {
                TrajectoryError::VelocityTooLow {
                    distance: d,
                    v_max,
                    duration,
                }
            });
        }
        match stretch {
            Stretch::KeepAcceleration => Self::with_acceleration_and_time(q0, q1, a_max, duration),
            Stretch::KeepVelocity => {
                if fastest.is_triangular() {
                    // v_max is never reached: keep the triangle, slower.
                    Self::with_acceleration_and_time(q0, q1, a_max, duration)
                } else {
                    Self::with_velocity_and_time(q0, q1, v_max, duration)
                }
            }
        }
    }

    /// Standing still at `q` for `duration`.
    pub fn at_rest(q: f64, duration: f64) -> Self {
        Self {
            q0: q,
            q1: q,
            sign: 1.0,
            t_a: 0.0,
            duration,
            v: 0.0,
            a: 0.0,
        }
    }

    /// The one place a profile is assembled: velocity and acceleration are derived from
    /// the timing so that `|Δ| = v·(T − t_a)` and `v = a·t_a` hold to rounding, which
    /// keeps the three phases continuous.
    pub(super) fn from_timing(
        q0: f64,
        q1: f64,
        t_a: f64,
        duration: f64,
    ) -> Result<Self, TrajectoryError> {
        let d = math::abs(q1 - q0);
        let v = d / (duration - t_a);
        let a = v / t_a;
        if !(duration.is_finite() && v.is_finite() && a.is_finite() && t_a > 0.0) {
            return Err(TrajectoryError::Overflow);
        }
        Ok(Self {
            q0,
            q1,
            sign: if q1 >= q0 { 1.0 } else { -1.0 },
            t_a,
            duration,
            v,
            a,
        })
    }

    /// Time left in the final blend, `T − t`, capped at `t_a`: when `t_a` is far smaller
    /// than `T`, `T − t` rounds to a value up to one ulp of `T` above `t_a`, which would
    /// put the speed above the cruise speed.
    fn remaining(&self, t: f64) -> f64 {
        (self.duration - t).min(self.t_a)
    }

    /// Start position.
    pub fn start(&self) -> f64 {
        self.q0
    }

    /// Goal position.
    pub fn goal(&self) -> f64 {
        self.q1
    }

    /// `|q1 − q0|`.
    pub fn distance(&self) -> f64 {
        math::abs(self.q1 - self.q0)
    }

    /// Acceleration time `t_a` (also the deceleration time).
    pub fn accel_time(&self) -> f64 {
        self.t_a
    }

    /// Time spent cruising, `T − 2·t_a` (0 for a triangle).
    pub fn cruise_time(&self) -> f64 {
        (self.duration - 2.0 * self.t_a).max(0.0)
    }

    /// Peak speed `|q̇|` (the cruise speed, or the triangle's apex).
    pub fn peak_velocity(&self) -> f64 {
        self.v
    }

    /// Acceleration magnitude `|q̈|` during the blends.
    pub fn peak_acceleration(&self) -> f64 {
        self.a
    }

    /// True when there is no cruise phase (or only a rounding error's worth of one).
    pub fn is_triangular(&self) -> bool {
        self.cruise_time() <= 1e-12 * self.duration
    }
}

/// How to slow a trapezoid down to a longer duration while keeping both limits.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Stretch {
    /// Keep accelerating at `a_max`, cruise slower (the `(a_max, T)` form): short blends,
    /// long cruise.
    #[default]
    KeepAcceleration,
    /// Keep cruising at `v_max`, accelerate more gently (the `(v_max, T)` form): long
    /// blends. Falls back to a triangle when `v_max` is not reached.
    KeepVelocity,
}

/// `|q1 − q0|`, checking both are finite and the difference does not overflow.
fn displacement(q0: f64, q1: f64) -> Result<f64, TrajectoryError> {
    error::finite(q0, "start position")?;
    error::finite(q1, "goal position")?;
    let d = math::abs(q1 - q0);
    if d.is_finite() {
        Ok(d)
    } else {
        Err(TrajectoryError::Overflow)
    }
}

impl Profile for Trapezoid {
    fn duration(&self) -> f64 {
        self.duration
    }

    fn position(&self, t: f64) -> f64 {
        let t = clamp_time(t, self.duration);
        if t >= self.duration {
            return self.q1;
        }
        let s = self.sign;
        if t < self.t_a {
            self.q0 + s * 0.5 * self.a * t * t
        } else if t < self.duration - self.t_a {
            self.q0 + s * self.v * (t - 0.5 * self.t_a)
        } else {
            // Measured back from the goal, so q(T) = q1 with no rounding.
            let r = self.remaining(t);
            self.q1 - s * 0.5 * self.a * r * r
        }
    }

    fn velocity(&self, t: f64) -> f64 {
        let t = clamp_time(t, self.duration);
        let s = self.sign;
        if t < self.t_a {
            s * self.a * t
        } else if t < self.duration - self.t_a {
            s * self.v
        } else {
            s * self.a * self.remaining(t)
        }
    }

    fn acceleration(&self, t: f64) -> f64 {
        let t = clamp_time(t, self.duration);
        if t < self.t_a {
            self.sign * self.a
        } else if t < self.duration - self.t_a {
            0.0
        } else {
            -self.sign * self.a
        }
    }

    fn jerk(&self, _t: f64) -> f64 {
        0.0
    }
}
