kinegen::kinematics! {
    pub struct Bad;
    convention: standard,
    joints: [
        revolute { a: 0, alhpa: pi/2, d: 0 },
    ],
}

fn main() {}
