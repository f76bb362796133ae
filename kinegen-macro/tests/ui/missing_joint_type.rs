kinegen::kinematics! {
    pub struct Bad;
    convention: standard,
    joints: [
        { a: 0, alpha: 0, d: 0 },
    ],
}

fn main() {}
