kinegen::kinematics! {
    pub struct Bad = urdf("tests/ui/data/arm.urdf", base = "base", tip = "tool0");
}

fn main() {}
