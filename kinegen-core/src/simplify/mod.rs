//! Simplification: the symbolic outputs rewritten to fewer operations, every rewrite
//! checked equal before it is used.
//!
//! - [`order`]: the evaluation order (middle frame) with the fewest operations.
//! - [`pass`]: one model through [`polish`] (e-graph, `egg`) and [`signs`] (fewest
//!   negations), in that order.
//! - [`check`]: the equality test each rewrite must pass.

pub mod check;
pub mod order;
pub mod pass;
pub mod polish;
pub mod signs;
