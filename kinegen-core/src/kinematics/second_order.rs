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
use crate::kinematics::hessian::hessian;
use crate::kinematics::jacobian::{columns, from_columns, Column, Rows};
use crate::kinematics::jdot::{jacobian_dot, jacobian_ee_dot, jdot_qdot, jdot_qdot_in};
use crate::kinematics::model::Model;

/// Largest normal form (terms) the Hessian's nodes keep. Measured on UR5 and Panda: 64
/// finds the same zeros as 256 in a third of the time; 16 misses some.
pub const MAX_TERMS: usize = 64;

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
}

impl SecondOrder {
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

/// The second-order outputs of `model`'s Jacobian, added to its graph.
///
/// `J̇ q̇` is formed in the world frame and, when the model has a middle frame, in that
/// frame too (where the columns after it do not depend on the joints before it); the
/// one with fewer operations is kept.
pub fn second_order(chain: &Chain, model: &mut Model) -> SecondOrder {
    let qd = model.sym.rates(chain.dof());
    let cols = columns(&model.jacobian);
    let ee = columns(&model.jacobian_ee);
    let saved = (model.sym.graph.max_terms, model.sym.graph.nf_overflows);
    model.sym.graph.max_terms = saved.0.min(MAX_TERMS);
    let local = model.local.clone().filter(|l| l.k > 0);
    let in_frame = local
        .as_ref()
        .map(|l| (l.all(chain, &mut model.sym), l.frame, l.k));
    let g = &mut model.sym.graph;
    let hessian = hessian(g, &cols);
    g.max_terms = saved.0.min(MAX_RATE_TERMS);
    let jacobian_dot = from_columns(&jacobian_dot(g, &cols, &qd));
    let jacobian_ee_dot = from_columns(&jacobian_ee_dot(g, &ee, &qd));
    // In the middle frame first: built second, it would find the world form's nodes by
    // value and be a mixture of the two.
    let there = in_frame.map(|(cols, frame, k)| (flat(jdot_qdot_in(g, &cols, &frame, &qd)), k));
    let world = flat(jdot_qdot(g, &cols, &qd));
    let (jdot_qdot, jdot_qdot_frame) = match there {
        Some((ids, k)) if g.op_count(&ids) < g.op_count(&world) => (ids, Some(k)),
        _ => (world, None),
    };
    // Normal forms dropped here are dropped by design (see MAX_TERMS): no note.
    (g.max_terms, g.nf_overflows) = saved;
    SecondOrder {
        hessian,
        jacobian_dot,
        jdot_qdot,
        jdot_qdot_frame,
        jacobian_ee_dot,
    }
}

fn flat(c: Column) -> Vec<Id> {
    c.lin.iter().chain(&c.ang).copied().collect()
}
