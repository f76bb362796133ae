//! Straight-line code of some of the engine's nodes, for batches: the engine's register
//! programs (`kinegen_core::kinematics::program`), which keep only the nodes the
//! requested outputs need and give the bits of `Model::eval` (a graph walk with a memo
//! the size of the whole graph, cleared on each call: right for one evaluation, costly
//! for a batch), with scratch registers shared between the module's calls.

use kinegen_core::algebra::graph::Id;
use kinegen_core::kinematics::model::Model;
use kinegen_core::kinematics::program::Program;
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
        self.program.eval(q, regs, &mut out[start..]);
    }
}
