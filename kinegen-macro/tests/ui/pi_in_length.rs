kinegen::kinematics! {
    pub struct Bad;
    convention: standard,
    joints: [
        revolute { a: pi/2, alpha: 0, d: 0 },
    ],
}

fn main() {}
