kinegen::kinematics! {
    pub struct Bad = "tests/ui/data/malformed.toml";
}

fn main() {}
