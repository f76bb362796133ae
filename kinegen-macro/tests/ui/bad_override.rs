kinegen::kinematics! {
    pub struct Bad = "tests/ui/data/valid.toml";
    scalar: f16,
}

fn main() {}
