//! Print a robot's closed-form Jacobian determinant: `cargo run -p kinegen-core --example det -- robots/ur5.toml`.
fn main() {
    for path in std::env::args().skip(1) {
        let (robot, options) =
            match kinegen_core::front::toml_file::load_file(std::path::Path::new(&path)) {
                Ok(x) => x,
                Err(e) => {
                    eprintln!("{e}");
                    continue;
                }
            };
        let t = std::time::Instant::now();
        let det = kinegen_core::derive(&robot.chain(), &options).det;
        let det = det.unwrap_or_else(|| Err("the Jacobian is not square".into()));
        let dt = t.elapsed();
        match det {
            Ok(d) => {
                println!(
                    "{}: det J = {}   [{:.1} ms]",
                    robot.name,
                    d.text,
                    dt.as_secs_f64() * 1e3
                );
                for f in &d.factors {
                    println!("    factor (joints {:?}): {} = 0", f.joints, f.text);
                }
            }
            Err(e) => println!("{}: {e}   [{:.1} ms]", robot.name, dt.as_secs_f64() * 1e3),
        }
    }
}
