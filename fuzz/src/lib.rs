//! Fuzzing support for kinegen: the checks every input goes through ([`check`]) and the
//! structured DH tables of the engine target ([`table`]).

pub mod check;
pub mod table;
