//! The generated type's second-order methods — `hessian`, `jacobian_dot`, `jdot_qdot`,
//! `jacobian_ee_dot`, `det_gradient`, `singular_factor_gradients`,
//! `manipulability_gradient`, `manipulability_task_gradient` — each body from
//! [`crate::emit::code::Coder`], each doc with its closed form, formulas into `FORMULAS`.

use crate::algebra::graph::Id;
use crate::emit::code::Body;
use crate::emit::docs::{formula_doc_with_math, matrix_names};
use crate::emit::functions::{rows_literal, Item, Method, MethodBody, Out};
use crate::kinematics::det::closed_form::DetModel;
use crate::kinematics::det::gradient::DetGradient;
use crate::kinematics::second_order::{AtRunTime, SecondOrder};
use crate::model::robot::Scalar;

const HESSIAN: &str = "Kinematic Hessian of the world-frame Jacobian: `H[j] = ∂J/∂q_j` for every \
joint j, indexed `H[j][row][column]` (rows `[vx, vy, vz, ωx, ωy, ωz]`), the layout of the Robotics \
Toolbox's `hessian0`. From the Jacobian's columns `J_i = [v_i; ω_i]` (`ω_i = 0` for a prismatic \
joint): `∂J_i/∂q_j = [ω_j × v_i; ω_j × ω_i]` for j ≤ i and `[ω_i × v_j; 0]` for j > i. The linear \
rows are symmetric, `H[j][r][i] == H[i][r][j]` for r < 3 (one expression serves both); the \
angular rows are zero for j > i. `Σ_j H[j]·q̇_j` is [`Self::jacobian_dot`].";

const JACOBIAN_DOT: &str = "Time derivative of the world-frame Jacobian along the joint rates \
`qd`: `J̇ = Σ_j H[j]·q̇_j`, column i `[W_i × v_i + ω_i × R_i; W_i × ω_i]` with `W_i = Σ_(k≤i) \
ω_k·q̇_k` (the angular velocity of link i) and `R_i = Σ_(k>i) v_k·q̇_k` (the tool point's velocity \
due to the joints after i).";

const JEE_DOT: &str = "Time derivative of [`Self::jacobian_ee`] (the Jacobian in the tool frame) \
along the joint rates `qd`: `d/dt (diag(Rᵀ, Rᵀ)·J) = diag(Rᵀ, Rᵀ)·(J̇ − diag([Ω]×, [Ω]×)·J)` with \
`Ω` the tool frame's angular velocity; column i is `[ω_i × R_i + v_i × Ω_i⁺; ω_i × Ω_i⁺]` in \
tool-frame vectors (the columns of `jacobian_ee`), `R_i = Σ_(k>i) v_k·q̇_k`, `Ω_i⁺ = Σ_(k>i) \
ω_k·q̇_k`. Not `diag(Rᵀ, Rᵀ)·J̇` — what the Robotics Toolbox's `hessiane` contracts with `q̇` to — \
which leaves out the rotation of the tool frame itself.";

const JDOT_QDOT: &str = "Bias acceleration `J̇(q, q̇)·q̇` in the world frame, `[ax, ay, az, αx, αy, \
αz]`: the acceleration of the tool point and the angular acceleration of the tool frame at `q̈ = 0`, \
so that `ẍ = J·q̈ + J̇·q̇`.";

impl Out<'_> {
    /// `hessian`, `jacobian_dot`, `jdot_qdot`, `jacobian_ee_dot`.
    pub(super) fn second_order(&mut self, s: &SecondOrder) {
        if let Some(why) = &s.at_run_time {
            return self.second_order_at_run_time(why);
        }
        let n = self.n();
        let [hessian, jdot, jdot_qdot, jee_dot] = s.groups();
        let names: Vec<String> = (0..n)
            .flat_map(|j| matrix_names(&format!("H[{j}]"), 6, n))
            .collect();
        let body = self.coder.body(&hessian);
        // The lower triangle j ≤ i only: the rest is its mirror image or zero.
        let lower = |k: usize| (k / (6 * n)) <= (k % n);
        let (listed, listed_names) = self.listed(&body, &names, lower);
        let doc = formula_doc_with_math(
            &format!("{HESSIAN}\n\nListed: `H[j][r][i]` for j ≤ i where it is not 0."),
            &listed,
            &listed_names,
        );
        self.formulas.add_body("hessian", &listed, &listed_names);
        self.stats.hessian = body.ops;
        let result = hessian_literal(&body.outputs, n);
        let ret = format!("[{}; {n}]", self.jac());
        self.method_of(false, doc, "hessian", ret, body, result);

        for (name, ids, summary, short) in [
            ("jacobian_dot", &jdot, JACOBIAN_DOT, "Jdot"),
            ("jacobian_ee_dot", &jee_dot, JEE_DOT, "Jee_dot"),
        ] {
            let body = self.coder.body(ids);
            let names = matrix_names(short, 6, n);
            let (listed, listed_names) = self.listed(&body, &names, |_| true);
            let doc = formula_doc_with_math(
                &format!("{summary}\n\nListed where not 0."),
                &listed,
                &listed_names,
            );
            self.formulas.add_body(name, &listed, &listed_names);
            if name == "jacobian_dot" {
                self.stats.jacobian_dot = body.ops;
            } else {
                self.stats.jacobian_ee_dot = body.ops;
            }
            let result = rows_literal(&body.outputs, n);
            self.method_of(true, doc, name, self.jac(), body, result);
        }

        let body = self.coder.body(&jdot_qdot);
        let frame = match s.jdot_qdot_frame {
            Some(k) => format!(
                " Formed in link {k}'s frame (where the columns of the joints after it do not \
                 depend on the joints before it) and rotated into the world frame once."
            ),
            None => String::new(),
        };
        let summary = format!(
            "{JDOT_QDOT} Accumulated over the joints without forming `J̇` \
             (velocity and acceleration propagation): `[Σ_i (W_(i−1) + W_i) × u_i; Σ_i W_(i−1) × \
             w_i]` with `w_i = ω_i·q̇_i`, `u_i = v_i·q̇_i` (column i of the Jacobian times its \
             rate) and `W_i = w_1 + ⋯ + w_i`.{frame}"
        );
        let names: Vec<String> = (0..6).map(|r| format!("Jdot_qdot[{r}]")).collect();
        let (listed, listed_names) = self.listed(&body, &names, |_| true);
        let doc = formula_doc_with_math(&summary, &listed, &listed_names);
        self.formulas.add_body("jdot_qdot", &listed, &listed_names);
        self.stats.jdot_qdot = body.ops;
        let result = format!("[{}]", body.outputs.join(", "));
        let ret = format!("[{}; 6]", self.f());
        self.method_of(true, doc, "jdot_qdot", ret, body, result);
    }

    /// The four second-order methods as calls of `kinegen::jacobian_rates` on the
    /// generated Jacobians: the same formulas, evaluated at run time, for a chain whose
    /// second order was not derived (`why`).
    fn second_order_at_run_time(&mut self, why: &AtRunTime) {
        let n = self.n();
        // A chain too long for closed forms is a design choice, said in the docs; a
        // deadline is a note (a compiler warning).
        if matches!(why, AtRunTime::Deadline(_)) {
            self.notes.push(format!(
                "second order: {why}; `hessian`, `jacobian_dot`, `jdot_qdot` and `jacobian_ee_dot` \
                 compute it at run time from the Jacobian's columns"
            ));
        }
        let how = format!(
            "\n\nNot derived in closed form for this robot ({why}): computed at run time from \
             the Jacobian's columns by `kinegen::jacobian_rates`, the same formulas."
        );
        let rt = "::kinegen::jacobian_rates";
        let methods = [
            (
                HESSIAN,
                "hessian",
                false,
                format!("[{}; {n}]", self.jac()),
                format!("{rt}::hessian(&self.jacobian(q))"),
            ),
            (
                JACOBIAN_DOT,
                "jacobian_dot",
                true,
                self.jac(),
                format!("{rt}::jacobian_dot(&self.jacobian(q), qd)"),
            ),
            (
                JDOT_QDOT,
                "jdot_qdot",
                true,
                format!("[{}; 6]", self.f()),
                format!("{rt}::jdot_qdot(&self.jacobian(q), qd)"),
            ),
            (
                JEE_DOT,
                "jacobian_ee_dot",
                true,
                self.jac(),
                format!("{rt}::jacobian_ee_dot(&self.jacobian_ee(q), qd)"),
            ),
        ];
        for (summary, name, rates, ret, expr) in methods {
            self.items.push(Item::Method(Method {
                doc: format!("{summary}{how}"),
                name,
                rates,
                ret,
                body: MethodBody::Expr(expr),
            }));
        }
    }

    /// `det_gradient` and `singular_factor_gradients` (or a note why not).
    pub(super) fn det_gradient(
        &mut self,
        det: &DetModel,
        gradient: &Option<Result<DetGradient, String>>,
    ) {
        let g = match gradient {
            Some(Ok(g)) => g,
            Some(Err(why)) => {
                self.notes
                    .push(format!("det_gradient: {why}; not generated"));
                return;
            }
            None => return,
        };
        let n = self.n();
        let body = self.coder.body(&g.gradient);
        let all: Vec<String> = (0..n).map(|j| format!("ddet[{j}]")).collect();
        let (listed, names) = self.listed(&body, &all, |_| true);
        let summary = format!(
            "Gradient of [`Self::jacobian_det`], `∂det/∂q_j` for j = 1..N, by exact \
             differentiation of its factored closed form `det J = {}`: the product rule over the \
             factors `f_k` of [`Self::singular_factors`], `∂det/∂q_j = C·Σ_k p_k·f_k^(p_k−1)·\
             ∂f_k/∂q_j·Π_(l≠k) f_l^(p_l)`, with `∂f_k/∂q_j` from [`Self::singular_factor_gradients`] \
             (nothing is divided by a factor that may vanish). Checked against the derivative of \
             the expanded determinant.",
            det.text
        );
        let doc = formula_doc_with_math(&summary, &listed, &names);
        self.formulas.add_body("det_gradient", &listed, &names);
        self.stats.det_gradient = Some(body.ops);
        let result = format!("[{}]", body.outputs.join(", "));
        let ret = format!("[{}; {n}]", self.f());
        self.method_of(false, doc, "det_gradient", ret, body, result);

        let k = g.factors.len();
        let ids: Vec<Id> = g.factors.iter().flatten().copied().collect();
        let body = self.coder.body(&ids);
        let mut list = Vec::new();
        for (i, (f, texts)) in det.factors.iter().zip(&g.texts).enumerate() {
            for (j, (text, latex)) in texts.iter().enumerate() {
                if text != "0" {
                    let name = format!("df[{i}][{j}]");
                    self.formulas
                        .push("singular_factor_gradients", &name, text, latex);
                    list.push(format!("∂({})/∂q{} = {text}", f.text, j + 1));
                }
            }
        }
        let doc = format!(
            "Gradients of the factors of `det J` ([`Self::singular_factors`], in their order): \
             `df[k][j] = ∂f_k/∂q_j`, by exact differentiation (`∂sin q/∂q = cos q`, \
             `∂cos q/∂q = −sin q`, a flipped joint's angle `−q` turning the signs). A controller \
             that climbs `f_k²` moves away from one singular family only. Listed where not 0.\n\n\
             ```text\n{}\n```\n\n{} operations, {} `sin_cos`.",
            list.join("\n"),
            body.ops.total(),
            body.ops.trig
        );
        let rows: Vec<String> = body
            .outputs
            .chunks(n)
            .map(|r| format!("[{}]", r.join(", ")))
            .collect();
        let result = format!("[{}]", rows.join(", "));
        let ret = format!("[[{}; {n}]; {k}]", self.f());
        self.method_of(false, doc, "singular_factor_gradients", ret, body, result);
    }

    /// `manipulability_gradient` (full Jacobian) and, with task rows,
    /// `manipulability_task_gradient`: the generated `jacobian` and `hessian` handed to
    /// the runtime's stack-only SVD (the SVD costs far more than computing the sines and
    /// cosines twice, and the code stays small).
    pub(super) fn manipulability_gradients(&mut self) {
        let n = self.n();
        let measure = "Yoshikawa's manipulability `m = √det(J Jᵀ)` of the world-frame Jacobian \
                       (`kinegen::manipulability::manipulability`, the Robotics Toolbox's \
                       `manipulability(q)`)";
        if n < 6 {
            // J Jᵀ (6×6) has rank ≤ N < 6: m is identically 0.
            let doc = format!(
                "Gradient of {measure}: with {n} joints `J Jᵀ` has rank ≤ {n} < 6, so `m` is \
                 identically 0 and so is its gradient.{}",
                if self.chain.task.is_some() {
                    " The measure to climb is the task rows' one, \
                     [`Self::manipulability_task_gradient`]."
                } else {
                    ""
                }
            );
            self.expr_method(
                doc,
                "manipulability_gradient",
                format!("let _ = q; [0.0; {n}]"),
            );
        } else {
            let doc = format!(
                "Gradient of {measure}: `∂m/∂q_j = m·tr(J⁺·H[j])`, from [`Self::jacobian`] and \
                 [`Self::hessian`] and the stack-only SVD of \
                 `kinegen::manipulability::manipulability_gradient`. At a singular configuration \
                 (m = 0) m is not differentiable and the result is 0, the least element of its \
                 generalised gradient. NaN for non-finite `q`."
            );
            let call = self.gradient_call("&self.jacobian(q)", "&self.hessian(q)");
            self.expr_method(doc, "manipulability_gradient", call);
        }
        let Some(task) = &self.chain.task else {
            return;
        };
        let rows: Vec<String> = task.iter().map(|r| format!("h[{}]", r.index())).collect();
        let names: Vec<&str> = task.iter().map(|r| r.name()).collect();
        let doc = format!(
            "Gradient of the task manipulability `m = √det(Jt Jtᵀ)` of [`Self::task_jacobian`] \
             `Jt` (rows `[{}]`; identically 0, and so its gradient, when it has more rows than joints): `∂m/∂q_j = \
             m·tr(Jt⁺·Ht[j])` with `Ht[j]` the same rows of [`Self::hessian`]. At a singular \
             configuration (m = 0) the result is 0, the least element of the generalised \
             gradient. NaN for non-finite `q`.",
            names.join(", ")
        );
        let h = format!("&self.hessian(q).map(|h| [{}])", rows.join(", "));
        let call = self.gradient_call("&self.task_jacobian(q)", &h);
        self.expr_method(doc, "manipulability_task_gradient", call);
    }

    /// The runtime's manipulability gradient of `j` and `h`, NaN where it refuses.
    fn gradient_call(&self, j: &str, h: &str) -> String {
        let (helper, f) = match self.chain.scalar {
            Scalar::F64 => ("manipulability_gradient", "f64"),
            Scalar::F32 => ("manipulability_gradient_f32", "f32"),
        };
        format!(
            "match ::kinegen::manipulability::{helper}({j}, {h}) {{ Ok(g) => g, Err(_) => [{f}::NAN; {}] }}",
            self.n()
        )
    }

    /// A method `fn name(&self, q) -> [F; N] { expr }`.
    fn expr_method(&mut self, doc: String, name: &'static str, expr: String) {
        let ret = format!("[{}; {}]", self.f(), self.n());
        self.items.push(Item::Method(Method {
            doc,
            name,
            rates: false,
            ret,
            body: MethodBody::Expr(expr),
        }));
    }

    /// The outputs of `body` (and their `names`) that docs and `FORMULAS` list: those
    /// with `keep(index)` that are not the literal 0.
    fn listed(
        &self,
        body: &Body,
        names: &[String],
        keep: impl Fn(usize) -> bool,
    ) -> (Body, Vec<String>) {
        let zero = self.coder.lit(0.0);
        let (outputs, names): (Vec<String>, Vec<String>) = body
            .outputs
            .iter()
            .zip(names)
            .enumerate()
            .filter(|(k, (e, _))| keep(*k) && **e != zero)
            .map(|(_, (e, n))| (e.clone(), n.clone()))
            .unzip();
        let listed = Body {
            lets: Vec::new(),
            outputs,
            defs: body.defs.clone(),
            ops: body.ops,
        };
        (listed, names)
    }
}

/// `[H[0], …, H[N−1]]` from the outputs, each `H[j]` 6×N row-major.
fn hessian_literal(o: &[String], n: usize) -> String {
    let parts: Vec<String> = o.chunks(6 * n).map(|c| rows_literal(c, n)).collect();
    format!("[{}]", parts.join(", "))
}
