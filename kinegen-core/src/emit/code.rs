//! Straight-line code → readable Rust statements.
//!
//! A function body is the set of nodes its outputs reach. Nodes used more than once
//! get a `let` (common-subexpression sharing across all outputs of the function);
//! nodes used once are inlined into their single user. Sines and cosines come first:
//! the joint angles of an f64 robot in one `sin_cos_n` call (SIMD lanes), any other
//! angle (and every angle of an f32 robot) with one `sin_cos` each; intermediates
//! whose value is the sine or cosine of a sum or difference of joint angles are named
//! after it (`c23`, `c2m3`: [`AngleName`](crate::emit::angle_names::AngleName), recognised
//! by `angle_sums`).

use std::collections::{BTreeMap, BTreeSet, HashMap, HashSet};

use crate::algebra::angles::AngleSource;
use crate::algebra::fast_hash::{FastMap, FastSet};
use crate::algebra::graph::{Graph, Id, Node};
use crate::algebra::poly::VarKind;
use crate::chain::Chain;
use crate::emit::angle_sums::AngleSums;
use crate::kinematics::frames::SymbolicChain;
use crate::model::robot::Scalar;
use crate::model::value::{rat_to_f64, Value};

/// Operation counts of generated code (a subtraction counts as an add; a `sin_cos`
/// counts one trig).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct OpCount {
    /// Additions and subtractions.
    pub add: usize,
    /// Multiplications.
    pub mul: usize,
    /// Divisions.
    pub div: usize,
    /// Negations.
    pub neg: usize,
    /// `sin_cos` calls.
    pub trig: usize,
}

impl OpCount {
    /// add + mul + div + neg.
    pub fn total(&self) -> usize {
        self.add + self.mul + self.div + self.neg
    }
}

/// A generated body: statements, output expressions, formulas and counts.
#[derive(Clone, Debug, Default)]
pub struct Body {
    /// `let` statements, in order.
    pub lets: Vec<String>,
    /// One Rust expression per requested output.
    pub outputs: Vec<String>,
    /// `(name, formula)` of the shared intermediates, in order (for docs).
    pub defs: Vec<(String, String)>,
    /// Operation counts of the whole body.
    pub ops: OpCount,
}

/// Deepest expression written inline before it gets a `let` of its own.
const MAX_INLINE_DEPTH: usize = 12;

/// Most `let`s a body writes in one run. Every `let` opens a lexical scope inside the one
/// before, and LLVM writes a debug build's scopes recursively: the 4 157 nested `let`s
/// of a 100-joint oblique chain's `fk` overflowed rustc's stack in a default debug build
/// (a SIGSEGV in `DwarfCompileUnit::createAndAddScopeChildren`); 50 joints' (about 2 000)
/// built. A longer body is cut into blocks of this many ([`in_blocks`]), so scopes nest
/// at most this deep plus one per block. The shipped robots' bodies are shorter.
const MAX_LET_RUN: usize = 1024;

/// `lets` as they are if there are at most [`MAX_LET_RUN`], else cut into blocks of that
/// many, each `let (a, b, …) = { …; (a, b, …) };` binding the names it defines that a
/// later statement or one of `outputs` reads (read off the text: an identifier that
/// merely looks like a name, a field `self.d1`, only hands on one name more).
fn in_blocks(lets: Vec<String>, outputs: &[String]) -> Vec<String> {
    if lets.len() <= MAX_LET_RUN {
        return lets;
    }
    let blocks: Vec<&[String]> = lets.chunks(MAX_LET_RUN).collect();
    // Each block's names, in order, and where each name is bound.
    let defines: Vec<Vec<&str>> = blocks
        .iter()
        .map(|block| block.iter().flat_map(|s| bound_names(s)).collect())
        .collect();
    let mut defined_in: FastMap<&str, usize> = FastMap::default();
    for (b, names) in defines.iter().enumerate() {
        for &name in names {
            defined_in.insert(name, b);
        }
    }
    let mut read_later: Vec<FastSet<&str>> = vec![FastSet::default(); blocks.len()];
    // (Block 0's statements can read no earlier block.)
    let reads = blocks
        .iter()
        .enumerate()
        .skip(1)
        .flat_map(|(b, block)| block.iter().map(move |s| (b, s.as_str())))
        .chain(outputs.iter().map(|o| (blocks.len(), o.as_str())));
    for (b, text) in reads {
        for id in identifiers(text) {
            match defined_in.get(id) {
                Some(&d) if d < b => {
                    read_later[d].insert(id);
                }
                _ => {}
            }
        }
    }
    blocks
        .iter()
        .zip(defines.iter().zip(&read_later))
        .map(|(block, (names, later))| {
            let names: Vec<&str> = names
                .iter()
                .copied()
                .filter(|n| later.contains(n))
                .collect();
            let tuple = match names.as_slice() {
                [one] => one.to_string(),
                _ => format!("({})", names.join(", ")),
            };
            format!("let {tuple} = {{\n{}\n{tuple}\n}};", block.join("\n"))
        })
        .collect()
}

/// The names a statement `let PATTERN = …;` binds (none for `_` or another statement).
fn bound_names(statement: &str) -> Vec<&str> {
    let Some(rest) = statement.strip_prefix("let ") else {
        return Vec::new();
    };
    let pattern = rest.split(" = ").next().unwrap_or("");
    identifiers(pattern)
        .filter(|&n| n != "_" && n != "mut")
        .collect()
}

/// The identifiers of a piece of Rust (numbers, with their exponents and suffixes,
/// skipped): the names a formula reads.
///
/// ```
/// use kinegen_core::emit::code::identifiers;
/// let ids: Vec<&str> = identifiers("t12 * 1.5e-3 + self.d1 * s_k2").collect();
/// assert_eq!(ids, ["t12", "self", "d1", "s_k2"]);
/// ```
pub fn identifiers(text: &str) -> impl Iterator<Item = &str> {
    let bytes = text.as_bytes();
    let mut i = 0;
    std::iter::from_fn(move || {
        while i < bytes.len() {
            let c = bytes[i];
            let start = i;
            if c.is_ascii_alphabetic() || c == b'_' {
                while i < bytes.len() && (bytes[i].is_ascii_alphanumeric() || bytes[i] == b'_') {
                    i += 1;
                }
                return Some(&text[start..i]);
            }
            if c.is_ascii_digit() {
                while i < bytes.len()
                    && (bytes[i].is_ascii_alphanumeric() || bytes[i] == b'_' || bytes[i] == b'.')
                {
                    i += 1;
                }
                continue;
            }
            i += 1;
        }
        None
    })
}

/// Emits bodies for one chain.
pub struct Coder<'a> {
    chain: &'a Chain,
    sym: &'a SymbolicChain,
    /// Names of angle-sum values by normal form.
    sums: AngleSums<'a>,
    scalar: Scalar,
    /// Parameters are `f32` fields read into f64 code (see [`Coder::in_f64`]).
    widen: bool,
}

impl<'a> Coder<'a> {
    /// A coder for the symbolic frames `sym` of `chain`.
    pub fn new(chain: &'a Chain, sym: &'a SymbolicChain) -> Self {
        Coder {
            chain,
            sym,
            sums: AngleSums::new(chain, sym),
            scalar: chain.scalar,
            widen: false,
        }
    }

    /// This coder writing f64 code whatever the chain's scalar: an f32 robot's
    /// parameters are read with `f64::from(self.name)`, literals and `sin_cos` are f64.
    /// (The closed-form IK of an f32 robot solves in f64.)
    pub fn in_f64(mut self) -> Self {
        self.widen = self.scalar == Scalar::F32;
        self.scalar = Scalar::F64;
        self
    }

    /// How the body reads parameter `name` from `self`.
    fn param(&self, name: &str) -> String {
        if self.widen {
            format!("f64::from(self.{name})")
        } else {
            format!("self.{name}")
        }
    }

    fn g(&self) -> &Graph {
        &self.sym.graph
    }

    /// The floating-point type name.
    pub fn float(&self) -> &'static str {
        match self.scalar {
            Scalar::F64 => "f64",
            Scalar::F32 => "f32",
        }
    }

    /// A float literal.
    pub fn lit(&self, x: f64) -> String {
        let s = match self.scalar {
            Scalar::F64 => format!("{x:?}"),
            Scalar::F32 => format!("{:?}", x as f32),
        };
        if s.contains(['.', 'e', 'E']) || s.contains("inf") || s.contains("NaN") {
            s
        } else {
            format!("{s}.0")
        }
    }

    /// Rust expression of a constant value (parameters read from `self`).
    fn value_expr(&self, v: &Value) -> String {
        let mut parts = Vec::new();
        let k = rat_to_f64(&v.konst) + rat_to_f64(&v.pi) * std::f64::consts::PI;
        for (name, c) in &v.params {
            let c = rat_to_f64(c);
            parts.push(if c == 1.0 {
                self.param(name)
            } else {
                format!("{} * {}", self.lit(c), self.param(name))
            });
        }
        if k != 0.0 || parts.is_empty() {
            parts.push(self.lit(k));
        }
        parts.join(" + ")
    }

    /// The body computing `outputs`: inputs, shared intermediates, outputs.
    pub fn body(&self, outputs: &[Id]) -> Body {
        let (uses, seen) = self.reachable(outputs);
        let mut body = Body::default();
        self.inputs(&seen, &mut body);
        let names = self.intermediates(&uses, &mut body);
        for &o in outputs {
            let (e, _) = self.expr(o, &names, &mut body.ops);
            body.outputs.push(e);
        }
        body.lets = in_blocks(std::mem::take(&mut body.lets), &body.outputs);
        body
    }

    /// Nodes reachable from `outputs` with their use counts, and the set of them.
    fn reachable(&self, outputs: &[Id]) -> (BTreeMap<Id, usize>, BTreeSet<Id>) {
        let g = self.g();
        let mut uses: BTreeMap<Id, usize> = BTreeMap::new();
        let mut stack: Vec<Id> = outputs.to_vec();
        for &o in outputs {
            *uses.entry(o).or_default() += 1;
        }
        let mut seen = BTreeSet::new();
        while let Some(id) = stack.pop() {
            if !seen.insert(id) {
                continue;
            }
            for c in g.node(id).children() {
                *uses.entry(c).or_default() += 1;
                stack.push(c);
            }
        }
        (uses, seen)
    }

    /// `let`s for the inputs the body reads: parameters, prismatic joint values, joint
    /// rates (`let qd2 = qd[1];`), and the sines and cosines (the f64 joint angles in one batched `sin_cos_n` call,
    /// which goes where the first of them would have gone).
    fn inputs(&self, seen: &BTreeSet<Id>, body: &mut Body) {
        let g = self.g();
        let mut used_vars: Vec<u32> = seen
            .iter()
            .filter_map(|&id| match g.node(id) {
                Node::Leaf(v) => Some(*v),
                _ => None,
            })
            .collect();
        used_vars.sort_unstable();
        // A search, not a scan: a long chain reads thousands of variables.
        let used = |v: &u32| used_vars.binary_search(v).is_ok();
        for (name, v) in &self.sym.param_vars {
            if used(v) {
                body.lets
                    .push(format!("let {name} = {};", self.param(name)));
            }
        }
        for (j, v) in &self.sym.joint_vars {
            if used(v) {
                body.lets.push(format!("let q{} = q[{j}];", j + 1));
            }
        }
        for (j, v) in &self.sym.rate_vars {
            if used(v) {
                body.lets
                    .push(format!("let {} = qd[{j}];", g.ring.name(*v)));
            }
        }
        // `(sine, cosine, argument)` of the batched f64 joint angles.
        let mut batch: Vec<(String, String, String)> = Vec::new();
        let mut batch_at = None;
        for a in &self.sym.angles {
            let (s, c) = a.vars;
            if !(used(&s) || used(&c)) {
                continue;
            }
            let (sn, cn) = (g.ring.name(s), g.ring.name(c));
            let name = |v, n: &str| if used(&v) { n } else { "_" }.to_string();
            let (sp, cp) = (name(s, sn), name(c, cn));
            let pat = format!("({sp}, {cp})");
            let rhs = match &a.source {
                AngleSource::Joint {
                    joint,
                    sign,
                    offset,
                } => {
                    body.ops.trig += 1;
                    let arg = if offset.is_zero() {
                        format!("q[{joint}]")
                    } else if *sign < 0 {
                        body.ops.add += 1;
                        format!("{} - q[{joint}]", self.value_expr(offset))
                    } else {
                        body.ops.add += 1;
                        format!("q[{joint}] + {}", self.value_expr(offset))
                    };
                    if self.scalar == Scalar::F64 {
                        batch_at.get_or_insert(body.lets.len());
                        batch.push((sp, cp, arg));
                        continue;
                    }
                    format!("{}({arg})", self.sin_cos_fn())
                }
                AngleSource::Constant(v) if v.is_constant() => {
                    let x = self.chain.eval(v);
                    format!("({}, {})", self.lit(x.sin()), self.lit(x.cos()))
                }
                AngleSource::Constant(v) => {
                    body.ops.trig += 1;
                    format!("{}({})", self.sin_cos_fn(), self.value_expr(v))
                }
            };
            body.lets.push(format!("let {pat} = {rhs};"));
        }
        if let Some(at) = batch_at {
            body.lets.insert(at, batched_sin_cos(&batch));
        }
    }

    /// `let`s for shared intermediates; also for long single-use chains (a sum of many
    /// terms), cut every few levels so lines stay readable and emission stays shallow.
    /// Returns the name of every bound node.
    fn intermediates(&self, uses: &BTreeMap<Id, usize>, body: &mut Body) -> HashMap<Id, String> {
        let g = self.g();
        let mut names: HashMap<Id, String> = HashMap::new();
        // The names given so far, for `sum_name`'s look-up (a scan of `names` was
        // quadratic: a long chain's bodies bind tens of thousands).
        let mut taken: HashSet<String> = HashSet::new();
        let mut temp = 0usize;
        let mut depth: HashMap<Id, usize> = HashMap::new();
        for (&id, &n) in uses {
            let node = g.node(id);
            let shared = n >= 2
                && match node {
                    Node::Num(_) | Node::Leaf(_) => false,
                    // `-c1` once for all the products it signs.
                    Node::Neg(x) => !matches!(g.node(*x), Node::Num(_)),
                    _ => true,
                };
            let d = match node {
                Node::Num(_) | Node::Leaf(_) => 0,
                _ => {
                    1 + node
                        .children()
                        .map(|c| depth.get(&c).copied().unwrap_or(0))
                        .max()
                        .unwrap_or(0)
                }
            };
            let bind = shared || d > MAX_INLINE_DEPTH;
            depth.insert(id, if bind { 0 } else { d });
            if !bind {
                continue;
            }
            let (expr, _) = self.expr(id, &names, &mut body.ops);
            let name = self.sum_name(id, &taken).unwrap_or_else(|| {
                temp += 1;
                format!("t{temp}")
            });
            body.lets.push(format!("let {name} = {expr};"));
            body.defs.push((name.clone(), expr));
            taken.insert(name.clone());
            names.insert(id, name);
        }
        names
    }

    /// `c23` for a node whose value is cos(q2 + q3) (`nc23` for its negation, which the
    /// sign pass may compute instead), unless the name is `taken`.
    fn sum_name(&self, id: Id, taken: &HashSet<String>) -> Option<String> {
        self.g()
            .nf(id)
            .and_then(|p| self.sums.name(p))
            .filter(|n| !taken.contains(n))
    }

    /// The scalar `sin_cos` of the robot's float type.
    fn sin_cos_fn(&self) -> &'static str {
        match self.scalar {
            Scalar::F64 => "::kinegen::math::sin_cos",
            Scalar::F32 => "::kinegen::math::sin_cos_f32",
        }
    }

    /// Expression text of a node and its precedence (1 sum, 2 product, 3 unary, 4 atom).
    fn expr(&self, id: Id, names: &HashMap<Id, String>, ops: &mut OpCount) -> (String, u8) {
        if let Some(n) = names.get(&id) {
            return (n.clone(), 4);
        }
        let g = self.g();
        match g.node(id) {
            Node::Num(r) => {
                let x = rat_to_f64(r);
                if x < 0.0 {
                    (format!("-{}", self.lit(-x)), 3)
                } else {
                    (self.lit(x), 4)
                }
            }
            Node::Leaf(v) => match g.ring.kind(*v) {
                VarKind::Sqrt(k) => (self.lit((*k as f64).sqrt()), 4),
                _ => (g.ring.name(*v).to_string(), 4),
            },
            Node::Add(a, b) => {
                ops.add += 1;
                let (x, px) = self.expr(*a, names, ops);
                let (y, py) = self.expr(*b, names, ops);
                // Keep the graph's evaluation order exactly (so every function computing
                // a node gets the same bits): `x + (u + v)` is written `u + v + x`
                // (addition commutes exactly in IEEE arithmetic), or with parentheses.
                let s = match (px <= 1, py <= 1) {
                    (_, false) => format!("{x} + {y}"),
                    (false, true) => format!("{y} + {x}"),
                    (true, true) => format!("{x} + ({y})"),
                };
                (s, 1)
            }
            Node::Sub(a, b) => {
                ops.add += 1;
                let (x, _) = self.expr(*a, names, ops);
                let (y, py) = self.expr(*b, names, ops);
                let y = if py <= 1 { format!("({y})") } else { y };
                (format!("{x} - {y}"), 1)
            }
            Node::Mul(a, b) => {
                ops.mul += 1;
                // Constants first: `0.5 * x`.
                let (a, b) = if g.as_num(*b).is_some() {
                    (*b, *a)
                } else {
                    (*a, *b)
                };
                let (x, px) = self.expr(a, names, ops);
                let (y, py) = self.expr(b, names, ops);
                let x = if px < 2 { format!("({x})") } else { x };
                let y = if py <= 2 { format!("({y})") } else { y };
                (format!("{x} * {y}"), 2)
            }
            Node::Neg(a) => {
                ops.neg += 1;
                let (x, px) = self.expr(*a, names, ops);
                if px < 2 || px == 3 {
                    (format!("-({x})"), 3)
                } else {
                    (format!("-{x}"), 3)
                }
            }
        }
    }
}

/// One `let` for the sines and cosines of several f64 angles `(sine name or _, cosine
/// name or _, argument)`: `kinegen::math::sin_cos_n`, whose lanes are `sin_cos` bit for
/// bit and share SIMD registers; a lone angle keeps the scalar `sin_cos`.
fn batched_sin_cos(batch: &[(String, String, String)]) -> String {
    if let [(s, c, arg)] = batch {
        return format!("let ({s}, {c}) = ::kinegen::math::sin_cos({arg});");
    }
    let side = |names: Vec<&str>| {
        if names.iter().all(|n| *n == "_") {
            "_".to_string()
        } else {
            format!("[{}]", names.join(", "))
        }
    };
    format!(
        "let ({}, {}) = ::kinegen::math::sin_cos_n([{}]);",
        side(batch.iter().map(|b| b.0.as_str()).collect()),
        side(batch.iter().map(|b| b.1.as_str()).collect()),
        batch
            .iter()
            .map(|b| b.2.as_str())
            .collect::<Vec<_>>()
            .join(", ")
    )
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// A body of `defs` intermediates `t1`, `t2`, … and one output, with its name (the
    /// docs' and `FORMULAS`' tests).
    pub(crate) fn body(defs: usize) -> (Body, Vec<String>) {
        let body = Body {
            lets: Vec::new(),
            outputs: vec!["t1 + c1".into()],
            defs: (1..=defs)
                .map(|i| (format!("t{i}"), format!("c{i} * s{i} + L{i}")))
                .collect(),
            ops: OpCount::default(),
        };
        (body, vec!["T[0][3]".into()])
    }

    #[test]
    fn identifiers_skip_numbers_and_their_exponents() {
        let ids: Vec<&str> =
            identifiers("t12 * 1.5e-3f64 + ::kinegen::math::sqrt(s_k2) - 2e5").collect();
        assert_eq!(ids, ["t12", "kinegen", "math", "sqrt", "s_k2"]);
    }

    /// A body of 2 500 `let`s in a chain, each reading the one before and the first:
    /// three blocks, each handing on what a later block or the output reads.
    #[test]
    fn a_long_body_is_cut_into_blocks_that_hand_on_what_is_read_later() {
        let mut lets = vec![
            "let _ = q;".to_string(),
            "let (s1, c1) = (0.5, 0.8);".to_string(),
        ];
        lets.extend((2..2500).map(|k| format!("let t{k} = t{} * s1 + c1;", k - 1)));
        lets[2] = "let t2 = s1 * c1;".to_string();
        let blocks = in_blocks(lets.clone(), &["t2499".to_string()]);
        assert_eq!(blocks.len(), 3);
        assert!(
            blocks[0].starts_with("let (s1, c1, t1023) = {\nlet _ = q;"),
            "{}",
            &blocks[0][..80]
        );
        assert!(blocks[0].ends_with("\n(s1, c1, t1023)\n};"));
        assert!(blocks[1].starts_with("let t2047 = {\nlet t1024 = t1023 * s1 + c1;"));
        assert!(blocks[2].ends_with("\nt2499\n};"));
        // t2 is read by the output: block 0 hands it on too.
        let blocks = in_blocks(lets.clone(), &["t2499 + t2 + t1500".to_string()]);
        assert!(blocks[0].starts_with("let (s1, c1, t2, t1023) = {"));
        assert!(blocks[1].starts_with("let (t1500, t2047) = {"));
        // Short bodies are left as they are.
        assert_eq!(
            in_blocks(lets[..MAX_LET_RUN].to_vec(), &[]),
            lets[..MAX_LET_RUN]
        );
    }
}
