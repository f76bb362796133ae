//! Formulas for people: the engine's Rust-syntax formula strings rendered as LaTeX (and,
//! re-exported from [`crate::emit::text`], as compact plain text).
//!
//! Formulas come from [`crate::emit::code::Body`] (`c1 * L1 + L2 * c12`). Each is parsed
//! with `syn` and the tree is printed again with the least parentheses its
//! precedence needs (the engine's parentheses are Rust's, not the reader's): the walk
//! is [`crate::emit::walk`]'s, shared with [`crate::emit::mathml`].
//! Variable names follow the textbooks' subscripts: `c23` → `c_{23}` (= cos(q2 + q3)),
//! `L1` → `L_{1}`, `s_k1` → `s_{k1}`.
//!
//! ```
//! use kinegen_core::emit::latex::{to_latex, to_text};
//! assert_eq!(to_latex("c1 * L1 + L2 * c12").unwrap(), r"c_{1}\,L_{1} + L_{2}\,c_{12}");
//! assert_eq!(to_text("-(s1 * L1 + t2)").unwrap(), "-(s1·L1 + t2)");
//! ```

use std::fmt::Write;

pub use crate::emit::text::to_text;
pub use crate::emit::walk::FormulaError;
use crate::emit::walk::{self, name_parts, Accent, Base, Node, Style, ATOM};

/// A Rust-syntax formula (`c1 * L1 + L2 * c12`) as LaTeX (`c_{1}\,L_{1} + L_{2}\,c_{12}`).
///
/// Products are juxtaposed with a thin space (`\cdot` before a number), quotients are
/// `\frac`, `sin`/`cos`/`sqrt` calls become `\sin`/`\cos`/`\sqrt`, powers `x^{2}`.
pub fn to_latex(formula: &str) -> Result<String, FormulaError> {
    walk::render(formula, &Latex)
}

/// The LaTeX style of the shared walk.
struct Latex;

impl Style for Latex {
    /// A number as written, without a float's `.0` (`1.0` → `1`); exponents as powers
    /// of ten.
    fn number(&self, digits: &str) -> String {
        let s = digits.strip_suffix(".0").unwrap_or(digits);
        match s.split_once(['e', 'E']) {
            Some((m, e)) => {
                let m = m.strip_suffix(".0").unwrap_or(m);
                format!(r"{m} \times 10^{{{e}}}")
            }
            None => s.to_string(),
        }
    }

    fn name(&self, name: &str) -> String {
        latex_name(name)
    }

    fn paren(&self, s: &str) -> String {
        format!(r"\left({s}\right)")
    }

    fn neg(&self, x: &str) -> String {
        format!("-{x}")
    }

    fn sum(&self, x: &str, minus: bool, y: &str) -> String {
        format!("{x} {} {y}", if minus { '-' } else { '+' })
    }

    fn product(&self, x: &str, y: &str, y_number: bool) -> String {
        let sep = if y_number { r" \cdot " } else { r"\," };
        format!("{x}{sep}{y}")
    }

    fn quotient(&self, x: &Node, y: &Node) -> Node {
        Node::new(format!(r"\frac{{{}}}{{{}}}", x.text, y.text), ATOM)
    }

    fn call(&self, f: &str, args: &[String]) -> String {
        match (f, args) {
            ("sqrt", [x]) => format!(r"\sqrt{{{x}}}"),
            ("sin" | "cos" | "tan", [x]) => format!(r"\{f}\left({x}\right)"),
            _ => format!(r"\operatorname{{{f}}}\left({}\right)", args.join(", ")),
        }
    }

    fn power(&self, base: &str, exp: &str) -> String {
        format!("{base}^{{{exp}}}")
    }
}

/// A variable name in textbook notation: `c23` → `c_{23}`, `L1` → `L_{1}`,
/// `s_k1` → `s_{k1}`, `c1_2` → `c_{1,2}` (angle sums of robots with ten or more joints),
/// `alpha2` → `\alpha_{2}`, `d_bs` → `d_{bs}`, `q` → `q`, the joint rates `qd3` →
/// `\dot{q}_{3}`, the negated angle sums of generated code `nc23` → `\bar{c}_{23}`
/// (= −c₂₃), and differences `c2m3` → `c_{2-3}` (= cos(q₂ − q₃)).
pub fn latex_name(name: &str) -> String {
    let parts = name_parts(name);
    let base = match &parts.base {
        Base::Letter(l) => l.clone(),
        Base::Greek(g) => format!(r"\{g}"),
        Base::Word(w) => format!(r"\mathrm{{{w}}}"),
        Base::Raw(r) => return format!(r"\mathrm{{{}}}", r.replace('_', r"\_")),
    };
    let base = match parts.accent {
        Accent::None => base,
        Accent::Bar => format!(r"\bar{{{base}}}"),
        Accent::Dot => format!(r"\dot{{{base}}}"),
    };
    if parts.sub.is_empty() {
        base
    } else {
        format!("{base}_{{{}}}", parts.sub)
    }
}

/// One displayed equation `lhs = rhs`, both already LaTeX.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Equation {
    /// Left-hand side (`c_{23}`, `J_{1,2}`).
    pub lhs: String,
    /// Right-hand side.
    pub rhs: String,
}

/// A titled group of equations: one `align*` environment.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Block {
    /// Prose printed before the environment (LaTeX allowed).
    pub title: String,
    /// The equations, aligned at `=`.
    pub equations: Vec<Equation>,
}

/// An `align*` environment, one equation per line, aligned at `=`.
///
/// ```
/// use kinegen_core::emit::latex::{align, Equation};
/// let eq = Equation { lhs: "c_{12}".into(), rhs: r"\cos(q_{1} + q_{2})".into() };
/// assert_eq!(
///     align(&[eq]),
///     "\\begin{align*}\n  c_{12} &= \\cos(q_{1} + q_{2})\n\\end{align*}\n"
/// );
/// ```
pub fn align(equations: &[Equation]) -> String {
    let mut s = String::from("\\begin{align*}\n");
    for (i, e) in equations.iter().enumerate() {
        let end = if i + 1 < equations.len() { r" \\" } else { "" };
        let _ = writeln!(s, "  {} &= {}{end}", e.lhs, e.rhs);
    }
    s.push_str("\\end{align*}\n");
    s
}

/// A LaTeX document body (to paste between `\begin{document}` and `\end{document}`;
/// needs `amsmath`): a `\section*` heading, then each block's title and its `align*`.
/// Empty blocks print their title only.
pub fn latex_document_body(heading: &str, blocks: &[Block]) -> String {
    let mut s = format!("\\section*{{{}}}\n", escape_text(heading));
    for b in blocks {
        let _ = writeln!(s, "\n{}", b.title);
        if !b.equations.is_empty() {
            s.push_str(&align(&b.equations));
        }
    }
    s
}

/// Plain text made safe for LaTeX's text mode (`&`, `%`, `_`, …; `—`, `ω` spelled
/// for pdfLaTeX).
pub fn escape_text(text: &str) -> String {
    let mut s = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' | '%' | '$' | '#' | '_' | '{' | '}' => {
                s.push('\\');
                s.push(c);
            }
            '~' => s.push_str(r"\textasciitilde{}"),
            '^' => s.push_str(r"\textasciicircum{}"),
            '\\' => s.push_str(r"\textbackslash{}"),
            // Characters pdfLaTeX's default fonts lack.
            '—' => s.push_str("---"),
            '–' => s.push_str("--"),
            'ω' => s.push_str(r"$\omega$"),
            'θ' => s.push_str(r"$\theta$"),
            'α' => s.push_str(r"$\alpha$"),
            '·' => s.push_str(r"$\cdot$"),
            _ => s.push(c),
        }
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tex(s: &str) -> String {
        to_latex(s).unwrap()
    }

    fn text(s: &str) -> String {
        to_text(s).unwrap()
    }

    #[test]
    fn names_take_textbook_subscripts() {
        assert_eq!(latex_name("s1"), "s_{1}");
        assert_eq!(latex_name("c23"), "c_{23}");
        assert_eq!(latex_name("nc23"), r"\bar{c}_{23}");
        assert_eq!(latex_name("ns1_2"), r"\bar{s}_{1,2}");
        assert_eq!(latex_name("nu2"), r"\nu_{2}");
        assert_eq!(latex_name("t4"), "t_{4}");
        assert_eq!(latex_name("a2"), "a_{2}");
        assert_eq!(latex_name("L1"), "L_{1}");
        assert_eq!(latex_name("d4"), "d_{4}");
        assert_eq!(latex_name("q3"), "q_{3}");
        assert_eq!(latex_name("qd3"), r"\dot{q}_{3}");
        assert_eq!(latex_name("qd_x"), r"\mathrm{qd}_{x}");
        assert_eq!(latex_name("s_k1"), "s_{k1}");
        assert_eq!(latex_name("c1_2_3"), "c_{1,2,3}");
        assert_eq!(latex_name("c2m3"), "c_{2-3}");
        assert_eq!(latex_name("ns2m34"), r"\bar{s}_{2-3+4}");
        assert_eq!(latex_name("c9_m10"), "c_{9-10}");
        assert_eq!(latex_name("alpha2"), r"\alpha_{2}");
        assert_eq!(latex_name("pi"), r"\pi");
        assert_eq!(latex_name("d_bs"), "d_{bs}");
        assert_eq!(latex_name("x"), "x");
        assert_eq!(latex_name("len12"), r"\mathrm{len}_{12}");
    }

    #[test]
    fn products_juxtapose_and_sums_keep_order() {
        assert_eq!(tex("c1 * L1 + L2 * c12"), r"c_{1}\,L_{1} + L_{2}\,c_{12}");
        assert_eq!(tex("s12 * t1 - c12 * t2"), r"s_{12}\,t_{1} - c_{12}\,t_{2}");
        // A number after a factor needs a visible operator.
        assert_eq!(tex("a2 * 0.5"), r"a_{2} \cdot 0.5");
        assert_eq!(tex("0.5 * a2"), r"0.5\,a_{2}");
    }

    #[test]
    fn parentheses_only_where_precedence_needs_them() {
        assert_eq!(
            tex("L2 * (c1 * c2 - s1 * s2)"),
            r"L_{2}\,\left(c_{1}\,c_{2} - s_{1}\,s_{2}\right)"
        );
        assert_eq!(tex("(a * b) * c"), r"a\,b\,c");
        assert_eq!(tex("a + (b + c)"), "a + b + c");
        assert_eq!(tex("a - (b + c)"), r"a - \left(b + c\right)");
        assert_eq!(tex("a - (b * c)"), r"a - b\,c");
        assert_eq!(
            tex("-(s1 * L1 + t2)"),
            r"-\left(s_{1}\,L_{1} + t_{2}\right)"
        );
        assert_eq!(tex("-(a * b)"), r"-a\,b");
        assert_eq!(tex("-s1 * L1"), r"-s_{1}\,L_{1}");
        assert_eq!(tex("a * -b"), r"a\,\left(-b\right)");
        assert_eq!(tex("a - -b"), r"a - \left(-b\right)");
        assert_eq!(tex("a + -b"), r"a + \left(-b\right)");
        assert_eq!(tex("-(-a)"), r"-\left(-a\right)");
        assert_eq!(text("(a + b) * (c - d)"), "(a + b)·(c - d)");
    }

    #[test]
    fn numbers_and_functions() {
        assert_eq!(tex("1.0"), "1");
        assert_eq!(tex("-0.425"), "-0.425");
        assert_eq!(tex("1e-5 * a"), r"1 \times 10^{-5}\,a");
        assert_eq!(tex("a / (b + c)"), r"\frac{a}{b + c}");
        assert_eq!(tex("cos(q2 + q3)"), r"\cos\left(q_{2} + q_{3}\right)");
        assert_eq!(tex("x.sqrt()"), r"\sqrt{x}");
        assert_eq!(tex("self.L1 * s1"), r"L_{1}\,s_{1}");
        assert_eq!(text("a / (b * c)"), "a/(b·c)");
        assert_eq!(text("(a + b) / c"), "(a + b)/c");
        assert_eq!(text("1.0 * c12"), "1·c12");
        assert_eq!(text("sin(q1 + 0.3)"), "sin(q1 + 0.3)");
    }

    #[test]
    fn text_reads_like_the_rustdoc_without_noise() {
        assert_eq!(text("-(s1 * L1 + t2)"), "-(s1·L1 + t2)");
        assert_eq!(text("c1 * c2 - s1 * s2"), "c1·c2 - s1·s2");
    }

    #[test]
    fn what_the_engine_does_not_produce_is_an_error_not_a_guess() {
        let e = to_latex("a && b").unwrap_err();
        assert!(e.to_string().starts_with("cannot render `a && b`"), "{e}");
        assert!(to_latex("a +").is_err());
        assert!(to_text("\"s\"").is_err());
    }

    #[test]
    fn document_body_has_one_align_per_block() {
        let body = latex_document_body(
            "UR5 & co_1 — ω",
            &[
                Block {
                    title: "Where".into(),
                    equations: vec![
                        Equation {
                            lhs: "a".into(),
                            rhs: "1".into(),
                        },
                        Equation {
                            lhs: "b".into(),
                            rhs: "2".into(),
                        },
                    ],
                },
                Block {
                    title: "Nothing".into(),
                    equations: vec![],
                },
            ],
        );
        assert_eq!(
            body,
            "\\section*{UR5 \\& co\\_1 --- $\\omega$}\n\nWhere\n\\begin{align*}\n  a &= 1 \\\\\n  b &= 2\n\\end{align*}\n\nNothing\n"
        );
    }

    /// Every formula of the engine's output for a real robot renders.
    #[test]
    fn renders_every_generated_formula_of_a_robot() {
        let src = "name = \"RRP\"\nconvention = \"standard\"\n[params]\nL1 = 0.5\n\
                   [[joints]]\ntype = \"revolute\"\na = \"L1\"\nalpha = \"pi/2\"\nd = 0.1\n\
                   [[joints]]\ntype = \"revolute\"\na = 0.3\nalpha = 0.3\nd = 0\ntheta = 0.2\n\
                   [[joints]]\ntype = \"prismatic\"\na = 0\nalpha = 0\ntheta = 0\n";
        let (robot, options) = crate::front::toml_file::load_str(src, "rrp.toml").unwrap();
        let chain = robot.chain();
        let model = crate::simplify::order::build(&chain, &options);
        let coder = crate::emit::code::Coder::new(&chain, &model.sym);
        let ids: Vec<_> = model.jacobian.iter().flatten().copied().collect();
        let body = coder.body(&ids);
        assert!(!body.defs.is_empty());
        for f in body.defs.iter().map(|(_, f)| f).chain(&body.outputs) {
            let t = to_latex(f).unwrap();
            assert!(!t.contains('*'), "{f} → {t}");
            to_text(f).unwrap();
        }
    }
}
