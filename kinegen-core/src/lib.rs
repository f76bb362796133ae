//! kinegen's engine: the DH model, an exact polynomial core, symbolic forward
//! kinematics and Jacobians as straight-line code, and Rust emission.
//!
//! The `kinematics!` macro and the `kinegen` CLI are thin callers of [`generate()`].

pub mod chain;
pub mod code;
pub mod det;
pub mod dh;
pub mod emit;
pub mod generate;
pub mod graph;
pub mod input;
pub mod jacobian;
pub mod latex;
pub mod model;
pub mod numeric;
pub mod polish;
pub mod poly;
pub mod signs;
pub mod toml_input;
pub mod trig;
pub mod value;

pub use dh::{validate, Robot};
pub use generate::{generate, Budget, Generated, ItemHeader, Options};
