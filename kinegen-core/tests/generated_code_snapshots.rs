//! The generated code of each reference robot, pinned: a change to the engine shows up
//! here as a reviewable diff of the Rust users get.

use kinegen_core::{front::toml_file, generate, ItemHeader};

fn generated(file: &str) -> String {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../robots")
        .join(file);
    let (robot, options) = toml_file::load_file(&path).unwrap();
    let g = generate(&robot.chain(), &ItemHeader::public(&robot.name), &options);
    g.pretty()
}

macro_rules! snapshot {
    ($($test:ident => $file:literal),* $(,)?) => {$(
        #[test]
        fn $test() {
            insta::assert_snapshot!(generated($file));
        }
    )*};
}

snapshot! {
    planar_rr => "planar_rr.toml",
    planar_rrr => "planar_rrr.toml",
    scara => "scara.toml",
    stanford => "stanford.toml",
    ur5 => "ur5.toml",
    puma560 => "puma560.toml",
    panda => "panda.toml",
}

/// The UR5 in single precision (`scalar = "f32"`): f32 kinematics, and the closed-form
/// IK with f32 poses and joint values, solved in f64.
#[test]
fn ur5_f32() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../robots/ur5.toml");
    let (mut robot, options) = toml_file::load_file(&path).unwrap();
    robot.scalar = kinegen_core::model::robot::Scalar::F32;
    let g = generate(&robot.chain(), &ItemHeader::public("Ur5F32"), &options);
    insta::assert_snapshot!(g.pretty());
}

#[test]
fn generation_is_deterministic() {
    for file in ["ur5.toml", "panda.toml", "stanford.toml"] {
        assert_eq!(generated(file), generated(file), "{file}");
    }
}
