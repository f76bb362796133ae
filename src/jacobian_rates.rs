//! Second-order kinematics from the Jacobian's columns at run time: the kinematic Hessian,
//! `J̇`, `J̇ q̇` and the derivative of the tool-frame Jacobian.
//!
//! The generated code derives these symbolically for ordinary arms. For long chains —
//! where the Hessian's `6·N²` closed forms would be most of the generated code, or where
//! the engine's time budget ran out first — its methods call these functions on its own
//! `jacobian` / `jacobian_ee` instead (the doc of the generated method says which). The
//! formulas are the ones the engine derives with (Haviland & Corke, "Manipulator
//! Differential Kinematics", arXiv 2207.01794): column `i` of the world-frame Jacobian is
//! `[v_i; ω_i]` (`ω_i = 0` for a prismatic joint), and
//!
//! ```text
//! ∂J_i/∂q_j = [ω_j × v_i; ω_j × ω_i]   (j ≤ i)
//! ∂J_i/∂q_j = [ω_i × v_j; 0]           (j > i)
//! ```
//!
//! No allocation, `no_std`; generic over the scalar so that f32 robots use them too.
//! `hessian` is `O(N²)`, the others `O(N)`.
//!
//! ```
//! use kinegen::jacobian_rates::{hessian, jacobian_dot, jdot_qdot};
//! use kinegen::{Kinematics, SecondOrderKinematics};
//! kinegen::kinematics! {
//!     struct Arm;
//!     convention: standard,
//!     params: { L1: 1.0, L2: 0.8 },
//!     joints: [
//!         revolute { a: L1, alpha: 0, d: 0 },
//!         revolute { a: L2, alpha: 0, d: 0 },
//!     ],
//! }
//! let (arm, q, qd) = (Arm::default(), [0.3, 1.2], [0.5, -0.4]);
//! let j = arm.jacobian(&q);
//! // The same values as the closed forms the macro derived.
//! let (h, symbolic) = (hessian(&j), SecondOrderKinematics::hessian(&arm, &q));
//! for k in 0..2 {
//!     for r in 0..6 {
//!         for i in 0..2 {
//!             assert!((h[k][r][i] - symbolic[k][r][i]).abs() < 1e-12);
//!         }
//!     }
//! }
//! let jdq = jdot_qdot(&j, &qd);
//! let expected = arm.jdot_qdot(&q, &qd);
//! assert!((0..6).all(|r| (jdq[r] - expected[r]).abs() < 1e-12));
//! assert_eq!(jacobian_dot(&j, &qd)[5], [0.0, 0.0]); // a planar arm's ω does not turn
//! ```

use core::ops::{Add, Mul, Sub};

/// What the functions compute with: `f64` and `f32`.
pub trait Scalar:
    Copy + Default + Add<Output = Self> + Sub<Output = Self> + Mul<Output = Self>
{
}
impl Scalar for f64 {}
impl Scalar for f32 {}

type V3<T> = [T; 3];

fn cross<T: Scalar>(a: V3<T>, b: V3<T>) -> V3<T> {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn plus<T: Scalar>(a: V3<T>, b: V3<T>) -> V3<T> {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

fn scaled<T: Scalar>(a: V3<T>, s: T) -> V3<T> {
    [a[0] * s, a[1] * s, a[2] * s]
}

/// Column `i` of a row-major 6×N Jacobian as `(v_i, ω_i)`.
fn column<T: Scalar, const N: usize>(j: &[[T; N]; 6], i: usize) -> (V3<T>, V3<T>) {
    ([j[0][i], j[1][i], j[2][i]], [j[3][i], j[4][i], j[5][i]])
}

/// Writes `(lin, ang)` into column `i` of a row-major 6×N matrix.
fn set_column<T: Scalar, const N: usize>(m: &mut [[T; N]; 6], i: usize, lin: V3<T>, ang: V3<T>) {
    for r in 0..3 {
        m[r][i] = lin[r];
        m[r + 3][i] = ang[r];
    }
}

/// The kinematic Hessian `H[j] = ∂J/∂q_j` of a world-frame geometric Jacobian `j`
/// (rows `[vx vy vz ωx ωy ωz]`), indexed `H[j][row][column]` like the generated
/// `hessian` and the Robotics Toolbox's `hessian0`.
pub fn hessian<T: Scalar, const N: usize>(j: &[[T; N]; 6]) -> [[[T; N]; 6]; N] {
    let mut h = [[[T::default(); N]; 6]; N];
    for i in 0..N {
        let (v_i, w_i) = column(j, i);
        for k in 0..=i {
            let (_, w_k) = column(j, k);
            let lin = cross(w_k, v_i);
            set_column(&mut h[k], i, lin, cross(w_k, w_i));
            // ∂J_k/∂q_i for i > k: the same linear part, no angular part.
            if k < i {
                set_column(&mut h[i], k, lin, [T::default(); 3]);
            }
        }
    }
    h
}

/// `J̇ = Σ_j H[j]·q̇_j` along the joint rates `qd`: column i is
/// `[W_i × v_i + ω_i × R_i; W_i × ω_i]` with `W_i = Σ_(k≤i) ω_k·q̇_k` and
/// `R_i = Σ_(k>i) v_k·q̇_k`.
pub fn jacobian_dot<T: Scalar, const N: usize>(j: &[[T; N]; 6], qd: &[T; N]) -> [[T; N]; 6] {
    let mut out = [[T::default(); N]; 6];
    let after = tails(j, qd);
    let mut w_sum = [T::default(); 3];
    for i in 0..N {
        let (v, w) = column(j, i);
        w_sum = plus(w_sum, scaled(w, qd[i]));
        let lin = plus(cross(w_sum, v), cross(w, after[i].0));
        set_column(&mut out, i, lin, cross(w_sum, w));
    }
    out
}

/// The bias acceleration `J̇ q̇` in the world frame, `[ax ay az αx αy αz]`.
pub fn jdot_qdot<T: Scalar, const N: usize>(j: &[[T; N]; 6], qd: &[T; N]) -> [T; 6] {
    let jd = jacobian_dot(j, qd);
    let mut out = [T::default(); 6];
    for (o, row) in out.iter_mut().zip(&jd) {
        *o = row
            .iter()
            .zip(qd)
            .fold(T::default(), |s, (&a, &b)| s + a * b);
    }
    out
}

/// `d/dt` of the tool-frame Jacobian `ee` (the generated `jacobian_ee`) along `qd`:
/// column i is `[ω_i × R_i + v_i × Ω_i⁺; ω_i × Ω_i⁺]` in tool-frame vectors, with
/// `R_i = Σ_(k>i) v_k·q̇_k` and `Ω_i⁺ = Σ_(k>i) ω_k·q̇_k` — the tool frame's own rotation
/// included, as the generated `jacobian_ee_dot` does.
pub fn jacobian_ee_dot<T: Scalar, const N: usize>(ee: &[[T; N]; 6], qd: &[T; N]) -> [[T; N]; 6] {
    let mut out = [[T::default(); N]; 6];
    let after = tails(ee, qd);
    for (i, &(r, omega)) in after.iter().enumerate() {
        let (v, w) = column(ee, i);
        let lin = plus(cross(w, r), cross(v, omega));
        set_column(&mut out, i, lin, cross(w, omega));
    }
    out
}

/// For each column i: `(Σ_(k>i) v_k·q̇_k, Σ_(k>i) ω_k·q̇_k)`.
fn tails<T: Scalar, const N: usize>(j: &[[T; N]; 6], qd: &[T; N]) -> [(V3<T>, V3<T>); N] {
    let zero = [T::default(); 3];
    let mut out = [(zero, zero); N];
    let mut acc = (zero, zero);
    for i in (0..N).rev() {
        out[i] = acc;
        let (v, w) = column(j, i);
        acc = (plus(acc.0, scaled(v, qd[i])), plus(acc.1, scaled(w, qd[i])));
    }
    out
}
