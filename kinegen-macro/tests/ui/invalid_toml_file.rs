kinegen::kinematics! {
    pub struct Bad = "tests/ui/data/invalid.toml";
}

fn main() {}
