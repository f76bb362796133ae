//! Cubic and quintic polynomial trajectories over `[0, T]`.
//!
//! A cubic `q(t) = a₀ + a₁t + a₂t² + a₃t³` meets four boundary conditions (position and
//! velocity at both ends); a quintic adds the two accelerations. Jerk is finite
//! everywhere (constant for the cubic), unlike the trapezoid's.

use super::error::{self, TrajectoryError};
use super::profile::{clamp_time, Profile};
use crate::math;

/// Coefficients `c₀ + c₁t + … + c₅t⁵` (a cubic leaves `c₄ = c₅ = 0`).
#[derive(Debug, Clone, Copy, PartialEq)]
struct Poly5([f64; 6]);

impl Poly5 {
    /// The `k`-th derivative at `t`, by Horner's rule on the differentiated coefficients.
    fn derivative(&self, k: usize, t: f64) -> f64 {
        let c = &self.0;
        let mut acc = 0.0;
        for i in (k..6).rev() {
            // i·(i−1)⋯(i−k+1): the factor d^k/dt^k brings down from t^i.
            let mut factor = 1.0;
            for j in 0..k {
                factor *= (i - j) as f64;
            }
            acc = acc * t + factor * c[i];
        }
        acc
    }
}

/// Boundary state of one end: position, velocity and (quintic only) acceleration.
fn check_end(q: f64, v: f64, a: f64) -> Result<(), TrajectoryError> {
    error::finite(q, "boundary position")?;
    error::finite(v, "boundary velocity")?;
    error::finite(a, "boundary acceleration")?;
    Ok(())
}

fn checked(coeffs: [f64; 6]) -> Result<Poly5, TrajectoryError> {
    if coeffs.iter().all(|c| c.is_finite()) {
        Ok(Poly5(coeffs))
    } else {
        Err(TrajectoryError::Overflow)
    }
}

/// Cubic polynomial with given positions and velocities at `t = 0` and `t = T`.
///
/// ```
/// use kinegen::trajectory::{Cubic, Profile};
/// let c = Cubic::new(0.0, 1.0, 0.0, 0.0, 2.0)?;
/// assert!((c.position(1.0) - 0.5).abs() < 1e-12); // symmetric: half way at T/2
/// assert!((c.velocity(1.0) - 0.75).abs() < 1e-12); // peak 1.5·Δ/T
/// # Ok::<(), kinegen::trajectory::TrajectoryError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(
        into = "super::stored::CubicEnds",
        try_from = "super::stored::CubicEnds"
    )
)]
pub struct Cubic {
    poly: Poly5,
    duration: f64,
    /// Boundary values at `T`, returned there exactly (the polynomial meets them only
    /// to rounding).
    end: [f64; 3],
}

impl Cubic {
    /// From `q(0) = q0`, `q(T) = q1`, `q̇(0) = v0`, `q̇(T) = v1`:
    /// `a₂ = (3Δ − (2v0 + v1)T)/T²`, `a₃ = (−2Δ + (v0 + v1)T)/T³`.
    pub fn new(q0: f64, q1: f64, v0: f64, v1: f64, duration: f64) -> Result<Self, TrajectoryError> {
        check_end(q0, v0, 0.0)?;
        check_end(q1, v1, 0.0)?;
        let t = error::duration(duration)?;
        let d = q1 - q0;
        let a2 = (3.0 * d - (2.0 * v0 + v1) * t) / (t * t);
        let a3 = (-2.0 * d + (v0 + v1) * t) / (t * t * t);
        let poly = checked([q0, v0, a2, a3, 0.0, 0.0])?;
        // The end acceleration is not a boundary condition of the cubic: take the
        // polynomial's own.
        let end = [q1, v1, poly.derivative(2, t)];
        Ok(Self {
            poly,
            duration: t,
            end,
        })
    }

    /// Rest-to-rest cubic in the shortest time that keeps `|q̇| ≤ v_max` and
    /// `|q̈| ≤ a_max`: its peaks are `1.5|Δ|/T` (at `T/2`) and `6|Δ|/T²` (at the ends),
    /// so `T = max(1.5|Δ|/v_max, √(6|Δ|/a_max))`. `Err` for a zero displacement (no
    /// positive duration is implied); use [`Cubic::new`] with a duration of your choice.
    pub fn rest_to_rest(q0: f64, q1: f64, v_max: f64, a_max: f64) -> Result<Self, TrajectoryError> {
        let t = rest_to_rest_time(q0, q1, v_max, a_max, 1.5, 6.0)?;
        Self::new(q0, q1, 0.0, 0.0, t)
    }
}

/// Quintic polynomial with given positions, velocities and accelerations at both ends.
///
/// ```
/// use kinegen::trajectory::{Profile, Quintic};
/// let q = Quintic::new([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], 1.0)?;
/// assert!((q.velocity(0.5) - 1.875).abs() < 1e-12); // peak 15Δ/(8T)
/// assert!(q.acceleration(0.0).abs() < 1e-12);
/// # Ok::<(), kinegen::trajectory::TrajectoryError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(
        into = "super::stored::QuinticEnds",
        try_from = "super::stored::QuinticEnds"
    )
)]
pub struct Quintic {
    poly: Poly5,
    duration: f64,
    /// Boundary values at `T`, returned there exactly.
    end: [f64; 3],
}

impl Quintic {
    /// From `start = [q0, v0, acc0]` and `end = [q1, v1, acc1]` over `T`, solving the six
    /// boundary equations in closed form (with `Δ = q1 − q0`):
    /// `a₃ = (20Δ − (8v1 + 12v0)T − (3acc0 − acc1)T²)/(2T³)`,
    /// `a₄ = (−30Δ + (14v1 + 16v0)T + (3acc0 − 2acc1)T²)/(2T⁴)`,
    /// `a₅ = (12Δ − 6(v1 + v0)T + (acc1 − acc0)T²)/(2T⁵)`.
    pub fn new(start: [f64; 3], end: [f64; 3], duration: f64) -> Result<Self, TrajectoryError> {
        let [q0, v0, acc0] = start;
        let [q1, v1, acc1] = end;
        check_end(q0, v0, acc0)?;
        check_end(q1, v1, acc1)?;
        let t = error::duration(duration)?;
        let d = q1 - q0;
        let t2 = t * t;
        let t3 = t2 * t;
        let a3 = (20.0 * d - (8.0 * v1 + 12.0 * v0) * t - (3.0 * acc0 - acc1) * t2) / (2.0 * t3);
        let a4 = (-30.0 * d + (14.0 * v1 + 16.0 * v0) * t + (3.0 * acc0 - 2.0 * acc1) * t2)
            / (2.0 * t3 * t);
        let a5 = (12.0 * d - 6.0 * (v1 + v0) * t + (acc1 - acc0) * t2) / (2.0 * t3 * t2);
        Ok(Self {
            poly: checked([q0, v0, 0.5 * acc0, a3, a4, a5])?,
            duration: t,
            end,
        })
    }

    /// Rest-to-rest quintic (zero velocity and acceleration at both ends) in the shortest
    /// time that keeps the limits: its peaks are `15|Δ|/(8T)` (at `T/2`) and
    /// `10|Δ|/(√3·T²)` (at `T/2 ∓ T/(2√3)`). `Err` for a zero displacement.
    pub fn rest_to_rest(q0: f64, q1: f64, v_max: f64, a_max: f64) -> Result<Self, TrajectoryError> {
        let t = rest_to_rest_time(q0, q1, v_max, a_max, 15.0 / 8.0, 10.0 / math::sqrt(3.0))?;
        Self::new([q0, 0.0, 0.0], [q1, 0.0, 0.0], t)
    }
}

/// `max(kv·|Δ|/v_max, √(ka·|Δ|/a_max))`: the shortest duration of a rest-to-rest
/// polynomial whose peak velocity is `kv·|Δ|/T` and peak acceleration `ka·|Δ|/T²`.
fn rest_to_rest_time(
    q0: f64,
    q1: f64,
    v_max: f64,
    a_max: f64,
    kv: f64,
    ka: f64,
) -> Result<f64, TrajectoryError> {
    error::finite(q0, "start position")?;
    error::finite(q1, "goal position")?;
    let v_max = error::limit(v_max, "v_max")?;
    let a_max = error::limit(a_max, "a_max")?;
    let d = math::abs(q1 - q0);
    let t = (kv * d / v_max).max(math::sqrt(ka * d / a_max));
    if !t.is_finite() {
        return Err(TrajectoryError::Overflow);
    }
    error::duration(t)
}

macro_rules! polynomial_profile {
    ($ty:ty) => {
        impl $ty {
            /// Coefficients `[a₀, a₁, …, a₅]` of `q(t) = Σ aᵢ tⁱ` (a cubic has `a₄ = a₅ = 0`).
            pub fn coefficients(&self) -> [f64; 6] {
                self.poly.0
            }

            /// Derivative `k ≤ 2` at `t` (clamped); the boundary values exactly at `T`.
            fn eval(&self, k: usize, t: f64) -> f64 {
                let t = clamp_time(t, self.duration);
                if t >= self.duration {
                    self.end[k]
                } else {
                    self.poly.derivative(k, t)
                }
            }
        }

        impl Profile for $ty {
            fn duration(&self) -> f64 {
                self.duration
            }
            fn position(&self, t: f64) -> f64 {
                self.eval(0, t)
            }
            fn velocity(&self, t: f64) -> f64 {
                self.eval(1, t)
            }
            fn acceleration(&self, t: f64) -> f64 {
                self.eval(2, t)
            }
            fn jerk(&self, t: f64) -> f64 {
                self.poly.derivative(3, clamp_time(t, self.duration))
            }
        }
    };
}

polynomial_profile!(Cubic);
polynomial_profile!(Quintic);
