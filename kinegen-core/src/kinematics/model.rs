//! The symbolic outputs of a chain — forward kinematics, every link frame, the
//! Jacobians — as nodes of one shared graph.
//!
//! [`Model::symbolic`] builds them in one evaluation order (a middle frame or none,
//! [`crate::kinematics::frames::Pivot`]); the simplify stage rewrites their
//! expressions ([`Model::set_ids`]) without changing a value.

use crate::algebra::graph::Id;
use crate::chain::Chain;
use crate::kinematics::frames::SymbolicChain;
use crate::kinematics::jacobian::{self, LocalColumns, Rows};
use crate::kinematics::transform::Transform;
use crate::model::options::Deadline;
use crate::simplify::polish::Report;

/// The symbolic outputs of a robot.
#[derive(Clone, Debug)]
pub struct Model {
    /// The frames and the graph every output lives in.
    pub sym: SymbolicChain,
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
    /// With a middle frame: the Jacobian columns of the joints after it, in its
    /// coordinates, as built (not simplified; see [`LocalColumns`]).
    pub local: Option<LocalColumns>,
    /// The tool pose's 12 entries then the Jacobian's, row-major, for the fused
    /// `fk_and_jacobian` (same values as `fk_rows` and `jacobian`; the sign pass
    /// chooses their signs for the two together).
    pub fused: Vec<Id>,
    /// Notes for the user (budgets hit, fallbacks).
    pub notes: Vec<String>,
    /// What the e-graph polish changed and rejected (filled by the simplify stage).
    pub polish: Report,
}

impl Model {
    /// The outputs of `chain` built with middle frame `pivot` (`None`: none), shared by
    /// value in the graph but not otherwise simplified. The graph keeps normal forms of
    /// up to `max_terms` terms, and none once `deadline` has passed.
    pub fn symbolic(
        chain: &Chain,
        max_terms: usize,
        pivot: Option<usize>,
        deadline: Deadline,
    ) -> Model {
        Model::candidate(chain, max_terms, pivot, deadline).with_tool_frame(chain)
    }

    /// [`Model::symbolic`] without the tool-frame Jacobian (`jacobian_ee` empty): what
    /// the evaluation orders are compared on. The nodes made so far are those of the full
    /// build, in the same order.
    pub fn candidate(
        chain: &Chain,
        max_terms: usize,
        pivot: Option<usize>,
        deadline: Deadline,
    ) -> Model {
        let (mut sym, pivot) = SymbolicChain::build(chain, max_terms, pivot, deadline);
        let fk_rows = sym.tool.rows();
        let frame_rows = sym.frames.iter().map(Transform::rows).collect();
        let (jacobian, local) = jacobian::geometric(chain, &mut sym, pivot.as_ref());
        let jacobian_ee = Vec::new();
        let task = chain
            .task
            .as_ref()
            .map(|t| t.iter().map(|r| jacobian[r.index()].clone()).collect())
            .unwrap_or_default();
        let mut model = Model {
            sym,
            fk_rows,
            frame_rows,
            jacobian,
            jacobian_ee,
            task,
            local,
            fused: Vec::new(),
            notes: Vec::new(),
            polish: Report::default(),
        };
        model.fused = model.fused_ids();
        model
    }

    /// A [`Model::candidate`] completed with the tool-frame Jacobian.
    pub fn with_tool_frame(mut self, chain: &Chain) -> Model {
        self.jacobian_ee = jacobian::tool_frame(chain, &mut self.sym);
        self
    }

    /// The tool pose's ids then the Jacobian's, as `fk_and_jacobian` returns them.
    pub fn fused_ids(&self) -> Vec<Id> {
        let [fk, _, jacobian, _, _] = self.groups();
        [fk, jacobian].concat()
    }

    /// The names of the outputs that have no normal form, as a note's tail
    /// (``" (outputs without a normal form: `fk[0][3]`, …)"``), or nothing.
    pub fn without_normal_form(&self) -> String {
        let g = &self.sym.graph;
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

    /// The name of every id, in the order of [`Model::ids`]: `fk[0][3]`,
    /// `frames[2][1][3]`, `jacobian[2][4]`, `jacobian_ee[0][0]`, `task_jacobian[1][2]`.
    pub fn names(&self) -> Vec<String> {
        let mut v = Vec::new();
        let mut rows = |name: &str, m: &mut dyn Iterator<Item = (usize, usize)>| {
            v.extend(m.map(|(r, c)| format!("`{name}[{r}][{c}]`")));
        };
        let cells =
            |rows: usize, cols: usize| (0..rows).flat_map(move |r| (0..cols).map(move |c| (r, c)));
        rows("fk", &mut cells(3, 4));
        for i in 0..self.frame_rows.len() {
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
    pub fn ids(&self) -> Vec<Id> {
        self.groups().concat()
    }

    /// The ids per generated function — fk, frames (all joints), jacobian,
    /// jacobian_ee, task — each row-major; concatenated they are [`Model::ids`].
    pub fn groups(&self) -> [Vec<Id>; 5] {
        let flat = |m: &[[Id; 4]; 3]| m.iter().flatten().copied().collect::<Vec<Id>>();
        let matrix = |m: &Rows| m.iter().flatten().copied().collect::<Vec<Id>>();
        [
            flat(&self.fk_rows),
            self.frame_rows.iter().flat_map(flat).collect(),
            matrix(&self.jacobian),
            matrix(&self.jacobian_ee),
            matrix(&self.task),
        ]
    }

    /// The outputs replaced by `ids`, in the order of [`Model::ids`] (same values,
    /// other expressions: what the simplify passes hand back).
    pub fn set_ids(&mut self, ids: Vec<Id>) {
        let mut it = ids.into_iter();
        let mut next = || it.next().expect("same shape");
        let fk = self.fk_rows.map(|r| r.map(|_| next()));
        let frames = self
            .frame_rows
            .iter()
            .map(|f| f.map(|r| r.map(|_| next())))
            .collect();
        let [jacobian, jacobian_ee, task] =
            [&self.jacobian, &self.jacobian_ee, &self.task].map(|m| {
                m.iter()
                    .map(|row| row.iter().map(|_| next()).collect())
                    .collect::<Rows>()
            });
        self.fk_rows = fk;
        self.frame_rows = frames;
        self.jacobian = jacobian;
        self.jacobian_ee = jacobian_ee;
        self.task = task;
    }
}

impl Model {
    /// Values of the ring's variables at joint values `q` with the chain's parameters
    /// (see [`SymbolicChain::variables`]).
    pub fn variables(&self, chain: &Chain, q: &[f64]) -> Vec<f64> {
        self.sym.variables(chain, q)
    }

    /// Evaluate nodes at `q`.
    pub fn eval(&self, chain: &Chain, q: &[f64], ids: &[Id]) -> Vec<f64> {
        self.sym.eval(chain, q, ids)
    }

    /// Evaluate nodes at `q` and joint rates `qd` (`None`: rates are NaN; see
    /// [`SymbolicChain::eval_with_rates`]).
    pub fn eval_with_rates(
        &self,
        chain: &Chain,
        q: &[f64],
        qd: Option<&[f64]>,
        ids: &[Id],
    ) -> Vec<f64> {
        self.sym.eval_with_rates(chain, q, qd, ids)
    }
}
