kinegen::kinematics! {
    pub struct Bad = udrf("tests/ui/data/arm.urdf");
}

fn main() {}
