//! Front ends that read text: each turns a file into a checked robot description,
//! with errors that name the line. (The `kinematics!` macro is the other front end:
//! it reads tokens, in the `kinegen-macro` crate, with errors at spans.)
//!
//! - [`toml_file`]: a DH table in TOML (`robots/*.toml`), or a TOML file that names a
//!   URDF and the options for it.
//! - [`urdf`]: a URDF file: its links and joints, the tree, the path from a base link
//!   to a tip link.
//! - [`urdf_robot`]: a URDF with a description's options (base, tip, snap, named
//!   lengths) as the engine's chain.
//! - [`located`]: the errors both report, `file:line: message`.

pub mod located;
pub mod toml_file;
pub mod urdf;
pub mod urdf_robot;
