kinegen::kinematics! {
    pub struct Bad;
    convention: standard,
    joints: [
        revolute { a: 0, alpha: 0 },
    ],
}

fn main() {}
