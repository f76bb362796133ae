//! Front ends that read text: each turns a file into a checked robot description,
//! with errors that name the line. (The `kinematics!` macro is the other front end:
//! it reads tokens, in the `kinegen-macro` crate, with errors at spans.)
//!
//! - [`toml_file`]: a DH table in TOML (`robots/*.toml`).

pub mod toml_file;
