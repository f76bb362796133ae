//! The `kinematics!` macro accepts the inline table and the file form.

kinegen::kinematics! {
    /// The planar RR arm, written inline.
    pub struct PlanarRr;
    name: "planar RR",
    convention: standard,
    params: { L1: 1.0, L2: 0.5 },
    joints: [
        revolute { a: L1, alpha: 0, d: 0, limits: [-pi, pi] },
        revolute { a: L2, alpha: 0, d: 0 },
    ],
    task: [x, y],
}

kinegen::kinematics! {
    /// The same arm, from its TOML file.
    pub struct PlanarRrFile = "tests/data/planar_rr.toml";
}

kinegen::kinematics! {
    /// The same file with entries overridden in the macro.
    struct PlanarRrF32 = "tests/data/planar_rr.toml";
    scalar: f32,
    budget: { nodes: 1000, iterations: 5, time_ms: 200 },
}

kinegen::kinematics! {
    /// Every optional entry, modified DH and a prismatic joint.
    // No closed-form IK family fits this arm: the note saying so is expected here.
    #[allow(deprecated)]
    pub(crate) struct Everything;
    convention: modified,
    params: { d1: 0.089159, a2: -0.425 },
    joints: [
        revolute  { a: 0,  alpha: 0,     d: d1, offset: -pi/2, limits: [-2*pi, 2*pi] },
        revolute  { a: 0,  alpha: pi/2,  d: 0 },
        prismatic { a: a2, alpha: -pi/2, theta: 0, limits: [0, 0.5] },
    ],
    task: [x, y, z, rz],
    base: { xyz: [0, 0, 0.1], rpy: [0, 0, pi/2] },
    tool: { xyz: [0, 0, "0.1"], rpy: [0, 0, 0] },
    scalar: f64,
}

#[test]
fn the_structs_exist() {
    let _ = PlanarRr::default();
    let _ = PlanarRrFile::default();
    let _ = PlanarRrF32::default();
    let _ = Everything::default();
}
