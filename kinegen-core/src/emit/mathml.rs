//! Formulas as MathML Core (native in Chromium, Firefox and Safari: no script, no
//! network): the third style of [`crate::emit::walk`]'s printer, beside plain text
//! ([`crate::emit::text`]) and LaTeX ([`crate::emit::latex`]), so the three agree on
//! structure and parentheses.
//!
//! Names take the textbooks' subscripts as the LaTeX form does (`c23` → c₂₃, `L1` → L₁,
//! `nc23` → c̄₂₃, `qd3` → q̇₃); products are juxtaposed with an invisible times (`·`
//! before a number), quotients are `<mfrac>`, square roots `<msqrt>`, powers `<msup>`.
//! Every printed piece is one MathML element, and every text is escaped.
//!
//! ```
//! use kinegen_core::emit::mathml::{math, to_mathml};
//! assert_eq!(
//!     to_mathml("c1 * L1").unwrap(),
//!     "<mrow><msub><mi>c</mi><mn>1</mn></msub><mo>&#x2062;</mo><msub><mi>L</mi><mn>1</mn></msub></mrow>"
//! );
//! assert_eq!(to_mathml("a / 2.0").unwrap(), "<mfrac><mi>a</mi><mn>2</mn></mfrac>");
//! assert!(math("<mi>x</mi>", true).starts_with(r#"<math display="block""#));
//! ```

use crate::emit::walk::{
    self, name_parts, Accent, Base, FormulaError, NameParts, Node, Style, ATOM, GREEK,
};

/// A Rust-syntax formula (`c1 * L1 + L2 * c12`) as one MathML Core element (an
/// `<mrow>`, `<mi>`, `<mn>`, `<mfrac>` …, without the `<math>` around it: see [`math`]).
pub fn to_mathml(formula: &str) -> Result<String, FormulaError> {
    walk::render(formula, &MathMl)
}

/// A formula as a whole `<math>` element: `display` block (its own line) or inline.
/// Where the formula does not parse, its text in an `<mtext>` (escaped), so a page
/// always shows it.
pub fn formula_math(formula: &str, display: bool) -> String {
    let inner = to_mathml(formula).unwrap_or_else(|_| mtext(formula));
    math(&inner, display)
}

/// `content` (MathML elements) inside `<math>`; `display`: a block of its own.
pub fn math(content: &str, display: bool) -> String {
    if display {
        format!(r#"<math display="block">{content}</math>"#)
    } else {
        format!("<math>{content}</math>")
    }
}

/// `lhs = rhs₁ = rhs₂ …` as one `<mrow>`; the operands are MathML elements.
pub fn equation(lhs: &str, rhs: &[String]) -> String {
    let mut s = format!("<mrow>{lhs}");
    for r in rhs {
        s.push_str("<mo>=</mo>");
        s.push_str(r);
    }
    s.push_str("</mrow>");
    s
}

/// Text inside a formula, escaped: `<mtext>…</mtext>`.
pub fn mtext(text: &str) -> String {
    format!("<mtext>{}</mtext>", escape(text))
}

/// `&`, `<`, `>`, `"` and `'` as character references: text safe in HTML and
/// MathML, in content and in attribute values.
pub fn escape(text: &str) -> String {
    let mut s = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => s.push_str("&amp;"),
            '<' => s.push_str("&lt;"),
            '>' => s.push_str("&gt;"),
            '"' => s.push_str("&quot;"),
            '\'' => s.push_str("&#39;"),
            _ => s.push(c),
        }
    }
    s
}

/// A variable name in textbook notation, as one element: `c23` → c with subscript 23,
/// `nc23` → c̄₂₃, `c2m3` → c₂₋₃ (= cos(q₂ − q₃)), `qd3` → q̇₃, `alpha2` → α₂, `len12` →
/// an upright `len` with subscript 12 (the names of [`crate::emit::latex::latex_name`]).
pub fn mathml_name(name: &str) -> String {
    let parts = name_parts(name);
    let base = match &parts.base {
        Base::Letter(l) => format!("<mi>{}</mi>", escape(l)),
        Base::Greek(g) => {
            let c = GREEK.iter().find(|(n, _)| n == g).map_or('?', |(_, c)| *c);
            format!("<mi>{c}</mi>")
        }
        // A multi-letter `<mi>` is upright in MathML Core, as `\mathrm` in LaTeX.
        Base::Word(w) => format!("<mi>{}</mi>", escape(w)),
        Base::Raw(r) => return format!("<mi>{}</mi>", escape(r)),
    };
    let base = match parts.accent {
        Accent::None => base,
        Accent::Bar => format!(r#"<mover accent="true">{base}<mo>&#xAF;</mo></mover>"#),
        Accent::Dot => format!(r#"<mover accent="true">{base}<mo>&#x2D9;</mo></mover>"#),
    };
    if parts.sub.is_empty() {
        base
    } else {
        format!("<msub>{base}{}</msub>", subscript(&parts.sub))
    }
}

/// The left-hand side of a listed formula: a matrix entry `T[0][3]` as T with the
/// 1-based subscript `1,4` (as the LaTeX form numbers them; `Jt[1][2]` → J with the
/// subscript `t,2,3`; `Jdot[0][1]` → J̇₁,₂; `Jdot_qdot[2]` → (J̇q̇)₃; `ddet[1]` →
/// ∂det J/∂q₂), any other name as [`mathml_name`].
///
/// ```
/// use kinegen_core::emit::mathml::mathml_lhs;
/// assert_eq!(
///     mathml_lhs("T[0][3]"),
///     "<msub><mi>T</mi><mrow><mn>1</mn><mo>,</mo><mn>4</mn></mrow></msub>"
/// );
/// assert_eq!(mathml_lhs("c23"), "<msub><mi>c</mi><mn>23</mn></msub>");
/// // Link 2's frame, entry (1, 4): (⁰T₂)₁,₄.
/// assert!(mathml_lhs("T0_2[0][3]").contains("<mprescripts/><none/><mn>0</mn>"));
/// assert_eq!(
///     mathml_lhs("Jt[1][2]"),
///     "<msub><mi>J</mi><mrow><mi>t</mi><mo>,</mo><mrow><mn>2</mn><mo>,</mo><mn>3</mn></mrow></mrow></msub>"
/// );
/// assert!(mathml_lhs("Jee_dot[0][1]").starts_with("<msub><mover accent=\"true\"><mi>J</mi>"));
/// assert!(mathml_lhs("ddet[1]").starts_with("<mfrac>"));
/// ```
pub fn mathml_lhs(name: &str) -> String {
    let Some((m, rest)) = name.split_once('[') else {
        return mathml_name(name);
    };
    let idx: Option<Vec<usize>> = rest
        .split(['[', ']'])
        .filter(|s| !s.is_empty())
        .map(|s| s.parse().ok())
        .collect();
    let Some(idx) = idx else {
        return mtext(name);
    };
    let sub: Vec<String> = idx.iter().map(|i| format!("<mn>{}</mn>", i + 1)).collect();
    let sub = match sub.len() {
        1 => sub[0].clone(),
        _ => format!("<mrow>{}</mrow>", sub.join("<mo>,</mo>")),
    };
    // `T0_3`, link 3's frame in the world frame (`frames`): ⁰T₃, its entry's indices
    // after it, the frame in parentheses.
    if let Some(k) = m.strip_prefix("T0_").filter(|k| k.parse::<usize>().is_ok()) {
        return format!(
            "<msub><mrow><mo>(</mo><mmultiscripts><mi>T</mi><mn>{k}</mn><none/><mprescripts/>\
             <none/><mn>0</mn></mmultiscripts><mo>)</mo></mrow>{sub}</msub>"
        );
    }
    // The Jacobians' names (`FORMULAS`' and the docs'): J with its frame as a subscript
    // (`Jt`, `Jee`), dotted for the rates; the entry's indices after a comma.
    let dot = |x: &str| format!("<mover accent=\"true\">{x}<mo>&#x2D9;</mo></mover>");
    let (base, frame) = match m {
        "Jt" => ("<mi>J</mi>".to_string(), "t"),
        "Jee" => ("<mi>J</mi>".to_string(), "ee"),
        "Jdot" => (dot("<mi>J</mi>"), ""),
        "Jee_dot" => (dot("<mi>J</mi>"), "ee"),
        "Jdot_qdot" => (
            format!("<mrow>{}{}</mrow>", dot("<mi>J</mi>"), dot("<mi>q</mi>")),
            "",
        ),
        // The determinant's gradient: ∂det J/∂q_j.
        "ddet" if idx.len() == 1 => {
            return format!(
                "<mfrac><mrow><mo>∂</mo><mi>det</mi><mo>&#x2061;</mo><mi>J</mi></mrow>\
                 <mrow><mo>∂</mo><msub><mi>q</mi>{sub}</msub></mrow></mfrac>"
            )
        }
        // A letter with a subscript of its own: the entry's indices after a comma.
        _ => {
            return match name_parts(m) {
                NameParts {
                    accent: Accent::None,
                    base: Base::Letter(l),
                    sub: s,
                } if !s.is_empty() => format!(
                    "<msub><mi>{}</mi><mrow>{}<mo>,</mo>{sub}</mrow></msub>",
                    escape(&l),
                    subscript(&s)
                ),
                _ => format!("<msub>{}{sub}</msub>", mathml_name(m)),
            }
        }
    };
    if frame.is_empty() {
        format!("<msub>{base}{sub}</msub>")
    } else {
        format!("<msub>{base}<mrow><mi>{frame}</mi><mo>,</mo>{sub}</mrow></msub>")
    }
}

/// `23` → `<mn>23</mn>`; `2-3+4` → numbers and operators in an `<mrow>`; `k1`, `bs`
/// → letters and digits as tokens.
fn subscript(sub: &str) -> String {
    let mut tokens: Vec<String> = Vec::new();
    let mut run = String::new();
    let flush = |run: &mut String, tokens: &mut Vec<String>| {
        if run.is_empty() {
            return;
        }
        let tag = if run.starts_with(|c: char| c.is_ascii_digit()) {
            "mn"
        } else {
            "mi"
        };
        tokens.push(format!("<{tag}>{}</{tag}>", escape(run)));
        run.clear();
    };
    for c in sub.chars() {
        match c {
            '-' | '+' | ',' => {
                flush(&mut run, &mut tokens);
                let op = if c == '-' { '−' } else { c };
                tokens.push(format!("<mo>{op}</mo>"));
            }
            _ => {
                // A digit after letters (`k1`) starts a new token.
                let kind_changes = run
                    .chars()
                    .last()
                    .is_some_and(|l| l.is_ascii_digit() != c.is_ascii_digit());
                if kind_changes {
                    flush(&mut run, &mut tokens);
                }
                run.push(c);
            }
        }
    }
    flush(&mut run, &mut tokens);
    match tokens.len() {
        1 => tokens.remove(0),
        _ => format!("<mrow>{}</mrow>", tokens.concat()),
    }
}

/// The MathML style of the shared walk.
struct MathMl;

/// A number token: a leading minus (from `-1e-5`'s exponent) as an operator.
fn mn(digits: &str) -> String {
    match digits.strip_prefix('-') {
        Some(d) => format!("<mrow><mo>−</mo><mn>{}</mn></mrow>", escape(d)),
        None => format!("<mn>{}</mn>", escape(digits)),
    }
}

impl Style for MathMl {
    fn number(&self, digits: &str) -> String {
        let s = digits.strip_suffix(".0").unwrap_or(digits);
        match s.split_once(['e', 'E']) {
            Some((m, e)) => {
                let m = m.strip_suffix(".0").unwrap_or(m);
                let e = e.strip_prefix('+').unwrap_or(e);
                format!(
                    "<mrow>{}<mo>×</mo><msup><mn>10</mn>{}</msup></mrow>",
                    mn(m),
                    mn(e)
                )
            }
            None => mn(s),
        }
    }

    fn name(&self, name: &str) -> String {
        mathml_name(name)
    }

    fn paren(&self, s: &str) -> String {
        // Parentheses grow around a fraction only: around subscripts they would stand
        // taller than the line.
        if s.contains("<mfrac>") {
            format!("<mrow><mo>(</mo>{s}<mo>)</mo></mrow>")
        } else {
            format!(r#"<mrow><mo stretchy="false">(</mo>{s}<mo stretchy="false">)</mo></mrow>"#)
        }
    }

    fn neg(&self, x: &str) -> String {
        format!("<mrow><mo>−</mo>{x}</mrow>")
    }

    fn sum(&self, x: &str, minus: bool, y: &str) -> String {
        format!(
            "<mrow>{x}<mo>{}</mo>{y}</mrow>",
            if minus { '−' } else { '+' }
        )
    }

    fn product(&self, x: &str, y: &str, y_number: bool) -> String {
        // Invisible times between factors; a visible dot before a number (`a · 0.5`).
        let op = if y_number { "&#xB7;" } else { "&#x2062;" };
        format!("<mrow>{x}<mo>{op}</mo>{y}</mrow>")
    }

    fn quotient(&self, x: &Node, y: &Node) -> Node {
        Node::new(format!("<mfrac>{}{}</mfrac>", x.text, y.text), ATOM)
    }

    fn call(&self, f: &str, args: &[String]) -> String {
        match (f, args) {
            ("sqrt", [x]) => format!("<msqrt>{x}</msqrt>"),
            _ => {
                let mut list = String::new();
                for (i, a) in args.iter().enumerate() {
                    if i > 0 {
                        list.push_str("<mo>,</mo>");
                    }
                    list.push_str(a);
                }
                // U+2061 FUNCTION APPLICATION between the name and its argument.
                format!(
                    "<mrow><mi>{}</mi><mo>&#x2061;</mo>{}</mrow>",
                    escape(f),
                    self.paren(&list)
                )
            }
        }
    }

    fn power(&self, base: &str, exp: &str) -> String {
        format!("<msup>{base}{exp}</msup>")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn m(s: &str) -> String {
        to_mathml(s).unwrap()
    }

    #[test]
    fn names_take_textbook_subscripts() {
        assert_eq!(mathml_name("c23"), "<msub><mi>c</mi><mn>23</mn></msub>");
        assert_eq!(mathml_name("L1"), "<msub><mi>L</mi><mn>1</mn></msub>");
        assert_eq!(mathml_name("q"), "<mi>q</mi>");
        assert_eq!(
            mathml_name("c2m3"),
            "<msub><mi>c</mi><mrow><mn>2</mn><mo>−</mo><mn>3</mn></mrow></msub>"
        );
        assert_eq!(
            mathml_name("c1_2"),
            "<msub><mi>c</mi><mrow><mn>1</mn><mo>,</mo><mn>2</mn></mrow></msub>"
        );
        assert_eq!(
            mathml_name("nc23"),
            "<msub><mover accent=\"true\"><mi>c</mi><mo>&#xAF;</mo></mover><mn>23</mn></msub>"
        );
        assert_eq!(
            mathml_name("qd3"),
            "<msub><mover accent=\"true\"><mi>q</mi><mo>&#x2D9;</mo></mover><mn>3</mn></msub>"
        );
        assert_eq!(mathml_name("alpha2"), "<msub><mi>α</mi><mn>2</mn></msub>");
        assert_eq!(mathml_name("pi"), "<mi>π</mi>");
        assert_eq!(
            mathml_name("s_k1"),
            "<msub><mi>s</mi><mrow><mi>k</mi><mn>1</mn></mrow></msub>"
        );
        assert_eq!(mathml_name("len12"), "<msub><mi>len</mi><mn>12</mn></msub>");
        assert_eq!(mathml_name("_x"), "<mi>_x</mi>");
    }

    #[test]
    fn structure_follows_the_shared_walk() {
        // The same parentheses as the LaTeX form: `a - (b + c)`, none in `a - b c`.
        assert_eq!(
            m("a - (b + c)"),
            "<mrow><mi>a</mi><mo>−</mo><mrow><mo stretchy=\"false\">(</mo><mrow><mi>b</mi><mo>+</mo><mi>c</mi></mrow><mo stretchy=\"false\">)</mo></mrow></mrow>"
        );
        assert_eq!(
            m("a - (b * c)"),
            "<mrow><mi>a</mi><mo>−</mo><mrow><mi>b</mi><mo>&#x2062;</mo><mi>c</mi></mrow></mrow>"
        );
        assert_eq!(
            m("-(a * b)"),
            "<mrow><mo>−</mo><mrow><mi>a</mi><mo>&#x2062;</mo><mi>b</mi></mrow></mrow>"
        );
        // A number after a factor gets a visible dot.
        assert_eq!(
            m("a2 * 0.5"),
            "<mrow><msub><mi>a</mi><mn>2</mn></msub><mo>&#xB7;</mo><mn>0.5</mn></mrow>"
        );
    }

    #[test]
    fn numbers_functions_powers() {
        assert_eq!(m("1.0"), "<mn>1</mn>");
        assert_eq!(m("-0.425"), "<mrow><mo>−</mo><mn>0.425</mn></mrow>");
        assert_eq!(
            m("1e-5"),
            "<mrow><mn>1</mn><mo>×</mo><msup><mn>10</mn><mrow><mo>−</mo><mn>5</mn></mrow></msup></mrow>"
        );
        assert_eq!(m("x.sqrt()"), "<msqrt><mi>x</mi></msqrt>");
        assert_eq!(m("sqrt(3)"), "<msqrt><mn>3</mn></msqrt>");
        assert_eq!(
            m("cos(q2 + q3)"),
            "<mrow><mi>cos</mi><mo>&#x2061;</mo><mrow><mo stretchy=\"false\">(</mo><mrow><msub><mi>q</mi><mn>2</mn></msub><mo>+</mo><msub><mi>q</mi><mn>3</mn></msub></mrow><mo stretchy=\"false\">)</mo></mrow></mrow>"
        );
        // The determinant's text writes powers with `^`: a square, not `(a·c)^2`.
        assert_eq!(
            m("a*c3^2"),
            "<mrow><mi>a</mi><mo>&#x2062;</mo><msup><msub><mi>c</mi><mn>3</mn></msub><mn>2</mn></msup></mrow>"
        );
        assert_eq!(
            m("(a + b).powi(2)"),
            "<msup><mrow><mo stretchy=\"false\">(</mo><mrow><mi>a</mi><mo>+</mo><mi>b</mi></mrow><mo stretchy=\"false\">)</mo></mrow><mn>2</mn></msup>"
        );
        assert_eq!(
            m("self.L1 / (a + b)"),
            "<mfrac><msub><mi>L</mi><mn>1</mn></msub><mrow><mi>a</mi><mo>+</mo><mi>b</mi></mrow></mfrac>"
        );
    }

    #[test]
    fn everything_is_escaped() {
        assert_eq!(
            escape("a<b & 'c' \"d\" >"),
            "a&lt;b &amp; &#39;c&#39; &quot;d&quot; &gt;"
        );
        assert_eq!(mtext("x < 1 & y"), "<mtext>x &lt; 1 &amp; y</mtext>");
        // What does not parse is shown as escaped text, not dropped and not raw.
        assert_eq!(
            formula_math("a && <b>", false),
            "<math><mtext>a &amp;&amp; &lt;b&gt;</mtext></math>"
        );
        assert!(to_mathml("a && b").is_err());
    }

    #[test]
    fn equations_chain_their_sides() {
        assert_eq!(
            equation("<mi>x</mi>", &["<mn>1</mn>".into(), "<mn>2</mn>".into()]),
            "<mrow><mi>x</mi><mo>=</mo><mn>1</mn><mo>=</mo><mn>2</mn></mrow>"
        );
    }

    /// Every formula of the engine's output for a real robot prints as MathML whose
    /// tags balance, with nothing of the Rust syntax left over.
    #[test]
    fn renders_every_generated_formula_of_a_robot() {
        let (robot, options) =
            crate::front::toml_file::load_str(include_str!("../../../robots/ur5.toml"), "ur5.toml")
                .unwrap();
        let chain = robot.chain();
        let model = crate::simplify::order::build(&chain, &options);
        let coder = crate::emit::code::Coder::new(&chain, &model.sym);
        let ids: Vec<_> = model.jacobian.iter().flatten().copied().collect();
        let body = coder.body(&ids);
        assert!(!body.defs.is_empty());
        for f in body.defs.iter().map(|(_, f)| f).chain(&body.outputs) {
            let x = to_mathml(f).unwrap();
            assert!(!x.contains('*') && !x.contains("self"), "{f} → {x}");
            let opens = x.matches("<m").count();
            let closes = x.matches("</m").count();
            assert_eq!(opens, closes, "{f} → {x}");
        }
    }
}
