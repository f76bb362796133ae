kinegen::kinematics! {
    pub struct Bad;
    convention: standard,
    joints: [],
}

fn main() {}
