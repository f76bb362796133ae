//! kinegen's engine: the DH model, an exact polynomial core, symbolic forward
//! kinematics and Jacobians as straight-line code, and Rust emission.
//!
//! The `kinematics!` macro and the `kinegen` CLI are thin callers of [`generate()`].

pub mod dh;
mod emit;
pub mod generate;
pub mod value;

pub use dh::{validate, Robot};
pub use generate::{generate, Budget, Generated, ItemHeader, Options};
