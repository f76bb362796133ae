//! Print a robot's closed-form Jacobian determinant: `cargo run -p kinegen-core --example det -- robots/ur5.toml`.
fn main() {
    for path in std::env::args().skip(1) {
        let (robot, options) =
            match kinegen_core::toml_input::load_file(std::path::Path::new(&path)) {
                Ok(x) => x,
                Err(e) => {
                    eprintln!("{e}");
                    continue;
                }
            };
        let t = std::time::Instant::now();
        let mut model = kinegen_core::model::Model::build(&robot, &options);
        let det = model.determinant(&robot);
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
