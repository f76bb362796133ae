//! Straight-line code of some of the engine's nodes, for batches: the engine's register
//! programs (`kinegen_core::kinematics::program`), which keep only the nodes the
//! requested outputs need (the graph walk of `Model::eval` clears a memo the size of the
//! whole graph on each call: right for one evaluation, costly for a batch).
//!
//! Sines and cosines come from `kinegen::math::sin_cos_n`, as in the generated code; a
//! batch runs [`LANES`] joint vectors side by side ([`Program::eval_lanes`]), each with the
//! bits a single call gives it.

use kinegen_core::algebra::graph::Id;
use kinegen_core::kinematics::model::Model;
use kinegen_core::kinematics::program::{Program, LANES};
use kinegen_core::Chain;

/// The program computing some nodes of a model.
#[derive(Clone, Debug)]
pub struct Tape {
    program: Program,
}

impl Tape {
    /// The tape of `ids` in `model`'s graph (outputs in the order of `ids`).
    pub fn new(model: &Model, chain: &Chain, ids: &[Id]) -> Tape {
        Tape {
            program: Program::new(&model.sym, chain, ids),
        }
    }

    /// Append the outputs' values at `q` to `out`; `regs` is scratch space, reused
    /// (and shared with other tapes: it is reset on each call).
    pub fn eval(&self, q: &[f64], regs: &mut Vec<f64>, out: &mut Vec<f64>) {
        self.program.registers_into(regs);
        let start = out.len();
        out.resize(start + self.program.outputs(), 0.0);
        self.program
            .eval_with(q, regs, &mut out[start..], kinegen::math::sin_cos_n);
    }

    /// Append the outputs of each of `rows` joint vectors (`n` values each, one after
    /// the other in `q`) to `out`, row after row, each laid out by `layout` (`None`: as
    /// they are): `LANES` at a time side by side, the rest one by one, with the same bits
    /// either way.
    pub fn eval_rows(
        &self,
        q: &[f64],
        n: usize,
        rows: usize,
        layout: Option<Layout>,
        out: &mut Vec<f64>,
    ) {
        let k = self.program.outputs();
        let vector = |i: usize| &q[i * n..(i + 1) * n];
        let mut row = Vec::new();
        let put = |row: &[f64], out: &mut Vec<f64>| match layout {
            Some(f) => f(row, out),
            None => out.extend_from_slice(row),
        };
        let full = rows - rows % LANES;
        if full > 0 {
            let mut regs = self.program.lane_registers();
            let mut lanes = vec![[0.0; LANES]; k];
            for first in (0..full).step_by(LANES) {
                let q: [&[f64]; LANES] = core::array::from_fn(|l| vector(first + l));
                kinegen_cli::eval::eval_lanes(&self.program, q, &mut regs, &mut lanes);
                for l in 0..LANES {
                    row.clear();
                    row.extend(lanes.iter().map(|v| v[l]));
                    put(&row, out);
                }
            }
        }
        // The rest one by one, in this thread's registers (no allocation per call).
        SCALAR_REGISTERS.with_borrow_mut(|regs| {
            for i in full..rows {
                if layout.is_none() {
                    self.eval(vector(i), regs, out);
                    continue;
                }
                row.clear();
                self.eval(vector(i), regs, &mut row);
                put(&row, out);
            }
        });
    }
}

std::thread_local! {
    /// Registers of the one-by-one evaluations, reused from call to call on a thread.
    static SCALAR_REGISTERS: std::cell::RefCell<Vec<f64>> = const {
        std::cell::RefCell::new(Vec::new())
    };
}

/// How a row's outputs become the values of the returned array (e.g. a 3×4 transform's
/// rows with `0 0 0 1` after them).
pub type Layout = fn(&[f64], &mut Vec<f64>);
