kinegen::kinematics! {
    pub struct Bad;
    convention: standard,
    joints: [
        revolute { a: 1, alpha: 0, d: 0 },
    ],
    tool: { xyz: [0, 0, 0.1], rot: [0, 0, 0] },
}

fn main() {}
