//! kinegen's engine: a robot description in, closed-form kinematics code out.
//!
//! The modules are the pipeline's stages, in order (see `docs/ARCHITECTURE.md`):
//!
//! - [`model`]: what the engine is told — exact values, DH tables, validation, budget.
//! - [`front`]: text front ends (TOML) with line-numbered errors.
//! - [`chain`]: the engine's only input, a chain of elementary transforms; [`chain::dh`]
//!   builds it from a DH table.
//! - [`algebra`]: exact polynomials, straight-line code with normal forms, trigonometry.
//! - [`kinematics`]: frames, Jacobians and determinants as straight-line code.
//! - [`simplify`]: evaluation order, e-graph polish, sign moves — each rewrite checked.
//! - [`emit`]: Rust, rustdoc, `FORMULAS`, LaTeX — printing only.
//! - [`numeric`]: an independent numeric reference for the tests.
//! - [`words`]: several names in one sentence, for messages and notes.
//!
//! [`generate()`] runs them; the `kinematics!` macro and the `kinegen` CLI are thin
//! callers of it.

pub mod algebra;
pub mod chain;
pub mod emit;
pub mod front;
pub mod generate;
pub mod kinematics;
pub mod model;
pub mod numeric;
pub mod simplify;
pub mod words;

pub use chain::Chain;
pub use emit::functions::Stats;
pub use emit::rust::ItemHeader;
pub use generate::{derive, generate, generate_from, Derived, Generated, StageTimes};
pub use model::dh::Robot;
pub use model::options::{Budget, Deadline, Options};
