//! # kinegen
//!
//! Closed-form robot kinematics generated at compile time from a Denavit–Hartenberg
//! table: forward kinematics, the geometric Jacobian and its determinant, the kinematic
//! Hessian, `J̇ q̇` and the gradients of det J and of the manipulability as
//! allocation-free, `no_std` Rust, plus a runtime that does what the textbooks do with
//! them.
//!
//! ```
//! kinegen::kinematics! {
//!     /// A planar RR arm.
//!     pub struct PlanarRr;
//!     convention: standard,
//!     params: { L1: 1.0, L2: 0.8 },
//!     joints: [
//!         revolute { a: L1, alpha: 0, d: 0 },
//!         revolute { a: L2, alpha: 0, d: 0, limits: [-pi, pi] },
//!     ],
//!     task: [x, y],
//! }
//!
//! let arm = PlanarRr::default(); // the named parameters are public fields
//! let q = [0.3, 0.5];
//! let t = arm.fk(&q); // [[f64; 4]; 4], the tool pose
//! assert!((t[0][3] - (0.3f64.cos() + 0.8 * 0.8f64.cos())).abs() < 1e-12);
//! let j = arm.jacobian(&q); // [[f64; 2]; 6], rows [vx vy vz ωx ωy ωz]
//! assert_eq!(j[5], [1.0, 1.0]);
//! // The task rows [x, y] are square, so their determinant has a closed form:
//! assert_eq!(PlanarRr::DET, "L1*L2*sin(q2)");
//! assert!((arm.jacobian_det(&q) - 0.8 * 0.5f64.sin()).abs() < 1e-12);
//! // Calibrated values are just other field values; the code is the same.
//! let longer = PlanarRr { L1: 1.2, ..arm };
//! assert!((longer.jacobian_det(&q) - 1.2 * 0.8 * 0.5f64.sin()).abs() < 1e-12);
//! ```
//!
//! A table can also come from a TOML file, relative to the crate's manifest
//! (`kinegen::kinematics! { pub struct Ur5 = "robots/ur5.toml"; }`); the
//! [`kinegen-robots`](https://docs.rs/kinegen-robots) crate holds 16 real robots made
//! that way. Every generated function's rustdoc shows its closed form. The runtime
//! modules work on any [`Kinematics`] robot: [`velocity`] (inverse velocity,
//! pseudo-inverses, damped least squares), [`forces`], [`manipulability`], [`ik`],
//! [`control`], [`trajectory`], and on the generated second order
//! ([`SecondOrderKinematics`]) [`acceleration`] (resolved-acceleration control) and
//! [`redundancy`] (gradient projection); [`math`] and [`jacobian_rates`] (the second
//! order of chains too long for closed forms) are what the generated code calls.
//!
//! ## Optional features
//!
//! - `std` (default): the platform's `sqrt`/`atan2`/`acos`; without it the `libm` crate
//!   (generated code gives the same bits either way).
//! - `serde`: `Serialize`/`Deserialize` for IK solutions ([`ik::IkSolutions`],
//!   [`ik::IkBranch`], [`ik::IkSolution`]), trajectories ([`trajectory::Trapezoid`],
//!   [`trajectory::Cubic`], [`trajectory::Quintic`], [`trajectory::Synchronized`],
//!   [`trajectory::StopAtVias`], [`trajectory::ThroughVias`],
//!   [`trajectory::CartesianLine`], stored as the inputs that define them and read back
//!   through their constructors' checks), poses (nalgebra's types, through its own
//!   feature) and [`SolveError`]; `Serialize` for the errors that hold `&'static str`
//!   ([`ik::IkError`], [`trajectory::TrajectoryError`]).
//! - `defmt`: `defmt::Format` for what firmware logs: IK solutions (and the
//!   subproblems' [`ik::subproblems::Fit`]), the errors.
//! - `small-ik`: the closed-form IK without the regular poses' lanes (every pose of the
//!   UR and PUMA families solved branch by branch): the same solutions in about a third
//!   less flash on a microcontroller, slower on a PC.
//! - `mint`: `adapters::pose_to_mint` and `adapters::pose_from_mint`, and nalgebra's
//!   `mint` conversions, for glam, cgmath and other math crates.
#![no_std]
#![cfg_attr(docsrs, feature(doc_cfg))]
#![warn(missing_docs)]

#[cfg(feature = "std")]
extern crate std;

// Lets generated code say `::kinegen::…` inside this crate's own tests too.
extern crate self as kinegen;

pub use kinegen_macro::kinematics;

pub mod acceleration;
pub mod adapters;
pub mod analytic;
pub mod control;
pub mod error;
pub mod forces;
pub mod ik;
pub mod jacobian_rates;
pub mod linalg;
pub mod manipulability;
pub mod math;
pub mod pose_error;
pub mod redundancy;
pub mod velocity;

pub use error::SolveError;
pub use ik::closed_form::InverseKinematics;

/// The nalgebra the runtime's public types come from. kinegen accepts every nalgebra
/// from 0.33 to 0.35, so a crate that depends on one of them shares it with kinegen
/// (cargo picks the newest in the range; a crate on an older one runs
/// `cargo update -p nalgebra@<newest> --precise <its version>`, see the README). Naming
/// this re-export (`kinegen::nalgebra::Isometry3`) always names kinegen's. The
/// generated code's interface is plain arrays and needs none of it.
///
/// ```
/// use kinegen::nalgebra::{Isometry3, Vector3};
/// let pose: Isometry3<f64> = Isometry3::translation(0.1, 0.2, 0.3);
/// assert_eq!(pose.translation.vector, Vector3::new(0.1, 0.2, 0.3));
/// ```
pub use nalgebra;
pub mod trajectory;

/// A robot arm with `N` joints whose kinematics kinegen generated.
///
/// Conventions: `q` holds joint values (radians for revolute, metres for prismatic
/// joints); transforms are row-major 4×4 homogeneous matrices; Jacobians are row-major
/// with rows `[vx, vy, vz, ωx, ωy, ωz]`: the linear velocity of the tool point and the
/// angular velocity of the tool frame.
pub trait Kinematics<const N: usize> {
    /// The robot's display name.
    const NAME: &'static str;

    /// Tool pose in the world frame: `base · A1(q1) ⋯ AN(qN) · tool`.
    fn fk(&self, q: &[f64; N]) -> [[f64; 4]; 4];

    /// Frame of every joint's link in the world frame (`base · A1 ⋯ Ai`, without the tool).
    fn frames(&self, q: &[f64; N]) -> [[[f64; 4]; 4]; N];

    /// Geometric Jacobian in the world frame.
    fn jacobian(&self, q: &[f64; N]) -> [[f64; N]; 6];

    /// Geometric Jacobian expressed in the tool frame (same tool point).
    fn jacobian_ee(&self, q: &[f64; N]) -> [[f64; N]; 6];

    /// Tool pose and world-frame Jacobian together, sharing their common work.
    fn fk_and_jacobian(&self, q: &[f64; N]) -> ([[f64; 4]; 4], [[f64; N]; 6]) {
        (self.fk(q), self.jacobian(q))
    }

    /// Joint limits `[min, max]`; `[-inf, inf]` where the table gives none.
    fn limits(&self) -> [[f64; 2]; N];

    /// Determinant of the 6×6 Jacobian (`None` unless N = 6).
    fn jacobian_det(&self, _q: &[f64; N]) -> Option<f64> {
        None
    }
}

/// Second-order kinematics of a robot whose kinematics kinegen generated, in closed form:
/// the kinematic Hessian, the time derivative of the Jacobian and the bias acceleration
/// `J̇ q̇`, and the gradients a controller climbs away from singularities. Every method is
/// generated (there are no defaults); rows and frames as in [`Kinematics`].
pub trait SecondOrderKinematics<const N: usize>: Kinematics<N> {
    /// `H[j] = ∂J/∂q_j` of the world-frame Jacobian for every joint `j`, indexed
    /// `H[j][row][column]` (the Robotics Toolbox's `hessian0` layout).
    fn hessian(&self, q: &[f64; N]) -> [[[f64; N]; 6]; N];

    /// `J̇ = Σ_j H[j] q̇_j`, world frame, along the joint rates `qd`.
    fn jacobian_dot(&self, q: &[f64; N], qd: &[f64; N]) -> [[f64; N]; 6];

    /// The bias acceleration `J̇ q̇` (world frame): the tool point's linear and the tool
    /// frame's angular acceleration when `q̈ = 0`, so that `ẍ = J q̈ + J̇ q̇`.
    fn jdot_qdot(&self, q: &[f64; N], qd: &[f64; N]) -> [f64; 6];

    /// `d/dt` of [`Kinematics::jacobian_ee`] (not `Rᵀ J̇`, which leaves out the rotation of
    /// the tool frame itself).
    fn jacobian_ee_dot(&self, q: &[f64; N], qd: &[f64; N]) -> [[f64; N]; 6];

    /// The gradient of Yoshikawa's manipulability of the world-frame Jacobian
    /// ([`manipulability::manipulability_gradient`]; 0 at a singular configuration).
    fn manipulability_gradient(&self, q: &[f64; N]) -> [f64; N];

    /// The gradient of [`Kinematics::jacobian_det`], by exact differentiation of its
    /// factored closed form (`None` where that is `None`, and where det J has no closed
    /// form and is computed by LU).
    fn det_gradient(&self, q: &[f64; N]) -> Option<[f64; N]>;
}

/// A robot with a reduced (task) Jacobian of `M` rows, e.g. `[x, y, rz]` for a planar arm.
pub trait TaskKinematics<const N: usize, const M: usize>: Kinematics<N> {
    /// Which rows of the full Jacobian, as indices into `[vx, vy, vz, ωx, ωy, ωz]`.
    const TASK_ROWS: [usize; M];

    /// The task Jacobian: the rows `TASK_ROWS` of [`Kinematics::jacobian`].
    fn task_jacobian(&self, q: &[f64; N]) -> [[f64; N]; M];

    /// Determinant of the task Jacobian (`None` unless M = N).
    fn task_jacobian_det(&self, _q: &[f64; N]) -> Option<f64> {
        None
    }
}

/// A closed form the generated code computes, for people: `J[0][1]`, `det`, …
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Formula {
    /// The generated function it belongs to (`"fk"`, `"jacobian"`, `"task_jacobian"`,
    /// `"jacobian_det"`, `"singular_factors"`, `"hessian"`, `"jacobian_dot"`,
    /// `"jdot_qdot"`, `"jacobian_ee_dot"`, `"det_gradient"`,
    /// `"singular_factor_gradients"`); intermediate names are per function.
    pub function: &'static str,
    /// What it is (`"T[0][3]"`, `"J[2][1]"`, `"det"`, `"H[1][0][2]"`, `"Jdot_qdot[4]"`,
    /// `"ddet[2]"`, `"df[0][1]"`, `"t4"` for a shared intermediate).
    pub name: &'static str,
    /// Plain text, Rust syntax (`a2 * c2 + a3 * c23`).
    pub text: &'static str,
    /// LaTeX (`a_{2} c_{2} + a_{3} c_{23}`).
    pub latex: &'static str,
}

/// A singular configuration family: a factor of `det J` and the condition that it vanishes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Singularity {
    /// `"sin(q3) = 0"`.
    pub condition: &'static str,
    /// LaTeX of the condition.
    pub latex: &'static str,
    /// Joints (1-based) the factor depends on; empty for a parameter (a design singularity).
    pub joints: &'static [usize],
}
