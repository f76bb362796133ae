//! `kinegen show --what model`: the chain as the engine reads it, the description's
//! table, and every snapped value with the error it can cause.

use std::fmt::Write;

use kinegen_core::chain::bound;
use kinegen_core::Chain;

/// The text of `show --what model`.
pub fn show(chain: &Chain) -> String {
    let mut s = format!(
        "{} — {} joints, {}\n\n",
        chain.name,
        chain.dof(),
        chain.description
    );
    s.push_str("== Chain: elementary transforms, base to tip (q_i = joint i's variable)\n");
    s.push_str(&chain.to_string());
    if !chain.params.is_empty() {
        let p: Vec<String> = chain
            .params
            .iter()
            .map(|p| format!("{} = {}", p.name, p.value))
            .collect();
        let _ = writeln!(s, "parameters: {}", p.join(", "));
    }
    s.push_str("\n== Description\n");
    for line in &chain.summary {
        let _ = writeln!(s, "{line}");
    }
    s.push_str("\n== Snapped values\n");
    if chain.snaps.is_empty() {
        s.push_str("none: the chain is the description as written\n");
        return s;
    }
    for snap in &chain.snaps {
        let _ = writeln!(s, "{snap}");
    }
    let (p, o) = chain.snap_bounds();
    let _ = writeln!(
        s,
        "together (first order): tool position within {} m and orientation within {:.1e} rad \
         of the description read literally (`--snap 0`)",
        bound(p),
        o
    );
    s
}
