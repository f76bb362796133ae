//! `kinegen stats`: operation counts of the generated code, and the engine's wall time.

use std::fmt::Write;

use kinegen_core::emit::code::{Coder, OpCount};
use kinegen_core::kinematics::model::Model;
use kinegen_core::StageTimes;
use kinegen_core::{derive, generate_from, Chain, Derived, Generated, ItemHeader, Options};
use serde_json::{json, Value};

use crate::det_hook::{self, Determinants};

/// A chain derived and its code emitted once, timed: the derivation, the determinants
/// and the counts that `kinegen stats` prints and `kinegen report` lays out.
pub struct Measured {
    /// The engine's symbolic results.
    pub derived: Derived,
    /// det J (or the task det) and its factors, or why none.
    pub dets: Determinants,
    /// The counts of the emitted code and the engine's time, derivation and emission.
    pub stats: Stats,
}

/// [`Measured`] for `chain`: `derive`, then `generate_from` on its result (the code the
/// macro emits for `pub struct <Name>`), the wall time spanning both.
pub fn measured(chain: &Chain, options: &Options) -> Measured {
    let t = std::time::Instant::now();
    let derived = derive(chain, options);
    let generated = generate_from(chain, &ItemHeader::public(&chain.name), &derived);
    let time_ms = t.elapsed().as_secs_f64() * 1e3;
    let dets = det_hook::determinants(chain, &derived);
    let stats = stats(chain, &derived.model, &dets, &generated, time_ms);
    Measured {
        derived,
        dets,
        stats,
    }
}

/// Counts per output and the engine time.
#[derive(Clone, Debug)]
pub struct Stats {
    /// `fk` as generated.
    pub fk: OpCount,
    /// `jacobian` as generated.
    pub jacobian: OpCount,
    /// The determinant's code, where the engine has it.
    pub det: Option<OpCount>,
    /// The second-order functions as generated: `hessian`, `jacobian_dot`, `jdot_qdot`,
    /// `jacobian_ee_dot`, and `det_gradient` where there is one.
    pub second: Vec<(&'static str, OpCount)>,
    /// Wall time of `generate`, milliseconds.
    pub time_ms: f64,
    /// Its stages (`Generated::times`).
    pub stages: StageTimes,
}

/// Counts from the generated code itself (`Generated::stats`, the counts of the very
/// bodies emitted) and, for the determinant, from its own body.
pub fn stats(
    chain: &Chain,
    model: &Model,
    dets: &Determinants,
    generated: &Generated,
    time_ms: f64,
) -> Stats {
    let det = dets
        .det
        .as_ref()
        .or(dets.det_task.as_ref())
        .map(|d| Coder::new(chain, &model.sym).body(&[d.node]).ops);
    let g = &generated.stats;
    let mut second = vec![
        ("hessian", g.hessian),
        ("jacobian_dot", g.jacobian_dot),
        ("jdot_qdot", g.jdot_qdot),
        ("jacobian_ee_dot", g.jacobian_ee_dot),
    ];
    second.extend(g.det_gradient.map(|o| ("det_gradient", o)));
    Stats {
        fk: g.fk,
        jacobian: g.jacobian,
        det,
        second,
        time_ms,
        stages: generated.times,
    }
}

fn ops_json(o: &OpCount) -> Value {
    json!({"add": o.add, "mul": o.mul, "div": o.div, "neg": o.neg, "trig": o.trig, "total": o.total()})
}

/// `{"fk": {…}, "jacobian": {…}, "det": {…} or null, "hessian": {…}, "jacobian_dot":
/// {…}, "jdot_qdot": {…}, "jacobian_ee_dot": {…}, "det_gradient": {…} or null,
/// "time_ms": …, "stages_ms": {"order": …, "det": …, "second_order": …, "ik": …, "emit":
/// …, "ik_emit": …, "print": …}}` (`ik_emit` is the IK's share of `emit`).
pub fn to_json(s: &Stats) -> Value {
    let mut v = json!({
        "fk": ops_json(&s.fk),
        "jacobian": ops_json(&s.jacobian),
        "det": s.det.as_ref().map(ops_json),
    });
    let obj = v.as_object_mut().expect("an object");
    obj.insert("det_gradient".into(), Value::Null);
    for (name, o) in &s.second {
        obj.insert((*name).into(), ops_json(o));
    }
    obj.insert("time_ms".into(), json!(s.time_ms));
    let t = &s.stages;
    obj.insert(
        "stages_ms".into(),
        json!({
            "order": t.order_ms, "det": t.det_ms, "second_order": t.second_order_ms,
            "ik": t.ik_ms, "emit": t.emit_ms, "ik_emit": t.ik_emit_ms, "print": t.print_ms,
        }),
    );
    v
}

/// A readable table, its columns as wide as its largest count needs (a long chain's
/// counts run to six digits and more).
pub fn to_table(chain: &Chain, s: &Stats, missing: &str) -> String {
    let counts = [&s.fk, &s.jacobian]
        .into_iter()
        .chain(&s.det)
        .chain(s.second.iter().map(|(_, o)| o));
    let digits = counts
        .map(|o| o.total().to_string().len())
        .max()
        .unwrap_or(1);
    // One space at least between columns: `total` is the widest count.
    let w = (digits + 1).max(6);
    // One line of the table: a name, then four counts, the total and the `sin_cos`.
    let line = |out: &mut String, width: usize, name: &str, cells: [String; 6]| {
        let [add, mul, div, neg, total, trig] = cells;
        let _ = writeln!(
            out,
            "{name:<width$}{add:>w$}{mul:>w$}{div:>w$}{neg:>w$}{total:>t$}{trig:>r$}",
            t = w + 2,
            r = w + 1
        );
    };
    let head = |out: &mut String, title: &str, width: usize| {
        let names = ["add", "mul", "div", "neg", "total", "trig"];
        line(out, width, title, names.map(String::from));
    };
    let row_of = |out: &mut String, width: usize, name: &str, o: &OpCount| {
        let counts = [o.add, o.mul, o.div, o.neg, o.total(), o.trig];
        line(out, width, name, counts.map(|c| c.to_string()));
    };
    let mut out = format!(
        "{} — operations of the generated code (after sharing; a subtraction counts as an add)\n\n",
        chain.name
    );
    head(&mut out, "output", 10);
    let row = |out: &mut String, name: &str, o: &OpCount| row_of(out, 10, name, o);
    row(&mut out, "fk", &s.fk);
    row(&mut out, "jacobian", &s.jacobian);
    match &s.det {
        Some(d) => row(&mut out, "det", d),
        None => {
            let _ = writeln!(out, "{:<10}{missing}", "det");
        }
    }
    out.push('\n');
    head(&mut out, "second order", 16);
    for (name, o) in &s.second {
        row_of(&mut out, 16, name, o);
    }
    let _ = writeln!(out, "\nengine time: {}", engine_time(s));
    out
}

/// `12.3 ms (FK and Jacobians 4.5, det …, printing 0.4)`: the engine's time and each
/// stage's, as the table and the report say it.
pub fn engine_time(s: &Stats) -> String {
    let t = &s.stages;
    format!(
        "{:.1} ms (FK and Jacobians {:.1}, det {:.1}, second order {:.1}, IK {:.2}, \
         emitting the code {:.1} of which the IK's {:.2}, printing {:.1})",
        s.time_ms,
        t.order_ms,
        t.det_ms,
        t.second_order_ms,
        t.ik_ms,
        t.emit_ms,
        t.ik_emit_ms,
        t.print_ms
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ops(add: usize, mul: usize) -> OpCount {
        OpCount {
            add,
            mul,
            div: 0,
            neg: 3,
            trig: 2000,
        }
    }

    #[test]
    fn the_table_s_columns_fit_six_digit_counts() {
        let src = "name = \"RR\"\nconvention = \"standard\"\n[[joints]]\ntype = \"revolute\"\n\
                   a = 1.0\nalpha = 0\nd = 0\n";
        let (robot, _) = kinegen_core::front::toml_file::load_str(src, "rr.toml").unwrap();
        let s = Stats {
            fk: ops(89_977, 161_969),
            jacobian: ops(12, 34),
            det: None,
            second: vec![("hessian", ops(1, 2))],
            time_ms: 1.0,
            stages: StageTimes::default(),
        };
        let table = to_table(&robot.chain(), &s, "not available");
        let fk = table.lines().find(|l| l.starts_with("fk")).unwrap();
        let cells: Vec<&str> = fk.split_whitespace().collect();
        assert_eq!(
            cells,
            ["fk", "89977", "161969", "0", "3", "251949", "2000"],
            "{table}"
        );
        // Every row's counts end where their header's names end.
        let head = table.lines().find(|l| l.starts_with("output")).unwrap();
        assert_eq!(head.len(), fk.len(), "{table}");
        assert_eq!(
            head.find("total").unwrap() + 5,
            fk.find("251949").unwrap() + 6
        );
    }
}
