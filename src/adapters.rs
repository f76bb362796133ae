//! Adapters from the plain arrays of [`Kinematics`] (row-major
//! `[[f64; N]; 6]` Jacobians, `[[f64; 4]; 4]` transforms) to nalgebra's fixed-size types.

use crate::{Kinematics, TaskKinematics};
use nalgebra::{Isometry3, Matrix3, Rotation3, SMatrix, Translation3, UnitQuaternion, Vector3};

/// A row-major `R × C` array as a nalgebra matrix.
pub fn matrix_from_rows<const R: usize, const C: usize>(
    rows: &[[f64; C]; R],
) -> SMatrix<f64, R, C> {
    SMatrix::from_fn(|r, c| rows[r][c])
}

/// The world-frame geometric Jacobian `J(q)` (rows `[vx vy vz ωx ωy ωz]`) as a matrix.
pub fn jacobian_matrix<R: Kinematics<N>, const N: usize>(
    robot: &R,
    q: &[f64; N],
) -> SMatrix<f64, 6, N> {
    matrix_from_rows(&robot.jacobian(q))
}

/// The tool-frame geometric Jacobian as a matrix.
pub fn jacobian_ee_matrix<R: Kinematics<N>, const N: usize>(
    robot: &R,
    q: &[f64; N],
) -> SMatrix<f64, 6, N> {
    matrix_from_rows(&robot.jacobian_ee(q))
}

/// The task Jacobian (rows [`TaskKinematics::TASK_ROWS`]) as a matrix.
pub fn task_jacobian_matrix<R: TaskKinematics<N, M>, const N: usize, const M: usize>(
    robot: &R,
    q: &[f64; N],
) -> SMatrix<f64, M, N> {
    matrix_from_rows(&robot.task_jacobian(q))
}

/// The rotation block of a homogeneous transform.
pub fn rotation_of(t: &[[f64; 4]; 4]) -> Matrix3<f64> {
    Matrix3::from_fn(|r, c| t[r][c])
}

/// The translation column of a homogeneous transform.
pub fn translation_of(t: &[[f64; 4]; 4]) -> Vector3<f64> {
    Vector3::new(t[0][3], t[1][3], t[2][3])
}

/// A homogeneous transform as an [`Isometry3`]. The rotation block is assumed orthonormal
/// (as FK produces it); it is converted to a unit quaternion, which renormalises it.
pub fn pose_isometry(t: &[[f64; 4]; 4]) -> Isometry3<f64> {
    let r = Rotation3::from_matrix_unchecked(rotation_of(t));
    Isometry3::from_parts(
        Translation3::from(translation_of(t)),
        UnitQuaternion::from_rotation_matrix(&r),
    )
}

/// An [`Isometry3`] as the row-major homogeneous transform `fk` and `ik` use.
pub fn pose_matrix(pose: &Isometry3<f64>) -> [[f64; 4]; 4] {
    let m = pose.to_homogeneous();
    core::array::from_fn(|r| core::array::from_fn(|c| m[(r, c)]))
}

/// The tool pose `fk(q)` as an [`Isometry3`].
pub fn fk_isometry<R: Kinematics<N>, const N: usize>(robot: &R, q: &[f64; N]) -> Isometry3<f64> {
    pose_isometry(&robot.fk(q))
}

/// A homogeneous transform as a [`mint`] column-major 4×4 matrix (the `mint` feature):
/// what glam (`DMat4::from`), cgmath and other math crates take. Positions and
/// rotations convert through nalgebra's own `mint` conversions
/// (`translation_of(&t).into()`, `pose_isometry(&t).rotation.into()`).
///
/// ```
/// # #[cfg(feature = "mint")] {
/// use kinegen::adapters::{pose_from_mint, pose_isometry, pose_to_mint};
/// let t = [[0.0, -1.0, 0.0, 0.1], [1.0, 0.0, 0.0, 0.2], [0.0, 0.0, 1.0, 0.3], [0.0, 0.0, 0.0, 1.0]];
/// let m = pose_to_mint(&t);
/// assert_eq!(m.w, mint::Vector4 { x: 0.1, y: 0.2, z: 0.3, w: 1.0 }); // the translation column
/// assert_eq!(pose_from_mint(m), t);
/// let q: mint::Quaternion<f64> = pose_isometry(&t).rotation.into();
/// assert!((q.s - 0.5f64.sqrt()).abs() < 1e-15 && (q.v.z - 0.5f64.sqrt()).abs() < 1e-15);
/// # }
/// ```
#[cfg(feature = "mint")]
#[cfg_attr(docsrs, doc(cfg(feature = "mint")))]
pub fn pose_to_mint(t: &[[f64; 4]; 4]) -> mint::ColumnMatrix4<f64> {
    let column = |c: usize| mint::Vector4 {
        x: t[0][c],
        y: t[1][c],
        z: t[2][c],
        w: t[3][c],
    };
    mint::ColumnMatrix4 {
        x: column(0),
        y: column(1),
        z: column(2),
        w: column(3),
    }
}

/// A [`mint`] column-major 4×4 matrix (or anything that converts into one, such as
/// glam's `DMat4`) as the row-major transform `fk` and `ik` use (the `mint` feature).
#[cfg(feature = "mint")]
#[cfg_attr(docsrs, doc(cfg(feature = "mint")))]
pub fn pose_from_mint(m: impl Into<mint::ColumnMatrix4<f64>>) -> [[f64; 4]; 4] {
    let m: mint::ColumnMatrix4<f64> = m.into();
    let columns: [[f64; 4]; 4] = [m.x.into(), m.y.into(), m.z.into(), m.w.into()];
    core::array::from_fn(|r| core::array::from_fn(|c| columns[c][r]))
}
