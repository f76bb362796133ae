//! Straight-line code of some of the engine's nodes as a flat instruction list.
//!
//! `Model::eval` walks the graph with a memo the size of the whole graph (every output
//! the engine derived), cleared on each call: right for one evaluation, costly for a
//! batch. A [`Tape`] keeps only the nodes the requested outputs need, in dependency
//! order, one register each, so an evaluation is one pass over a few dozen operations
//! with no allocation. Each register applies the node's own operation to the same
//! operands, so the values are bit for bit those of `Model::eval` (the tests compare).

use kinegen_core::algebra::angles::AngleSource;
use kinegen_core::algebra::graph::{Id, Node};
use kinegen_core::algebra::poly::VarKind;
use kinegen_core::kinematics::model::Model;
use kinegen_core::model::value::rat_to_f64;
use kinegen_core::Chain;

/// One instruction: its result goes to the register of its own index.
#[derive(Clone, Copy, Debug)]
enum Op {
    Const(f64),
    /// The value of ring variable `v` (a joint's sine, a parameter, …).
    Var(u32),
    Add(u32, u32),
    Sub(u32, u32),
    Mul(u32, u32),
    Neg(u32),
}

/// The instructions computing some nodes, and which registers hold them.
///
/// Registers `0..init.len()` hold the ring's variables (set before the instructions
/// run), the instructions' results follow.
#[derive(Clone, Debug)]
pub struct Tape {
    ops: Vec<Op>,
    outputs: Vec<u32>,
    /// The variables' values that do not depend on q (parameters, square roots, sines of
    /// constant angles); NaN for the others (a joint rate stays NaN, as in `Model::eval`).
    init: Vec<f64>,
    /// `(variable, joint)`: a prismatic joint's value.
    joints: Vec<(u32, usize)>,
    /// `(sin variable, cos variable, joint, sign, offset)`: `sin_cos(sign·q + offset)`.
    angles: Vec<(u32, u32, usize, f64, f64)>,
}

impl Tape {
    /// The tape of `ids` in `model`'s graph (outputs in the order of `ids`).
    pub fn new(model: &Model, chain: &Chain, ids: &[Id]) -> Tape {
        let graph = &model.sym.graph;
        let ring = &graph.ring;
        let nv = ring.len() as u32;
        let mut reg: Vec<Option<u32>> = vec![None; graph.len()];
        let mut ops = Vec::new();
        // Iterative post-order: the graphs of long chains are deep.
        let mut stack: Vec<(Id, bool)> = Vec::new();
        for &root in ids {
            stack.push((root, false));
            while let Some((id, expanded)) = stack.pop() {
                if reg[id as usize].is_some() {
                    continue;
                }
                let node = graph.node(id);
                let children: &[Id] = match node {
                    Node::Num(_) | Node::Leaf(_) => &[],
                    Node::Add(a, b) | Node::Sub(a, b) | Node::Mul(a, b) => &[*a, *b],
                    Node::Neg(a) => std::slice::from_ref(a),
                };
                if !expanded {
                    stack.push((id, true));
                    for &c in children.iter().rev() {
                        if reg[c as usize].is_none() {
                            stack.push((c, false));
                        }
                    }
                    continue;
                }
                let r = |c: &Id| reg[*c as usize].expect("operands come first");
                let op = match node {
                    Node::Num(x) => Op::Const(rat_to_f64(x)),
                    Node::Leaf(v) => Op::Var(*v),
                    Node::Add(a, b) => Op::Add(r(a), r(b)),
                    Node::Sub(a, b) => Op::Sub(r(a), r(b)),
                    Node::Mul(a, b) => Op::Mul(r(a), r(b)),
                    Node::Neg(a) => Op::Neg(r(a)),
                };
                reg[id as usize] = Some(nv + ops.len() as u32);
                ops.push(op);
            }
        }
        let outputs = ids
            .iter()
            .map(|id| reg[*id as usize].expect("every output is on the tape"))
            .collect();
        // The variables, as `SymbolicChain::variables_with_rates` computes them (the same
        // expressions, so the same bits), with what does not depend on q done once.
        let mut init = vec![f64::NAN; nv as usize];
        let mut joints = Vec::new();
        for (v, slot) in init.iter_mut().enumerate() {
            match ring.kind(v as u32) {
                VarKind::Joint(j) => joints.push((v as u32, *j)),
                VarKind::Param(n) => *slot = chain.param_value(n),
                VarKind::Sqrt(k) => *slot = (*k as f64).sqrt(),
                VarKind::Rate(_) | VarKind::Sin(_) | VarKind::Cos(_) => {}
            }
        }
        let mut angles = Vec::new();
        for a in &model.sym.angles {
            let (s, c) = a.vars;
            match &a.source {
                AngleSource::Joint {
                    joint,
                    sign,
                    offset,
                } => angles.push((s, c, *joint, f64::from(*sign), chain.eval(offset))),
                AngleSource::Constant(v) => {
                    let x = chain.eval(v);
                    init[s as usize] = x.sin();
                    init[c as usize] = x.cos();
                }
            }
        }
        Tape {
            ops,
            outputs,
            init,
            joints,
            angles,
        }
    }

    /// Append the outputs' values at `q` to `out`; `regs` is scratch space, reused.
    pub fn eval(&self, q: &[f64], regs: &mut Vec<f64>, out: &mut Vec<f64>) {
        regs.clear();
        regs.reserve(self.init.len() + self.ops.len());
        regs.extend_from_slice(&self.init);
        for &(v, j) in &self.joints {
            regs[v as usize] = q[j];
        }
        for &(s, c, j, sign, offset) in &self.angles {
            let x = sign * q[j] + offset;
            regs[s as usize] = x.sin();
            regs[c as usize] = x.cos();
        }
        for op in &self.ops {
            let r = |i: &u32| regs[*i as usize];
            let v = match op {
                Op::Const(x) => *x,
                Op::Var(v) => regs[*v as usize],
                Op::Add(a, b) => r(a) + r(b),
                Op::Sub(a, b) => r(a) - r(b),
                Op::Mul(a, b) => r(a) * r(b),
                Op::Neg(a) => -r(a),
            };
            regs.push(v);
        }
        out.extend(self.outputs.iter().map(|i| regs[*i as usize]));
    }
}
