//! Emission: the symbolic outputs printed, nothing built.
//!
//! - [`code`]: straight-line code as Rust statements (shared `let`s, batched
//!   `sin_cos_n`, angle-sum names) and operation counts; [`angle_names`] what those
//!   names (`c23`, `c2m3`) mean.
//! - [`functions`]: what the generated type holds — each method's body and doc, the
//!   constants — as values; [`second_order`] its second-order methods.
//! - [`item`]: a method or a constant of the generated `impl`, as a value.
//! - [`ik`]: the closed-form IK methods and constants.
//! - [`docs`], [`formulas`]: the closed forms for people (rustdoc, `FORMULAS`), printed
//!   by [`walk`] — one walk over a formula — in three styles: [`text`], [`latex`],
//!   [`mathml`] (one output form per file).
//! - [`rust`]: the item printed and parsed into tokens.

pub mod angle_names;
mod angle_sums;
pub mod code;
pub mod docs;
pub mod formulas;
pub mod functions;
pub mod ik;
pub mod item;
pub mod latex;
pub mod mathml;
pub mod rust;
pub mod second_order;
pub mod text;
pub mod walk;
