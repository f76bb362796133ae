//! Inverse kinematics: closed forms for the arm families that have them, and numerical
//! solvers for every arm.
//!
//! - Closed form ([`families`], built from [`subproblems`] on a [`geometry::Geometry`]):
//!   the `kinematics!` macro classifies the robot's joint axes exactly at expansion time
//!   and, when a family fits, generates `ik`, `ik_near` and `IK_FAMILY`. Every solution,
//!   in a fixed-size [`IkSolutions`], each flagged exact or least squares, singular, and
//!   within limits ([`solutions`]). Regular poses of the UR, PUMA and h1 ∩ h2 families take
//!   [`regular`]: the branches of each level side by side in [`lanes`]. An arm that fits a
//!   family only read from the tool to the base (the Panda) is solved through
//!   [`reversed`].
//! - Numerical ([`numeric`], re-exported here): Newton–Raphson, damped least squares,
//!   Levenberg–Marquardt, Jacobian transpose, multi-start — for any robot.
//!
//! No allocation anywhere: solution sets and solver state are on the stack.

pub mod closed_form;
pub mod continuum;
#[cfg(feature = "std")]
pub mod dispatch;
pub mod double_root;
pub mod families;
pub mod geometry;
pub mod lanes;
pub mod numeric;
pub mod polish;
pub mod regular;
pub mod reversed;
pub mod setup;
pub mod solutions;
pub mod subproblems;

pub use closed_form::InverseKinematics;
pub use numeric::*;
pub use solutions::{IkBranch, IkSolutions};
