//! Rust emission: the robot type, its methods with their closed forms in the rustdoc,
//! and the `Kinematics` trait implementations.

use std::fmt::Write;

use crate::code::{Body, Coder, OpCount};
use crate::dh::{Robot, Scalar};
use crate::generate::{Deadline, Generated, ItemHeader, Options};
use crate::graph::Id;
use crate::model::Model;
use crate::value::fmt_rat;

pub(crate) fn emit(
    robot: &Robot,
    header: &ItemHeader,
    options: &Options,
    deadline: Deadline,
) -> Generated {
    let mut model = Model::build_until(robot, options, deadline);
    let det = crate::det::square_rows(robot).map(|_| model.determinant(robot));
    let coder = Coder::new(robot, &model.chain);
    let n = robot.dof();
    let f = coder.float();
    let ident = header.ident.to_string();
    let mut notes = model.notes.clone();
    let mut items = String::new();
    let mut formulas = Formulas::default();

    // The struct and its Default.
    let mut fields = String::new();
    let mut defaults = String::new();
    for p in &robot.params {
        let x = robot.eval(&p.value);
        let _ = writeln!(
            fields,
            "/// `{}` (default `{}`).\npub {}: {f},",
            p.name, p.value, p.name
        );
        let _ = writeln!(defaults, "{}: {},", p.name, coder.lit(x));
    }
    let vis = header.vis.to_string();
    let attrs = header.attrs.to_string();
    let summary = struct_doc(robot);
    if robot.params.is_empty() {
        let _ = writeln!(
            items,
            "{attrs}\n{summary}\n#[derive(Clone, Copy, Debug, Default, PartialEq)]\n{vis} struct {ident};"
        );
    } else {
        let _ = writeln!(
            items,
            "{attrs}\n{summary}\n#[derive(Clone, Copy, Debug, PartialEq)]\n{vis} struct {ident} {{\n{fields}}}\n\
             impl ::core::default::Default for {ident} {{\n/// The DH table's values.\nfn default() -> Self {{ Self {{ {defaults} }} }}\n}}"
        );
    }

    let qty = format!("&[{f}; {n}]");
    let mat4 = format!("[[{f}; 4]; 4]");
    let jac = format!("[[{f}; {n}]; 6]");
    let mut methods = String::new();
    let _ = writeln!(
        methods,
        "/// Number of joints.\npub const DOF: usize = {n};\n/// Display name.\npub const NAME: &'static str = {:?};",
        robot.name
    );

    // fk
    let fk_ids = transform_ids(&model.fk_rows);
    let body = coder.body(&fk_ids);
    let doc = formula_doc(
        "Tool pose in the world frame: `base · A1(q1) ⋯ AN(qN) · tool` (row-major 4×4).",
        &body,
        &matrix_names("T", 3, 4),
    );
    method(&mut methods, &doc, "fk", &qty, &mat4, &body, |o| {
        transform_literal(&coder, o)
    });
    formulas.add_body("fk", &body, &matrix_names("T", 3, 4));
    let fk_ops = body.ops;

    // frames
    let mut frame_ids = Vec::new();
    for fr in &model.frame_rows {
        frame_ids.extend(transform_ids(fr));
    }
    let body = coder.body(&frame_ids);
    let mut names = Vec::new();
    for i in 0..n {
        names.extend(matrix_names(&format!("T0_{}", i + 1), 3, 4));
    }
    let doc = formula_doc(
        "Every joint's link frame in the world frame, `base · A1 ⋯ Ai` for i = 1..N (no tool).",
        &body,
        &names,
    );
    method(
        &mut methods,
        &doc,
        "frames",
        &qty,
        &format!("[{mat4}; {n}]"),
        &body,
        |o| {
            let parts: Vec<String> = o.chunks(12).map(|c| transform_literal(&coder, c)).collect();
            format!("[{}]", parts.join(", "))
        },
    );

    // jacobian
    let jac_ids: Vec<Id> = model.jacobian.iter().flatten().copied().collect();
    let body = coder.body(&jac_ids);
    let doc = formula_doc(
        "Geometric Jacobian of the tool point in the world frame, rows `[vx, vy, vz, ωx, ωy, ωz]`.",
        &body,
        &matrix_names("J", 6, n),
    );
    method(&mut methods, &doc, "jacobian", &qty, &jac, &body, |o| {
        rows_literal(o, n)
    });
    formulas.add_body("jacobian", &body, &matrix_names("J", 6, n));
    let jac_ops = body.ops;

    // jacobian_ee
    let ee_ids: Vec<Id> = model.jacobian_ee.iter().flatten().copied().collect();
    let body = coder.body(&ee_ids);
    let doc = formula_doc(
        "Geometric Jacobian of the tool point expressed in the tool frame, `diag(Rᵀ, Rᵀ) · J`.",
        &body,
        &matrix_names("Jee", 6, n),
    );
    method(&mut methods, &doc, "jacobian_ee", &qty, &jac, &body, |o| {
        rows_literal(o, n)
    });

    // fk_and_jacobian: one body, everything shared.
    let body = coder.body(&model.fused);
    let doc = format!(
        "Tool pose and world-frame Jacobian together, sharing their common subexpressions \
         ({} operations, {} `sin_cos`; see [`Self::fk`] and [`Self::jacobian`] for the formulas).",
        body.ops.total(),
        body.ops.trig
    );
    method(
        &mut methods,
        &doc,
        "fk_and_jacobian",
        &qty,
        &format!("({mat4}, {jac})"),
        &body,
        |o| {
            format!(
                "({}, {})",
                transform_literal(&coder, &o[..12]),
                rows_literal(&o[12..], n)
            )
        },
    );

    // task_jacobian
    if let Some(task) = &robot.task {
        let ids: Vec<Id> = model.task.iter().flatten().copied().collect();
        let body = coder.body(&ids);
        let rows: Vec<&str> = task.iter().map(|r| r.name()).collect();
        let doc = formula_doc(
            &format!(
                "Task Jacobian: rows `[{}]` of the geometric Jacobian.",
                rows.join(", ")
            ),
            &body,
            &matrix_names("Jt", task.len(), n),
        );
        method(
            &mut methods,
            &doc,
            "task_jacobian",
            &qty,
            &format!("[[{f}; {n}]; {}]", task.len()),
            &body,
            |o| rows_literal(o, n),
        );
        formulas.add_body("task_jacobian", &body, &matrix_names("Jt", task.len(), n));
    }

    // jacobian_det, singular factors
    let mut det_ops = None;
    let det_rows = crate::det::square_rows(robot);
    match (&det, &det_rows) {
        (Some(Ok(d)), _) => {
            let mut ids = vec![d.node];
            ids.extend(d.factors.iter().map(|f| f.node));
            let body = coder.body(&ids[..1]);
            det_ops = Some(body.ops);
            let which = if d.rows.len() == 6 && robot.dof() == 6 {
                "the 6×6 geometric Jacobian".to_string()
            } else {
                "the task Jacobian".to_string()
            };
            let doc = format!(
                "Determinant of {which}, in closed form:\n\n```text\ndet J = {}\n```\n\n\
                 LaTeX: `{}`\n\n\
                 Rows `[vx vy vz ωx ωy ωz]` (linear velocity of the tool point); the value does not depend on \
                 the frame the Jacobian is expressed in nor on the reference point. Signs follow the \
                 table's convention and joint offsets. {} operations, {} `sin_cos`.",
                d.text,
                d.latex,
                body.ops.total(),
                body.ops.trig
            );
            method(&mut methods, &doc, "jacobian_det", &qty, f, &body, |o| {
                o[0].clone()
            });
            formulas.push("jacobian_det", "det", &d.text, &d.latex);
            for (k, x) in d.factors.iter().enumerate() {
                formulas.push("singular_factors", &format!("f[{k}]"), &x.text, &x.latex);
            }
            let fbody = coder.body(&ids[1..]);
            let k = d.factors.len();
            let list: Vec<String> = d
                .factors
                .iter()
                .map(|x| format!("{} = 0", x.text))
                .collect();
            let doc = format!(
                "The factors of `det J` ({k}): the Jacobian is singular exactly where one of them is zero.\n\n```text\n{}\n```",
                list.join("\n")
            );
            method(
                &mut methods,
                &doc,
                "singular_factors",
                &qty,
                &format!("[{f}; {k}]"),
                &fbody,
                |o| format!("[{}]", o.join(", ")),
            );
            let sing: Vec<String> = d
                .factors
                .iter()
                .map(|x| {
                    format!(
                        "::kinegen::Singularity {{ condition: {:?}, latex: {:?}, joints: &{:?} }}",
                        format!("{} = 0", x.text),
                        format!("{} = 0", x.latex),
                        x.joints
                    )
                })
                .collect();
            let _ = writeln!(
                methods,
                "/// `det J` as text: `{}`.\npub const DET: &'static str = {:?};\n/// `det J` in LaTeX.\npub const DET_LATEX: &'static str = {:?};\n\
                 /// Singular configurations: where each factor of `det J` vanishes (in the order of [`Self::singular_factors`]).\n\
                 pub const SINGULARITIES: &'static [::kinegen::Singularity] = &[{}];",
                d.text,
                d.text,
                d.latex,
                sing.join(", ")
            );
        }
        (Some(Err(why)), Some(rows)) => {
            notes.push(format!(
                "jacobian_det: {why}; emitted a numeric LU determinant instead"
            ));
            let src = if rows.len() == 6
                && robot.dof() == 6
                && robot.task.as_ref().is_none_or(|t| t.len() != 6)
            {
                "self.jacobian(q)"
            } else {
                "self.task_jacobian(q)"
            };
            let lu = if robot.scalar == Scalar::F64 {
                "det_lu"
            } else {
                "det_lu_f32"
            };
            let _ = writeln!(
                methods,
                "/// Determinant of the square Jacobian, numerically (LU with partial pivoting on a \
                 stack array): the closed form was not produced ({why}).\n#[inline]\n#[must_use]\n\
                 pub fn jacobian_det(&self, q: {qty}) -> {f} {{ ::kinegen::math::{lu}({src}) }}"
            );
        }
        _ => {}
    }

    let _ = writeln!(
        methods,
        "/// The closed forms above as data, for people and tools: each function's shared \
         intermediates (`t4`, `c23`, in order) then its outputs (`T[0][3]`, `J[2][1]`, `det`, \
         the singular factors `f[k]`), as plain text and LaTeX.\n\
         pub const FORMULAS: &'static [::kinegen::Formula] = &[{}];",
        formulas.rust()
    );

    // limits
    let lims: Vec<String> = robot
        .joints
        .iter()
        .map(|j| match j.limits {
            Some([lo, hi]) => format!("[{}, {}]", coder.lit(lo), coder.lit(hi)),
            None => format!("[{f}::NEG_INFINITY, {f}::INFINITY]"),
        })
        .collect();
    let _ = writeln!(
        methods,
        "/// Joint limits `[min, max]` from the table (`±∞` where none is given).\npub const LIMITS: [[{f}; 2]; {n}] = [{}];",
        lims.join(", ")
    );

    let _ = writeln!(
        items,
        "#[allow(clippy::all, clippy::pedantic, unused_parens, non_snake_case)]\nimpl {ident} {{\n{methods}}}"
    );

    if robot.scalar == Scalar::F64 {
        let mut tr = format!(
            "impl ::kinegen::Kinematics<{n}> for {ident} {{\n\
             const NAME: &'static str = {:?};\n\
             #[inline] fn fk(&self, q: &[f64; {n}]) -> [[f64; 4]; 4] {{ {ident}::fk(self, q) }}\n\
             #[inline] fn frames(&self, q: &[f64; {n}]) -> [[[f64; 4]; 4]; {n}] {{ {ident}::frames(self, q) }}\n\
             #[inline] fn jacobian(&self, q: &[f64; {n}]) -> [[f64; {n}]; 6] {{ {ident}::jacobian(self, q) }}\n\
             #[inline] fn jacobian_ee(&self, q: &[f64; {n}]) -> [[f64; {n}]; 6] {{ {ident}::jacobian_ee(self, q) }}\n\
             #[inline] fn fk_and_jacobian(&self, q: &[f64; {n}]) -> ([[f64; 4]; 4], [[f64; {n}]; 6]) {{ {ident}::fk_and_jacobian(self, q) }}\n\
             #[inline] fn limits(&self) -> [[f64; 2]; {n}] {{ Self::LIMITS }}\n",
            robot.name
        );
        if det.is_some() && det_rows.as_ref().is_some_and(|r| r.len() == 6 && n == 6) {
            let _ = writeln!(
                tr,
                "#[inline] fn jacobian_det(&self, q: &[f64; {n}]) -> Option<f64> {{ Some({ident}::jacobian_det(self, q)) }}"
            );
        }
        tr.push_str("}\n");
        items.push_str(&tr);
        if let Some(task) = &robot.task {
            let m = task.len();
            let rows: Vec<String> = task.iter().map(|r| r.index().to_string()).collect();
            let _ = writeln!(
                items,
                "impl ::kinegen::TaskKinematics<{n}, {m}> for {ident} {{\n\
                 const TASK_ROWS: [usize; {m}] = [{}];\n\
                 #[inline] fn task_jacobian(&self, q: &[f64; {n}]) -> [[f64; {n}]; {m}] {{ {ident}::task_jacobian(self, q) }}\n{}}}",
                rows.join(", "),
                if det.is_some() && m == n {
                    format!("#[inline] fn task_jacobian_det(&self, q: &[f64; {n}]) -> Option<f64> {{ Some({ident}::jacobian_det(self, q)) }}\n")
                } else {
                    String::new()
                }
            );
        }
    }

    let tokens = match syn::parse_str::<syn::File>(&items) {
        Ok(file) => quote::quote!(#file),
        Err(e) => {
            // An engine bug, never the user's input: report it instead of emitting
            // code that does not parse.
            let msg = format!("kinegen internal error: generated code does not parse: {e}");
            quote::quote!(::core::compile_error!(#msg);)
        }
    };
    Generated {
        tokens,
        notes,
        stats: Stats {
            fk: fk_ops,
            jacobian: jac_ops,
            det: det_ops,
        },
    }
}

/// `(function, name, text, latex)` of every formula, for the `FORMULAS` constant.
#[derive(Default)]
struct Formulas(Vec<[String; 4]>);

impl Formulas {
    fn push(&mut self, function: &str, name: &str, text: &str, latex: &str) {
        self.0
            .push([function.into(), name.into(), text.into(), latex.into()]);
    }

    /// The intermediates and outputs of a body (Rust syntax; LaTeX rendered from it).
    fn add_body(&mut self, function: &str, body: &Body, names: &[String]) {
        let defs = body.defs.iter().map(|(n, e)| (n.as_str(), e.as_str()));
        let outs = names
            .iter()
            .map(String::as_str)
            .zip(body.outputs.iter().map(String::as_str));
        for (name, expr) in defs.chain(outs) {
            let latex = crate::latex::to_latex(expr).unwrap_or_else(|_| expr.to_string());
            self.push(function, name, expr, &latex);
        }
    }

    fn rust(&self) -> String {
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

/// Operation counts of the main outputs.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Stats {
    /// `fk`.
    pub fk: OpCount,
    /// `jacobian`.
    pub jacobian: OpCount,
    /// `jacobian_det`, when it has a closed form.
    pub det: Option<OpCount>,
}

fn struct_doc(robot: &Robot) -> String {
    let mut s = format!(
        "/// {} — {} joints, {} DH, generated by kinegen.\n///\n/// | joint | type | a | α | d | θ |\n/// |---|---|---|---|---|---|\n",
        robot.name,
        robot.dof(),
        match robot.convention {
            crate::dh::Convention::Standard => "standard",
            crate::dh::Convention::Modified => "modified (Craig)",
        }
    );
    for (i, j) in robot.joints.iter().enumerate() {
        let q = format!("q{}", i + 1);
        let (d, th) = match j.kind {
            crate::dh::JointKind::Revolute => (j.d.to_string(), with_var(&q, &j.theta.to_string())),
            crate::dh::JointKind::Prismatic => {
                (with_var(&q, &j.d.to_string()), j.theta.to_string())
            }
        };
        let _ = writeln!(
            s,
            "/// | {} | {:?} | {} | {} | {} | {} |",
            i + 1,
            j.kind,
            j.a,
            j.alpha,
            d,
            th
        );
    }
    s.push_str(
        "///\n/// Joint angles enter as `s_i = sin(q_i)`, `c_i = cos(q_i)`; `s23 = sin(q2 + q3)`.",
    );
    let _ = fmt_rat;
    s
}

fn with_var(q: &str, rest: &str) -> String {
    if rest == "0" {
        q.to_string()
    } else if let Some(r) = rest.strip_prefix('-') {
        format!("{q} - {r}")
    } else {
        format!("{q} + {rest}")
    }
}

fn transform_ids(rows: &[[Id; 4]; 3]) -> Vec<Id> {
    rows.iter().flatten().copied().collect()
}

fn matrix_names(m: &str, rows: usize, cols: usize) -> Vec<String> {
    let mut v = Vec::new();
    for r in 0..rows {
        for c in 0..cols {
            v.push(format!("{m}[{r}][{c}]"));
        }
    }
    v
}

fn transform_literal(coder: &Coder, o: &[String]) -> String {
    let (z, one) = (coder.lit(0.0), coder.lit(1.0));
    format!(
        "[[{}, {}, {}, {}], [{}, {}, {}, {}], [{}, {}, {}, {}], [{z}, {z}, {z}, {one}]]",
        o[0], o[1], o[2], o[3], o[4], o[5], o[6], o[7], o[8], o[9], o[10], o[11]
    )
}

fn rows_literal(o: &[String], n: usize) -> String {
    let rows: Vec<String> = o.chunks(n).map(|r| format!("[{}]", r.join(", "))).collect();
    format!("[{}]", rows.join(", "))
}

fn formula_doc(summary: &str, body: &Body, names: &[String]) -> String {
    let mut s = format!(
        "{summary}\n\nClosed form ({} operations: {} add, {} mul, {} neg; {} `sin_cos`):\n\n```text\n",
        body.ops.total(),
        body.ops.add,
        body.ops.mul,
        body.ops.neg,
        body.ops.trig
    );
    for (n, e) in &body.defs {
        match angle_sum_meaning(n) {
            Some(m) => {
                let _ = writeln!(s, "{n} = {e}    // = {m}");
            }
            None => {
                let _ = writeln!(s, "{n} = {e}");
            }
        }
    }
    for (n, e) in names.iter().zip(&body.outputs) {
        let _ = writeln!(s, "{n} = {e}");
    }
    s.push_str("```");
    s
}

/// `c23` → `cos(q2+q3)`, `s1_2` → `sin(q1+q2)`, `nc23` → `−cos(q2+q3)`: what an
/// angle-sum name means.
fn angle_sum_meaning(name: &str) -> Option<String> {
    if let Some(m) = name.strip_prefix('n').and_then(angle_sum_meaning) {
        return Some(format!("−{m}"));
    }
    let f = match name.chars().next()? {
        's' => "sin",
        'c' => "cos",
        _ => return None,
    };
    let rest = &name[1..];
    if rest.is_empty() || !rest.chars().all(|c| c.is_ascii_digit() || c == '_') {
        return None;
    }
    let joints: Vec<String> = if rest.contains('_') {
        rest.split('_').map(|j| format!("q{j}")).collect()
    } else {
        rest.chars().map(|j| format!("q{j}")).collect()
    };
    (joints.len() >= 2).then(|| format!("{f}({})", joints.join("+")))
}

fn method(
    out: &mut String,
    doc: &str,
    name: &str,
    arg: &str,
    ret: &str,
    body: &Body,
    result: impl Fn(&[String]) -> String,
) {
    for line in doc.lines() {
        let _ = writeln!(out, "///{}{line}", if line.is_empty() { "" } else { " " });
    }
    let _ = writeln!(
        out,
        "#[inline]\n#[must_use]\npub fn {name}(&self, q: {arg}) -> {ret} {{\nlet _ = q;\n{}\n{}\n}}",
        body.lets.join("\n"),
        result(&body.outputs)
    );
}
