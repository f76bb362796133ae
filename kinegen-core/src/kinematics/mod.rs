//! The symbolic outputs of a chain, as straight-line code in one graph.
//!
//! - [`entries`]: lengths and angles as nodes (exact twists fold here).
//! - [`transform`]: rigid transforms and vectors of nodes.
//! - [`frames`]: the chain unrolled into link frames, tool and joint axes.
//! - [`jacobian`]: geometric Jacobian columns `z × (p − o)`, world and tool frame.
//! - [`model`]: all outputs of one evaluation order, together.
//! - [`det`]: the Jacobian determinant in factored closed form.
//! - [`ik`]: closed-form inverse kinematics: family, derivation, zero-configuration geometry.

pub mod det;
pub mod entries;
pub mod frames;
pub mod ik;
pub mod jacobian;
pub mod model;
pub mod transform;
