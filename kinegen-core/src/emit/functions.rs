//! What the generated type contains: each method's body (straight-line code from
//! [`Coder`]), its doc with the closed form, and the constants — all as values for
//! [`crate::emit::rust`] to print.

use crate::algebra::graph::Id;
use crate::chain::Chain;
use crate::emit::code::{Body, Coder, OpCount};
use crate::emit::docs::{formula_doc_with_math, math_block, matrix_names};
use crate::emit::formulas::{Formulas, MAX_FORMULAS};
use crate::emit::ik::{items as ik_items, CheckImpl, SingularCheck};
pub use crate::emit::item::{Const, Item, Method, MethodBody};
use crate::emit::mathml;
use crate::kinematics::det::closed_form::DetModel;
use crate::kinematics::det::gradient::DetGradient;
use crate::kinematics::det::structural::square_rows;
use crate::kinematics::ik::IkModel;
use crate::kinematics::model::Model;
use crate::kinematics::second_order::SecondOrder;
use crate::model::robot::Scalar;

/// Operation counts of the main outputs.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Stats {
    /// `fk`.
    pub fk: OpCount,
    /// `jacobian`.
    pub jacobian: OpCount,
    /// `jacobian_det`, when it has a closed form.
    pub det: Option<OpCount>,
    /// `hessian`.
    pub hessian: OpCount,
    /// `jacobian_dot`.
    pub jacobian_dot: OpCount,
    /// `jdot_qdot`.
    pub jdot_qdot: OpCount,
    /// `jacobian_ee_dot`.
    pub jacobian_ee_dot: OpCount,
    /// `det_gradient`, when the determinant has a closed form.
    pub det_gradient: Option<OpCount>,
}

/// Everything the generated type holds, ready to print.
#[derive(Clone, Debug)]
pub struct Functions {
    /// The struct's fields: `(name, doc, default value literal)` per parameter.
    pub fields: Vec<(String, String, String)>,
    /// The inherent `impl`'s items, in order.
    pub items: Vec<Item>,
    /// Whether `jacobian_det` exists (closed form or numeric), and for which Jacobian.
    pub det: Option<DetOf>,
    /// Whether `det_gradient` exists.
    pub det_gradient: bool,
    /// Operation counts.
    pub stats: Stats,
    /// Notes for the user (fallbacks taken while emitting).
    pub notes: Vec<String>,
    /// The float type name (`f64`, `f32`).
    pub float: &'static str,
    /// What `FORMULAS` lists, as data.
    pub formulas: Formulas,
    /// The `Check` impl closed-form IK needs, when there is an `ik`.
    pub check: Option<CheckImpl>,
    /// Wall time of emitting the closed-form IK's items, milliseconds (for
    /// `StageTimes::ik_emit_ms`).
    pub ik_emit_ms: f64,
}

/// Which square Jacobian `jacobian_det` takes the determinant of.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DetOf {
    /// The 6×6 world-frame Jacobian of a six-joint arm.
    Full,
    /// The task Jacobian (as many task rows as joints).
    Task,
}

/// The generated type's contents for `chain`, from its simplified `model`, its
/// determinant (`None` when the Jacobian is not square), its second-order outputs, the
/// determinant's gradient and its closed-form IK (`Err`: why none).
pub fn functions(
    chain: &Chain,
    model: &Model,
    det: &Option<Result<DetModel, String>>,
    second: &SecondOrder,
    det_gradient: &Option<Result<DetGradient, String>>,
    ik: &Result<IkModel, String>,
) -> Functions {
    let coder = Coder::new(chain, &model.sym);
    let mut out = Out {
        chain,
        model,
        coder: &coder,
        items: Vec::new(),
        formulas: Formulas::default(),
        stats: Stats::default(),
        notes: Vec::new(),
    };
    out.header();
    out.fk();
    out.frames();
    out.jacobians();
    out.task_jacobian();
    let det_of = out.determinant(det);
    out.second_order(second);
    if let Some(Ok(d)) = det {
        out.det_gradient(d, det_gradient);
    }
    out.manipulability_gradients();
    out.formulas_and_limits();
    let det_gradient = out
        .items
        .iter()
        .any(|i| matches!(i, Item::Method(m) if m.name == "det_gradient"));
    let ik_start = std::time::Instant::now();
    let check = match ik {
        Ok(m) => {
            let singular = match det {
                // An f32 robot's IK solves in f64: its singular factors are evaluated in f64
                // too, so they are tested at the same `SINGULAR_TOLERANCE` as an f64 robot's.
                Some(Ok(d)) if chain.scalar == Scalar::F32 => {
                    let factors: Vec<_> = d.factors.iter().map(|f| f.node).collect();
                    SingularCheck::Widened(Coder::new(chain, &model.sym).in_f64().body(&factors))
                }
                Some(Ok(_)) => SingularCheck::Factors,
                _ => SingularCheck::None,
            };
            let (items, check) = ik_items(chain, m, singular);
            out.items.extend(items);
            Some(check)
        }
        Err(why) if why != crate::kinematics::ik::family::OUT_OF_DOMAIN => {
            out.notes.push(format!(
                "no closed-form inverse kinematics ({why}); the numerical solvers of `kinegen::ik` serve this robot"
            ));
            None
        }
        Err(_) => None,
    };
    let ik_emit_ms = ik_start.elapsed().as_secs_f64() * 1e3;
    let fields = chain
        .params
        .iter()
        .map(|p| {
            let doc = format!("`{}` (default `{}`).", p.name, p.value);
            (p.name.clone(), doc, coder.lit(chain.eval(&p.value)))
        })
        .collect();
    Functions {
        fields,
        items: out.items,
        det: det_of,
        det_gradient,
        stats: out.stats,
        notes: out.notes,
        float: coder.float(),
        formulas: out.formulas,
        check,
        ik_emit_ms,
    }
}

/// The items as they are made.
pub(super) struct Out<'a> {
    pub(super) chain: &'a Chain,
    pub(super) model: &'a Model,
    pub(super) coder: &'a Coder<'a>,
    pub(super) items: Vec<Item>,
    pub(super) formulas: Formulas,
    pub(super) stats: Stats,
    pub(super) notes: Vec<String>,
}

impl Out<'_> {
    pub(super) fn n(&self) -> usize {
        self.chain.dof()
    }

    pub(super) fn f(&self) -> &'static str {
        self.coder.float()
    }

    fn mat4(&self) -> String {
        format!("[[{}; 4]; 4]", self.f())
    }

    pub(super) fn jac(&self) -> String {
        format!("[[{}; {}]; 6]", self.f(), self.n())
    }

    fn konst(&mut self, doc: String, name: &'static str, ty: String, value: String) {
        self.items.push(Item::Const(Const {
            doc,
            name,
            ty,
            value,
        }));
    }

    fn method(&mut self, doc: String, name: &'static str, ret: String, body: Body, result: String) {
        self.method_of(false, doc, name, ret, body, result);
    }

    /// A method with straight-line code; with `rates` it also takes `qd`.
    pub(super) fn method_of(
        &mut self,
        rates: bool,
        doc: String,
        name: &'static str,
        ret: String,
        body: Body,
        result: String,
    ) {
        self.items.push(Item::Method(Method {
            doc,
            name,
            rates,
            ret,
            body: MethodBody::Code { body, result },
        }));
    }

    fn header(&mut self) {
        let n = self.n();
        self.konst(
            "Number of joints.".into(),
            "DOF",
            "usize".into(),
            n.to_string(),
        );
        let name = format!("{:?}", self.chain.name);
        self.konst("Display name.".into(), "NAME", "&'static str".into(), name);
    }

    fn fk(&mut self) {
        let body = self.coder.body(&transform_ids(&self.model.fk_rows));
        let names = matrix_names("T", 3, 4);
        let doc = formula_doc_with_math(
            "Tool pose in the world frame: `base · A1(q1) ⋯ AN(qN) · tool` (row-major 4×4).",
            &body,
            &names,
        );
        self.formulas.add_body("fk", &body, &names);
        self.stats.fk = body.ops;
        let result = transform_literal(self.coder, &body.outputs);
        self.method(doc, "fk", self.mat4(), body, result);
    }

    fn frames(&mut self) {
        let n = self.n();
        let ids: Vec<Id> = self
            .model
            .frame_rows
            .iter()
            .flat_map(transform_ids)
            .collect();
        let body = self.coder.body(&ids);
        let names: Vec<String> = (0..n)
            .flat_map(|i| matrix_names(&format!("T0_{}", i + 1), 3, 4))
            .collect();
        let doc = formula_doc_with_math(
            "Every joint's link frame in the world frame, `base · A1 ⋯ Ai` for i = 1..N (no tool).",
            &body,
            &names,
        );
        let parts: Vec<String> = body
            .outputs
            .chunks(12)
            .map(|c| transform_literal(self.coder, c))
            .collect();
        let result = format!("[{}]", parts.join(", "));
        self.method(
            doc,
            "frames",
            format!("[{}; {n}]", self.mat4()),
            body,
            result,
        );
    }

    fn jacobians(&mut self) {
        let n = self.n();
        let ids: Vec<Id> = self.model.jacobian.iter().flatten().copied().collect();
        let body = self.coder.body(&ids);
        let names = matrix_names("J", 6, n);
        let doc = formula_doc_with_math(
            "Geometric Jacobian of the tool point in the world frame, rows `[vx, vy, vz, ωx, ωy, ωz]`.",
            &body,
            &names,
        );
        self.formulas.add_body("jacobian", &body, &names);
        self.stats.jacobian = body.ops;
        let result = rows_literal(&body.outputs, n);
        self.method(doc, "jacobian", self.jac(), body, result);

        let ids: Vec<Id> = self.model.jacobian_ee.iter().flatten().copied().collect();
        let body = self.coder.body(&ids);
        let doc = formula_doc_with_math(
            "Geometric Jacobian of the tool point expressed in the tool frame, `diag(Rᵀ, Rᵀ) · J`.",
            &body,
            &matrix_names("Jee", 6, n),
        );
        let result = rows_literal(&body.outputs, n);
        self.method(doc, "jacobian_ee", self.jac(), body, result);

        // fk_and_jacobian: one body, everything shared.
        let body = self.coder.body(&self.model.fused);
        let doc = format!(
            "Tool pose and world-frame Jacobian together, sharing their common subexpressions \
             ({} operations, {} `sin_cos`; see [`Self::fk`] and [`Self::jacobian`] for the formulas).",
            body.ops.total(),
            body.ops.trig
        );
        let result = format!(
            "({}, {})",
            transform_literal(self.coder, &body.outputs[..12]),
            rows_literal(&body.outputs[12..], n)
        );
        let ret = format!("({}, {})", self.mat4(), self.jac());
        self.method(doc, "fk_and_jacobian", ret, body, result);
    }

    fn task_jacobian(&mut self) {
        let Some(task) = &self.chain.task else {
            return;
        };
        let n = self.n();
        let ids: Vec<Id> = self.model.task.iter().flatten().copied().collect();
        let body = self.coder.body(&ids);
        let rows: Vec<&str> = task.iter().map(|r| r.name()).collect();
        let names = matrix_names("Jt", task.len(), n);
        let doc = formula_doc_with_math(
            &format!(
                "Task Jacobian: rows `[{}]` of the geometric Jacobian.",
                rows.join(", ")
            ),
            &body,
            &names,
        );
        self.formulas.add_body("task_jacobian", &body, &names);
        let result = rows_literal(&body.outputs, n);
        let ret = format!("[[{}; {n}]; {}]", self.f(), task.len());
        self.method(doc, "task_jacobian", ret, body, result);
    }

    /// `jacobian_det`, `singular_factors` and the `DET`/`SINGULARITIES` constants, or
    /// the numeric LU determinant when the closed form was not produced.
    fn determinant(&mut self, det: &Option<Result<DetModel, String>>) -> Option<DetOf> {
        let rows = square_rows(self.chain)?;
        let n = self.n();
        let full = rows.len() == 6 && n == 6;
        match det {
            Some(Ok(d)) => {
                self.closed_form_det(d);
                Some(if full { DetOf::Full } else { DetOf::Task })
            }
            Some(Err(why)) => {
                self.notes.push(format!(
                    "jacobian_det: {why}; emitted a numeric LU determinant instead"
                ));
                let task_square = self.chain.task.as_ref().is_some_and(|t| t.len() == 6);
                let src = if full && !task_square {
                    "self.jacobian(q)"
                } else {
                    "self.task_jacobian(q)"
                };
                let lu = match self.chain.scalar {
                    Scalar::F64 => "det_lu",
                    Scalar::F32 => "det_lu_f32",
                };
                self.items.push(Item::Method(Method {
                    doc: format!(
                        "Determinant of the square Jacobian, numerically (LU with partial pivoting on a \
                         stack array): the closed form was not produced ({why})."
                    ),
                    name: "jacobian_det",
                    rates: false,
                    ret: self.f().into(),
                    body: MethodBody::Expr(format!("::kinegen::math::{lu}({src})")),
                }));
                Some(if full { DetOf::Full } else { DetOf::Task })
            }
            None => None,
        }
    }

    fn closed_form_det(&mut self, d: &DetModel) {
        let mut ids = vec![d.node];
        ids.extend(d.factors.iter().map(|f| f.node));
        let body = self.coder.body(&ids[..1]);
        self.stats.det = Some(body.ops);
        let which = if d.rows.len() == 6 && self.n() == 6 {
            "the 6×6 geometric Jacobian"
        } else {
            "the task Jacobian"
        };
        let det_math = math_block(&[mathml::equation(
            "<mrow><mi>det</mi><mo>&#x2061;</mo><mi>J</mi></mrow>",
            &[mathml::to_mathml(&d.text).unwrap_or_else(|_| mathml::mtext(&d.text))],
        )]);
        let doc = format!(
            "Determinant of {which}, in closed form:\n\n```text\ndet J = {}\n```\n\n{det_math}\n\n\
             In LaTeX: [`Self::DET_LATEX`].\n\n\
             Rows `[vx vy vz ωx ωy ωz]` (linear velocity of the tool point); the value does not depend on \
             the frame the Jacobian is expressed in nor on the reference point. Signs follow the \
             table's convention and joint offsets. {} operations, {} `sin_cos`.",
            d.text,
            body.ops.total(),
            body.ops.trig
        );
        let result = body.outputs[0].clone();
        self.method(doc, "jacobian_det", self.f().into(), body, result);
        self.formulas.push("jacobian_det", "det", &d.text, &d.latex);
        for (k, x) in d.factors.iter().enumerate() {
            self.formulas
                .push("singular_factors", &format!("f[{k}]"), &x.text, &x.latex);
        }
        let fbody = self.coder.body(&ids[1..]);
        let k = d.factors.len();
        let list: Vec<String> = d
            .factors
            .iter()
            .map(|x| format!("{} = 0", x.text))
            .collect();
        let factor_math: Vec<String> = d
            .factors
            .iter()
            .map(|x| {
                let f = mathml::to_mathml(&x.text).unwrap_or_else(|_| mathml::mtext(&x.text));
                mathml::equation(&f, &["<mn>0</mn>".into()])
            })
            .collect();
        let doc = format!(
            "The factors of `det J` ({k}): the Jacobian is singular exactly where one of them is zero.\n\n```text\n{}\n```\n\n{}",
            list.join("\n"),
            math_block(&factor_math)
        );
        let result = format!("[{}]", fbody.outputs.join(", "));
        let ret = format!("[{}; {k}]", self.f());
        self.method(doc, "singular_factors", ret, fbody, result);
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
        let text = format!("{:?}", d.text);
        self.konst(
            "`det J` as plain text, the closed form [`Self::jacobian_det`] computes.".into(),
            "DET",
            "&'static str".into(),
            text,
        );
        let latex = format!("{:?}", d.latex);
        self.konst(
            "`det J` in LaTeX.".into(),
            "DET_LATEX",
            "&'static str".into(),
            latex,
        );
        self.konst(
            "Singular configurations: where each factor of `det J` vanishes (in the order of \
             [`Self::singular_factors`])."
                .into(),
            "SINGULARITIES",
            "&'static [::kinegen::Singularity]".into(),
            format!("&[{}]", sing.join(", ")),
        );
    }

    fn formulas_and_limits(&mut self) {
        let formulas = format!("&[{}]", self.formulas.rust());
        let mut doc =
            "The closed forms above as data, for people and tools: each function's shared \
             intermediates (`t4`, `c23`, in order) then its outputs (`T[0][3]`, `J[2][1]`, `det`, \
             the singular factors `f[k]`), as plain text and LaTeX."
                .to_string();
        let left_out = self.formulas.left_out();
        if left_out > 0 {
            let (listed, total) = (self.formulas.len(), self.formulas.len() + left_out);
            doc.push_str(&format!(
                "\n\nThe first {listed} of {total}: a constant lists at most {MAX_FORMULAS}; \
                 `kinegen show` prints every one."
            ));
            self.notes.push(format!(
                "`FORMULAS` lists the first {listed} of the chain's {total} formulas (the most a \
                 generated constant lists); `kinegen show` prints every one"
            ));
        }
        self.konst(
            doc,
            "FORMULAS",
            "&'static [::kinegen::Formula]".into(),
            formulas,
        );
        let f = self.f();
        let lims: Vec<String> = self
            .chain
            .links
            .iter()
            .map(|l| match l.limits {
                Some([lo, hi]) => format!("[{}, {}]", self.coder.lit(lo), self.coder.lit(hi)),
                None => format!("[{f}::NEG_INFINITY, {f}::INFINITY]"),
            })
            .collect();
        self.konst(
            "Joint limits `[min, max]` from the table (`±∞` where none is given).".into(),
            "LIMITS",
            format!("[[{f}; 2]; {}]", self.n()),
            format!("[{}]", lims.join(", ")),
        );
    }
}

fn transform_ids(rows: &[[Id; 4]; 3]) -> Vec<Id> {
    rows.iter().flatten().copied().collect()
}

/// `[[r00, r01, r02, p0], …, [0, 0, 0, 1]]` from the 12 entries of the top three rows.
fn transform_literal(coder: &Coder, o: &[String]) -> String {
    let (z, one) = (coder.lit(0.0), coder.lit(1.0));
    format!(
        "[[{}, {}, {}, {}], [{}, {}, {}, {}], [{}, {}, {}, {}], [{z}, {z}, {z}, {one}]]",
        o[0], o[1], o[2], o[3], o[4], o[5], o[6], o[7], o[8], o[9], o[10], o[11]
    )
}

/// `[[row 0], [row 1], …]` of rows of `n` entries.
pub(super) fn rows_literal(o: &[String], n: usize) -> String {
    let rows: Vec<String> = o.chunks(n).map(|r| format!("[{}]", r.join(", "))).collect();
    format!("[{}]", rows.join(", "))
}
