//! The symbolic outputs of a chain, as straight-line code in one graph.
//!
//! - [`entries`]: lengths and angles as nodes (exact twists fold here).
//! - [`transform`]: rigid transforms and vectors of nodes.
//! - [`frames`]: the chain unrolled into link frames, tool and joint axes.
//! - [`jacobian`]: geometric Jacobian columns `z × (p − o)`, world and tool frame.
//! - [`model`]: all outputs of one evaluation order, together.
//! - [`program`]: chosen nodes as a register program, for tools evaluating many configurations.
//! - [`det`]: the Jacobian determinant in factored closed form, its gradient.
//! - [`hessian`]: `H[j] = ∂J/∂q_j` from the Jacobian's columns.
//! - [`jdot`]: `J̇`, `J̇ q̇` and the tool-frame `J̇_ee`, accumulated over the joints.
//! - [`second_order`]: the second-order outputs of a model, together.
//! - [`ik`]: closed-form inverse kinematics: family, derivation, zero-configuration geometry.

pub mod det;
pub mod entries;
pub mod frames;
pub mod hessian;
pub mod ik;
pub mod jacobian;
pub mod jdot;
pub mod model;
pub mod program;
pub mod second_order;
pub mod transform;
