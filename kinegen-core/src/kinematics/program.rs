//! Chosen nodes of a model as a register program: for tools that evaluate the same
//! outputs at many configurations (a reachability map, a file of IK poses) without
//! walking the graph or allocating per call.
//!
//! Every operation is the node's own (`a + b`, `a − b`, `a · b`, `−a`) on the same
//! operand values, and the leaves are what [`SymbolicChain::variables`] gives, so a
//! program returns the bits [`SymbolicChain::eval`] returns.

use crate::algebra::angles::AngleSource;
use crate::algebra::graph::{Id, Node};
use crate::algebra::poly::VarKind;
use crate::chain::Chain;
use crate::kinematics::frames::SymbolicChain;

/// One operation: destination register, then operand registers. The last five fuse a
/// product into the sum or difference that is its only reader (`a·b ± c·d`, `a·b ± c`,
/// `c − a·b`): one dispatch instead of two or three, each product and the sum rounded
/// as the separate operations round them, so the bits are the same.
#[derive(Clone, Copy, Debug)]
enum Op {
    Add(u32, u32, u32),
    Sub(u32, u32, u32),
    Mul(u32, u32, u32),
    Neg(u32, u32),
    /// `d = a·b + c·e`.
    AddProducts(u32, u32, u32, u32, u32),
    /// `d = a·b − c·e`.
    SubProducts(u32, u32, u32, u32, u32),
    /// `d = a·b + c` (either order of the sum: IEEE addition commutes exactly).
    AddProduct(u32, u32, u32, u32),
    /// `d = a·b − c`.
    ProductSub(u32, u32, u32, u32),
    /// `d = c − a·b`.
    SubProduct(u32, u32, u32, u32),
}

impl Op {
    /// The registers it reads.
    fn reads(&self) -> impl Iterator<Item = u32> {
        let (v, n) = match *self {
            Op::Add(_, a, b) | Op::Sub(_, a, b) | Op::Mul(_, a, b) => ([a, b, 0, 0], 2),
            Op::Neg(_, a) => ([a, 0, 0, 0], 1),
            Op::AddProducts(_, a, b, c, e) | Op::SubProducts(_, a, b, c, e) => ([a, b, c, e], 4),
            Op::AddProduct(_, a, b, c)
            | Op::ProductSub(_, a, b, c)
            | Op::SubProduct(_, a, b, c) => ([a, b, c, 0], 3),
        };
        v.into_iter().take(n)
    }

    /// The arithmetic operations it stands for.
    fn weight(&self) -> usize {
        match self {
            Op::Add(..) | Op::Sub(..) | Op::Mul(..) | Op::Neg(..) => 1,
            Op::AddProducts(..) | Op::SubProducts(..) => 3,
            Op::AddProduct(..) | Op::ProductSub(..) | Op::SubProduct(..) => 2,
        }
    }
}

/// `ops` with each product that only one sum or difference reads (and no output) folded
/// into it. Registers are never reused (one per node), so a product's operands still
/// hold their values where the sum reads them.
fn fuse(ops: Vec<Op>, outputs: &[u32], registers: usize) -> Vec<Op> {
    let mut uses = vec![0u32; registers];
    for op in &ops {
        for r in op.reads() {
            uses[r as usize] += 1;
        }
    }
    for &o in outputs {
        uses[o as usize] += 1;
    }
    // The product writing each register, where only one operation reads it.
    let mut product: Vec<Option<(u32, u32)>> = vec![None; registers];
    for op in &ops {
        if let Op::Mul(d, a, b) = *op {
            if uses[d as usize] == 1 {
                product[d as usize] = Some((a, b));
            }
        }
    }
    let mut folded = vec![false; registers];
    let mut fused = Vec::with_capacity(ops.len());
    for op in &ops {
        let p = |r: u32| product[r as usize];
        let new = match *op {
            Op::Add(d, x, y) => match (p(x), p(y)) {
                (Some((a, b)), Some((c, e))) => Some((Op::AddProducts(d, a, b, c, e), [x, y])),
                (Some((a, b)), None) => Some((Op::AddProduct(d, a, b, y), [x, x])),
                (None, Some((a, b))) => Some((Op::AddProduct(d, a, b, x), [y, y])),
                (None, None) => None,
            },
            Op::Sub(d, x, y) => match (p(x), p(y)) {
                (Some((a, b)), Some((c, e))) => Some((Op::SubProducts(d, a, b, c, e), [x, y])),
                (Some((a, b)), None) => Some((Op::ProductSub(d, a, b, y), [x, x])),
                (None, Some((a, b))) => Some((Op::SubProduct(d, a, b, x), [y, y])),
                (None, None) => None,
            },
            _ => None,
        };
        match new {
            Some((f, gone)) => {
                for g in gone {
                    folded[g as usize] = true;
                }
                fused.push(f);
            }
            None => fused.push(*op),
        }
    }
    // The folded products' own operations go (they ran before their reader: the order
    // of the rest is kept).
    fused.retain(|op| !matches!(*op, Op::Mul(d, ..) if folded[d as usize]));
    fused
}

/// A joint angle's sine and cosine leaves: `sin_cos(sign·q[joint] + offset)`, each
/// only where an operation or output reads it.
#[derive(Clone, Copy, Debug)]
struct AngleLeaf {
    sin: Option<u32>,
    cos: Option<u32>,
    joint: usize,
    sign: f64,
    offset: f64,
}

/// Straight-line code for a fixed list of nodes of one chain's graph.
///
/// ```
/// use kinegen_core::front::toml_file::load_description_file;
/// use kinegen_core::kinematics::program::Program;
/// use kinegen_core::derive;
///
/// let (robot, options) = load_description_file("../robots/ur5.toml".as_ref()).unwrap();
/// let chain = robot.chain();
/// let derived = derive(&chain, &options);
/// let ids: Vec<_> = derived.model.fk_rows.iter().flatten().copied().collect();
/// let program = Program::new(&derived.model.sym, &chain, &ids);
/// let mut registers = program.registers();
/// let mut out = vec![0.0; program.outputs()];
/// let q = [0.1, -1.2, 1.4, -0.3, 1.1, 0.2];
/// program.eval(&q, &mut registers, &mut out);
/// assert_eq!(out, derived.model.eval(&chain, &q, &ids));
/// ```
#[derive(Clone, Debug)]
pub struct Program {
    /// Registers at the start of a call: constants and fixed leaves set, the rest 0.
    initial: Vec<f64>,
    /// Prismatic joints' leaves: `(register, joint)`.
    joints: Vec<(u32, usize)>,
    angles: Vec<AngleLeaf>,
    ops: Vec<Op>,
    outputs: Vec<u32>,
}

impl Program {
    /// The program computing `outputs` (nodes of `sym`'s graph) of `chain`.
    pub fn new(sym: &SymbolicChain, chain: &Chain, outputs: &[Id]) -> Program {
        let graph = &sym.graph;
        let ring = &graph.ring;
        // Registers: the ring's variables keep their numbers; nodes get theirs in order
        // of first need.
        let mut initial = vec![0.0; ring.len()];
        let mut joints = Vec::new();
        for (v, slot) in initial.iter_mut().enumerate() {
            *slot = match ring.kind(v as u32) {
                VarKind::Joint(j) => {
                    joints.push((v as u32, *j));
                    0.0
                }
                // Rates are not inputs of a program: NaN, as `variables` gives without them.
                VarKind::Rate(_) => f64::NAN,
                VarKind::Param(n) => chain.param_value(n),
                VarKind::Sqrt(k) => f64::from(*k).sqrt(),
                VarKind::Sin(_) | VarKind::Cos(_) => f64::NAN,
            };
        }
        let mut angles = Vec::new();
        for a in &sym.angles {
            let (s, c) = (a.vars.0, a.vars.1);
            match &a.source {
                AngleSource::Joint {
                    joint,
                    sign,
                    offset,
                } => angles.push(AngleLeaf {
                    sin: Some(s),
                    cos: Some(c),
                    joint: *joint,
                    sign: f64::from(*sign),
                    offset: chain.eval(offset),
                }),
                AngleSource::Constant(v) => {
                    let x = chain.eval(v);
                    initial[s as usize] = x.sin();
                    initial[c as usize] = x.cos();
                }
            }
        }
        // Each needed node after its operands (an explicit stack: chains are deep).
        let mut register: Vec<Option<u32>> = vec![None; graph.len()];
        let mut ops = Vec::new();
        let mut stack: Vec<(Id, bool)> = outputs.iter().rev().map(|&id| (id, false)).collect();
        while let Some((id, expanded)) = stack.pop() {
            if register[id as usize].is_some() {
                continue;
            }
            let node = graph.node(id);
            let operands: &[Id] = match node {
                Node::Num(_) | Node::Leaf(_) => &[],
                Node::Add(a, b) | Node::Sub(a, b) | Node::Mul(a, b) => &[*a, *b],
                Node::Neg(a) => core::slice::from_ref(a),
            };
            if !expanded && operands.iter().any(|o| register[*o as usize].is_none()) {
                stack.push((id, true));
                stack.extend(operands.iter().rev().map(|&o| (o, false)));
                continue;
            }
            let r = |o: Id| register[o as usize].expect("operand placed first");
            let reg = match node {
                Node::Leaf(v) => *v,
                Node::Num(x) => {
                    initial.push(crate::model::value::rat_to_f64(x));
                    (initial.len() - 1) as u32
                }
                _ => {
                    initial.push(0.0);
                    let d = (initial.len() - 1) as u32;
                    ops.push(match *node {
                        Node::Add(a, b) => Op::Add(d, r(a), r(b)),
                        Node::Sub(a, b) => Op::Sub(d, r(a), r(b)),
                        Node::Mul(a, b) => Op::Mul(d, r(a), r(b)),
                        Node::Neg(a) => Op::Neg(d, r(a)),
                        Node::Num(_) | Node::Leaf(_) => unreachable!("handled above"),
                    });
                    d
                }
            };
            register[id as usize] = Some(reg);
        }
        let outputs: Vec<u32> = outputs
            .iter()
            .map(|&id| register[id as usize].expect("every output placed"))
            .collect();
        let ops = fuse(ops, &outputs, initial.len());
        // Sines and cosines nothing reads are not computed (a measure reading q2..q5
        // skips q1's and q6's).
        let mut read = vec![false; initial.len()];
        for op in &ops {
            for a in op.reads() {
                read[a as usize] = true;
            }
        }
        for &o in &outputs {
            read[o as usize] = true;
        }
        for a in &mut angles {
            a.sin = a.sin.filter(|r| read[*r as usize]);
            a.cos = a.cos.filter(|r| read[*r as usize]);
        }
        angles.retain(|a| a.sin.is_some() || a.cos.is_some());
        Program {
            initial,
            joints,
            angles,
            ops,
            outputs,
        }
    }

    /// Registers for [`Program::eval`], ready to use (reuse them across calls).
    pub fn registers(&self) -> Vec<f64> {
        self.initial.clone()
    }

    /// Reset `registers` (any `Vec`, e.g. shared by several programs) to this program's
    /// starting values, reusing its allocation.
    pub fn registers_into(&self, registers: &mut Vec<f64>) {
        registers.clear();
        registers.extend_from_slice(&self.initial);
    }

    /// How many values [`Program::eval`] writes.
    pub fn outputs(&self) -> usize {
        self.outputs.len()
    }

    /// Whether any output depends on joint `j` (its value, sine or cosine is read).
    pub fn reads_joint(&self, j: usize) -> bool {
        self.joints.iter().any(|&(_, k)| k == j) || self.angles.iter().any(|a| a.joint == j)
    }

    /// How many operations one call runs.
    pub fn operations(&self) -> usize {
        self.ops.iter().map(Op::weight).sum()
    }

    /// The outputs at `q` into `out`, using `registers` from [`Program::registers`];
    /// sines and cosines by `f64::sin` and `f64::cos`, as the graph walk takes them.
    ///
    /// # Panics
    /// If `registers` did not come from this program, `q` is shorter than the chain or
    /// `out` shorter than [`Program::outputs`].
    pub fn eval(&self, q: &[f64], registers: &mut [f64], out: &mut [f64]) {
        self.eval_with(q, registers, out, |x| (x.map(f64::sin), x.map(f64::cos)));
    }

    /// [`Program::eval`] with the joint angles' sines and cosines from `sin_cos`, four
    /// angles a call (the generated code's `kinegen::math::sin_cos_n` takes them side
    /// by side, faster than the platform's one by one; values then differ from
    /// [`Program::eval`]'s by rounding).
    pub fn eval_with(
        &self,
        q: &[f64],
        registers: &mut [f64],
        out: &mut [f64],
        sin_cos: impl Fn([f64; 4]) -> ([f64; 4], [f64; 4]),
    ) {
        let r = registers;
        for &(reg, j) in &self.joints {
            r[reg as usize] = q[j];
        }
        for chunk in self.angles.chunks(4) {
            let mut x = [0.0; 4];
            for (x, a) in x.iter_mut().zip(chunk) {
                *x = a.sign * q[a.joint] + a.offset;
            }
            let (s, c) = sin_cos(x);
            for (k, a) in chunk.iter().enumerate() {
                if let Some(reg) = a.sin {
                    r[reg as usize] = s[k];
                }
                if let Some(reg) = a.cos {
                    r[reg as usize] = c[k];
                }
            }
        }
        for op in &self.ops {
            match *op {
                Op::Add(d, a, b) => r[d as usize] = r[a as usize] + r[b as usize],
                Op::Sub(d, a, b) => r[d as usize] = r[a as usize] - r[b as usize],
                Op::Mul(d, a, b) => r[d as usize] = r[a as usize] * r[b as usize],
                Op::Neg(d, a) => r[d as usize] = -r[a as usize],
                Op::AddProducts(d, a, b, c, e) => {
                    r[d as usize] = r[a as usize] * r[b as usize] + r[c as usize] * r[e as usize]
                }
                Op::SubProducts(d, a, b, c, e) => {
                    r[d as usize] = r[a as usize] * r[b as usize] - r[c as usize] * r[e as usize]
                }
                Op::AddProduct(d, a, b, c) => {
                    r[d as usize] = r[a as usize] * r[b as usize] + r[c as usize]
                }
                Op::ProductSub(d, a, b, c) => {
                    r[d as usize] = r[a as usize] * r[b as usize] - r[c as usize]
                }
                Op::SubProduct(d, a, b, c) => {
                    r[d as usize] = r[c as usize] - r[a as usize] * r[b as usize]
                }
            }
        }
        for (o, &reg) in out.iter_mut().zip(&self.outputs) {
            *o = r[reg as usize];
        }
    }
}

/// Joint vectors [`Program::eval_lanes`] takes side by side: eight, every solution of a
/// UR or PUMA pose in one call when IK measures them, each operation decoded once for
/// all eight (with four the UR5's residuals took 9 % more instructions).
pub const LANES: usize = 8;

impl Program {
    /// Registers for [`Program::eval_lanes`]: [`Program::registers`] in every lane.
    pub fn lane_registers(&self) -> Vec<[f64; LANES]> {
        self.initial.iter().map(|&v| [v; LANES]).collect()
    }

    /// [`Program::eval_with`] on [`LANES`] joint vectors at once, for batches: each
    /// operation is decoded once for all of them, and one `sin_cos` call takes one
    /// angle of every vector. Lane `l` of `out[k]` is output `k` of `q[l]`, with the bits
    /// `eval_with` gives for `q[l]` alone when `sin_cos` works lane by lane (as
    /// `kinegen::math::sin_cos_n` does). Pad a short batch by repeating a vector.
    ///
    /// # Panics
    /// If `registers` did not come from [`Program::lane_registers`], a `q` is shorter
    /// than the chain or `out` is shorter than [`Program::outputs`].
    pub fn eval_lanes(
        &self,
        q: [&[f64]; LANES],
        registers: &mut [[f64; LANES]],
        out: &mut [[f64; LANES]],
        sin_cos: impl Fn([f64; LANES]) -> ([f64; LANES], [f64; LANES]),
    ) {
        #[cfg(target_arch = "x86_64")]
        {
            /// # Safety
            /// The CPU must have AVX2.
            #[target_feature(enable = "avx2")]
            unsafe fn avx2(
                p: &Program,
                q: [&[f64]; LANES],
                registers: &mut [[f64; LANES]],
                out: &mut [[f64; LANES]],
                sin_cos: impl Fn([f64; LANES]) -> ([f64; LANES], [f64; LANES]),
            ) {
                p.eval_lanes_here(q, registers, out, sin_cos)
            }
            if std::is_x86_feature_detected!("avx2") {
                // SAFETY: the CPU has AVX2 (asked just now; `std` caches the answer).
                return unsafe { avx2(self, q, registers, out, sin_cos) };
            }
        }
        self.eval_lanes_here(q, registers, out, sin_cos)
    }

    /// [`Program::eval_lanes`] itself, inlined into each build: with AVX2 where the CPU
    /// has it (four `f64` a register instead of SSE2's two), the same operations in the
    /// same order, so the same bits (Rust never contracts `a * b + c` into a fused
    /// multiply-add).
    #[inline(always)]
    fn eval_lanes_here(
        &self,
        q: [&[f64]; LANES],
        registers: &mut [[f64; LANES]],
        out: &mut [[f64; LANES]],
        sin_cos: impl Fn([f64; LANES]) -> ([f64; LANES], [f64; LANES]),
    ) {
        // Every register an operation, angle, joint or output names is below
        // `initial.len()` (`Program::new` numbers them so): with `registers` at least that
        // long, the operations read and write without a bounds check each (the checks
        // were a tenth of the instructions measuring a UR5 pose's eight solutions).
        assert!(
            registers.len() >= self.initial.len(),
            "fewer registers than the program has (take them from `lane_registers`)"
        );
        let p = registers.as_mut_ptr();
        // SAFETY: `i < initial.len() <= registers.len()` (above), and `p` is the only
        // access to `registers` while these run.
        let load = |i: u32| unsafe { *p.add(i as usize) };
        let store = |i: u32, v: [f64; LANES]| unsafe { *p.add(i as usize) = v };
        for &(reg, j) in &self.joints {
            store(reg, core::array::from_fn(|l| q[l][j]));
        }
        for a in &self.angles {
            let (s, c) = sin_cos(core::array::from_fn(|l| a.sign * q[l][a.joint] + a.offset));
            if let Some(reg) = a.sin {
                store(reg, s);
            }
            if let Some(reg) = a.cos {
                store(reg, c);
            }
        }
        let lanes = |x: [f64; LANES], y: [f64; LANES], f: fn(f64, f64) -> f64| -> [f64; LANES] {
            core::array::from_fn(|l| f(x[l], y[l]))
        };
        for op in &self.ops {
            match *op {
                Op::Add(d, a, b) => store(d, lanes(load(a), load(b), |x, y| x + y)),
                Op::Sub(d, a, b) => store(d, lanes(load(a), load(b), |x, y| x - y)),
                Op::Mul(d, a, b) => store(d, lanes(load(a), load(b), |x, y| x * y)),
                Op::Neg(d, a) => store(d, load(a).map(|x| -x)),
                Op::AddProducts(d, a, b, c, e) => {
                    let (a, b, c, e) = (load(a), load(b), load(c), load(e));
                    store(d, core::array::from_fn(|l| a[l] * b[l] + c[l] * e[l]));
                }
                Op::SubProducts(d, a, b, c, e) => {
                    let (a, b, c, e) = (load(a), load(b), load(c), load(e));
                    store(d, core::array::from_fn(|l| a[l] * b[l] - c[l] * e[l]));
                }
                Op::AddProduct(d, a, b, c) => {
                    let (a, b, c) = (load(a), load(b), load(c));
                    store(d, core::array::from_fn(|l| a[l] * b[l] + c[l]));
                }
                Op::ProductSub(d, a, b, c) => {
                    let (a, b, c) = (load(a), load(b), load(c));
                    store(d, core::array::from_fn(|l| a[l] * b[l] - c[l]));
                }
                Op::SubProduct(d, a, b, c) => {
                    let (a, b, c) = (load(a), load(b), load(c));
                    store(d, core::array::from_fn(|l| c[l] - a[l] * b[l]));
                }
            }
        }
        for (o, &reg) in out.iter_mut().zip(&self.outputs) {
            *o = load(reg);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::derive;
    use crate::front::toml_file::load_description_file;

    /// A shipped robot's chain and derivation.
    fn shipped(file: &str) -> (Chain, crate::Derived) {
        let path = format!("{}/../robots/{file}.toml", env!("CARGO_MANIFEST_DIR"));
        let (robot, options) = load_description_file(path.as_ref()).unwrap();
        let chain = robot.chain();
        let derived = derive(&chain, &options);
        (chain, derived)
    }

    /// Every output group of shipped robots (revolute and prismatic joints, offsets,
    /// constant twists) gives the graph walk's bits.
    #[test]
    fn same_bits_as_the_graph_walk() {
        for file in ["ur5", "puma560", "scara", "stanford", "panda"] {
            let (chain, derived) = shipped(file);
            let m = &derived.model;
            let mut ids: Vec<Id> = m.fk_rows.iter().flatten().copied().collect();
            ids.extend(m.jacobian.iter().flatten());
            if let Some(Ok(det)) = &derived.det {
                ids.push(det.node);
                ids.extend(det.factors.iter().map(|f| f.node));
            }
            let program = Program::new(&m.sym, &chain, &ids);
            let mut regs = program.registers();
            let mut out = vec![0.0; program.outputs()];
            for k in 0..20 {
                let q: Vec<f64> = (0..chain.dof())
                    .map(|j| ((k * 7 + j * 3) as f64 * 0.61).sin() * 2.5)
                    .collect();
                program.eval(&q, &mut regs, &mut out);
                let walked = m.eval(&chain, &q, &ids);
                for (a, b) in out.iter().zip(&walked) {
                    assert_eq!(a.to_bits(), b.to_bits(), "{file} at {q:?}");
                }
            }
        }
    }

    /// Products folded into the sums that read them: fewer operations to dispatch, the
    /// same arithmetic (every node of the outputs' graph computed once).
    #[test]
    fn products_fold_into_their_sums() {
        let (chain, derived) = shipped("ur5");
        let m = &derived.model;
        let ids: Vec<Id> = m.jacobian.iter().flatten().copied().collect();
        let program = Program::new(&m.sym, &chain, &ids);
        let arithmetic = m.sym.graph.op_count(&ids);
        assert_eq!(program.operations(), arithmetic);
        assert!(
            program.ops.len() * 10 < arithmetic * 8,
            "{} operations dispatched for {arithmetic}",
            program.ops.len()
        );
    }

    /// [`LANES`] vectors side by side give each vector's bits of `eval_with` (with a sin_cos
    /// that works lane by lane, as the runtime's does).
    #[test]
    fn lanes_give_each_vectors_bits() {
        let sin_cos = |x: [f64; 4]| (x.map(f64::sin), x.map(f64::cos));
        let sin_cos_lanes = |x: [f64; LANES]| (x.map(f64::sin), x.map(f64::cos));
        for file in ["ur5", "stanford", "panda"] {
            let (chain, derived) = shipped(file);
            let m = &derived.model;
            let mut ids: Vec<Id> = m.fk_rows.iter().flatten().copied().collect();
            ids.extend(m.jacobian_ee.iter().flatten());
            let program = Program::new(&m.sym, &chain, &ids);
            let qs: Vec<Vec<f64>> = (0..LANES)
                .map(|k| {
                    (0..chain.dof())
                        .map(|j| ((k * 5 + j * 3) as f64 * 0.73).sin() * 2.0)
                        .collect()
                })
                .collect();
            let mut lane_regs = program.lane_registers();
            let mut lane_out = vec![[0.0; LANES]; program.outputs()];
            let q: [&[f64]; LANES] = core::array::from_fn(|l| qs[l].as_slice());
            program.eval_lanes(q, &mut lane_regs, &mut lane_out, sin_cos_lanes);
            for (l, q) in qs.iter().enumerate() {
                let mut regs = program.registers();
                let mut out = vec![0.0; program.outputs()];
                program.eval_with(q, &mut regs, &mut out, sin_cos);
                for (k, v) in out.iter().enumerate() {
                    assert_eq!(v.to_bits(), lane_out[k][l].to_bits(), "{file} lane {l}");
                }
            }
        }
    }
}
