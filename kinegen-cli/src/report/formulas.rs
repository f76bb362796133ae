//! The closed forms as MathML, each with its plain-text form under it: FK and the
//! Jacobian (the sections `show` prints, from [`crate::formulas::sections`]), det J,
//! each singular factor with what it means, and the second order (`J̇ q̇`, `J̇`, the
//! Hessian).

use std::fmt::Write;

use kinegen_core::algebra::graph::Id;
use kinegen_core::emit::code::Coder;
use kinegen_core::emit::mathml::{self, escape, math, mathml_lhs, mtext};
use kinegen_core::emit::text::to_text;
use kinegen_core::{Chain, Derived};

use super::html::{self, Section};
use crate::det_hook::{Determinants, Factor};
use crate::formulas::{ops_text, sections, Line, What};

/// FK, the Jacobian(s) and det J.
pub fn first_order(chain: &Chain, derived: &Derived, dets: &Determinants) -> Section {
    let mut body = html::p(
        "Joint angles enter as s_i = sin(q_i), c_i = cos(q_i); c23 = cos(q2 + q3) (a subtracted \
         joint: c2m3 = cos(q2 − q3)). Each output lists the inputs and shared intermediates it \
         reads, then its entries, as the generated function computes them.",
    );
    for what in [What::Fk, What::Jacobian, What::Det] {
        for sec in sections(chain, &derived.model, dets, what) {
            let _ = writeln!(body, "<h3>{}</h3>", escape(&sec.title));
            if let Some(o) = &sec.ops {
                body.push_str(&html::p(&ops_text(o)));
            }
            if let Some(n) = &sec.note {
                body.push_str(&html::note(n));
            }
            if !sec.defs.is_empty() {
                body.push_str("<p>where</p>\n");
                for l in &sec.defs {
                    body.push_str(&line(l));
                }
            }
            for l in &sec.entries {
                body.push_str(&line(l));
            }
        }
    }
    Section {
        id: "formulas",
        title: "Forward kinematics, Jacobian, determinant".into(),
        body,
    }
}

/// Where det J vanishes: each factor `= 0` with the joints it involves and what that
/// kind of factor means.
pub fn singular_factors(dets: &Determinants) -> Section {
    let mut body = String::new();
    let list = [("det J", &dets.det), ("det Jt", &dets.det_task)];
    let mut any = false;
    for (name, d) in list {
        let Some(d) = d else { continue };
        any = true;
        body.push_str(&html::p(&format!(
            "{name} = 0 exactly where one of these factors is zero:"
        )));
        for f in &d.factors {
            let lhs = mathml::to_mathml(&f.text).unwrap_or_else(|_| mtext(&f.text));
            let eq = math(&mathml::equation(&lhs, &["<mn>0</mn>".into()]), false);
            let power = if f.power > 1 {
                format!(" (power {})", f.power)
            } else {
                String::new()
            };
            body.push_str(&html::equation(
                &eq,
                &format!("{} = 0{power}: {}", f.text, meaning(f)),
            ));
        }
    }
    if !any {
        body.push_str(&html::note(&format!("Determinant {}", dets.missing)));
    }
    Section {
        id: "singularities",
        title: "Singular factors".into(),
        body,
    }
}

/// What a factor's zero set is: the joints it involves, then what happens on the arm
/// there, found on the arm's geometry ([`Factor::meaning`]).
pub fn meaning(f: &Factor) -> String {
    if f.joints.is_empty() {
        return f.meaning.clone();
    }
    let joints: Vec<String> = f.joints.iter().map(|j| format!("q{j}")).collect();
    format!("depends on {}; {}", joints.join(", "), f.meaning)
}

/// The second order, each as the generated method computes it (its non-zero entries,
/// named as `FORMULAS` names them): the bias acceleration `J̇ q̇`, then `J̇` and the
/// Hessian `H[j] = ∂J/∂q_j`, each in a `<details>` element (open: its MathML is laid out
/// like the rest; a reader folds it away).
pub fn second_order(chain: &Chain, derived: &Derived) -> Section {
    let mut body = String::new();
    let s = &derived.second;
    match &s.at_run_time {
        Some(why) => body.push_str(&html::note(&format!(
            "Not in closed form ({why}); the generated methods compute the second order at \
             run time from the Jacobian's columns."
        ))),
        None => {
            let coder = Coder::new(chain, &derived.model.sym);
            body.push_str(&group(
                &coder,
                &s.jdot_qdot,
                "Bias acceleration J̇(q, q̇)·q̇ in the world frame, [ax ay az αx αy αz]: the \
                 tool's acceleration at q̈ = 0, so that ẍ = J·q̈ + J̇·q̇; q̇_i is joint i's rate",
                |r| format!("Jdot_qdot[{r}]"),
            ));
            let n = chain.dof();
            let rows: Vec<_> = s.jacobian_dot.iter().flatten().copied().collect();
            let jdot = group(
                &coder,
                &rows,
                "J̇ = dJ/dt in the world frame (6×N, entry [row][joint]; q̇_i is joint i's rate)",
                |k| format!("Jdot[{}][{}]", k / n, k % n),
            );
            body.push_str(&details("J̇, the Jacobian's time derivative", &jdot));
            let entries: Vec<_> = s.hessian.iter().flatten().flatten().copied().collect();
            let hessian = group(
                &coder,
                &entries,
                "Hessian H[j] = ∂J/∂q_j in the world frame (N × 6×N, entry [j][row][joint]), \
                 so that J̇ = Σ_j H[j]·q̇_j",
                |k| format!("H[{}][{}][{}]", k / (6 * n), k / n % 6, k % n),
            );
            body.push_str(&details("The Hessian ∂J/∂q", &hessian));
        }
    }
    Section {
        id: "second-order",
        title: "Second order".into(),
        body,
    }
}

/// The straight-line code of `ids` as the page shows it: what it is and costs, the
/// shared intermediates, then each non-zero output (`name(k)` for the `k`-th).
fn group(coder: &Coder, ids: &[Id], what: &str, name: impl Fn(usize) -> String) -> String {
    let code = coder.body(ids);
    let mut out = html::p(&format!("{what} ({}).", ops_text(&code.ops)));
    if !code.defs.is_empty() {
        out.push_str("<p>where</p>\n");
    }
    for (n, f) in &code.defs {
        out.push_str(&line(&Line {
            text_lhs: n.clone(),
            latex_lhs: String::new(),
            meaning: kinegen_core::emit::docs::angle_sum_meaning(n)
                .map(|m| (m.replace('−', "-"), String::new())),
            rust: Some(f.clone()),
        }));
    }
    let zero = coder.lit(0.0);
    for (k, f) in code.outputs.iter().enumerate() {
        if *f != zero {
            out.push_str(&line(&Line {
                text_lhs: name(k),
                latex_lhs: String::new(),
                meaning: None,
                rust: Some(f.clone()),
            }));
        }
    }
    out
}

/// `inner` under a heading a reader can fold.
fn details(summary: &str, inner: &str) -> String {
    format!(
        "<details open>\n<summary>{}</summary>\n{inner}</details>\n",
        escape(summary)
    )
}

/// `det J`, and the names of [`mathml_lhs`] (`T[0][3]` → T with subscript 1,4: 1-based,
/// as the LaTeX form; `Jdot_qdot[2]` → (J̇q̇)₃).
pub fn lhs(name: &str) -> String {
    match name {
        "det J" => "<mrow><mi>det</mi><mo>&#x2061;</mo><mi>J</mi></mrow>".into(),
        "det Jt" => {
            "<mrow><mi>det</mi><mo>&#x2061;</mo><msub><mi>J</mi><mi>t</mi></msub></mrow>".into()
        }
        n => mathml_lhs(n),
    }
}

/// One `lhs = meaning = formula` line: MathML, and the text form under it.
fn line(l: &Line) -> String {
    let mut rhs = Vec::new();
    let mut text = vec![l.text_lhs.clone()];
    if let Some((m, _)) = &l.meaning {
        rhs.push(mathml::to_mathml(m).unwrap_or_else(|_| mtext(m)));
        text.push(m.clone());
    }
    if let Some(r) = &l.rust {
        rhs.push(mathml::to_mathml(r).unwrap_or_else(|_| mtext(r)));
        text.push(to_text(r).unwrap_or_else(|_| r.clone()));
    }
    let eq = math(&mathml::equation(&lhs(&l.text_lhs), &rhs), false);
    html::equation(&eq, &text.join(" = "))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn matrix_entries_are_one_based_like_the_latex() {
        assert_eq!(
            lhs("T[0][3]"),
            "<msub><mi>T</mi><mrow><mn>1</mn><mo>,</mo><mn>4</mn></mrow></msub>"
        );
        assert_eq!(lhs("c23"), "<msub><mi>c</mi><mn>23</mn></msub>");
    }

    /// The UR5's factors read as what happens on the arm.
    #[test]
    fn ur5_factors_are_named() {
        let (chain, options) =
            crate::robots::load("ur5", &crate::robots::UrdfArgs::default()).unwrap();
        let derived = kinegen_core::derive(&chain, &options);
        let dets = crate::det_hook::determinants(&chain, &derived);
        let named: Vec<(String, String)> = dets
            .det
            .unwrap()
            .factors
            .iter()
            .map(|f| (f.text.clone(), meaning(f)))
            .collect();
        let of = |t: &str| &named.iter().find(|(x, _)| x == t).unwrap().1;
        assert!(
            of("sin(q3)")
                .starts_with("depends on q3; axes 2, 3 and 4 are parallel and in one plane"),
            "{named:?}"
        );
        assert!(
            of("sin(q5)").starts_with("depends on q5; axes 2, 3, 4 and 6 are parallel"),
            "{named:?}"
        );
        assert!(of("a2").contains("constant"), "{named:?}");
        let shoulder = named.iter().find(|(t, _)| t.contains("d5")).unwrap();
        assert!(
            shoulder
                .1
                .contains("the point where axes 5 and 6 meet lies in the plane through axis 1"),
            "{named:?}"
        );
    }
}
