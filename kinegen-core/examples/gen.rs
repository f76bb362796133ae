//! Print the code kinegen generates for a TOML robot: `cargo run -p kinegen-core --example gen -- robots/ur5.toml`.
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
    println!("{}", g.pretty());
    eprintln!(
        "engine: {:.1} ms; {:?}; notes: {:?}",
        dt.as_secs_f64() * 1e3,
        g.stats,
        g.notes
    );
}
