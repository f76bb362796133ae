//! The numbers of `kinegen stats`: operation counts of each generated output after
//! sharing, and the engine's time by stage.

use kinegen_core::emit::code::OpCount;
use kinegen_core::Chain;

use super::html::{self, Section};

fn row(name: &str, o: &OpCount) -> Vec<String> {
    let mut r = vec![format!("<code>{name}</code>")];
    r.extend(
        [o.add, o.mul, o.div, o.neg, o.total(), o.trig]
            .iter()
            .map(|x| x.to_string()),
    );
    r
}

/// The section; `missing` says why a determinant is absent.
pub fn section(chain: &Chain, s: &crate::stats::Stats, missing: &str) -> Section {
    let mut rows = vec![row("fk", &s.fk), row("jacobian", &s.jacobian)];
    match &s.det {
        Some(d) => rows.push(row("jacobian_det", d)),
        None => rows.push(vec![
            "<code>jacobian_det</code>".into(),
            kinegen_core::emit::mathml::escape(missing),
        ]),
    }
    for (name, o) in &s.second {
        rows.push(row(name, o));
    }
    let mut body = html::p(&format!(
        "{}: operations of the generated code (after sharing; a subtraction counts as an add).",
        chain.name
    ));
    body.push_str(&html::table(
        &["output", "add", "mul", "div", "neg", "total", "sin_cos"],
        &rows,
    ));
    body.push_str(&html::p(&format!(
        "Engine time: {}.",
        crate::stats::engine_time(s)
    )));
    Section {
        id: "stats",
        title: "Operation counts".into(),
        body,
    }
}
