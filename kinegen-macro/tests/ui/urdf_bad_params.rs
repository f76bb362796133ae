kinegen::kinematics! {
    pub struct Bad = urdf("tests/ui/data/arm.urdf", tip = "tool");
    params: { L2: "elbow.origin.x", s1: "flange.origin.x", L3: "shoulder.axis.z" },
}

fn main() {}
