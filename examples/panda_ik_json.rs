//! The Franka Panda's IK cases as JSON, for `benches/panda_ik/panda_ik_bench.py`, which
//! compares He & Liu's analytic Panda IK (PyPI's `frankik` and `panda-python`) with
//! kinegen's `ik_with` on the very poses `benches/ik_closed_form.rs` times.
//!
//! `cargo run --release --example panda_ik_json [COUNT] > panda.json` — `COUNT` (default
//! 1 000) poses `fk(q)` of configurations drawn uniformly within `Panda::LIMITS` with the
//! bench's seed (2026, the bench's own `poses`), each with its generating `q` (row-major
//! 4×4 pose in kinegen's base and tool frames: the Franka Hand's TCP of
//! `robots/panda.toml`). Also kinegen's geometry at `q = 0` (product-of-exponentials form:
//! unit axes `h`, a point `p` on each, the tool's `r_tool`, `p_tool`), so the script can
//! evaluate kinegen's forward kinematics on any other library's answers; the script
//! checks that form against every pose here before using it. And, at `q = 0`, joint 7's
//! frame (`frames`: the flange, as the table folds the flange's 0.107 m into joint 7's d)
//! and the tool pose, from which the script takes the flange → tool transform.

#[path = "../benches/common/ik.rs"]
#[allow(dead_code)]
mod ik_common;

use kinegen::ik::geometry::V3;
use kinegen_robots::Panda;

fn list(xs: impl Iterator<Item = String>) -> String {
    format!("[{}]", xs.collect::<Vec<_>>().join(", "))
}

fn num(x: &f64) -> String {
    // `{:e}` prints the shortest digits that read back to the same f64.
    format!("{x:e}")
}

fn main() {
    let count = match std::env::args().nth(1).map(|c| c.parse::<usize>()) {
        None => 1000,
        Some(Ok(c)) => c,
        Some(Err(e)) => {
            eprintln!("usage: panda_ik_json [COUNT]: {e}");
            std::process::exit(2);
        }
    };
    let panda = Panda::default();
    let g = panda.ik_geometry();
    let v = |x: &V3| list([x.x, x.y, x.z].iter().map(num));
    let m = |t: &[[f64; 4]; 4]| list(t.iter().map(|r| list(r.iter().map(num))));
    let flange0 = panda.frames(&[0.0; 7])[6];
    let tool0 = panda.fk(&[0.0; 7]);
    let cases = ik_common::poses(&panda, 2026, count)
        .into_iter()
        .map(|(t, q)| {
            format!(
                "{{\"q\": {}, \"pose\": {}}}",
                list(q.iter().map(num)),
                m(&t)
            )
        });
    println!(
        "{{\"robot\": \"panda\", \"seed\": 2026, \"limits\": {}, \"h\": {}, \"p\": {}, \
         \"r_tool\": {}, \"p_tool\": {}, \"flange_at_zero\": {}, \"tool_at_zero\": {}, \
         \"cases\": {}}}",
        list(Panda::LIMITS.iter().map(|l| list(l.iter().map(num)))),
        list(g.h.iter().map(v)),
        list(g.p.iter().map(v)),
        list((0..3).map(|i| list((0..3).map(|j| num(&g.r_tool[(i, j)]))))),
        v(&g.p_tool),
        m(&flange0),
        m(&tool0),
        list(cases)
    );
}
