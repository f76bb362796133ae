kinegen::kinematics! {
    pub struct Bad;
    convention: standard,
    joints: [
        revolute { a: 1, alpha: 0, d: 0 },
    ],
    base: { xyz: [0, 0.1], rpy: [0, 0, 0] },
}

fn main() {}
