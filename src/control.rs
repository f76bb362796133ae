//! Proportional motion control, one control period at a time (as in the course material):
//!
//! - joint space: `q ← q + K_p (q_d − q)` — a straight line in joint space, curved in
//!   Cartesian space;
//! - Cartesian space: `q ← q + K_p J(q)⁻¹ E` with `E = x_d ⊖ x(q)`, angle differences wrapped
//!   to `(−π, π]` — approximately straight lines in Cartesian space.
//!
//! Every step returns `Err` instead of NaN/∞ (singular Jacobian, non-finite input).

use crate::adapters::{jacobian_matrix, matrix_from_rows, rotation_of, translation_of};
use crate::error::SolveError;
use crate::math::atan2;
use crate::pose_error::{pose_error, wrap_angle};
use crate::velocity::inverse_velocity;
use crate::{Kinematics, TaskKinematics};
use nalgebra::{Isometry3, SVector};

fn finite<const N: usize>(q: &[f64; N]) -> bool {
    q.iter().all(|x| x.is_finite())
}

/// One joint-space proportional step `q + K_p (q_d − q)`; `0 < K_p ≤ 1` converges without
/// overshoot.
///
/// ```
/// use kinegen::control::joint_p_step;
/// let q = joint_p_step(&[0.0, 1.0], &[1.0, 0.0], 0.5).unwrap();
/// assert_eq!(q, [0.5, 0.5]);
/// ```
pub fn joint_p_step<const N: usize>(
    q: &[f64; N],
    q_desired: &[f64; N],
    kp: f64,
) -> Result<[f64; N], SolveError> {
    if !finite(q) || !finite(q_desired) || !kp.is_finite() {
        return Err(SolveError::NonFinite);
    }
    let mut out = *q;
    for i in 0..N {
        out[i] += kp * (q_desired[i] - q[i]);
    }
    Ok(out)
}

/// Whether a task row (index into `[vx, vy, vz, ωx, ωy, ωz]`) is an angle.
pub fn is_angle_row(row: usize) -> bool {
    row >= 3
}

/// The task coordinates `x(q)` matching [`TaskKinematics::TASK_ROWS`]: positions for rows
/// 0–2, and for rows 3–5 the rotation angle about x, y or z. The angle is read as a planar
/// angle (e.g. `θ = atan2(R₁₀, R₀₀)` about z), which is exact when the tool only rotates
/// about that axis — the case task Jacobians with angular rows are made for (planar arms,
/// SCARA).
pub fn task_coordinates<R: TaskKinematics<N, M>, const N: usize, const M: usize>(
    robot: &R,
    q: &[f64; N],
) -> SVector<f64, M> {
    let t = robot.fk(q);
    let mut x = SVector::<f64, M>::zeros();
    for (k, row) in R::TASK_ROWS.iter().enumerate() {
        x[k] = match row {
            0..=2 => t[*row][3],
            3 => atan2(t[2][1], t[1][1]),
            4 => atan2(t[0][2], t[0][0]),
            _ => atan2(t[1][0], t[0][0]),
        };
    }
    x
}

/// `E = x_d ⊖ x`: component-wise difference, angles wrapped to `(−π, π]`.
pub fn task_error<const M: usize>(
    rows: &[usize; M],
    desired: &SVector<f64, M>,
    current: &SVector<f64, M>,
) -> SVector<f64, M> {
    let mut e = desired - current;
    for k in 0..M {
        if is_angle_row(rows[k]) {
            e[k] = wrap_angle(e[k]);
        }
    }
    e
}

/// One Cartesian proportional step on a square task Jacobian (e.g. planar RRR with task
/// `[x, y, θ]`): `q + K_p J⁻¹ (x_d ⊖ x(q))`. `Err(Singular)` at a singularity of the task
/// Jacobian (tolerance [`DEFAULT_TOLERANCE`](crate::velocity::DEFAULT_TOLERANCE)).
pub fn cartesian_p_step_task<R: TaskKinematics<N, N>, const N: usize>(
    robot: &R,
    q: &[f64; N],
    x_desired: &SVector<f64, N>,
    kp: f64,
) -> Result<[f64; N], SolveError> {
    if !finite(q) || !kp.is_finite() || !x_desired.iter().all(|x| x.is_finite()) {
        return Err(SolveError::NonFinite);
    }
    let e = task_error(&R::TASK_ROWS, x_desired, &task_coordinates(robot, q));
    let j = matrix_from_rows(&robot.task_jacobian(q));
    let dq = inverse_velocity(&j, &(e * kp), crate::velocity::DEFAULT_TOLERANCE)?;
    let mut out = *q;
    for i in 0..N {
        out[i] += dq[i];
    }
    Ok(out)
}

/// One Cartesian proportional step for a 6-joint arm towards a full pose:
/// `q + K_p J⁻¹ [p_d − p; log(R_d Rᵀ)]`, the orientation error as a rotation vector (the
/// 3-D counterpart of the wrapped angle difference). `Err(Singular)` at a singularity.
pub fn cartesian_p_step_pose<R: Kinematics<6>>(
    robot: &R,
    q: &[f64; 6],
    target: &Isometry3<f64>,
    kp: f64,
) -> Result<[f64; 6], SolveError> {
    if !finite(q)
        || !kp.is_finite()
        || !target.translation.vector.iter().all(|x| x.is_finite())
        || !target.rotation.coords.iter().all(|x| x.is_finite())
    {
        return Err(SolveError::NonFinite);
    }
    let t = robot.fk(q);
    let r_d = *target.rotation.to_rotation_matrix().matrix();
    let e = pose_error(
        &target.translation.vector,
        &r_d,
        &translation_of(&t),
        &rotation_of(&t),
    );
    let dq = inverse_velocity(
        &jacobian_matrix(robot, q),
        &(e * kp),
        crate::velocity::DEFAULT_TOLERANCE,
    )?;
    let mut out = *q;
    for i in 0..6 {
        out[i] += dq[i];
    }
    Ok(out)
}
