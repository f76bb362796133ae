kinegen::kinematics! {
    pub struct Bad = urdf("tests/ui/data/floating.urdf");
}

fn main() {}
