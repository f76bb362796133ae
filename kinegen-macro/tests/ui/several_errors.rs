kinegen::kinematics! {
    pub struct Bad;
    convention: standard,
    params: { L1: 1.0 },
    joints: [
        revolute { a: L1, alpha: pi/2, d: L3 },
        prismatic { a: 0, alpha: 0, d: 0 },
    ],
    task: [x, y, q],
}

fn main() {}
