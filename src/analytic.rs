//! The analytical Jacobian: tool velocity as `[ṗ; φ̇]` with Euler-angle rates `φ̇` instead
//! of the angular velocity `ω` of the geometric Jacobian.
//!
//! With `ω = T(φ) φ̇`, `J_A = diag(I, T(φ)⁻¹) J`. `T(φ)` is singular where the Euler
//! angles are (the *representation* singularity, not a singularity of the arm):
//!
//! | convention | `R` | `det T(φ)` | singular at |
//! |---|---|---|---|
//! | [`EulerConvention::Zyx`] (yaw, pitch, roll = RPY) | `Rz(φ₁) Ry(φ₂) Rx(φ₃)` | `−cos φ₂` | `φ₂ = ±π/2` |
//! | [`EulerConvention::Zyz`] | `Rz(φ₁) Ry(φ₂) Rz(φ₃)` | `−sin φ₂` | `φ₂ = 0, π` |

use crate::adapters::{matrix_from_rows, rotation_of};
use crate::math::{abs, atan2, sin_cos, sqrt};
use crate::Kinematics;
use core::fmt;
use nalgebra::{Matrix3, SMatrix, Vector3};

/// Which Euler angles `φ = [φ₁, φ₂, φ₃]`, composed about current (moving) axes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum EulerConvention {
    /// `R = Rz(φ₁) Ry(φ₂) Rx(φ₃)`: yaw, pitch, roll (RPY about fixed axes X, Y, Z).
    Zyx,
    /// `R = Rz(φ₁) Ry(φ₂) Rz(φ₃)`.
    Zyz,
}

/// The Euler-angle rates are undefined: `|det T(φ)|` fell below the tolerance.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RepresentationSingularity {
    /// The convention used.
    pub convention: EulerConvention,
    /// `|det T(φ)|` (`|cos φ₂|` for ZYX, `|sin φ₂|` for ZYZ).
    pub det: f64,
    /// The tolerance it was compared with.
    pub tolerance: f64,
}

impl fmt::Display for RepresentationSingularity {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let which = match self.convention {
            EulerConvention::Zyx => "ZYX (pitch at ±90°)",
            EulerConvention::Zyz => "ZYZ (middle angle at 0 or 180°)",
        };
        write!(
            f,
            "{which} Euler-angle representation singularity: |det T(φ)| = {:e} below {:e}",
            self.det, self.tolerance
        )
    }
}

#[cfg(feature = "std")]
impl std::error::Error for RepresentationSingularity {}

/// Euler angles of a rotation matrix. ZYX: `φ₂ ∈ [−π/2, π/2]`; ZYZ: `φ₂ ∈ [0, π]`. At the
/// representation singularity only `φ₁ ± φ₃` is defined; `φ₃ = 0` is chosen.
pub fn euler_angles(r: &Matrix3<f64>, convention: EulerConvention) -> Vector3<f64> {
    match convention {
        EulerConvention::Zyx => {
            // R = [[cα cβ, ·, ·], [sα cβ, ·, ·], [−sβ, cβ sγ, cβ cγ]]
            let cb = sqrt(r[(0, 0)] * r[(0, 0)] + r[(1, 0)] * r[(1, 0)]);
            let beta = atan2(-r[(2, 0)], cb);
            if cb > 1e-12 {
                Vector3::new(
                    atan2(r[(1, 0)], r[(0, 0)]),
                    beta,
                    atan2(r[(2, 1)], r[(2, 2)]),
                )
            } else {
                Vector3::new(atan2(-r[(0, 1)], r[(1, 1)]), beta, 0.0)
            }
        }
        EulerConvention::Zyz => {
            // R = [[·, ·, cα sβ], [·, ·, sα sβ], [−sβ cγ, sβ sγ, cβ]]
            let sb = sqrt(r[(0, 2)] * r[(0, 2)] + r[(1, 2)] * r[(1, 2)]);
            let beta = atan2(sb, r[(2, 2)]);
            if sb > 1e-12 {
                Vector3::new(
                    atan2(r[(1, 2)], r[(0, 2)]),
                    beta,
                    atan2(r[(2, 1)], -r[(2, 0)]),
                )
            } else {
                Vector3::new(atan2(r[(1, 0)], r[(0, 0)]), beta, 0.0)
            }
        }
    }
}

/// `T(φ)` with `ω = T(φ) φ̇` (world-frame angular velocity from Euler-angle rates).
pub fn euler_rate_matrix(phi: &Vector3<f64>, convention: EulerConvention) -> Matrix3<f64> {
    let (sa, ca) = sin_cos(phi[0]);
    let (sb, cb) = sin_cos(phi[1]);
    match convention {
        // ω = φ̇₁ z + φ̇₂ Rz(φ₁) y + φ̇₃ Rz(φ₁) Ry(φ₂) x
        EulerConvention::Zyx => Matrix3::new(0.0, -sa, ca * cb, 0.0, ca, sa * cb, 1.0, 0.0, -sb),
        // ω = φ̇₁ z + φ̇₂ Rz(φ₁) y + φ̇₃ Rz(φ₁) Ry(φ₂) z
        EulerConvention::Zyz => Matrix3::new(0.0, -sa, ca * sb, 0.0, ca, sa * sb, 1.0, 0.0, cb),
    }
}

/// `T(φ)⁻¹` in closed form, `Err` where `|det T| < tolerance`.
pub fn euler_rate_matrix_inverse(
    phi: &Vector3<f64>,
    convention: EulerConvention,
    tolerance: f64,
) -> Result<Matrix3<f64>, RepresentationSingularity> {
    let (sa, ca) = sin_cos(phi[0]);
    let (sb, cb) = sin_cos(phi[1]);
    let d = match convention {
        EulerConvention::Zyx => cb,
        EulerConvention::Zyz => sb,
    };
    // Written so that a NaN angle or tolerance also fails the test.
    if abs(d) < tolerance || d.is_nan() || tolerance.is_nan() {
        return Err(RepresentationSingularity {
            convention,
            det: abs(d),
            tolerance,
        });
    }
    // Solve ω = T φ̇ by hand: the last rate from the first two rows, then the others.
    Ok(match convention {
        // φ̇₃ = (cα ωx + sα ωy)/cβ, φ̇₂ = −sα ωx + cα ωy, φ̇₁ = ωz + sβ φ̇₃
        EulerConvention::Zyx => Matrix3::new(
            sb * ca / cb,
            sb * sa / cb,
            1.0,
            -sa,
            ca,
            0.0,
            ca / cb,
            sa / cb,
            0.0,
        ),
        // φ̇₃ = (cα ωx + sα ωy)/sβ, φ̇₂ = −sα ωx + cα ωy, φ̇₁ = ωz − cβ φ̇₃
        EulerConvention::Zyz => Matrix3::new(
            -cb * ca / sb,
            -cb * sa / sb,
            1.0,
            -sa,
            ca,
            0.0,
            ca / sb,
            sa / sb,
            0.0,
        ),
    })
}

/// `J_A = diag(I, T(φ)⁻¹) J` from a geometric Jacobian and the current Euler angles.
pub fn analytical_jacobian<const N: usize>(
    geometric: &SMatrix<f64, 6, N>,
    phi: &Vector3<f64>,
    convention: EulerConvention,
    tolerance: f64,
) -> Result<SMatrix<f64, 6, N>, RepresentationSingularity> {
    let tinv = euler_rate_matrix_inverse(phi, convention, tolerance)?;
    let mut ja = *geometric;
    let w = tinv * geometric.fixed_rows::<3>(3);
    ja.fixed_rows_mut::<3>(3).copy_from(&w);
    Ok(ja)
}

/// The analytical Jacobian of a robot at `q`, with the Euler angles of its tool pose.
///
/// ```
/// use kinegen::analytic::{analytical_jacobian_at, EulerConvention};
/// # use kinegen::Kinematics;
/// # struct Rz; // one revolute joint about z, tool 1 m out along x
/// # impl Kinematics<1> for Rz {
/// #   const NAME: &'static str = "rz";
/// #   fn fk(&self, q: &[f64; 1]) -> [[f64; 4]; 4] { let (s, c) = (q[0].sin(), q[0].cos());
/// #     [[c, -s, 0., c], [s, c, 0., s], [0., 0., 1., 0.], [0., 0., 0., 1.]] }
/// #   fn frames(&self, q: &[f64; 1]) -> [[[f64; 4]; 4]; 1] { [self.fk(q)] }
/// #   fn jacobian(&self, q: &[f64; 1]) -> [[f64; 1]; 6] { [[-q[0].sin()], [q[0].cos()], [0.], [0.], [0.], [1.]] }
/// #   fn jacobian_ee(&self, q: &[f64; 1]) -> [[f64; 1]; 6] { [[0.], [1.], [0.], [0.], [0.], [1.]] }
/// #   fn limits(&self) -> [[f64; 2]; 1] { [[-3.0, 3.0]] }
/// # }
/// // Yaw rate equals the joint rate for a rotation about z.
/// let ja = analytical_jacobian_at(&Rz, &[0.3], EulerConvention::Zyx, 1e-9).unwrap();
/// assert!((ja[(3, 0)] - 1.0).abs() < 1e-12);
/// ```
pub fn analytical_jacobian_at<R: Kinematics<N>, const N: usize>(
    robot: &R,
    q: &[f64; N],
    convention: EulerConvention,
    tolerance: f64,
) -> Result<SMatrix<f64, 6, N>, RepresentationSingularity> {
    let (t, j) = robot.fk_and_jacobian(q);
    let phi = euler_angles(&rotation_of(&t), convention);
    analytical_jacobian(&matrix_from_rows(&j), &phi, convention, tolerance)
}
