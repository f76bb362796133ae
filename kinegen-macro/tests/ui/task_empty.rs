kinegen::kinematics! {
    pub struct Bad;
    convention: standard,
    joints: [
        revolute { a: 1, alpha: 0, d: 0 },
    ],
    task: [],
}

fn main() {}
