//! The `FORMULAS` constant: every intermediate and output of the generated functions as
//! plain text and LaTeX, for people and tools.

use crate::emit::code::Body;
use crate::emit::latex;

/// The most formulas `FORMULAS` lists, in order; past them it lists no more and says
/// how many it left out (`kinegen show` prints every one). Thirteen times the largest
/// shipped robot's (a Kinova Gen3: 773, second order included), and more than a
/// 12-joint chain of oblique axes has (3 857); a 1 000-joint one has 84 695, whose
/// 19 MB of text and LaTeX were half of its generated code and of its emission time,
/// and a constant nobody reads that far.
pub const MAX_FORMULAS: usize = 10_000;

/// `(function, name, text, latex)` of every formula, in order, up to [`MAX_FORMULAS`].
#[derive(Clone, Debug, Default)]
pub struct Formulas {
    listed: Vec<[String; 4]>,
    /// Formulas past [`MAX_FORMULAS`], counted, not rendered.
    left_out: usize,
}

impl Formulas {
    /// One formula (counted only, once [`MAX_FORMULAS`] are listed).
    pub fn push(&mut self, function: &str, name: &str, text: &str, latex: &str) {
        if self.listed.len() < MAX_FORMULAS {
            self.listed
                .push([function.into(), name.into(), text.into(), latex.into()]);
        } else {
            self.left_out += 1;
        }
    }

    /// The intermediates and outputs of a body (Rust syntax; LaTeX rendered from it).
    pub fn add_body(&mut self, function: &str, body: &Body, names: &[String]) {
        let defs = body.defs.iter().map(|(n, e)| (n.as_str(), e.as_str()));
        let outs = names
            .iter()
            .map(String::as_str)
            .zip(body.outputs.iter().map(String::as_str));
        let room = MAX_FORMULAS - self.listed.len();
        let count = body.defs.len() + names.len().min(body.outputs.len());
        for (name, expr) in defs.chain(outs).take(room) {
            let latex = latex::to_latex(expr).unwrap_or_else(|_| expr.to_string());
            self.push(function, name, expr, &latex);
        }
        self.left_out += count.saturating_sub(room);
    }

    /// `(function, name, text, latex)` of each listed formula, in order: the generated
    /// `FORMULAS` (each function's shared intermediates, then its outputs).
    pub fn entries(&self) -> impl Iterator<Item = (&str, &str, &str, &str)> {
        self.listed
            .iter()
            .map(|[f, n, t, l]| (f.as_str(), n.as_str(), t.as_str(), l.as_str()))
    }

    /// How many formulas are listed.
    pub fn len(&self) -> usize {
        self.listed.len()
    }

    /// Whether none is.
    pub fn is_empty(&self) -> bool {
        self.listed.is_empty()
    }

    /// How many formulas past [`MAX_FORMULAS`] are left out.
    pub fn left_out(&self) -> usize {
        self.left_out
    }

    /// The `::kinegen::Formula` literals, comma-separated.
    pub fn rust(&self) -> String {
        let items: Vec<String> = self
            .listed
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::emit::code::tests::body;

    #[test]
    fn formulas_past_the_bound_are_counted_not_listed() {
        let mut f = Formulas::default();
        let (small, names) = body(2);
        f.add_body("fk", &small, &names);
        assert_eq!((f.len(), f.left_out()), (3, 0));
        let (big, names) = body(MAX_FORMULAS);
        f.add_body("jacobian", &big, &names);
        // 3 + 10 001 formulas: the first 10 000 listed, in order.
        assert_eq!((f.len(), f.left_out()), (MAX_FORMULAS, 4));
        let last = f.entries().last().unwrap();
        assert_eq!(last.0, "jacobian");
        assert_eq!(last.1, format!("t{}", MAX_FORMULAS - 3));
        f.push("jacobian_det", "det", "s2", "s_2");
        assert_eq!((f.len(), f.left_out()), (MAX_FORMULAS, 5));
        assert_eq!(
            f.rust().matches("::kinegen::Formula {").count(),
            MAX_FORMULAS
        );
    }
}
