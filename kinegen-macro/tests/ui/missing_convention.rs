kinegen::kinematics! {
    pub struct Bad;
    joints: [
        revolute { a: 0, alpha: 0, d: 0 },
    ],
}

fn main() {}
