//! Print the code kinegen generates for a TOML robot: `cargo run -p kinegen-core --example gen -- robots/ur5.toml`.
//! On stderr: the engine's time, and the IK stage's alone. As a proc-macro runs it in a
//! user's debug build: `CARGO_PROFILE_DEV_PACKAGE_KINEGEN_CORE_OPT_LEVEL=0` (and the same for
//! `NUM_BIGINT`, `NUM_RATIONAL`, `NUM_INTEGER`), this workspace optimises them.
fn main() {
    let path = std::env::args().nth(1).expect("usage: gen FILE.toml");
    let (robot, options) =
        match kinegen_core::front::toml_file::load_file(std::path::Path::new(&path)) {
            Ok(x) => x,
            Err(e) => {
                eprintln!("{e}");
                std::process::exit(2);
            }
        };
    let t = std::time::Instant::now();
    let g = kinegen_core::generate(
        &robot.chain(),
        &kinegen_core::ItemHeader::public(&robot.name),
        &options,
    );
    let dt = t.elapsed();
    // The IK stage on its own (generate ran it too): what closed-form IK adds.
    let t = std::time::Instant::now();
    let ik = kinegen_core::kinematics::ik::model(
        &robot.chain(),
        options.budget.max_terms(),
        options.ik_free,
    );
    let dt_ik = t.elapsed();
    println!("{}", g.pretty());
    eprintln!(
        "engine: {:.1} ms (of which the IK stage {:.1} ms: {}); {:?}; notes: {:?}",
        dt.as_secs_f64() * 1e3,
        dt_ik.as_secs_f64() * 1e3,
        match &ik {
            Ok(m) => m.plan.name.as_str(),
            Err(_) => "no family",
        },
        g.stats,
        g.notes
    );
}
