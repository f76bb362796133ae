//! A robot's closed-form IK geometry (joint axes `h`, a point `p` on each, the tool pose at
//! q = 0, product-of-exponentials form) and seeded poses as JSON, for cross-checks with
//! tools that read that form (EAIK, IK-Geo): `benches/eaik/eaik_bench.py` reads it.
//!
//! `cargo run --release --example ik_geometry_json -- ur5|puma560 [COUNT]` — the poses are
//! `fk(q)` of `COUNT` (default 1 000) configurations drawn within the limits with the seed
//! of `benches/ik_closed_form.rs` (2026), so every tool solves the poses criterion times.

use kinegen::ik::geometry::Geometry;
use kinegen::ik::XorShift64;
use kinegen::Kinematics;
use kinegen_robots::{Puma560, Ur5};

fn json<R: Kinematics<6>>(robot: &R, g: &Geometry<6>, count: usize) -> String {
    let v = |x: &kinegen::ik::geometry::V3| format!("[{:e}, {:e}, {:e}]", x.x, x.y, x.z);
    let list = |xs: Vec<String>| format!("[{}]", xs.join(", "));
    let limits = robot.limits();
    let mut rng = XorShift64::new(2026);
    let poses: Vec<String> = (0..count)
        .map(|_| {
            let q = rng.configuration(&limits);
            let t = robot.fk(&q);
            let rows = t
                .iter()
                .map(|r| list(r.iter().map(|x| format!("{x:e}")).collect()));
            let q = list(q.iter().map(|x| format!("{x:e}")).collect());
            format!("{{\"q\": {q}, \"pose\": {}}}", list(rows.collect()))
        })
        .collect();
    let r = &g.r_tool;
    let r_tool = list(
        (0..3)
            .map(|i| list((0..3).map(|j| format!("{:e}", r[(i, j)])).collect()))
            .collect(),
    );
    format!(
        "{{\"h\": {}, \"p\": {}, \"r_tool\": {r_tool}, \"p_tool\": {}, \"cases\": {}}}",
        list(g.h.iter().map(v).collect()),
        list(g.p.iter().map(v).collect()),
        v(&g.p_tool),
        list(poses)
    )
}

fn main() {
    let mut args = std::env::args().skip(1);
    let name = args.next().unwrap_or_default();
    let count = match args.next().map(|c| c.parse::<usize>()) {
        None => 1000,
        Some(Ok(c)) => c,
        Some(Err(e)) => {
            eprintln!("COUNT: {e}");
            std::process::exit(2);
        }
    };
    let out = match name.as_str() {
        "ur5" => json(&Ur5::default(), &Ur5::default().ik_geometry(), count),
        "puma560" => json(
            &Puma560::default(),
            &Puma560::default().ik_geometry(),
            count,
        ),
        _ => {
            eprintln!("usage: ik_geometry_json ur5|puma560 [COUNT]");
            std::process::exit(2);
        }
    };
    println!("{out}");
}
