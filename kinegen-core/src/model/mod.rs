//! What the engine is told: a robot described by its front end, checked, and the
//! options that bound the engine.
//!
//! - [`value`]: exact entries (`pi/2`, `0.425`, `a2 + 0.1`) as rationals, multiples of
//!   π and named parameters.
//! - [`robot`]: the vocabulary every description shares (joint kinds, task rows,
//!   scalar type, parameters).
//! - [`raw`]: a description as written, each entry at a [`raw::Path`], before any check.
//! - [`validate`]: the rules, once for every front end; [`dh`]: the checked DH table.
//! - [`input`]: top-level keys and the `budget` entries, shared by the macro and TOML.
//! - [`options`]: [`options::Budget`], [`options::Deadline`], [`options::Options`].

pub mod dh;
pub mod input;
pub mod options;
pub mod raw;
pub mod robot;
pub mod validate;
pub mod value;
