kinegen::kinematics! {
    pub struct Bad;
    convention: standard,
    params: { L1: "one" },
    joints: [
        revolute { a: L1, alpha: 0, d: 0 },
    ],
}

fn main() {}
