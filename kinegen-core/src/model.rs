//! Everything the generated code outputs, as nodes of one shared graph.

use crate::chain::{Chain, Transform};
use crate::dh::Robot;
use crate::generate::{Deadline, Options};
use crate::graph::Id;
use crate::jacobian::{self, Rows};

/// The symbolic outputs of a robot.
#[derive(Clone, Debug)]
pub struct Model {
    /// The chain (graph, angles, frames).
    pub chain: Chain,
    /// Top three rows of the tool pose.
    pub fk_rows: [[Id; 4]; 3],
    /// Top three rows of every joint frame.
    pub frame_rows: Vec<[[Id; 4]; 3]>,
    /// World-frame geometric Jacobian.
    pub jacobian: Rows,
    /// Tool-frame geometric Jacobian.
    pub jacobian_ee: Rows,
    /// Task Jacobian rows (empty without task rows).
    pub task: Rows,
    /// The tool pose's 12 entries then the Jacobian's, row-major, for the fused
    /// `fk_and_jacobian` (same values as `fk_rows` and `jacobian`; signs chosen for the
    /// two together).
    pub fused: Vec<Id>,
    /// Notes for the user (budgets hit, fallbacks).
    pub notes: Vec<String>,
    /// What the e-graph polish changed and rejected.
    pub polish: crate::polish::Report,
}

/// Rows `[R | p]` of a transform.
pub fn rows(t: &Transform) -> [[Id; 4]; 3] {
    let mut r = [[0; 4]; 3];
    for (i, row) in r.iter_mut().enumerate() {
        for (j, e) in row.iter_mut().take(3).enumerate() {
            *e = t.r(i, j);
        }
        row[3] = t.p[i];
    }
    r
}

impl Model {
    /// Build the chain and all outputs, choosing the cheapest middle frame.
    ///
    /// The Jacobian is formed with the chain built left to right from the base, and
    /// with the tail of the chain expressed in a middle frame `k` (1 and N−1) (see
    /// [`crate::chain::Pivot`]); the variant whose `fk` and `jacobian` take the fewest
    /// operations after sharing wins (ties: the plain chain, then the smaller `k`).
    /// All variants compute the same values — they are different evaluation orders.
    ///
    /// `options.budget.time_ms` counts from here (see [`Model::build_until`]).
    pub fn build(robot: &Robot, options: &Options) -> Model {
        Model::build_until(robot, options, Deadline::start(&options.budget))
    }

    /// [`Model::build`] within a deadline: past it no further variant is tried and the
    /// chain keeps no new normal forms (correct, less simplified code), with a note. The
    /// model keeps the deadline for [`Model::determinant`].
    pub fn build_until(robot: &Robot, options: &Options, deadline: Deadline) -> Model {
        let n = robot.dof();
        let mut best: Option<(usize, Model)> = None;
        // Candidates: none, frame 1 (a vertical first axis drops out of everything),
        // frame N−1 (the wrist); trying all N costs N chain builds for little gain.
        let mut candidates = vec![None, Some(1)];
        if n > 2 {
            candidates.push(Some(n - 1));
        }
        let total = candidates.len();
        for (tried, pivot) in candidates.into_iter().enumerate() {
            if let Some((_, m)) = best.as_mut().filter(|_| deadline.passed()) {
                m.notes.push(format!(
                    "{} ran out while comparing evaluation orders (middle frames): \
                     kept the best of {tried} of {total}",
                    deadline.describe()
                ));
                break;
            }
            let model = Model::build_with_until(robot, options, pivot, deadline);
            let cost = model.cost(robot);
            if best.as_ref().is_none_or(|(c, _)| cost < *c) {
                best = Some((cost, model));
            }
            if model_overflowed(&best) {
                break;
            }
        }
        best.map(|(_, m)| m).expect("at least one variant")
    }

    /// Operations of `fk` plus `jacobian` after sharing.
    fn cost(&self, robot: &Robot) -> usize {
        let coder = crate::code::Coder::new(robot, &self.chain);
        let fk: Vec<Id> = self.fk_rows.iter().flatten().copied().collect();
        let j: Vec<Id> = self.jacobian.iter().flatten().copied().collect();
        coder.body(&fk).ops.total() + coder.body(&j).ops.total()
    }

    /// Build the chain and all outputs with the given middle frame (`None`: none).
    pub fn build_with(robot: &Robot, options: &Options, pivot: Option<usize>) -> Model {
        Model::build_with_until(robot, options, pivot, Deadline::start(&options.budget))
    }

    /// [`Model::build_with`] within a deadline (see [`Model::build_until`]).
    pub fn build_with_until(
        robot: &Robot,
        options: &Options,
        pivot: Option<usize>,
        deadline: Deadline,
    ) -> Model {
        let (mut chain, pivot) =
            Chain::with_pivot_until(robot, options.budget.max_terms(), pivot, deadline);
        let fk_rows = rows(&chain.tool);
        let frame_rows: Vec<[[Id; 4]; 3]> = chain.frames.iter().map(rows).collect();
        let jacobian = jacobian::geometric(robot, &mut chain, pivot.as_ref());
        let tool = chain.tool;
        let jacobian_ee = jacobian::rotate_into(&mut chain.graph, &tool, &jacobian);
        let task = robot
            .task
            .as_ref()
            .map(|t| t.iter().map(|r| jacobian[r.index()].clone()).collect())
            .unwrap_or_default();
        let out = Outputs {
            fk: fk_rows,
            frames: frame_rows,
            jacobian,
            jacobian_ee,
            task,
        };
        // e-graph polish of every inline expression, checked before use.
        let mut polish = crate::polish::Report::default();
        let ids = crate::polish::polish(
            &mut chain,
            &out.ids(),
            &options.budget,
            &options.extra_rewrites,
            &mut polish,
        );
        let out = out.with_ids(ids);
        let mut notes = polish.notes.clone();
        // Signs chosen for the fewest negations (`signs`), once per generated function:
        // a node the function would compute with both signs would be computed twice,
        // so `frames` is one problem and the fused `fk_and_jacobian` has its own. The
        // pass copies normal forms instead of recomputing them, so check it by value.
        let g = &mut chain.graph;
        let groups = out.groups();
        let signed: Vec<Id> = groups
            .iter()
            .flat_map(|group| crate::signs::assign(g, group))
            .collect();
        let inward = out.with_ids(signed);
        let fused_before = [groups[0].as_slice(), &groups[2]].concat();
        let fused_after = crate::signs::assign(g, &fused_before);
        let probe = crate::polish::Probe::new(&chain);
        let bad = out
            .ids()
            .into_iter()
            .chain(fused_before.iter().copied())
            .zip(inward.ids().into_iter().chain(fused_after.iter().copied()))
            .any(|(b, a)| a != b && !probe.same_values(&chain.graph, a, b));
        let (out, fused) = if bad {
            notes.push(
                "internal check failed after moving signs: the unsimplified expressions are emitted"
                    .into(),
            );
            (out, fused_before)
        } else {
            (inward, fused_after)
        };
        // Outputs whose expression reached a node without normal form have none.
        let lost = out.without_normal_form(&chain.graph);
        let g = &chain.graph;
        if g.nf_overflows > 0 {
            notes.push(format!(
                "{} expressions exceeded the normal-form budget of {} terms: they are shared structurally only{lost}",
                g.nf_overflows, g.max_terms
            ));
        }
        if g.nf_timeouts > 0 {
            notes.push(format!(
                "{} ran out while building normal forms: {} were not computed, and what is built on them is shared structurally only{lost}",
                g.deadline.describe(),
                g.nf_timeouts
            ));
        }
        Model {
            chain,
            fk_rows: out.fk,
            frame_rows: out.frames,
            jacobian: out.jacobian,
            jacobian_ee: out.jacobian_ee,
            task: out.task,
            fused,
            notes,
            polish,
        }
    }
}

/// The model's outputs while they are rewritten, and their ids in one fixed order.
struct Outputs {
    fk: [[Id; 4]; 3],
    frames: Vec<[[Id; 4]; 3]>,
    jacobian: Rows,
    jacobian_ee: Rows,
    task: Rows,
}

impl Outputs {
    /// ` (outputs without a normal form: `fk[0][3]`, `jacobian[2][4]`, …)`, or nothing.
    fn without_normal_form(&self, g: &crate::graph::Graph) -> String {
        const SHOWN: usize = 6;
        let lost: Vec<String> = self
            .names()
            .into_iter()
            .zip(self.ids())
            .filter(|&(_, id)| g.nf(id).is_none())
            .map(|(name, _)| name)
            .collect();
        match lost.len() {
            0 => String::new(),
            k if k <= SHOWN => format!(" (outputs without a normal form: {})", lost.join(", ")),
            k => format!(
                " (outputs without a normal form: {}, … {k} in all)",
                lost[..SHOWN].join(", ")
            ),
        }
    }

    /// The name of every id, in the order of [`Outputs::ids`]: `fk[0][3]`,
    /// `frames[2][1][3]`, `jacobian[2][4]`, `jacobian_ee[0][0]`, `task_jacobian[1][2]`.
    fn names(&self) -> Vec<String> {
        let mut v = Vec::new();
        let mut rows = |name: &str, m: &mut dyn Iterator<Item = (usize, usize)>| {
            v.extend(m.map(|(r, c)| format!("`{name}[{r}][{c}]`")));
        };
        let cells =
            |rows: usize, cols: usize| (0..rows).flat_map(move |r| (0..cols).map(move |c| (r, c)));
        rows("fk", &mut cells(3, 4));
        for i in 0..self.frames.len() {
            rows(&format!("frames[{i}]"), &mut cells(3, 4));
        }
        for (name, m) in [
            ("jacobian", &self.jacobian),
            ("jacobian_ee", &self.jacobian_ee),
            ("task_jacobian", &self.task),
        ] {
            let w = m.first().map_or(0, Vec::len);
            rows(name, &mut cells(m.len(), w));
        }
        v
    }

    /// Every id: fk, frames, jacobian, jacobian_ee, task, row-major.
    fn ids(&self) -> Vec<Id> {
        self.groups().concat()
    }

    /// The ids per generated function — fk, frames (all joints), jacobian,
    /// jacobian_ee, task — each row-major; concatenated they are [`Outputs::ids`].
    fn groups(&self) -> [Vec<Id>; 5] {
        let flat = |m: &[[Id; 4]; 3]| m.iter().flatten().copied().collect::<Vec<Id>>();
        let matrix = |m: &Rows| m.iter().flatten().copied().collect::<Vec<Id>>();
        [
            flat(&self.fk),
            self.frames.iter().flat_map(flat).collect(),
            matrix(&self.jacobian),
            matrix(&self.jacobian_ee),
            matrix(&self.task),
        ]
    }

    /// The same shape filled with `ids`, in the order of [`Outputs::ids`].
    fn with_ids(&self, ids: Vec<Id>) -> Outputs {
        let mut it = ids.into_iter();
        let mut next = || it.next().expect("same shape");
        let fk = self.fk.map(|r| r.map(|_| next()));
        let frames = self
            .frames
            .iter()
            .map(|f| f.map(|r| r.map(|_| next())))
            .collect();
        let [jacobian, jacobian_ee, task] =
            [&self.jacobian, &self.jacobian_ee, &self.task].map(|m| {
                m.iter()
                    .map(|row| row.iter().map(|_| next()).collect())
                    .collect::<Rows>()
            });
        Outputs {
            fk,
            frames,
            jacobian,
            jacobian_ee,
            task,
        }
    }
}

/// Past the normal-form budget the variants are not worth comparing: stop trying.
fn model_overflowed(best: &Option<(usize, Model)>) -> bool {
    best.as_ref()
        .is_some_and(|(_, m)| m.chain.graph.nf_overflows > 0)
}

impl Model {
    /// Values of the ring's variables at joint values `q` with the table's parameters:
    /// what the generated code computes before its first operation. Used to evaluate
    /// the symbolic outputs directly (tests, the CLI's `eval`).
    pub fn variables(&self, robot: &Robot, q: &[f64]) -> Vec<f64> {
        use crate::chain::AngleSource;
        use crate::poly::VarKind;
        let ring = &self.chain.graph.ring;
        let mut vals = vec![f64::NAN; ring.len()];
        for (v, slot) in vals.iter_mut().enumerate() {
            *slot = match ring.kind(v as u32) {
                VarKind::Joint(j) => q[*j],
                VarKind::Param(n) => robot.param_value(n),
                VarKind::Sqrt(k) => (*k as f64).sqrt(),
                VarKind::Sin(_) | VarKind::Cos(_) => continue,
            };
        }
        for a in &self.chain.angles {
            let x = match &a.source {
                AngleSource::Joint { joint, offset } => q[*joint] + robot.eval(offset),
                AngleSource::Constant(v) => robot.eval(v),
            };
            vals[a.vars.0 as usize] = x.sin();
            vals[a.vars.1 as usize] = x.cos();
        }
        vals
    }

    /// Evaluate nodes at `q`.
    pub fn eval(&self, robot: &Robot, q: &[f64], ids: &[Id]) -> Vec<f64> {
        let vals = self.variables(robot, q);
        ids.iter()
            .map(|&id| self.chain.graph.eval(id, &|v| vals[v as usize]))
            .collect()
    }
}

/// Largest determinant (terms summed over its factors) emitted in closed form.
const MAX_FACTOR_TERMS: usize = 64;

/// The closed-form Jacobian determinant and the singular factors it implies.
#[derive(Clone, Debug)]
pub struct DetModel {
    /// Rows of the square Jacobian (indices into `[vx vy vz ωx ωy ωz]`).
    pub rows: Vec<usize>,
    /// `constant · Π factors`.
    pub factored: crate::det::Factored,
    /// Distinct nonconstant factors with multiplicity, their node, text and LaTeX.
    pub factors: Vec<DetFactor>,
    /// The whole determinant.
    pub node: Id,
    /// Plain text: `a2*a3*sin(q3)*sin(q5)*(…)`.
    pub text: String,
    /// LaTeX.
    pub latex: String,
}

/// One factor of a determinant.
#[derive(Clone, Debug)]
pub struct DetFactor {
    /// Normal form.
    pub poly: crate::poly::Poly,
    /// Multiplicity.
    pub power: u32,
    /// Code.
    pub node: Id,
    /// Text (`sin(q3)`, `a2*cos(q2) + a3*cos(q2+q3)`).
    pub text: String,
    /// LaTeX.
    pub latex: String,
    /// Joints (1-based) it depends on.
    pub joints: Vec<usize>,
}

impl Model {
    /// The determinant of the square (task) Jacobian, if there is one and it is
    /// within budget (terms, and the deadline the model was built with); `Err` with
    /// the reason otherwise.
    pub fn determinant(&mut self, robot: &Robot) -> Result<DetModel, String> {
        use crate::det;
        use crate::poly::VarKind;
        use crate::trig;
        use num_traits::Signed;
        let rows = det::square_rows(robot).ok_or("the Jacobian is not square")?;
        let deadline = self.chain.graph.deadline;
        let late = || {
            format!(
                "{} ran out before the closed-form determinant was done",
                deadline.describe()
            )
        };
        let factored = det::determinant(robot, &mut self.chain, &rows).map_err(|e| match e {
            det::DetError::Deadline => late(),
            e => format!("closed-form determinant over budget ({e:?})"),
        })?;
        let size: usize = factored.factors.iter().map(|f| f.len()).sum();
        if size > MAX_FACTOR_TERMS {
            return Err(format!(
                "the closed form has {size} terms in its factors, more than a numeric LU costs"
            ));
        }
        let mut factors = Vec::new();
        let mut factored = factored;
        for (poly, power) in det::powers(&factored.clone()) {
            let mut poly = poly;
            let mut terms = trig::rewrite(&self.chain, &poly);
            // Sign: most terms positive, the first one positive on a tie.
            if let Some(t) = &mut terms {
                let neg = t.iter().filter(|x| x.coef.is_negative()).count();
                if 2 * neg > t.len() || (2 * neg == t.len() && t[0].coef.is_negative()) {
                    for x in t.iter_mut() {
                        x.coef = -x.coef.clone();
                    }
                    poly = poly.neg();
                    if power % 2 == 1 {
                        factored.constant = -factored.constant.clone();
                    }
                    for f in factored.factors.iter_mut() {
                        if *f == poly.neg() {
                            *f = poly.clone();
                        }
                    }
                }
            }
            let (text, latex) = match &terms {
                Some(t) => (trig::text(&self.chain, t), trig::latex(&self.chain, t)),
                None => {
                    let s = self.chain.graph.ring.display(&poly).to_string();
                    (s.clone(), s)
                }
            };
            let g = &mut self.chain.graph;
            let node = match &terms {
                Some(terms) => {
                    let mut acc = Vec::new();
                    for t in terms {
                        let mut x = g.num(t.coef.clone());
                        for &(v, e) in &t.rest {
                            let l = g.leaf(v);
                            for _ in 0..e {
                                x = g.mul(x, l);
                            }
                        }
                        for f in &t.trig {
                            let nf = trig::sum_nf(&g.ring, &self.chain.angles, f);
                            let y = g.from_poly(&nf);
                            x = g.mul(x, y);
                        }
                        acc.push(x);
                    }
                    g.sum(&acc)
                }
                None => g.from_poly(&poly),
            };
            let mut joints: Vec<usize> = poly
                .vars()
                .into_iter()
                .filter_map(|v| match g.ring.kind(v) {
                    VarKind::Sin(a) | VarKind::Cos(a) => match &self.chain.angles[*a].source {
                        crate::chain::AngleSource::Joint { joint, .. } => Some(joint + 1),
                        _ => None,
                    },
                    VarKind::Joint(j) => Some(j + 1),
                    _ => None,
                })
                .collect();
            joints.dedup();
            factors.push(DetFactor {
                poly,
                power,
                node,
                text,
                latex,
                joints,
            });
        }
        // Parameters first, then single sines and cosines, then the larger factors.
        factors.sort_by_key(|f| (!f.joints.is_empty(), f.poly.len(), f.joints.clone()));
        let g = &mut self.chain.graph;
        let mut node = g.num(factored.constant.clone());
        for f in &factors {
            for _ in 0..f.power {
                node = g.mul(node, f.node);
            }
        }
        // Past the deadline the product's nodes may have no normal form to check.
        if g.past_deadline() {
            return Err(late());
        }
        // Check: the emitted product equals the determinant's normal form.
        if let (Some(nf), Ok(expanded)) = (g.nf(node), factored.expand(&g.ring, g.max_terms)) {
            if *nf != expanded {
                return Err("internal check failed: simplified determinant differs".into());
            }
        }
        let (text, latex) = det_text(&factored.constant, &factors);
        Ok(DetModel {
            rows,
            factored,
            factors,
            node,
            text,
            latex,
        })
    }
}

fn det_text(constant: &crate::value::Rat, factors: &[DetFactor]) -> (String, String) {
    use num_traits::{One, Signed};
    let mut text: Vec<String> = Vec::new();
    let mut latex: Vec<String> = Vec::new();
    let neg = constant.is_negative();
    let k = constant.abs();
    if !k.is_one() || factors.is_empty() {
        text.push(crate::value::fmt_rat(&k));
        latex.push(crate::value::fmt_rat(&k));
    }
    for f in factors {
        let single = f.poly.len() == 1;
        let (t, l) = if single {
            (f.text.clone(), f.latex.clone())
        } else {
            (
                format!("({})", f.text),
                format!("\\left({}\\right)", f.latex),
            )
        };
        let (t, l) = if f.power > 1 {
            (format!("{t}^{}", f.power), format!("{l}^{{{}}}", f.power))
        } else {
            (t, l)
        };
        text.push(t);
        latex.push(l);
    }
    let sign = if neg { "-" } else { "" };
    (
        format!("{sign}{}", text.join("*")),
        format!("{sign}{}", latex.join(" \\, ")),
    )
}
