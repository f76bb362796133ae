//! Resolved-acceleration control (Luh, Walker & Paul 1980) on the generated closed forms:
//! the joint accelerations that give a tool acceleration, from `ẍ = J q̈ + J̇ q̇`.
//!
//! [`resolved_acceleration`] inverts that relation with damped least squares,
//! `q̈ = J⁺_λ (ẍ_d − J̇ q̇)`, using the generated `jacobian` and `jdot_qdot` (the bias
//! acceleration, never `J̇` itself); [`resolved_acceleration_step`] closes the loop on a
//! reference trajectory with the textbook PD law in task space,
//! `ẍ_d = ẍ_ref + K_d (ẋ_ref − J q̇) + K_p E`, `E` the pose error of
//! [`crate::pose_error`]. All rows are world-frame `[linear; angular]`: the tool point's
//! acceleration and the tool frame's angular acceleration. No allocation; `Err` instead of
//! NaN for non-finite input, a bounded result at singularities.

use crate::adapters::{jacobian_matrix, rotation_of, translation_of};
use crate::error::SolveError;
use crate::pose_error::pose_error;
use crate::velocity::{dls_velocity, Damping};
use crate::SecondOrderKinematics;
use nalgebra::{Isometry3, SVector};

/// Joint accelerations `q̈ = J⁺_λ (ẍ_d − J̇ q̇)` that produce the world-frame tool
/// acceleration `xdd = [a; α]` at joint values `q` and rates `qd`, with damped least squares
/// ([`Damping`]): `J q̈ + J̇ q̇ = ẍ_d` exactly where J has full row rank and its smallest
/// singular value is above `damping.epsilon`, bounded near and at a singularity (the
/// singular directions get no acceleration). For a redundant arm it is the least-norm `q̈`.
///
/// ```
/// use kinegen::acceleration::resolved_acceleration;
/// use kinegen::velocity::Damping;
/// use kinegen::{Kinematics, SecondOrderKinematics};
/// use nalgebra::SVector;
/// kinegen::kinematics! {
///     struct Arm;
///     convention: standard,
///     params: { L1: 1.0, L2: 0.8 },
///     joints: [
///         revolute { a: L1, alpha: 0, d: 0 },
///         revolute { a: L2, alpha: 0, d: 0 },
///     ],
/// }
/// let (arm, q, qd) = (Arm::default(), [0.3, 1.2], [0.5, -0.4]);
/// // The acceleration that q̈ = (1, −2) gives, `J q̈ + J̇ q̇`: asked for, q̈ comes back.
/// let (j, bias) = (arm.jacobian(&q), arm.jdot_qdot(&q, &qd));
/// let xdd = SVector::<f64, 6>::from_fn(|r, _| j[r][0] - 2.0 * j[r][1] + bias[r]);
/// let qdd = resolved_acceleration(&arm, &q, &qd, &xdd, &Damping::default()).unwrap();
/// assert!((qdd[0] - 1.0).abs() < 1e-12 && (qdd[1] + 2.0).abs() < 1e-12);
/// ```
pub fn resolved_acceleration<R: SecondOrderKinematics<N>, const N: usize>(
    robot: &R,
    q: &[f64; N],
    qd: &[f64; N],
    xdd: &SVector<f64, 6>,
    damping: &Damping,
) -> Result<SVector<f64, N>, SolveError> {
    if !(finite(q) && finite(qd)) {
        return Err(SolveError::NonFinite);
    }
    let bias = SVector::<f64, 6>::from(robot.jdot_qdot(q, qd));
    dls_velocity(&jacobian_matrix(robot, q), &(xdd - bias), damping)
}

/// Where the tool should be: pose, world-frame twist `[v; ω]` and acceleration `[a; α]`
/// of a reference trajectory at one instant (e.g. sampled from
/// [`crate::trajectory`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Reference {
    /// The tool pose.
    pub pose: Isometry3<f64>,
    /// The tool twist `[v; ω]`.
    pub twist: SVector<f64, 6>,
    /// The tool acceleration `[a; α]`.
    pub acceleration: SVector<f64, 6>,
}

/// Task-space PD gains of [`resolved_acceleration_step`]: the error dynamics are
/// `ë + K_d ė + K_p e = 0`, critically damped for `K_d = 2 √K_p`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Gains {
    /// Stiffness `K_p` (1/s²).
    pub kp: f64,
    /// Damping `K_d` (1/s).
    pub kd: f64,
}

impl Gains {
    /// Critically damped gains with natural frequency `omega` (rad/s): `K_p = ω²`,
    /// `K_d = 2ω`.
    pub fn critical(omega: f64) -> Gains {
        Gains {
            kp: omega * omega,
            kd: 2.0 * omega,
        }
    }
}

/// One step of resolved-acceleration tracking: the joint accelerations
/// `q̈ = J⁺_λ (ẍ_ref + K_d (ẋ_ref − J q̇) + K_p E − J̇ q̇)` toward `reference`, `E` the pose
/// error `[p_ref − p; log(R_ref Rᵀ)]`. Integrate `q̈` (and `q̇`) over the control period
/// to move; the task error then obeys `ë + K_d ė + K_p e = 0` to first order.
pub fn resolved_acceleration_step<R: SecondOrderKinematics<N>, const N: usize>(
    robot: &R,
    q: &[f64; N],
    qd: &[f64; N],
    reference: &Reference,
    gains: &Gains,
    damping: &Damping,
) -> Result<SVector<f64, N>, SolveError> {
    let refs = reference.twist.iter().chain(&reference.acceleration);
    let pose = &reference.pose;
    let pose_finite = pose.translation.vector.iter().all(|x| x.is_finite())
        && pose.rotation.coords.iter().all(|x| x.is_finite());
    let gains_finite = gains.kp.is_finite() && gains.kd.is_finite();
    if !(finite(q)
        && finite(qd)
        && pose_finite
        && gains_finite
        && refs.clone().all(|x| x.is_finite()))
    {
        return Err(SolveError::NonFinite);
    }
    let (t, j) = robot.fk_and_jacobian(q);
    let j = crate::adapters::matrix_from_rows(&j);
    let e = pose_error(
        &pose.translation.vector,
        pose.rotation.to_rotation_matrix().matrix(),
        &translation_of(&t),
        &rotation_of(&t),
    );
    let xdot = j * SVector::<f64, N>::from(*qd);
    let bias = SVector::<f64, 6>::from(robot.jdot_qdot(q, qd));
    let xdd = reference.acceleration + (reference.twist - xdot) * gains.kd + e * gains.kp - bias;
    dls_velocity(&j, &xdd, damping)
}

fn finite<const N: usize>(x: &[f64; N]) -> bool {
    x.iter().all(|v| v.is_finite())
}
