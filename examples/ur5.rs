//! Prints the UR5's closed-form Jacobian and determinant as kinegen derives them, then
//! evaluates the generated code at a configuration.
//!
//! `cargo run --example ur5`

use kinegen_core::emit::code::Coder;
use kinegen_robots::Ur5;

fn main() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/robots/ur5.toml");
    let (robot, options) = match kinegen_core::front::toml_file::load_file(path.as_ref()) {
        Ok(x) => x,
        Err(e) => {
            eprintln!("{e}");
            std::process::exit(2);
        }
    };
    let start = std::time::Instant::now();
    let chain = robot.chain();
    let derived = kinegen_core::derive(&chain, &options);
    let elapsed = start.elapsed();
    let (model, det) = (&derived.model, &derived.det);

    let coder = Coder::new(&chain, &model.sym);
    let ids: Vec<_> = model.jacobian.iter().flatten().copied().collect();
    let body = coder.body(&ids);
    println!("UR5 geometric Jacobian (world frame, rows [vx vy vz wx wy wz]), s_i = sin(q_i), c_i = cos(q_i),");
    println!("c23 = cos(q2 + q3), nc23 = -cos(q2 + q3) (likewise s234, ns234):\n");
    for (name, formula) in &body.defs {
        println!("  {name} = {formula}");
    }
    for (k, e) in body.outputs.iter().enumerate() {
        println!("  J[{}][{}] = {e}", k / 6, k % 6);
    }
    println!(
        "\n  {} operations ({} add, {} mul, {} neg) after sharing, {} sin_cos\n",
        body.ops.total(),
        body.ops.add,
        body.ops.mul,
        body.ops.neg,
        body.ops.trig
    );
    match det {
        Some(Ok(d)) => {
            println!("det J = {}\n\nSingular where:", d.text);
            for f in &d.factors {
                println!("  {} = 0", f.text);
            }
        }
        Some(Err(e)) => println!("det J: {e}"),
        None => println!("det J: the Jacobian is not square"),
    }
    println!(
        "\nEngine time (this build's profile): {:.1} ms",
        elapsed.as_secs_f64() * 1e3
    );

    let ur5 = Ur5::default();
    let q = [0.1, -1.2, 1.4, -0.3, 1.1, 0.2];
    let t = ur5.fk(&q);
    println!("\nAt q = {q:?}:");
    println!(
        "  tool position = [{:.6}, {:.6}, {:.6}]",
        t[0][3], t[1][3], t[2][3]
    );
    println!("  det J = {:.9}", ur5.jacobian_det(&q));
}
