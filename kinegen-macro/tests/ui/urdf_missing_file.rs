kinegen::kinematics! {
    pub struct Bad = urdf("tests/ui/data/does_not_exist.urdf", tip = "tool0");
}

fn main() {}
