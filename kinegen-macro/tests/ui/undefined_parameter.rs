kinegen::kinematics! {
    pub struct Bad;
    convention: standard,
    params: { d1: 0.089159 },
    joints: [
        revolute { a: 0, alpha: pi/2, d: d1 },
        revolute { a: a2, alpha: 0, d: 0 },
    ],
}

fn main() {}
