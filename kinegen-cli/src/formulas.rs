//! `kinegen show`: the closed forms of a robot, as terminal text or a LaTeX body.
//!
//! Each section is one output of the generated code (`fk`, `jacobian`, …) with the
//! same sharing as the generated function: the inputs (`s1 = sin(q1)`), the shared
//! intermediates (`c23 = cos(q2 + q3) = …`, `t1 = …`), then the entries. The formulas
//! are the engine's own ([`Coder::body`]), re-printed by [`kinegen_core::emit::latex`].

use std::collections::BTreeSet;
use std::fmt::Write;

use kinegen_core::algebra::graph::Id;
use kinegen_core::emit::angle_names::AngleName;
use kinegen_core::emit::code::{Body, Coder, OpCount};
use kinegen_core::emit::latex::{self, latex_name, Block, Equation};
use kinegen_core::kinematics::model::Model;
use kinegen_core::Chain;

use crate::det_hook::{Determinant, Determinants};

/// What `show` prints.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum What {
    /// Forward kinematics (tool pose).
    Fk,
    /// World-frame geometric Jacobian (and the task Jacobian, if the robot has one).
    Jacobian,
    /// Jacobian determinant.
    Det,
    /// Where the determinant vanishes.
    Singularities,
    /// Every formula section above.
    All,
    /// The chain as the engine reads it (elementary transforms), the description's
    /// table, and every value snapped with the error bound it implies.
    Model,
    /// The closed-form IK family and its derivation (which subproblem gives which joint).
    Ik,
}

/// One named formula: `lhs = meaning = rhs` (the meaning, when known, in words of
/// the joint angles: `cos(q2 + q3)`).
#[derive(Clone, Debug, PartialEq)]
pub struct Line {
    /// The name as text (`c23`, `T[0][3]`, `det J`).
    pub text_lhs: String,
    /// The name as LaTeX.
    pub latex_lhs: String,
    /// What it means, `(text, LaTeX)`.
    pub meaning: Option<(String, String)>,
    /// Rust-syntax formula (rendered with `kinegen_core::latex`), or `None` when the
    /// meaning is the whole definition (`s1 = sin(q1)`).
    pub rust: Option<String>,
}

/// One output with its definitions.
#[derive(Clone, Debug)]
pub struct Section {
    /// What the output is.
    pub title: String,
    /// Operation counts of its code.
    pub ops: Option<OpCount>,
    /// Shown when the section has no formulas (a missing determinant).
    pub note: Option<String>,
    /// Inputs and shared intermediates.
    pub defs: Vec<Line>,
    /// The outputs.
    pub entries: Vec<Line>,
}

/// The text of `show` for `what`; `latex` selects a LaTeX document body.
pub fn show(chain: &Chain, model: &Model, dets: &Determinants, what: What, latex: bool) -> String {
    let sections = sections(chain, model, dets, what);
    if latex {
        render_latex(chain, &sections)
    } else {
        render_text(chain, &sections)
    }
}

/// The sections `show` prints for `what` (also the report's formulas), before any
/// printer: one source for the terminal, LaTeX and the HTML page.
pub fn sections(chain: &Chain, model: &Model, dets: &Determinants, what: What) -> Vec<Section> {
    let coder = Coder::new(chain, &model.sym);
    let want = |w: What| what == w || what == What::All;
    let n = chain.dof();
    let mut sections = Vec::new();
    if want(What::Fk) {
        let ids: Vec<Id> = model.fk_rows.iter().flatten().copied().collect();
        sections.push(section(
            model,
            &coder,
            &ids,
            "Forward kinematics: tool pose T in the world frame (its last row is [0 0 0 1])",
            "T",
            4,
        ));
    }
    if want(What::Jacobian) {
        let ids: Vec<Id> = model.jacobian.iter().flatten().copied().collect();
        sections.push(section(
            model,
            &coder,
            &ids,
            "Geometric Jacobian J in the world frame, rows [vx vy vz ωx ωy ωz]",
            "J",
            n,
        ));
        if let Some(task) = &chain.task {
            let ids: Vec<Id> = model.task.iter().flatten().copied().collect();
            let rows: Vec<&str> = task.iter().map(|r| r.name()).collect();
            sections.push(section(
                model,
                &coder,
                &ids,
                &format!("Task Jacobian Jt: rows [{}] of J", rows.join(" ")),
                "Jt",
                n,
            ));
        }
    }
    let det_list: [(&str, &str, &Option<Determinant>); 2] = [
        ("det J", r"\det J", &dets.det),
        ("det Jt", r"\det J_{t}", &dets.det_task),
    ];
    if want(What::Det) {
        let mut any = false;
        for (name, tex, d) in det_list {
            if let Some(d) = d {
                any = true;
                let body = coder.body(&[d.node]);
                sections.push(Section {
                    title: format!("Jacobian determinant {name}"),
                    ops: Some(body.ops),
                    note: None,
                    defs: vec![],
                    entries: vec![Line {
                        text_lhs: name.into(),
                        latex_lhs: tex.into(),
                        meaning: Some((d.text.clone(), d.latex.clone())),
                        rust: None,
                    }],
                });
            }
        }
        if !any {
            sections.push(missing("Jacobian determinant", &dets.missing));
        }
    }
    if want(What::Singularities) {
        let mut any = false;
        for (name, _, d) in det_list {
            if let Some(d) = d {
                any = true;
                let entries = d
                    .factors
                    .iter()
                    .map(|f| Line {
                        text_lhs: f.text.clone(),
                        latex_lhs: f.latex.clone(),
                        meaning: Some((
                            format!(
                                "0   ({}{})",
                                if f.joints.is_empty() {
                                    "a link parameter: singular for every q".to_string()
                                } else {
                                    f.meaning.clone()
                                },
                                if f.power > 1 {
                                    format!("; power {}", f.power)
                                } else {
                                    String::new()
                                }
                            ),
                            "0".into(),
                        )),
                        rust: None,
                    })
                    .collect();
                sections.push(Section {
                    title: format!("Singularities: {name} = 0 where one of these factors is zero"),
                    ops: None,
                    note: None,
                    defs: vec![],
                    entries,
                });
            }
        }
        if !any {
            sections.push(missing("Singularities", &dets.missing));
        }
    }
    sections
}

fn missing(title: &str, why: &str) -> Section {
    Section {
        title: title.into(),
        ops: None,
        note: Some(why.into()),
        defs: vec![],
        entries: vec![],
    }
}

/// A section for the outputs `ids`, named `matrix[r][c]` row-major with `cols` columns.
fn section(
    model: &Model,
    coder: &Coder,
    ids: &[Id],
    title: &str,
    matrix: &str,
    cols: usize,
) -> Section {
    let body = coder.body(ids);
    let mut defs = inputs(model, &body);
    defs.extend(body.defs.iter().map(|(name, f)| Line {
        text_lhs: name.clone(),
        latex_lhs: latex_name(name),
        meaning: angle_sum(name),
        rust: Some(f.clone()),
    }));
    let entries = body
        .outputs
        .iter()
        .enumerate()
        .map(|(k, f)| {
            let (r, c) = (k / cols, k % cols);
            Line {
                text_lhs: format!("{matrix}[{r}][{c}]"),
                latex_lhs: format!("{}_{{{},{}}}", latex_matrix(matrix), r + 1, c + 1),
                meaning: None,
                rust: Some(f.clone()),
            }
        })
        .collect();
    Section {
        title: title.into(),
        ops: Some(body.ops),
        note: None,
        defs,
        entries,
    }
}

fn latex_matrix(m: &str) -> String {
    match m.strip_prefix('J') {
        Some("t") => "(J_{t})".into(),
        _ => m.into(),
    }
}

/// `s1 = sin(q1)`, `c1 = cos(q1)` for the angles the body reads.
fn inputs(model: &Model, body: &Body) -> Vec<Line> {
    let used = identifiers(body);
    let ring = &model.sym.graph.ring;
    let mut out = Vec::new();
    for a in &model.sym.angles {
        let arg = a.source.text();
        let arg_tex = latex::to_latex(&arg)
            .unwrap_or_else(|_| format!(r"\text{{{}}}", latex::escape_text(&arg)));
        for (var, f) in [(a.vars.0, "sin"), (a.vars.1, "cos")] {
            let name = ring.name(var);
            if used.contains(name) {
                out.push(Line {
                    text_lhs: name.to_string(),
                    latex_lhs: latex_name(name),
                    meaning: Some((
                        format!("{f}({arg})"),
                        format!(r"\{f}\left({arg_tex}\right)"),
                    )),
                    rust: None,
                });
            }
        }
    }
    out
}

/// Identifiers in a body's formulas (those starting with a letter).
fn identifiers(body: &Body) -> BTreeSet<String> {
    body.defs
        .iter()
        .map(|(_, f)| f)
        .chain(&body.outputs)
        .flat_map(|f| kinegen_core::emit::code::identifiers(f))
        .filter(|w| w.starts_with(|c: char| c.is_ascii_alphabetic()))
        .map(String::from)
        .collect()
}

/// The engine names the sine and cosine of a sum of consecutive joint angles after the
/// joints (`c23`; `c1_2_3` with ten or more joints), and `nc23` its negation: spell
/// out which sum.
fn angle_sum(name: &str) -> Option<(String, String)> {
    AngleName::parse(name).map(|n| (n.text(), n.latex()))
}

fn header_text(chain: &Chain) -> String {
    let mut s = format!(
        "{} — {} joints, {}\n",
        chain.name,
        chain.dof(),
        chain.description
    );
    if !chain.params.is_empty() {
        let ps: Vec<String> = chain
            .params
            .iter()
            .map(|p| format!("{} = {}", p.name, p.value))
            .collect();
        let _ = writeln!(s, "parameters: {}", ps.join(", "));
    }
    s
}

/// `19 ops: 8 add, 11 mul, 0 div, 0 neg; 2 sin_cos` (what `show` prints after each
/// section's title, and the report under each section).
pub fn ops_text(o: &OpCount) -> String {
    format!(
        "{} ops: {} add, {} mul, {} div, {} neg; {} sin_cos",
        o.total(),
        o.add,
        o.mul,
        o.div,
        o.neg,
        o.trig
    )
}

fn rhs_text(l: &Line) -> String {
    let mut parts = Vec::new();
    if let Some((m, _)) = &l.meaning {
        parts.push(m.clone());
    }
    if let Some(r) = &l.rust {
        // The engine's formulas always parse; fall back to them verbatim if not.
        parts.push(latex::to_text(r).unwrap_or_else(|_| r.clone()));
    }
    parts.join(" = ")
}

fn render_text(chain: &Chain, sections: &[Section]) -> String {
    let mut s = header_text(chain);
    for sec in sections {
        let _ = write!(s, "\n== {}", sec.title);
        if let Some(o) = &sec.ops {
            let _ = write!(s, "  [{}]", ops_text(o));
        }
        s.push('\n');
        if let Some(n) = &sec.note {
            let _ = writeln!(s, "  {n}");
        }
        if !sec.defs.is_empty() {
            s.push_str("where\n");
            for l in &sec.defs {
                let _ = writeln!(s, "  {} = {}", l.text_lhs, rhs_text(l));
            }
        }
        for l in &sec.entries {
            let _ = writeln!(s, "{} = {}", l.text_lhs, rhs_text(l));
        }
    }
    s
}

fn rhs_latex(l: &Line) -> String {
    let mut parts = Vec::new();
    if let Some((_, m)) = &l.meaning {
        parts.push(m.clone());
    }
    if let Some(r) = &l.rust {
        parts.push(
            latex::to_latex(r).unwrap_or_else(|_| format!(r"\text{{{}}}", latex::escape_text(r))),
        );
    }
    parts.join(" = ")
}

fn render_latex(chain: &Chain, sections: &[Section]) -> String {
    let mut blocks = Vec::new();
    let mut intro = latex::escape_text(header_text(chain).trim_end()).replace('\n', "\\\\\n");
    intro.push_str(r"\\ Indices are 1-based; $s_{i} = \sin q_{i}$, $c_{ij} = \cos(q_{i} + q_{j})$");
    let difference = |l: &Line| {
        AngleName::parse(&l.text_lhs).is_some_and(|n| n.joints.iter().any(|&(_, minus)| minus))
    };
    if sections.iter().flat_map(|s| &s.defs).any(difference) {
        intro.push_str(r", $c_{i-j} = \cos(q_{i} - q_{j})$");
    }
    intro.push('.');
    blocks.push(Block {
        title: intro,
        equations: vec![],
    });
    for sec in sections {
        let mut title = format!(r"\paragraph{{{}}}", latex::escape_text(&sec.title));
        if let Some(o) = &sec.ops {
            let _ = write!(title, " {}.", latex::escape_text(&ops_text(o)));
        }
        if let Some(n) = &sec.note {
            let _ = write!(title, " {}", latex::escape_text(n));
        }
        if !sec.defs.is_empty() {
            blocks.push(Block {
                title: title.clone() + " Where",
                equations: sec
                    .defs
                    .iter()
                    .map(|l| Equation {
                        lhs: l.latex_lhs.clone(),
                        rhs: rhs_latex(l),
                    })
                    .collect(),
            });
            title = String::new();
        }
        blocks.push(Block {
            title,
            equations: sec
                .entries
                .iter()
                .map(|l| Equation {
                    lhs: l.latex_lhs.clone(),
                    rhs: rhs_latex(l),
                })
                .collect(),
        });
    }
    latex::latex_document_body(&chain.name, &blocks)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn angle_sums_are_spelled_out() {
        assert_eq!(angle_sum("c23").unwrap().0, "cos(q2 + q3)");
        assert_eq!(
            angle_sum("s234").unwrap().1,
            r"\sin\left(q_{2} + q_{3} + q_{4}\right)"
        );
        assert_eq!(angle_sum("c1_2_3").unwrap().0, "cos(q1 + q2 + q3)");
        assert_eq!(angle_sum("nc23").unwrap().0, "-cos(q2 + q3)");
        assert_eq!(angle_sum("c2m3").unwrap().0, "cos(q2 - q3)");
        assert_eq!(angle_sum("c1"), None);
        assert_eq!(angle_sum("t12"), None);
        assert_eq!(angle_sum("s_k1"), None);
    }
}
