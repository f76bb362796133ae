//! The `FORMULAS` constant: every intermediate and output of the generated functions as
//! plain text and LaTeX, for people and tools.

use crate::emit::code::Body;
use crate::emit::latex;

/// `(function, name, text, latex)` of every formula, in order.
#[derive(Clone, Debug, Default)]
pub struct Formulas(Vec<[String; 4]>);

impl Formulas {
    /// One formula.
    pub fn push(&mut self, function: &str, name: &str, text: &str, latex: &str) {
        self.0
            .push([function.into(), name.into(), text.into(), latex.into()]);
    }

    /// The intermediates and outputs of a body (Rust syntax; LaTeX rendered from it).
    pub fn add_body(&mut self, function: &str, body: &Body, names: &[String]) {
        let defs = body.defs.iter().map(|(n, e)| (n.as_str(), e.as_str()));
        let outs = names
            .iter()
            .map(String::as_str)
            .zip(body.outputs.iter().map(String::as_str));
        for (name, expr) in defs.chain(outs) {
            let latex = latex::to_latex(expr).unwrap_or_else(|_| expr.to_string());
            self.push(function, name, expr, &latex);
        }
    }

    /// `(function, name, text, latex)` of each formula, in order: the generated
    /// `FORMULAS` (each function's shared intermediates, then its outputs).
    pub fn entries(&self) -> impl Iterator<Item = (&str, &str, &str, &str)> {
        self.0
            .iter()
            .map(|[f, n, t, l]| (f.as_str(), n.as_str(), t.as_str(), l.as_str()))
    }

    /// The `::kinegen::Formula` literals, comma-separated.
    pub fn rust(&self) -> String {
        let items: Vec<String> = self
            .0
            .iter()
            .map(|[f, n, t, l]| {
                format!(
                    "::kinegen::Formula {{ function: {f:?}, name: {n:?}, text: {t:?}, latex: {l:?} }}"
                )
            })
            .collect();
        items.join(", ")
    }
}
