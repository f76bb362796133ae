//! Where the minus signs go: each intermediate is computed as its value or as its
//! negation, whichever makes the fewest negations overall.
//!
//! Construction keeps signs outside products and sums (that is what lets value
//! numbering see `−x` as `x`), so a Jacobian arrives with many `−(…)`. A negation is
//! free wherever it can be absorbed: `a + (−b)` is `a − b`, `(−a)·(−b)` is `a·b`,
//! `−(a − b)` is `b − a`, a constant takes any sign. What it costs is a choice per node —
//! compute `v` or `−v` — and the choices interact through every use of the node, so
//! this is a small binary optimisation over the DAG: minimise the negations left, where
//!
//! * a sum `±a ± b` needs one only when both terms enter negated (`−(a + b)`);
//! * a product needs one when the signs of its factors multiply to the wrong sign,
//!   unless a factor is a constant, or a variable whose negation (`−c1`, one negation
//!   shared by every product it signs) is computed anyway;
//! * an output needs one when its node is computed negated.
//!
//! A deterministic local search (ejection chains: flip a node, then whichever
//! neighbours now want flipping) finds a low-cost choice in a few milliseconds; the
//! graph is then rebuilt with that choice. Readability breaks ties: a product
//! prefers `c1 * x` to `t2 * y` (`t2 = −c1`) at equal count. Negation is exact in IEEE arithmetic, so every output has the same
//! bits as before, only the count of `neg` instructions changes. Normal forms are
//! carried over (negated where the node is), so the value checks downstream apply.

use std::collections::HashMap;

use crate::algebra::graph::{Graph, Id, Node};
use crate::algebra::poly::Poly;
use crate::model::options::Deadline;

/// The same outputs with signs chosen to minimise negations.
pub struct Signed {
    /// The new ids of the outputs, in order.
    pub ids: Vec<Id>,
    /// The graph's deadline passed during the search: the choices made until then are
    /// kept (every choice is correct; fewer negations were saved).
    pub cut: bool,
}

/// The same outputs with signs chosen to minimise negations, searching until the
/// graph's deadline at the latest.
pub fn assign(g: &mut Graph, outputs: &[Id]) -> Signed {
    let problem = Problem::new(g, outputs);
    let (choice, cut) = problem.solve(&g.deadline);
    Signed {
        ids: problem.rebuild(g, &choice),
        cut,
    }
}

/// Cost of one negation instruction (outweighs any number of [`SIGNED_FACTOR`]s).
const NEG: u32 = 1 << 16;
/// Cost of writing a product with a negated variable (`t2 * x` for `−c1·x`) where a
/// sign-free form might exist: no instruction, but less readable; breaks ties.
const SIGNED_FACTOR: u32 = 1;

/// Moves of the search between two looks at the clock.
const MOVES_PER_CLOCK_READ: u32 = 1024;

/// Longest ejection chain (flips in one move).
const MAX_CHAIN: usize = 12;

/// Most consumers of a node a chain may pass through. A busier node only starts chains
/// of its own: passing through it costs a look at every consumer, and each consumer's
/// chain would pass through it. (In a long chain's Jacobian the tool position is used
/// by every column: through it, the search was quadratic in the joints — 2.7 s of one
/// 4 000-joint function's search.)
const MAX_CHAIN_DEGREE: usize = 64;

/// Work space of the local search.
struct Scratch {
    mark: Vec<u32>,
    stamp: u32,
    chain: Vec<usize>,
    queue: std::collections::VecDeque<usize>,
}

impl Scratch {
    fn new(n: usize) -> Self {
        Scratch {
            mark: vec![0; n],
            stamp: 0,
            chain: Vec::new(),
            queue: std::collections::VecDeque::new(),
        }
    }
}

/// The reachable part of the graph in local indices, children before parents.
struct Problem {
    /// Graph ids of the reachable nodes, ascending (children have smaller ids).
    ids: Vec<Id>,
    /// Node kinds in local indices.
    nodes: Vec<Local>,
    /// Consumers of each node (local indices; a node used twice appears twice).
    parents: Vec<Vec<usize>>,
    /// How many outputs are each node.
    output_uses: Vec<usize>,
    /// Local index of each output.
    outputs: Vec<usize>,
}

#[derive(Clone, Copy, Debug)]
enum Local {
    /// A constant: takes either sign for free.
    Num,
    /// A variable: computed as itself; its negation is a separate, shared choice.
    Leaf,
    /// `a + b`.
    Add(usize, usize),
    /// `a − b`.
    Sub(usize, usize),
    /// `a · b`.
    Mul(usize, usize),
    /// `−a`.
    Neg(usize),
}

/// A choice: `neg[i]` — node `i` is computed negated (never for constants and
/// variables); `neg_leaf[i]` — variable `i`'s negation is computed (shared).
#[derive(Clone, Debug, PartialEq, Eq)]
struct Choice {
    neg: Vec<bool>,
    neg_leaf: Vec<bool>,
}

impl Problem {
    fn new(g: &Graph, outputs: &[Id]) -> Problem {
        let mut seen = std::collections::BTreeSet::new();
        let mut stack = outputs.to_vec();
        while let Some(id) = stack.pop() {
            if seen.insert(id) {
                stack.extend(g.node(id).children());
            }
        }
        let ids: Vec<Id> = seen.into_iter().collect();
        let local: HashMap<Id, usize> = ids.iter().enumerate().map(|(i, &id)| (id, i)).collect();
        let nodes: Vec<Local> = ids
            .iter()
            .map(|&id| match *g.node(id) {
                Node::Num(_) => Local::Num,
                Node::Leaf(_) => Local::Leaf,
                Node::Add(a, b) => Local::Add(local[&a], local[&b]),
                Node::Sub(a, b) => Local::Sub(local[&a], local[&b]),
                Node::Mul(a, b) => Local::Mul(local[&a], local[&b]),
                Node::Neg(a) => Local::Neg(local[&a]),
            })
            .collect();
        let mut parents = vec![Vec::new(); ids.len()];
        for (i, n) in nodes.iter().enumerate() {
            for c in local_children(*n) {
                // Ids grow with construction: operands come first (`rebuild` relies on it).
                debug_assert!(c < i);
                parents[c].push(i);
            }
        }
        let mut output_uses = vec![0; ids.len()];
        let outputs: Vec<usize> = outputs.iter().map(|o| local[o]).collect();
        for &o in &outputs {
            output_uses[o] += 1;
        }
        Problem {
            ids,
            nodes,
            parents,
            output_uses,
            outputs,
        }
    }

    fn free(&self, i: usize) -> bool {
        !matches!(self.nodes[i], Local::Num | Local::Leaf)
    }

    /// Sign (+1 / −1) with which node `c` is available.
    fn sign(&self, ch: &Choice, c: usize) -> i8 {
        if ch.neg[c] {
            -1
        } else {
            1
        }
    }

    /// What node `i` costs under `ch` (its own, not its children's): [`NEG`] per
    /// negation it needs — its own, and one per output that is this node computed
    /// negated — and [`SIGNED_FACTOR`] when a product takes its sign from a negated
    /// variable.
    fn cost(&self, ch: &Choice, i: usize) -> u32 {
        let s = self.sign(ch, i);
        let own = match self.nodes[i] {
            Local::Num | Local::Leaf => 0,
            Local::Add(a, b) | Local::Sub(a, b) => {
                // Constants agree with any sign.
                let (ta, tb) = self.term_signs(ch, i);
                let neg_a = !self.is_num(a) && ta < 0;
                let neg_b = !self.is_num(b) && tb < 0;
                NEG * u32::from(neg_a && neg_b)
            }
            Local::Mul(a, b) => {
                let p = s * self.sign(ch, a) * self.sign(ch, b);
                let signed = |x: usize| self.is_leaf(x) && ch.neg_leaf[x];
                if p > 0 || self.is_num(a) || self.is_num(b) {
                    0
                } else if signed(a) || signed(b) {
                    SIGNED_FACTOR
                } else {
                    NEG
                }
            }
            Local::Neg(a) => {
                let shared = self.is_leaf(a) && ch.neg_leaf[a];
                NEG * u32::from(!self.is_num(a) && !shared && -s * self.sign(ch, a) < 0)
            }
        };
        let out = if s < 0 {
            NEG * self.output_uses[i] as u32
        } else {
            0
        };
        own + out
    }

    /// For a sum or difference `i` computed as `s·v`: the sign with which each
    /// operand, as it is available, enters (`s·(a ± b) = ta·wa + tb·wb`); a term enters
    /// negated when that sign is −1.
    fn term_signs(&self, ch: &Choice, i: usize) -> (i8, i8) {
        let s = self.sign(ch, i);
        match self.nodes[i] {
            Local::Add(a, b) => (s * self.sign(ch, a), s * self.sign(ch, b)),
            Local::Sub(a, b) => (s * self.sign(ch, a), -s * self.sign(ch, b)),
            _ => unreachable!("term_signs of a sum or difference"),
        }
    }

    fn is_num(&self, i: usize) -> bool {
        matches!(self.nodes[i], Local::Num)
    }

    fn is_leaf(&self, i: usize) -> bool {
        matches!(self.nodes[i], Local::Leaf)
    }

    /// Change of the total when node `i` (or, for a variable, its shared negation)
    /// flips.
    fn delta(&self, ch: &mut Choice, i: usize) -> i64 {
        let before = self.local_cost(ch, i);
        self.flip(ch, i);
        let after = self.local_cost(ch, i);
        self.flip(ch, i);
        after - before
    }

    /// Every cost term that depends on node `i`'s sign.
    fn local_cost(&self, ch: &Choice, i: usize) -> i64 {
        let mut c = i64::from(self.cost(ch, i));
        let mut last = usize::MAX;
        for &p in &self.parents[i] {
            // A parent using `i` twice (`x·x`) is counted once.
            if p != last && p != i {
                c += i64::from(self.cost(ch, p));
            }
            last = p;
        }
        if self.is_leaf(i) && ch.neg_leaf[i] {
            c += i64::from(NEG);
        }
        c
    }

    fn flip(&self, ch: &mut Choice, i: usize) {
        if self.is_leaf(i) {
            ch.neg_leaf[i] = !ch.neg_leaf[i];
        } else {
            ch.neg[i] = !ch.neg[i];
        }
    }

    /// Local search from "every node as built" (see [`Problem::descend`]).
    /// Deterministic: no randomness, nodes tried in index order. (Random restarts
    /// were measured: 200 of them saved one negation in UR5's `fk` for 15× the time.)
    /// Returns the choice and whether `deadline` cut the search short.
    fn solve(&self, deadline: &Deadline) -> (Choice, bool) {
        let n = self.nodes.len();
        let mut ch = Choice {
            neg: vec![false; n],
            neg_leaf: vec![false; n],
        };
        let is_var: Vec<bool> = (0..n)
            .map(|i| {
                self.free(i)
                    || (self.is_leaf(i)
                        && self.parents[i]
                            .iter()
                            .any(|&p| matches!(self.nodes[p], Local::Mul(..) | Local::Neg(_))))
            })
            .collect();
        let vars: Vec<usize> = (0..n).filter(|&i| is_var[i]).collect();
        if vars.is_empty() {
            return (ch, false);
        }
        let mut sc = Scratch::new(n);
        let cut = !self.descend(&mut ch, &vars, &is_var, &mut sc, deadline);
        (ch, cut)
    }

    /// Local descent from the nodes in `start`: flip a node, then each neighbour
    /// (consumer or operand) whose flip now pays or is free, transitively — an
    /// ejection chain, kept if the chain as a whole saves. The neighbours of a kept
    /// chain are tried again; done when no node is left to try (`true`) or at the
    /// deadline (`false`: the chains kept so far stay).
    fn descend(
        &self,
        ch: &mut Choice,
        start: &[usize],
        is_var: &[bool],
        sc: &mut Scratch,
        deadline: &Deadline,
    ) -> bool {
        let mut work: std::collections::VecDeque<usize> = start.iter().copied().collect();
        let mut waiting = vec![false; self.nodes.len()];
        for &v in start {
            waiting[v] = true;
        }
        while let Some(v) = work.pop_front() {
            if sc.stamp % MOVES_PER_CLOCK_READ == 0 && deadline.passed() {
                return false;
            }
            waiting[v] = false;
            sc.stamp += 1;
            sc.chain.clear();
            sc.queue.clear();
            let mut d = self.delta(ch, v);
            self.flip(ch, v);
            sc.mark[v] = sc.stamp;
            sc.chain.push(v);
            sc.queue.extend(self.parents[v].iter().copied());
            sc.queue.extend(local_children(self.nodes[v]));
            while let Some(p) = sc.queue.pop_front() {
                if sc.chain.len() >= MAX_CHAIN {
                    break;
                }
                // Variables (with their many consumers) and busy nodes only start chains.
                if sc.mark[p] == sc.stamp
                    || !self.free(p)
                    || self.parents[p].len() > MAX_CHAIN_DEGREE
                {
                    continue;
                }
                let dp = self.delta(ch, p);
                if dp <= 0 {
                    self.flip(ch, p);
                    sc.mark[p] = sc.stamp;
                    d += dp;
                    sc.chain.push(p);
                    sc.queue.extend(self.parents[p].iter().copied());
                    sc.queue.extend(local_children(self.nodes[p]));
                }
            }
            if d < 0 {
                for k in 0..sc.chain.len() {
                    let x = sc.chain[k];
                    let near = self.parents[x]
                        .iter()
                        .copied()
                        .chain(local_children(self.nodes[x]))
                        .chain([x]);
                    for y in near {
                        if is_var[y] && !waiting[y] {
                            waiting[y] = true;
                            work.push_back(y);
                        }
                    }
                }
            } else {
                for &x in sc.chain.iter().rev() {
                    self.flip(ch, x);
                }
            }
        }
        true
    }

    /// Rebuild the reachable graph under `ch`; returns the outputs' new ids.
    fn rebuild(&self, g: &mut Graph, ch: &Choice) -> Vec<Id> {
        let n = self.nodes.len();
        // `built[i]`: id of `sign(i) · node i`.
        let mut built: Vec<Id> = vec![0; n];
        for i in 0..n {
            let id = self.ids[i];
            let s = self.sign(ch, i);
            built[i] = match self.nodes[i] {
                Local::Num | Local::Leaf => id,
                Local::Add(a, b) | Local::Sub(a, b) => {
                    let (ta, tb) = self.term_signs(ch, i);
                    let (ta, xa) = self.term(g, &built, a, ta);
                    let (tb, xb) = self.term(g, &built, b, tb);
                    let nf = |g: &Graph| signed_nf(g, id, s);
                    match (ta > 0, tb > 0) {
                        (true, true) => g.intern_node(Node::Add(xa.min(xb), xa.max(xb)), nf),
                        (true, false) => g.intern_node(Node::Sub(xa, xb), nf),
                        (false, true) => g.intern_node(Node::Sub(xb, xa), nf),
                        (false, false) => {
                            let pos = |g: &Graph| signed_nf(g, id, -s);
                            let sum = g.intern_node(Node::Add(xa.min(xb), xa.max(xb)), pos);
                            g.intern_node(Node::Neg(sum), nf)
                        }
                    }
                }
                Local::Mul(a, b) => {
                    let p = s * self.sign(ch, a) * self.sign(ch, b);
                    let nf = |g: &Graph| signed_nf(g, id, s);
                    let (xa, xb) = (built[a], built[b]);
                    if p > 0 {
                        g.intern_node(Node::Mul(xa.min(xb), xa.max(xb)), nf)
                    } else if let Some((x, other)) = self.absorber(ch, a, b, &built) {
                        let nx = self.negated(g, x);
                        g.intern_node(Node::Mul(nx.min(other), nx.max(other)), nf)
                    } else {
                        let pos = |g: &Graph| signed_nf(g, id, -s);
                        let m = g.intern_node(Node::Mul(xa.min(xb), xa.max(xb)), pos);
                        g.intern_node(Node::Neg(m), nf)
                    }
                }
                Local::Neg(a) => {
                    if self.is_num(a) {
                        let v = g.as_num(self.ids[a]).expect("constant").clone();
                        g.num(if s > 0 { -v } else { v })
                    } else if -s * self.sign(ch, a) > 0 {
                        // `s·(−a)` is what is already computed for `a`.
                        built[a]
                    } else {
                        let nf = |g: &Graph| signed_nf(g, id, s);
                        g.intern_node(Node::Neg(built[a]), nf)
                    }
                }
            };
        }
        self.outputs
            .iter()
            .map(|&o| {
                if self.sign(ch, o) > 0 {
                    built[o]
                } else {
                    let o_id = self.ids[o];
                    let nf = |g: &Graph| signed_nf(g, o_id, 1);
                    g.intern_node(Node::Neg(built[o]), nf)
                }
            })
            .collect()
    }

    /// A term of a sum: `(sign it enters with, id)`; a constant is folded to enter
    /// positively.
    fn term(&self, g: &mut Graph, built: &[Id], c: usize, t: i8) -> (i8, Id) {
        if self.is_num(c) && t < 0 {
            let v = g.as_num(self.ids[c]).expect("constant").clone();
            return (1, g.num(-v));
        }
        (t, built[c])
    }

    /// For a product of the wrong sign: the factor that takes the sign (a constant,
    /// or a variable whose negation is computed) and the other factor's id.
    fn absorber(&self, ch: &Choice, a: usize, b: usize, built: &[Id]) -> Option<(usize, Id)> {
        let ok = |x: usize| self.is_num(x) || (self.is_leaf(x) && ch.neg_leaf[x]);
        // Constants first: folding costs nothing at all.
        [(a, b), (b, a)]
            .into_iter()
            .find(|&(x, _)| self.is_num(x))
            .or_else(|| [(a, b), (b, a)].into_iter().find(|&(x, _)| ok(x)))
            .map(|(x, other)| (x, built[other]))
    }

    /// `−x` for a constant or variable.
    fn negated(&self, g: &mut Graph, x: usize) -> Id {
        let id = self.ids[x];
        match g.as_num(id) {
            Some(v) => {
                let v = -v.clone();
                g.num(v)
            }
            None => {
                let nf = |g: &Graph| signed_nf(g, id, -1);
                g.intern_node(Node::Neg(id), nf)
            }
        }
    }
}

fn local_children(n: Local) -> Vec<usize> {
    match n {
        Local::Num | Local::Leaf => vec![],
        Local::Add(a, b) | Local::Sub(a, b) | Local::Mul(a, b) => vec![a, b],
        Local::Neg(a) => vec![a],
    }
}

fn signed_nf(g: &Graph, id: Id, s: i8) -> Option<Poly> {
    g.nf(id).map(|p| if s > 0 { p.clone() } else { p.neg() })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Negation instructions the emitted code would have: reachable `Neg` nodes
    /// (of anything but a constant, which is folded into the literal).
    fn negations(g: &Graph, outputs: &[Id]) -> usize {
        let mut seen = std::collections::BTreeSet::new();
        let mut stack = outputs.to_vec();
        while let Some(id) = stack.pop() {
            if seen.insert(id) {
                stack.extend(g.node(id).children());
            }
        }
        seen.iter()
            .filter(|&&id| matches!(g.node(id), Node::Neg(x) if g.as_num(*x).is_none()))
            .count()
    }

    /// A leaf for a new parameter `name`.
    fn param(g: &mut Graph, name: &str) -> Id {
        let v = g.ring.param(name);
        g.leaf(v)
    }

    fn values(g: &Graph, outputs: &[Id], x: &[f64]) -> Vec<f64> {
        outputs
            .iter()
            .map(|&o| g.eval(o, &|v| x[v as usize]))
            .collect()
    }

    #[test]
    fn signs_are_absorbed_by_sums_products_and_shared_negations() {
        let mut g = Graph::default();
        let [a, b, c, d] = ["a", "b", "c", "d"].map(|n| param(&mut g, n));
        // −(a·b), −(c·a), −(a·d) + b, −(−(c·d) + −b)
        let ab = g.mul(a, b);
        let o1 = g.neg(ab);
        let ca = g.mul(c, a);
        let o2 = g.neg(ca);
        let ad = g.mul(a, d);
        let nad = g.neg(ad);
        let o3 = g.add(nad, b);
        let cd = g.mul(c, d);
        let ncd = g.neg(cd);
        let nb = g.neg(b);
        let s = g.add(ncd, nb);
        let o4 = g.neg(s);
        let outs = [o1, o2, o3, o4];
        let before = negations(&g, &outs);
        let x = [0.3, -1.7, 2.9, 0.61];
        let v0 = values(&g, &outs, &x);
        let new = assign(&mut g, &outs).ids;
        assert_eq!(values(&g, &new, &x), v0);
        // o3 = b − a·d and o4 = c·d + b need none; o1, o2 share one `−a`.
        assert!(before >= 2, "the test needs negations to remove: {before}");
        assert_eq!(negations(&g, &new), 1);
    }

    #[test]
    fn a_node_too_busy_to_pass_through_keeps_the_values() {
        // h = a − b read by 100 consumers (more than a chain may pass through): −(h·c_k),
        // h·c_k − c_k and −(h + c_k). Chains stop at h; h starts its own, and each of the
        // other nodes too. (Flipping h would pay here, but only with its 100 consumers in
        // one chain, longer than `MAX_CHAIN`: the search is local either way.)
        let mut g = Graph::default();
        let [a, b] = ["a", "b"].map(|n| param(&mut g, n));
        let h = g.sub(a, b);
        let outs: Vec<Id> = (0..100)
            .map(|k| {
                let c = param(&mut g, &format!("c{k}"));
                match k % 3 {
                    0 => {
                        let m = g.mul(h, c);
                        g.neg(m)
                    }
                    1 => {
                        let m = g.mul(h, c);
                        g.sub(m, c)
                    }
                    _ => {
                        let s = g.add(h, c);
                        g.neg(s)
                    }
                }
            })
            .collect();
        let x: Vec<f64> = (0..g.ring.len()).map(|k| 0.37 + 0.61 * k as f64).collect();
        let (v0, n0) = (values(&g, &outs, &x), negations(&g, &outs));
        assert!(n0 >= 60, "the test needs negations: {n0}");
        let signed = assign(&mut g, &outs);
        assert!(!signed.cut);
        assert_eq!(values(&g, &signed.ids, &x), v0);
        assert!(negations(&g, &signed.ids) <= n0);
    }

    #[test]
    fn a_passed_deadline_stops_the_search_and_keeps_the_values() {
        let mut g = Graph::default();
        let [a, b] = ["a", "b"].map(|n| param(&mut g, n));
        // −(a·b) and −(b·a·a): one shared `−a` instead of two negations.
        let ab = g.mul(a, b);
        let aab = g.mul(ab, a);
        let outs = [g.neg(ab), g.neg(aab)];
        let x = [0.3, -1.7];
        let (v0, n0) = (values(&g, &outs, &x), negations(&g, &outs));
        let mut searched = g.clone();
        let full = assign(&mut searched, &outs);
        assert!(!full.cut);
        assert!(
            negations(&searched, &full.ids) < n0,
            "the test needs a negation to save"
        );
        g.deadline = Deadline::after_ms(0);
        let late = assign(&mut g, &outs);
        assert!(late.cut);
        assert_eq!(values(&g, &late.ids, &x), v0);
        assert_eq!(negations(&g, &late.ids), n0);
    }

    #[test]
    fn random_graphs_keep_their_values_and_never_gain_negations() {
        // A small linear congruential generator: reproducible without a dependency.
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut next = move |n: usize| {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            ((state >> 33) % n as u64) as usize
        };
        for case in 0..200 {
            let mut g = Graph::default();
            let mut pool: Vec<Id> = (0..4).map(|k| param(&mut g, &format!("p{k}"))).collect();
            pool.push(g.int(2));
            for _ in 0..24 {
                let (x, y) = (pool[next(pool.len())], pool[next(pool.len())]);
                let id = match next(4) {
                    0 => g.add(x, y),
                    1 => g.sub(x, y),
                    2 => g.mul(x, y),
                    _ => g.neg(x),
                };
                pool.push(id);
            }
            let outs: Vec<Id> = (0..6).map(|_| pool[4 + next(pool.len() - 4)]).collect();
            let x: Vec<f64> = (0..g.ring.len()).map(|k| 0.37 + 0.61 * k as f64).collect();
            let (v0, n0) = (values(&g, &outs, &x), negations(&g, &outs));
            let new = assign(&mut g, &outs).ids;
            assert_eq!(values(&g, &new, &x), v0, "case {case}");
            assert!(negations(&g, &new) <= n0, "case {case}");
        }
    }
}
