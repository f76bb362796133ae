//! What the firmware and the host check share: the UR5 in single precision and the
//! joint configurations the firmware evaluates (the UR5's, and the Kinova Jaco's for the
//! general 6R `ik`).
//!
//! The f64 UR5 is `kinegen_robots::Ur5`; its f32 twin is generated here from the same
//! TOML file with `scalar: f32` (the macro's file form, path relative to this crate).
#![no_std]
// Parameter names follow the DH table (`a2`, `d4`).
#![allow(non_snake_case)]

kinegen::kinematics! {
    /// Universal Robots UR5 in single precision (`robots/ur5.toml`, `scalar: f32`).
    pub struct Ur5F32 = "../../robots/ur5.toml";
    scalar: f32,
}

/// Joint configurations (rad) the firmware evaluates, in this order.
pub const CONFIGS: [[f64; 6]; 5] = [
    // UR's zero: the arm stretched out along the base x axis (q3 = 0: elbow singularity).
    [0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    // The robots crate's doc example.
    [0.1, -1.2, 1.4, -0.3, 1.1, 0.2],
    // Near the wrist singularity (q5 ≈ 0).
    [-0.7, -2.1, 2.3, 0.4, 1e-3, -1.9],
    // Large angles, near the ±2π limits.
    [6.0, -5.5, 3.0, 2.5, -4.0, 6.2],
    // Arbitrary.
    [2.5, 0.577, -1.414, 3.1, -2.236, -0.31],
];

/// Joint configurations (rad) of the Kinova Jaco (no joint limits) whose poses the
/// firmware solves with the general 6R `ik` (Raghavan–Roth's elimination, a 24 × 24
/// eigenproblem deflated to 16 × 16): regular configurations, the generating one among the solutions.
pub const JACO_CONFIGS: [[f64; 6]; 3] = [
    // Arbitrary; the check asks for the generating configuration among the solutions.
    [0.3, 2.9, 1.2, -0.8, 1.9, 0.4],
    [-1.1, 3.6, 0.7, 2.2, -1.3, -2.5],
    [2.4, 2.2, 2.0, 0.1, 0.9, 1.7],
];

/// First line the firmware prints: tells the check it reads this format.
pub const HEADER: &str = "kinegen-firmware v4";
/// Last line the firmware prints when every configuration was reported.
pub const TRAILER: &str = "end";

/// `q` as the f32 code gets it.
#[must_use]
pub fn to_f32(q: &[f64; 6]) -> [f32; 6] {
    q.map(|x| x as f32)
}
