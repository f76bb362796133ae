//! Fuzzing support for kinegen: the checks every input goes through ([`check`] for TOML
//! and the engine, [`urdf_check`] for URDF files) and the structured DH tables of the
//! engine target ([`table`]).

pub mod check;
pub mod table;
pub mod urdf_check;
