kinegen::kinematics! {
    pub struct Bad = "tests/ui/data/does_not_exist.toml";
}

fn main() {}
