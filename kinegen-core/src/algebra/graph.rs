//! Straight-line code as a hash-consed DAG whose nodes carry their exact normal form.
//!
//! Every node built through [`Graph`] is folded (`x·0`, `x·1`, `−(−x)`, constants) and
//! shared structurally; in addition, while the normal forms stay under a term budget,
//! a node whose value equals (or is the negation of) an existing node's value *is* that
//! node: value numbering modulo `s² + c² = 1`. Exact zeros vanish, equal entries are
//! computed once. Past the budget (or past the engine's deadline) a node simply has no
//! normal form and is shared only structurally — always correct, just less simplified.

use std::hash::{Hash, Hasher};
use std::sync::Arc;

use num_traits::{One, Signed, Zero};

use crate::algebra::fast_hash::{hash_rat, FastMap};
use crate::algebra::poly::{Poly, Ring, Var};
use crate::model::options::Deadline;
use crate::model::value::Rat;

/// A node index.
pub type Id = u32;

/// One operation of the straight-line code.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Node {
    /// A rational constant.
    Num(Rat),
    /// A ring variable (`s1`, `c1`, `q3`, a parameter, `√3`).
    Leaf(Var),
    /// `a + b` (operands ordered by id).
    Add(Id, Id),
    /// `a − b`.
    Sub(Id, Id),
    /// `a · b` (operands ordered by id).
    Mul(Id, Id),
    /// `−a`.
    Neg(Id),
}

/// Constants hash by their reduced numerator and denominator ([`hash_rat`]), not by
/// `num-rational`'s far costlier `Hash`; equal nodes hash alike.
impl Hash for Node {
    fn hash<H: Hasher>(&self, h: &mut H) {
        match self {
            Node::Num(r) => {
                h.write_u8(0);
                hash_rat(r, h);
            }
            Node::Leaf(v) => {
                h.write_u8(1);
                h.write_u32(*v);
            }
            Node::Add(a, b) | Node::Sub(a, b) | Node::Mul(a, b) => {
                h.write_u8(match self {
                    Node::Add(..) => 2,
                    Node::Sub(..) => 3,
                    _ => 4,
                });
                h.write_u64((u64::from(*a) << 32) | u64::from(*b));
            }
            Node::Neg(a) => {
                h.write_u8(5);
                h.write_u32(*a);
            }
        }
    }
}

impl Node {
    /// The operands of the node (no allocation: graph walks call this for every node).
    pub fn children(&self) -> impl Iterator<Item = Id> {
        let (ids, n) = match self {
            Node::Num(_) | Node::Leaf(_) => ([0, 0], 0),
            Node::Add(a, b) | Node::Sub(a, b) | Node::Mul(a, b) => ([*a, *b], 2),
            Node::Neg(a) => ([*a, 0], 1),
        };
        ids.into_iter().take(n)
    }
}

/// The DAG, its ring and its normal forms.
#[derive(Clone, Debug)]
pub struct Graph {
    /// Variables and reduction rules.
    pub ring: Ring,
    nodes: Vec<Node>,
    /// Shared, so that copying the graph to try a candidate (`second_order`'s frames,
    /// the determinant's rows) copies pointers, not every polynomial.
    nf: Vec<Option<Arc<Poly>>>,
    /// Operations in the node's expression tree (saturating).
    cost: Vec<u32>,
    memo: FastMap<Node, Id>,
    /// Value numbering: [`Poly::fingerprint`] → the nodes representing the values with
    /// that fingerprint (one per value; more than one only on a hash collision).
    by_nf: FastMap<u64, Vec<Id>>,
    /// Largest normal form (terms) kept; larger ones are dropped.
    pub max_terms: usize,
    /// Normal forms dropped for size.
    pub nf_overflows: usize,
    /// Past it, new normal forms are dropped (as if over [`Graph::max_terms`]).
    pub deadline: Deadline,
    /// Normal forms dropped because the deadline had passed.
    pub nf_timeouts: usize,
    /// Set once the deadline is seen passed: no clock reads after that.
    past_deadline: bool,
}

impl Default for Graph {
    fn default() -> Self {
        Graph::new(Ring::new(), 4_000)
    }
}

impl Graph {
    /// An empty graph over `ring`.
    pub fn new(ring: Ring, max_terms: usize) -> Self {
        Graph {
            ring,
            nodes: Vec::new(),
            nf: Vec::new(),
            cost: Vec::new(),
            memo: FastMap::default(),
            by_nf: FastMap::default(),
            max_terms,
            nf_overflows: 0,
            deadline: Deadline::never(),
            nf_timeouts: 0,
            past_deadline: false,
        }
    }

    /// Whether the deadline has passed (once it has, without reading the clock again).
    pub fn past_deadline(&mut self) -> bool {
        if !self.past_deadline && self.deadline.passed() {
            self.past_deadline = true;
        }
        self.past_deadline
    }

    /// The node with id `id`.
    pub fn node(&self, id: Id) -> &Node {
        &self.nodes[id as usize]
    }

    /// The exact normal form of a node, if it was small enough to keep.
    pub fn nf(&self, id: Id) -> Option<&Poly> {
        self.nf[id as usize].as_deref()
    }

    /// Number of nodes.
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    /// Whether the graph is empty.
    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// The constant value of a node, if it is a `Num`.
    pub fn as_num(&self, id: Id) -> Option<&Rat> {
        match &self.nodes[id as usize] {
            Node::Num(r) => Some(r),
            _ => None,
        }
    }

    /// Add `node` as it is (no folding, no value numbering), its normal form given by
    /// `nf` if the node is new: for passes that rewrite the graph's shape and carry
    /// the values over. The node does not become its value's representative (value
    /// numbering keeps finding the node it found before), which also spares hashing
    /// the normal form.
    pub(crate) fn intern_node(&mut self, node: Node, nf: impl FnOnce(&Self) -> Option<Poly>) -> Id {
        if let Some(&id) = self.memo.get(&node) {
            return id;
        }
        let nf = nf(self);
        let id = self.nodes.len() as Id;
        let cost = self.tree_cost(&node);
        self.nodes.push(node.clone());
        self.memo.insert(node, id);
        self.nf.push(nf.map(Arc::new));
        self.cost.push(cost);
        id
    }

    fn intern(&mut self, node: Node, nf: Option<Poly>) -> Id {
        let fp = nf.as_ref().map(Poly::fingerprint);
        self.intern_with(node, nf, fp)
    }

    /// [`Graph::intern`] with the normal form's fingerprint already computed.
    fn intern_with(&mut self, node: Node, nf: Option<Poly>, fp: Option<u64>) -> Id {
        if let Some(&id) = self.memo.get(&node) {
            return id;
        }
        let id = self.nodes.len() as Id;
        let cost = self.tree_cost(&node);
        self.nodes.push(node.clone());
        self.memo.insert(node, id);
        if let (Some(p), Some(fp)) = (&nf, fp) {
            // The cheapest node of a value represents it from now on.
            match self.representative(p, fp) {
                Some(old) if self.cost[old as usize] <= cost => {}
                Some(old) => {
                    let bucket = self.by_nf.get_mut(&fp).expect("found above");
                    let slot = bucket.iter_mut().find(|x| **x == old).expect("found above");
                    *slot = id;
                }
                None => self.by_nf.entry(fp).or_default().push(id),
            }
        }
        self.nf.push(nf.map(Arc::new));
        self.cost.push(cost);
        id
    }

    /// A rational constant.
    pub fn num(&mut self, r: Rat) -> Id {
        let p = Poly::constant(r.clone());
        self.intern(Node::Num(r), Some(p))
    }

    /// An integer constant.
    pub fn int(&mut self, i: i64) -> Id {
        self.num(Rat::from_integer(i.into()))
    }

    /// A variable.
    pub fn leaf(&mut self, v: Var) -> Id {
        self.intern(Node::Leaf(v), Some(Poly::var(v)))
    }

    fn tree_cost(&self, node: &Node) -> u32 {
        let c = |x: &Id| self.cost[*x as usize];
        match node {
            Node::Num(_) | Node::Leaf(_) => 0,
            Node::Add(a, b) | Node::Sub(a, b) | Node::Mul(a, b) => {
                c(a).saturating_add(c(b)).saturating_add(1)
            }
            Node::Neg(a) => c(a).saturating_add(1),
        }
    }

    /// The node representing the value `p` (whose fingerprint is `fp`), if any.
    fn representative(&self, p: &Poly, fp: u64) -> Option<Id> {
        let same = |id: &&Id| self.nf[**id as usize].as_deref() == Some(p);
        self.by_nf.get(&fp)?.iter().find(same).copied()
    }

    /// The node representing the value `−p` (`fp` is `p`'s fingerprint), if any.
    fn opposite(&self, p: &Poly, fp: u64) -> Option<Id> {
        let opposite = |id: &&Id| {
            self.nf[**id as usize]
                .as_ref()
                .is_some_and(|q| q.is_negation_of(p))
        };
        self.by_nf
            .get(&fp.wrapping_neg())?
            .iter()
            .find(opposite)
            .copied()
    }

    /// Look up or create a node whose value is `nf` (when known), built as `node`.
    fn make(&mut self, node: Node, nf: Option<Poly>) -> Id {
        if let Some(p) = &nf {
            if let Some(r) = p.as_constant() {
                return self.num(r);
            }
            let fp = p.fingerprint();
            if let Some(id) = self.representative(p, fp) {
                // An equal value exists; keep it unless this form is cheaper.
                if self.cost[id as usize] <= self.tree_cost(&node) {
                    return id;
                }
                return self.intern_with(node, nf, Some(fp));
            }
            if let Some(id) = self.opposite(p, fp) {
                // Value is −(existing): share it through a negation.
                if !matches!(node, Node::Neg(x) if x == id) {
                    return self.intern_with(Node::Neg(id), nf, Some(fp));
                }
            }
            return self.intern_with(node, nf, Some(fp));
        }
        self.intern(node, nf)
    }

    fn nf2(
        &mut self,
        a: Id,
        b: Id,
        f: impl Fn(&Ring, &Poly, &Poly, usize) -> Option<Poly>,
    ) -> Option<Poly> {
        self.nf[a as usize].as_ref()?;
        self.nf[b as usize].as_ref()?;
        // Past the deadline: structural sharing only, which is always correct.
        if self.past_deadline() {
            self.nf_timeouts += 1;
            return None;
        }
        let (pa, pb) = (
            self.nf[a as usize].as_deref()?,
            self.nf[b as usize].as_deref()?,
        );
        let p = f(&self.ring, pa, pb, self.max_terms);
        match p {
            Some(p) if p.len() <= self.max_terms => Some(p),
            _ => {
                self.nf_overflows += 1;
                None
            }
        }
    }

    /// `a + b`.
    pub fn add(&mut self, a: Id, b: Id) -> Id {
        if let (Some(x), Some(y)) = (self.as_num(a), self.as_num(b)) {
            let r = x + y;
            return self.num(r);
        }
        if self.as_num(a).is_some_and(Zero::is_zero) {
            return b;
        }
        if self.as_num(b).is_some_and(Zero::is_zero) {
            return a;
        }
        // a + (−b) is a − b.
        if let Node::Neg(x) = self.nodes[b as usize] {
            return self.sub(a, x);
        }
        if let Node::Neg(x) = self.nodes[a as usize] {
            return self.sub(b, x);
        }
        let (a, b) = (a.min(b), a.max(b));
        let nf = self.nf2(a, b, |_, x, y, _| Some(x.add(y)));
        self.make(Node::Add(a, b), nf)
    }

    /// `a − b`.
    pub fn sub(&mut self, a: Id, b: Id) -> Id {
        if a == b {
            return self.int(0);
        }
        if let (Some(x), Some(y)) = (self.as_num(a), self.as_num(b)) {
            let r = x - y;
            return self.num(r);
        }
        if self.as_num(b).is_some_and(Zero::is_zero) {
            return a;
        }
        if self.as_num(a).is_some_and(Zero::is_zero) {
            return self.neg(b);
        }
        if let Node::Neg(x) = self.nodes[b as usize] {
            return self.add(a, x);
        }
        // −x − b = −(x + b): keeps sums positive so that sin(q1+q2) is found as one.
        if let Node::Neg(x) = self.nodes[a as usize] {
            let s = self.add(x, b);
            return self.neg(s);
        }
        let nf = self.nf2(a, b, |_, x, y, _| Some(x.sub(y)));
        self.make(Node::Sub(a, b), nf)
    }

    /// `−a`.
    pub fn neg(&mut self, a: Id) -> Id {
        if let Some(x) = self.as_num(a) {
            let r = -x;
            return self.num(r);
        }
        match self.nodes[a as usize] {
            Node::Neg(x) => x,
            Node::Sub(x, y) => self.sub(y, x),
            _ => {
                let Some(p) = &self.nf[a as usize] else {
                    return self.intern(Node::Neg(a), None);
                };
                let fp = p.fingerprint();
                if let Some(id) = self.opposite(p, fp) {
                    return id;
                }
                let nf = p.neg();
                self.intern_with(Node::Neg(a), Some(nf), Some(fp.wrapping_neg()))
            }
        }
    }

    /// `a · b`.
    pub fn mul(&mut self, a: Id, b: Id) -> Id {
        if let (Some(x), Some(y)) = (self.as_num(a), self.as_num(b)) {
            let r = x * y;
            return self.num(r);
        }
        for (k, x) in [(a, b), (b, a)] {
            if let Some(r) = self.as_num(k) {
                if r.is_zero() {
                    return self.int(0);
                }
                if r.is_one() {
                    return x;
                }
                if (-r).is_one() {
                    return self.neg(x);
                }
            }
        }
        // Keep signs outside products: (−x)·y = −(x·y).
        if let Node::Neg(x) = self.nodes[a as usize] {
            let m = self.mul(x, b);
            return self.neg(m);
        }
        if let Node::Neg(y) = self.nodes[b as usize] {
            let m = self.mul(a, y);
            return self.neg(m);
        }
        // Constants first, then negative constants become negations of products.
        if let Some(r) = self.as_num(a).or(self.as_num(b)) {
            if r.is_negative() {
                let pos = -r.clone();
                let k = self.num(pos);
                let x = if self.as_num(a).is_some() { b } else { a };
                let m = self.mul(k, x);
                return self.neg(m);
            }
        }
        let (a, b) = (a.min(b), a.max(b));
        let nf = self.nf2(a, b, |ring, x, y, max| ring.mul_bounded(x, y, max).ok());
        self.make(Node::Mul(a, b), nf)
    }

    /// `Σ xᵢ` (0 for none).
    pub fn sum(&mut self, xs: &[Id]) -> Id {
        let mut acc = self.int(0);
        for &x in xs {
            acc = self.add(acc, x);
        }
        acc
    }

    /// Build a polynomial as straight-line code: terms grouped by their leading
    /// variables (a greedy Horner scheme), shared through the graph.
    pub fn from_poly(&mut self, p: &Poly) -> Id {
        let terms: Vec<(Vec<(Var, u32)>, Rat)> =
            p.terms().map(|(m, c)| (m.clone(), c.clone())).collect();
        self.horner(terms)
    }

    fn horner(&mut self, terms: Vec<(Vec<(Var, u32)>, Rat)>) -> Id {
        if terms.is_empty() {
            return self.int(0);
        }
        // Pull out the rational content: 2a + 4b = 2(a + 2b).
        if terms.len() > 1 {
            let g = terms
                .iter()
                .map(|(_, c)| c.abs())
                .reduce(|x, y| rat_gcd(&x, &y))
                .unwrap_or_else(Rat::one);
            let g = if terms[0].1.is_negative() { -g } else { g };
            if !g.is_one() {
                let inner = terms.into_iter().map(|(m, c)| (m, c / &g)).collect();
                let x = self.horner(inner);
                let k = self.num(g);
                return self.mul(k, x);
            }
        }
        if terms.len() == 1 {
            let (m, c) = &terms[0];
            let mut acc = self.num(c.clone());
            for &(v, e) in m {
                let l = self.leaf(v);
                for _ in 0..e {
                    acc = self.mul(acc, l);
                }
            }
            return acc;
        }
        // The variable in most terms.
        let mut count: std::collections::BTreeMap<Var, usize> = Default::default();
        for (m, _) in &terms {
            for &(v, _) in m {
                *count.entry(v).or_default() += 1;
            }
        }
        let best = count
            .iter()
            .max_by(|x, y| x.1.cmp(y.1).then(y.0.cmp(x.0)))
            .map(|(&v, &n)| (v, n));
        match best {
            Some((v, n)) if n >= 2 => {
                let (with, without): (Vec<_>, Vec<_>) = terms
                    .into_iter()
                    .partition(|(m, _)| m.iter().any(|&(w, _)| w == v));
                let reduced = with
                    .into_iter()
                    .map(|(m, c)| {
                        let m: Vec<(Var, u32)> = m
                            .into_iter()
                            .filter_map(|(w, e)| {
                                if w == v {
                                    (e > 1).then_some((w, e - 1))
                                } else {
                                    Some((w, e))
                                }
                            })
                            .collect();
                        (m, c)
                    })
                    .collect();
                let inner = self.horner(reduced);
                let l = self.leaf(v);
                let prod = self.mul(l, inner);
                let rest = self.horner(without);
                self.add(prod, rest)
            }
            _ => {
                let mut ids = Vec::new();
                for t in terms {
                    ids.push(self.horner(vec![t]));
                }
                self.sum(&ids)
            }
        }
    }

    /// Operations (additions, subtractions, products, negations of non-constants)
    /// reachable from `outputs`, each shared node once: what straight-line code computing
    /// them costs.
    pub fn op_count(&self, outputs: &[Id]) -> usize {
        let mut seen = std::collections::BTreeSet::new();
        let mut stack = outputs.to_vec();
        let mut ops = 0;
        while let Some(id) = stack.pop() {
            if !seen.insert(id) {
                continue;
            }
            let node = &self.nodes[id as usize];
            ops += usize::from(match node {
                Node::Num(_) | Node::Leaf(_) => false,
                Node::Neg(x) => self.as_num(*x).is_none(),
                _ => true,
            });
            stack.extend(node.children());
        }
        ops
    }

    /// Numeric value of a node with variable values `x`.
    pub fn eval(&self, id: Id, x: &dyn Fn(Var) -> f64) -> f64 {
        self.eval_in(id, x, &mut EvalScratch::default())
    }

    /// [`Graph::eval`] with reusable scratch space: repeated calls (16 points per checked
    /// rewrite) neither allocate nor clear a memo the size of the graph.
    pub fn eval_in(&self, id: Id, x: &dyn Fn(Var) -> f64, scratch: &mut EvalScratch) -> f64 {
        scratch.start(self.nodes.len());
        self.eval_memo(id, x, scratch)
    }

    /// [`Graph::eval_in`] keeping the values `scratch` holds from earlier calls: for a
    /// caller that evaluates many nodes of one growing graph at the same `x` (a node's
    /// value never changes once it is built), each node once in all.
    pub fn eval_kept(&self, id: Id, x: &dyn Fn(Var) -> f64, scratch: &mut EvalScratch) -> f64 {
        scratch.keep(self.nodes.len());
        self.eval_memo(id, x, scratch)
    }

    /// Values of several nodes at the same variable values `x`, each shared node
    /// evaluated once.
    pub fn eval_all(&self, ids: &[Id], x: &dyn Fn(Var) -> f64) -> Vec<f64> {
        let mut scratch = EvalScratch::default();
        scratch.start(self.nodes.len());
        ids.iter()
            .map(|&id| self.eval_memo(id, x, &mut scratch))
            .collect()
    }

    fn eval_memo(&self, id: Id, x: &dyn Fn(Var) -> f64, memo: &mut EvalScratch) -> f64 {
        if let Some(v) = memo.get(id) {
            return v;
        }
        let v = match &self.nodes[id as usize] {
            Node::Num(r) => crate::model::value::rat_to_f64(r),
            Node::Leaf(v) => x(*v),
            Node::Add(a, b) => self.eval_memo(*a, x, memo) + self.eval_memo(*b, x, memo),
            Node::Sub(a, b) => self.eval_memo(*a, x, memo) - self.eval_memo(*b, x, memo),
            Node::Mul(a, b) => self.eval_memo(*a, x, memo) * self.eval_memo(*b, x, memo),
            Node::Neg(a) => -self.eval_memo(*a, x, memo),
        };
        memo.set(id, v);
        v
    }
}

/// Memo of [`Graph::eval_in`]: each value is stamped with the call that computed it,
/// so a new call starts empty by bumping the stamp.
#[derive(Clone, Debug, Default)]
pub struct EvalScratch {
    values: Vec<(u32, f64)>,
    call: u32,
}

impl EvalScratch {
    fn start(&mut self, nodes: usize) {
        self.call = self.call.wrapping_add(1);
        if self.call == 0 {
            // Stamps wrapped around: forget everything once.
            self.values.clear();
            self.call = 1;
        }
        if self.values.len() < nodes {
            self.values.resize(nodes, (0, 0.0));
        }
    }

    /// Room for `nodes` values, those already stamped kept.
    fn keep(&mut self, nodes: usize) {
        if self.call == 0 {
            self.call = 1;
        }
        if self.values.len() < nodes {
            self.values.resize(nodes, (0, 0.0));
        }
    }

    fn get(&self, id: Id) -> Option<f64> {
        let (call, v) = self.values[id as usize];
        (call == self.call).then_some(v)
    }

    fn set(&mut self, id: Id, v: f64) {
        self.values[id as usize] = (self.call, v);
    }
}

fn rat_gcd(a: &Rat, b: &Rat) -> Rat {
    use num_integer::Integer;
    Rat::new(a.numer().gcd(b.numer()), a.denom().lcm(b.denom()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn equal_values_are_one_node() {
        let mut g = Graph::default();
        let (s, c) = g.ring.angle(0, "1");
        let (s, c) = (g.leaf(s), g.leaf(c));
        let ss = g.mul(s, s);
        let cc = g.mul(c, c);
        let one = g.add(ss, cc);
        assert_eq!(g.as_num(one), Some(&Rat::one()));
        // c² − 1 = −s²: found as the negation of the existing node.
        let m1 = g.int(1);
        let x = g.sub(cc, m1);
        assert_eq!(g.node(x), &Node::Neg(ss));
    }

    #[test]
    fn past_the_deadline_nodes_are_shared_structurally_only() {
        let mut g = Graph::default();
        let (s, c) = g.ring.angle(0, "1");
        let (s, c) = (g.leaf(s), g.leaf(c));
        g.deadline = Deadline::after_ms(0);
        let ss = g.mul(s, s);
        let cc = g.mul(c, c);
        let one = g.add(ss, cc);
        // s² + c² is no longer seen to be 1: a node without normal form, still correct.
        assert!(g.nf(one).is_none() && g.as_num(one).is_none());
        // Two products dropped theirs; the sum has operands without one.
        assert_eq!(g.nf_timeouts, 2);
        assert_eq!(g.nf_overflows, 0);
        let x = 0.3f64;
        let v = g.eval(one, &|v| if v == 0 { x.sin() } else { x.cos() });
        assert!((v - 1.0).abs() < 1e-15);
        // Structural sharing still applies.
        assert_eq!(g.mul(s, s), ss);
    }

    #[test]
    fn horner_groups_terms() {
        let mut g = Graph::default();
        let (s, c) = g.ring.angle(0, "1");
        let a = g.ring.param("a");
        let p = Poly::from_terms([
            (vec![(s, 1), (a, 1)], Rat::one()),
            (vec![(c, 1), (a, 1)], Rat::one()),
        ]);
        let id = g.from_poly(&p);
        assert_eq!(g.nf(id), Some(&p));
        // a·(s + c): one multiplication.
        assert!(matches!(g.node(id), Node::Mul(..)));
    }
}
