//! Exact arithmetic and straight-line code.
//!
//! - [`poly`]: sparse polynomials over ℚ in `s_i`, `c_i`, prismatic `q_i`, parameters
//!   and `√2`, `√3`, reduced by `s_i² = 1 − c_i²` after every product: a unique normal
//!   form, so zero tests and equality are exact.
//! - [`angles`]: the ring's sine/cosine variables and where each comes from.
//! - [`graph`]: straight-line code as a hash-consed DAG whose nodes carry their normal
//!   form — equal (or opposite) values are one node.
//! - [`trig`]: normal forms read back as sines and cosines of angle sums.
//! - [`rational`]: products and sums of rationals through machine integers when they fit.
//! - [`fast_hash`]: cheap, deterministic hashing for the graph's tables.

pub mod angles;
pub mod fast_hash;
pub mod graph;
pub mod poly;
pub mod rational;
pub mod trig;
