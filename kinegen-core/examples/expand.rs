//! What the `kinematics!` macro runs for a TOML robot (`generate`, the item lexed into
//! tokens), and nothing else — no pretty-printing — so that `/usr/bin/time -v` measures the
//! expansion's own time and peak memory: `cargo run --release -p kinegen-core --example
//! expand -- robot.toml` (a TOML that names a URDF reads it). Prints the wall time, the
//! number of tokens and the notes.
fn main() {
    let path = std::env::args().nth(1).expect("usage: expand FILE.toml");
    let (description, options) =
        match kinegen_core::front::toml_file::load_description_file(std::path::Path::new(&path)) {
            Ok(x) => x,
            Err(e) => {
                eprintln!("{e}");
                std::process::exit(2);
            }
        };
    let chain = description.chain();
    let t = std::time::Instant::now();
    let g = kinegen_core::generate(
        &chain,
        &kinegen_core::ItemHeader::public(&chain.name),
        &options,
    );
    let dt = t.elapsed();
    let tokens = g.tokens.into_iter().count();
    println!(
        "{} joints: {:.2} s, {tokens} top-level token trees; notes: {:?}",
        chain.dof(),
        dt.as_secs_f64(),
        g.notes
    );
}
