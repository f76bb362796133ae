//! The check every rewrite passes before it is used: two expressions are equal when
//! their exact normal forms are (when both are within the term budget), else when their
//! values agree at 16 fixed-seed points (relative 1e-9).

use std::cell::RefCell;

use crate::algebra::graph::{EvalScratch, Graph, Id};
use crate::algebra::poly::VarKind;
use crate::kinematics::frames::SymbolicChain;

/// The check: exact normal forms when both are known, else values at random points.
///
/// One probe serves one graph as it grows: the values of its nodes at each point are
/// kept between checks, so checking every output of a long chain costs one evaluation
/// of the graph per point, not one per check.
pub struct Probe {
    points: Vec<Vec<f64>>,
    /// Per point, the values of the nodes evaluated so far.
    values: RefCell<Vec<EvalScratch>>,
}

impl Probe {
    /// 16 fixed-seed points for the variables of `sym`.
    pub fn new(sym: &SymbolicChain) -> Self {
        // A fixed-seed generator: the check must not make the output nondeterministic.
        let mut state: u64 = 0x9E37_79B9_7F4A_7C15;
        let mut next = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let ring = &sym.graph.ring;
        let points: Vec<Vec<f64>> = (0..16)
            .map(|_| {
                let mut vals: Vec<f64> = (0..ring.len())
                    .map(|v| match ring.kind(v as u32) {
                        VarKind::Sqrt(k) => (*k as f64).sqrt(),
                        _ => 0.5 + next(),
                    })
                    .collect();
                for a in &sym.angles {
                    let x = (next() - 0.5) * 2.0 * std::f64::consts::PI;
                    vals[a.vars.0 as usize] = x.sin();
                    vals[a.vars.1 as usize] = x.cos();
                }
                vals
            })
            .collect();
        let values = RefCell::new(vec![EvalScratch::default(); points.len()]);
        Probe { points, values }
    }

    /// `a` and `b` are equal: their normal forms, else their values at the points.
    pub fn same(&self, g: &Graph, a: Id, b: Id) -> bool {
        if let (Some(x), Some(y)) = (g.nf(a), g.nf(b)) {
            return x == y;
        }
        self.same_values(g, a, b)
    }

    /// Values agree at every point (for rewrites whose normal forms are not recomputed).
    pub fn same_values(&self, g: &Graph, a: Id, b: Id) -> bool {
        let values = &mut *self.values.borrow_mut();
        self.points.iter().zip(values.iter_mut()).all(|(p, kept)| {
            let x = g.eval_kept(a, &|v| p[v as usize], kept);
            let y = g.eval_kept(b, &|v| p[v as usize], kept);
            (x - y).abs() <= 1e-9 * (1.0 + x.abs().max(y.abs()))
        })
    }
}
