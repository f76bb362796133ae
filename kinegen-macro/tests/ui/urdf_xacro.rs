kinegen::kinematics! {
    pub struct Bad = urdf("tests/ui/data/xacro.urdf");
}

fn main() {}
