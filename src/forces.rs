//! Static forces: the joint torques that balance a wrench at the tool, `τ = Jᵀ F`.
//!
//! By virtual work, a wrench `F = [Fx Fy Fz nx ny nz]` (force at the tool point and moment,
//! both in the world frame — the frame and point of [`Kinematics::jacobian`]) does work
//! `F · ẋ = F · J q̇ = (Jᵀ F) · q̇` for any joint motion, so `τ = Jᵀ F` are the joint
//! torques (forces, for prismatic joints) that hold it statically.

use crate::adapters::jacobian_matrix;
use crate::Kinematics;
use nalgebra::{SMatrix, SVector};

/// `τ = Jᵀ F` for any `M × N` (task) Jacobian and an `M`-vector of generalised forces.
///
/// ```
/// use kinegen::forces::joint_torques;
/// use nalgebra::{Matrix2, Vector2};
/// // Planar RR, L1 = L2 = 1, at q = (0, π/2): J = [[-1, -1], [1, 0]].
/// let j = Matrix2::new(-1.0, -1.0, 1.0, 0.0);
/// let tau = joint_torques(&j, &Vector2::new(0.0, 2.0)); // push 2 N along +y
/// assert_eq!(tau, Vector2::new(2.0, 0.0));
/// ```
pub fn joint_torques<const M: usize, const N: usize>(
    jacobian: &SMatrix<f64, M, N>,
    wrench: &SVector<f64, M>,
) -> SVector<f64, N> {
    jacobian.tr_mul(wrench)
}

/// `τ = J(q)ᵀ F` for a world-frame wrench `[Fx Fy Fz nx ny nz]` at the tool point.
pub fn joint_torques_at<R: Kinematics<N>, const N: usize>(
    robot: &R,
    q: &[f64; N],
    wrench: &SVector<f64, 6>,
) -> SVector<f64, N> {
    joint_torques(&jacobian_matrix(robot, q), wrench)
}
