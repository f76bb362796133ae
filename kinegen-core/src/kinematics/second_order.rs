//! The second-order outputs of a model, built on its (simplified) Jacobian's nodes: the
//! Hessian, `J̇`, `J̇ q̇` and the derivative of the tool-frame Jacobian.
//!
//! They are built after the first-order outputs are simplified, so that they share the
//! Jacobian's polished intermediates and leave the first-order code untouched. The normal
//! forms they would carry are products of Jacobian entries (and, with rates, of `q̇_i`):
//! only the small ones are kept ([`MAX_TERMS`], [`MAX_RATE_TERMS`]), enough to find the
//! exact zeros — parallel axes make `ω_j × ω_i` vanish (found by structure: equal axes
//! are one node), intersecting ones `ω_j × v_i` (found by normal form) — without the cost
//! of the large ones, which nothing downstream reads.

use crate::algebra::graph::Id;
use crate::chain::Chain;
use crate::kinematics::frames::SymbolicChain;
use crate::kinematics::hessian::hessian;
use crate::kinematics::jacobian::{
    columns, from_columns, in_frame_columns, Column, LocalColumns, Rows,
};
use crate::kinematics::jdot::{jacobian_dot, jacobian_ee_dot, jdot_qdot, jdot_qdot_in};
use crate::kinematics::model::Model;

/// Largest normal form (terms) the Hessian's nodes keep. Measured on UR5 and Panda: 64
/// finds the same zeros as 256 in a third of the time; 16 misses some.
pub const MAX_TERMS: usize = 64;

/// Largest Hessian (`6·N²` entries) derived in closed form: 20 joints. A longer chain's
/// Hessian would be most of its generated code (a 50-joint chain's 15 000 entries made
/// 8.6 MB of Rust) and most of its expansion time; its second order is computed at run
/// time from the Jacobian's columns instead ([`AtRunTime::TooLarge`]).
pub const MAX_HESSIAN_ENTRIES: usize = 6 * 20 * 20;

/// Largest normal form (terms) the rate-dependent nodes keep: their normal forms carry
/// products of rates, and past 16 terms they found no further zero on UR5 or Panda.
pub const MAX_RATE_TERMS: usize = 16;

/// The second-order outputs, as nodes of the model's graph.
#[derive(Clone, Debug)]
pub struct SecondOrder {
    /// `H[j] = ∂J/∂q_j`, world frame, each 6×N.
    pub hessian: Vec<Rows>,
    /// `J̇`, world frame, 6×N (reads the joint rates).
    pub jacobian_dot: Rows,
    /// `J̇ q̇`, world frame, `[ax ay az αx αy αz]` (reads the joint rates).
    pub jdot_qdot: Vec<Id>,
    /// Where `jdot_qdot` was formed: `None` in the world frame, `Some(k)` in frame `k`.
    pub jdot_qdot_frame: Option<usize>,
    /// `d/dt` of the tool-frame Jacobian, 6×N (reads the joint rates).
    pub jacobian_ee_dot: Rows,
    /// `Some(why)`: not derived (the fields above are empty); the generated methods
    /// compute it at run time from the Jacobian's columns (`kinegen::jacobian_rates`).
    pub at_run_time: Option<AtRunTime>,
}

/// Why a chain's second order is left to run time.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum AtRunTime {
    /// Its Hessian's `6·N²` entries are over [`MAX_HESSIAN_ENTRIES`].
    TooLarge {
        /// `6·N²`.
        entries: usize,
    },
    /// The engine's deadline had passed (its [`crate::Deadline::describe`]).
    Deadline(String),
}

impl std::fmt::Display for AtRunTime {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            AtRunTime::TooLarge { entries } => write!(
                f,
                "its Hessian's {entries} entries are over the {MAX_HESSIAN_ENTRIES} derived in closed form"
            ),
            AtRunTime::Deadline(budget) => {
                write!(f, "{budget} ran out before the second order was derived")
            }
        }
    }
}

impl SecondOrder {
    /// Second order left to run time, for the reason `why`.
    pub fn at_run_time(why: AtRunTime) -> Self {
        SecondOrder {
            hessian: Vec::new(),
            jacobian_dot: Vec::new(),
            jdot_qdot: Vec::new(),
            jdot_qdot_frame: None,
            jacobian_ee_dot: Vec::new(),
            at_run_time: Some(why),
        }
    }

    /// The ids per generated function — hessian (`H[j]` row-major, j = 1..N),
    /// jacobian_dot, jdot_qdot, jacobian_ee_dot.
    pub fn groups(&self) -> [Vec<Id>; 4] {
        let matrix = |m: &Rows| m.iter().flatten().copied().collect::<Vec<Id>>();
        [
            self.hessian.iter().flat_map(matrix).collect(),
            matrix(&self.jacobian_dot),
            self.jdot_qdot.clone(),
            matrix(&self.jacobian_ee_dot),
        ]
    }

    /// The outputs replaced by `ids`, in the order of [`SecondOrder::groups`]
    /// concatenated (same values, other expressions).
    pub fn set_ids(&mut self, ids: &[Id]) {
        let mut it = ids.iter().copied();
        let mut next = || it.next().expect("same shape");
        let mut rows = |m: &Rows| -> Rows {
            m.iter()
                .map(|r| r.iter().map(|_| next()).collect())
                .collect()
        };
        self.hessian = self.hessian.iter().map(&mut rows).collect();
        self.jacobian_dot = rows(&self.jacobian_dot);
        self.jdot_qdot = rows(&vec![self.jdot_qdot.clone()]).concat();
        self.jacobian_ee_dot = rows(&self.jacobian_ee_dot);
    }
}

/// The second-order outputs of `model`'s Jacobian, added to its graph — or left to run
/// time ([`SecondOrder::at_run_time`]) when the Hessian is larger than
/// [`MAX_HESSIAN_ENTRIES`] or the engine's deadline passes before it is built.
///
/// `J̇ q̇` is a sum of cross products, so it can be formed in any frame and rotated out
/// once: in the world frame, in the model's middle frame (where the columns after it do
/// not depend on the joints before it), or in one of the two link frames in the middle of
/// the chain (each half of a 7-joint arm short: the Panda's 341 operations become 288).
/// Each candidate is built in a scratch copy of the graph and counted, one copy at a time;
/// the cheapest is then built in the model's graph, so the others leave no nodes behind.
pub fn second_order(chain: &Chain, model: &mut Model) -> SecondOrder {
    let n = chain.dof();
    if 6 * n * n > MAX_HESSIAN_ENTRIES {
        return SecondOrder::at_run_time(AtRunTime::TooLarge { entries: 6 * n * n });
    }
    let deadline = model.sym.graph.deadline;
    let past = |model: &mut Model| model.sym.graph.past_deadline();
    if past(model) {
        return SecondOrder::at_run_time(AtRunTime::Deadline(deadline.describe()));
    }
    let qd = model.sym.rates(n);
    let cols = columns(&model.jacobian);
    let ee = columns(&model.jacobian_ee);
    let saved = (model.sym.graph.max_terms, model.sym.graph.nf_overflows);
    model.sym.graph.max_terms = saved.0.min(MAX_TERMS);
    let hessian = hessian(&mut model.sym.graph, &cols);
    let g = &mut model.sym.graph;
    g.max_terms = saved.0.min(MAX_RATE_TERMS);
    let jacobian_dot = from_columns(&jacobian_dot(g, &cols, &qd));
    let jacobian_ee_dot = from_columns(&jacobian_ee_dot(g, &ee, &qd));
    let mut others = Vec::new();
    if let Some(l) = model.local.clone().filter(|l| l.k > 0) {
        others.push(JdotFrame::Pivot(l));
    }
    if n >= 4 {
        others.extend([n / 2 - 1, n / 2].map(JdotFrame::Link));
    }
    // Alone, or past the deadline, the world frame is built without a copy.
    let cost = |sym: &SymbolicChain, c: &JdotFrame| {
        let mut scratch = sym.clone();
        let ids = c.build(chain, &mut scratch, &cols, &qd);
        scratch.graph.op_count(&ids)
    };
    let mut best = (JdotFrame::World, usize::MAX);
    if !others.is_empty() && !past(model) {
        best.1 = cost(&model.sym, &JdotFrame::World);
        for c in others {
            if past(model) {
                break;
            }
            // Ties to the earlier (the world frame first).
            let k = cost(&model.sym, &c);
            if k < best.1 {
                best = (c, k);
            }
        }
    }
    let jdot_qdot = best.0.build(chain, &mut model.sym, &cols, &qd);
    // Normal forms dropped here are dropped by design (see MAX_TERMS): no note.
    let g = &mut model.sym.graph;
    (g.max_terms, g.nf_overflows) = saved;
    SecondOrder {
        hessian,
        jacobian_dot,
        jdot_qdot,
        jdot_qdot_frame: best.0.link(),
        jacobian_ee_dot,
        at_run_time: None,
    }
}

/// A frame `J̇ q̇` may be formed in.
enum JdotFrame {
    World,
    /// The model's middle frame, from its local columns.
    Pivot(LocalColumns),
    /// Link frame `frames[k]` (0-based), seen directly.
    Link(usize),
}

impl JdotFrame {
    /// `J̇ q̇` formed in this frame and rotated into the world frame, in `sym`'s graph.
    fn build(
        &self,
        chain: &Chain,
        sym: &mut SymbolicChain,
        world: &[Column],
        qd: &[Id],
    ) -> Vec<Id> {
        match self {
            JdotFrame::World => flat(jdot_qdot(&mut sym.graph, world, qd)),
            JdotFrame::Pivot(l) => {
                let cols = l.all(chain, sym);
                flat(jdot_qdot_in(&mut sym.graph, &cols, &l.frame, qd))
            }
            &JdotFrame::Link(k) => {
                let cols = in_frame_columns(chain, sym, k);
                let frame = sym.frames[k];
                flat(jdot_qdot_in(&mut sym.graph, &cols, &frame, qd))
            }
        }
    }

    /// The link whose frame it is (1-based: `base · A1 ⋯ Ak`), `None` for the world.
    fn link(&self) -> Option<usize> {
        match self {
            JdotFrame::World => None,
            JdotFrame::Pivot(l) => Some(l.k),
            JdotFrame::Link(k) => Some(k + 1),
        }
    }
}

fn flat(c: Column) -> Vec<Id> {
    c.lin.iter().chain(&c.ang).copied().collect()
}
