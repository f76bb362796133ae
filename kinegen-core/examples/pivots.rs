//! Operation counts of `fk` + `jacobian` for every middle frame: `cargo run -p kinegen-core --example pivots -- robots/ur5.toml`.
fn main() {
    let path = std::env::args().nth(1).expect("usage: pivots FILE.toml");
    let (robot, options) = kinegen_core::front::toml_file::load_file(std::path::Path::new(&path))
        .unwrap_or_else(|e| {
            eprintln!("{e}");
            std::process::exit(2)
        });
    let chain = robot.chain();
    for pivot in std::iter::once(None).chain((1..robot.dof()).map(Some)) {
        let t = std::time::Instant::now();
        let deadline = kinegen_core::Deadline::start(&options.budget);
        let m = kinegen_core::simplify::order::variant(&chain, &options, pivot, deadline);
        let coder = kinegen_core::emit::code::Coder::new(&chain, &m.sym);
        let fk: Vec<_> = m.fk_rows.iter().flatten().copied().collect();
        let j: Vec<_> = m.jacobian.iter().flatten().copied().collect();
        let mut both = fk.clone();
        both.extend(&j);
        println!(
            "pivot {pivot:?}: fk {} jacobian {} fused {} ({:.1} ms, {} nodes; polish {:?})",
            coder.body(&fk).ops.total(),
            coder.body(&j).ops.total(),
            coder.body(&both).ops.total(),
            t.elapsed().as_secs_f64() * 1e3,
            m.sym.graph.len(),
            m.polish
        );
    }
}
