kinegen::kinematics! {
    pub struct Bad;
    convention: standard,
    joints: [
        revolute { a: 1e999, alpha: 0, d: 0 },
    ],
}

fn main() {}
