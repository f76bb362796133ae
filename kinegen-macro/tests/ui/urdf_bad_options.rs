kinegen::kinematics! {
    pub struct Bad = urdf("tests/ui/data/arm.urdf", tip = "tool");
    snap: -1e-4,
    params: { L1: "shoulder.origin.z", L2: "elbow.origin.x", s1: "flange.origin.x" },
    convention: standard,
}

fn main() {}
