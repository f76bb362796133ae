kinegen::kinematics! {
    pub struct Bad;
    convention: standard,
    joints: [
        revolute { a: 0, alpha: pi/, d: 0 },
    ],
}

fn main() {}
