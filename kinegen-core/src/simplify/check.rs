//! The check every rewrite passes before it is used: two expressions are equal when
//! their exact normal forms are (when both are within the term budget), else when their
//! values agree at 16 fixed-seed points (relative 1e-9).

use std::cell::RefCell;

use crate::algebra::graph::{EvalScratch, Graph, Id};
use crate::algebra::poly::VarKind;
use crate::kinematics::frames::SymbolicChain;

/// The check: exact normal forms when both are known, else values at random points.
pub struct Probe {
    points: Vec<Vec<f64>>,
    scratch: RefCell<EvalScratch>,
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
        let points = (0..16)
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
        Probe {
            points,
            scratch: RefCell::default(),
        }
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
        let scratch = &mut *self.scratch.borrow_mut();
        self.points.iter().all(|p| {
            let x = g.eval_in(a, &|v| p[v as usize], scratch);
            let y = g.eval_in(b, &|v| p[v as usize], scratch);
            (x - y).abs() <= 1e-9 * (1.0 + x.abs().max(y.abs()))
        })
    }
}
