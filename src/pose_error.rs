//! The error between a desired and a current pose, as a vector that the world-frame
//! geometric Jacobian maps joint steps onto: position difference, and the axis-angle
//! (rotation vector) of `R_d R(q)ᵀ` — not a difference of Euler angles, which is neither
//! unique nor a rotation near the representation singularity.

use crate::math::{atan2, sqrt};
use core::f64::consts::PI;
use nalgebra::{ComplexField, Matrix3, Rotation3, SVector, UnitQuaternion, Vector3};

/// Rotation vector `θ k` (axis `k`, angle `θ ∈ [0, π]`) of the rotation matrix `r`: the
/// logarithm map of SO(3). Robust at `θ = π` (where the skew part of `r` vanishes) because
/// it goes through a unit quaternion with non-negative scalar part.
pub fn rotation_vector(r: &Matrix3<f64>) -> Vector3<f64> {
    let q = UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(*r));
    let (mut w, mut v) = (q.w, q.imag());
    if w < 0.0 {
        w = -w;
        v = -v;
    }
    let n = sqrt(v.dot(&v));
    if n < 1e-12 {
        // θ = 2 atan2(n, w) ≈ 2n and k = v/n, so θ k → 2v (exact to O(n³)).
        v * 2.0
    } else {
        v * (2.0 * atan2(n, w) / n)
    }
}

/// Orientation error `log(R_d R_cᵀ)` as a world-frame rotation vector: the angular
/// displacement that turns the current orientation `R_c` into the desired `R_d`.
///
/// ```
/// use kinegen::pose_error::orientation_error;
/// use nalgebra::{Rotation3, Vector3};
/// let rd = Rotation3::from_axis_angle(&Vector3::z_axis(), 3.0);
/// let rc = Rotation3::from_axis_angle(&Vector3::z_axis(), -3.0);
/// // 6 rad apart the long way round is 2π − 6 ≈ 0.283 rad the short way, about −z.
/// let e = orientation_error(rd.matrix(), rc.matrix());
/// assert!((e - Vector3::new(0.0, 0.0, 6.0 - 2.0 * core::f64::consts::PI)).norm() < 1e-12);
/// ```
pub fn orientation_error(desired: &Matrix3<f64>, current: &Matrix3<f64>) -> Vector3<f64> {
    rotation_vector(&(desired * current.transpose()))
}

/// `[p_d − p_c; log(R_d R_cᵀ)]`, the 6-D pose error matching Jacobian rows `[v; ω]`.
pub fn pose_error(
    desired_position: &Vector3<f64>,
    desired_rotation: &Matrix3<f64>,
    current_position: &Vector3<f64>,
    current_rotation: &Matrix3<f64>,
) -> SVector<f64, 6> {
    let dp = desired_position - current_position;
    let dw = orientation_error(desired_rotation, current_rotation);
    SVector::<f64, 6>::new(dp[0], dp[1], dp[2], dw[0], dw[1], dw[2])
}

/// An angle wrapped to `(−π, π]`, for differences of planar angles (`θ_d ⊖ θ`).
///
/// ```
/// use kinegen::pose_error::wrap_angle;
/// use core::f64::consts::PI;
/// assert_eq!(wrap_angle(-PI), PI);
/// assert!((wrap_angle(3.0 * PI / 2.0) + PI / 2.0).abs() < 1e-15);
/// ```
pub fn wrap_angle(a: f64) -> f64 {
    if !a.is_finite() {
        return a;
    }
    let two_pi = 2.0 * PI;
    let mut r = a - two_pi * ComplexField::floor((a + PI) / two_pi); // [−π, π)
    if r <= -PI {
        r += two_pi;
    }
    if r > PI {
        r -= two_pi;
    }
    r
}
