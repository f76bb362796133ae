kinegen::kinematics! {
    pub struct Bad;
    convention: standard,
    params: { L1: 1.0, L2: 0.5, L1: 2.0 },
    joints: [
        revolute { a: L1, alpha: 0, d: 0 },
    ],
}

fn main() {}
