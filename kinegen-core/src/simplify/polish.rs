//! The e-graph polish: small rewrites under an operation-count cost, each result
//! checked against the unsimplified expression before it replaces it.
//!
//! The exact core already shares equal values and the chain is built in its
//! cheapest frame; what remains are local forms — `a·b + a·c` → `a·(b + c)`,
//! `−(a − b)` → `b − a`, `a + (−b)` → `a − b` — that depend on how terms happen to
//! line up. Each expression the generated code writes inline (everything between two
//! `let`s) goes through [`egg`] with these rules, bounded by the [`Budget`]'s node
//! and iteration limits and by the time left before the engine's deadline (past it,
//! the remaining expressions are kept as they are, with a note); the cheapest form
//! found replaces the original only if
//!
//! - it is cheaper, and
//! - **the check passes**: its exact normal form equals the original's (when both
//!   are within the term budget), else its value equals the original's at random
//!   points (16, relative 1e-9).
//!
//! A failed check keeps the original (correct) expression and leaves a note. Extra
//! rules can be passed in [`crate::model::options::Options::extra_rewrites`] — for
//! experiments, and for the test that shows a wrong rule cannot produce a wrong
//! formula.

use std::collections::HashMap;

use egg::{define_language, rewrite as rw, Id as EId, Pattern, RecExpr, Rewrite, Runner, Symbol};

use crate::algebra::graph::{Graph, Id, Node};
use crate::kinematics::frames::SymbolicChain;
use crate::model::options::Budget;
use crate::simplify::check::Probe;

define_language! {
    /// Arithmetic over the graph's nodes: leaves `g17` stand for graph node 17.
    pub enum Arith {
        "+" = Add([EId; 2]),
        "-" = Sub([EId; 2]),
        "*" = Mul([EId; 2]),
        "neg" = Neg(EId),
        Leaf(Symbol),
    }
}

/// The built-in rules: ring identities only (no `s² + c² = 1`), so every rewrite is
/// exact for any values of the leaves.
fn rules() -> Vec<Rewrite<Arith, ()>> {
    vec![
        rw!("comm-add"; "(+ ?a ?b)" => "(+ ?b ?a)"),
        rw!("comm-mul"; "(* ?a ?b)" => "(* ?b ?a)"),
        rw!("factor-add"; "(+ (* ?a ?b) (* ?a ?c))" => "(* ?a (+ ?b ?c))"),
        rw!("factor-sub"; "(- (* ?a ?b) (* ?a ?c))" => "(* ?a (- ?b ?c))"),
        rw!("add-neg"; "(+ ?a (neg ?b))" => "(- ?a ?b)"),
        rw!("sub-neg"; "(- ?a (neg ?b))" => "(+ ?a ?b)"),
        rw!("neg-sub"; "(neg (- ?a ?b))" => "(- ?b ?a)"),
        rw!("neg-neg"; "(neg (neg ?a))" => "?a"),
        rw!("neg-mul"; "(* (neg ?a) ?b)" => "(neg (* ?a ?b))"),
        rw!("neg-add"; "(neg (+ ?a ?b))" => "(- (neg ?a) ?b)"),
    ]
}

/// Parse user rules `(lhs, rhs)` in egg's pattern syntax.
fn extra_rules(extra: &[(String, String)]) -> Result<Vec<Rewrite<Arith, ()>>, String> {
    extra
        .iter()
        .enumerate()
        .map(|(i, (l, r))| {
            let lhs: Pattern<Arith> = l.parse().map_err(|e| format!("rule {i} lhs `{l}`: {e}"))?;
            let rhs: Pattern<Arith> = r.parse().map_err(|e| format!("rule {i} rhs `{r}`: {e}"))?;
            Rewrite::new(format!("extra-{i}"), lhs, rhs).map_err(|e| format!("rule {i}: {e}"))
        })
        .collect()
}

/// Operations of an expression: leaves are free.
struct OpCost;

impl egg::CostFunction<Arith> for OpCost {
    type Cost = usize;
    fn cost<C: FnMut(EId) -> usize>(&mut self, enode: &Arith, mut costs: C) -> usize {
        match enode {
            Arith::Leaf(_) => 0,
            Arith::Neg(a) => 1 + costs(*a),
            Arith::Add([a, b]) | Arith::Sub([a, b]) | Arith::Mul([a, b]) => {
                1 + costs(*a) + costs(*b)
            }
        }
    }
}

/// What the polish did.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Report {
    /// Expressions replaced by a cheaper, checked form.
    pub improved: usize,
    /// Operations saved (tree count, before sharing).
    pub saved: usize,
    /// Cheaper forms rejected by the check (a rule is wrong: the original is kept).
    pub rejected: usize,
    /// Expressions left as they were because the engine's deadline had passed.
    pub timed_out: usize,
    /// Notes for the user.
    pub notes: Vec<String>,
}

/// Largest inline expression (operations) handed to the e-graph; larger ones are
/// cut at shared intermediates anyway, this only bounds pathological cases.
const MAX_TREE: usize = 40;

/// Polish the expressions reachable from `outputs`; returns their new ids.
pub fn polish(
    sym: &mut SymbolicChain,
    outputs: &[Id],
    budget: &Budget,
    extra: &[(String, String)],
    report: &mut Report,
) -> Vec<Id> {
    let mut rules = rules();
    match extra_rules(extra) {
        Ok(mut r) => rules.append(&mut r),
        Err(e) => report
            .notes
            .push(format!("polish: extra rewrite ignored: {e}")),
    }
    let probe = Probe::new(sym);
    let g = &mut sym.graph;
    let (order, uses) = reachable(g, outputs);
    let output_set: std::collections::HashSet<Id> = outputs.iter().copied().collect();
    let is_root = |id: Id| output_set.contains(&id) || uses.get(&id).copied().unwrap_or(0) >= 2;
    let mut map: HashMap<Id, Id> = HashMap::new();
    let run = Run {
        rules: &rules,
        budget,
        probe: &probe,
    };
    for &id in &order {
        if matches!(g.node(id), Node::Num(_) | Node::Leaf(_)) || !is_root(id) {
            continue;
        }
        // Past the engine's deadline the remaining expressions stay as they are: their
        // original nodes are still in the graph, so nothing needs rebuilding.
        if g.past_deadline() {
            report.timed_out += 1;
            continue;
        }
        // The inline tree under this root, leaves mapped to their polished ids.
        let mut tree = Tree {
            expr: RecExpr::default(),
            size: 0,
            remapped: false,
        };
        to_expr(g, id, true, &uses, &output_set, &map, &mut tree);
        // The unsimplified expression, on the (already checked) polished operands;
        // untouched when none of them changed (rebuilding would re-canonicalise it).
        let original = if tree.remapped {
            from_expr(g, &tree.expr).unwrap_or(id)
        } else {
            id
        };
        if original != id {
            map.insert(id, original);
        }
        if let Some(new) = run.improve(g, &tree, original, report) {
            map.insert(id, new);
        }
    }
    finish_report(g, report);
    outputs
        .iter()
        .map(|o| map.get(o).copied().unwrap_or(*o))
        .collect()
}

/// The nodes reachable from `outputs`, ascending, and how often each is used.
fn reachable(g: &Graph, outputs: &[Id]) -> (Vec<Id>, HashMap<Id, usize>) {
    let mut uses: HashMap<Id, usize> = HashMap::new();
    let mut order: Vec<Id> = Vec::new();
    let mut stack: Vec<Id> = outputs.to_vec();
    let mut seen = std::collections::HashSet::new();
    while let Some(id) = stack.pop() {
        if !seen.insert(id) {
            continue;
        }
        order.push(id);
        for c in g.node(id).children() {
            *uses.entry(c).or_default() += 1;
            stack.push(c);
        }
    }
    order.sort_unstable();
    (order, uses)
}

/// One inline expression as an egg term: its operations and whether a leaf was
/// replaced by an already polished node.
struct Tree {
    expr: RecExpr<Arith>,
    size: usize,
    remapped: bool,
}

/// What every e-graph run shares.
struct Run<'a> {
    rules: &'a [Rewrite<Arith, ()>],
    budget: &'a Budget,
    probe: &'a Probe,
}

impl Run<'_> {
    /// The cheapest form of `tree` that passes the check, if it is cheaper than
    /// `original` (the same expression in the graph).
    fn improve(&self, g: &mut Graph, tree: &Tree, original: Id, report: &mut Report) -> Option<Id> {
        if tree.size < 2 {
            return None;
        }
        // Past the engine's deadline the remaining expressions stay as they are (their
        // operands are still remapped, which is cheap).
        if g.past_deadline() {
            report.timed_out += 1;
            return None;
        }
        // The time left of the engine's budget, not a full budget per run.
        let time = g
            .deadline
            .remaining()
            .min(std::time::Duration::from_millis(self.budget.time_ms.max(1)));
        let runner = Runner::default()
            .with_node_limit(self.budget.nodes.max(1))
            .with_iter_limit(self.budget.iterations.max(1))
            .with_time_limit(time)
            .with_expr(&tree.expr)
            .run(self.rules);
        let extractor = egg::Extractor::new(&runner.egraph, OpCost);
        let (cost, best) = extractor.find_best(runner.roots[0]);
        if cost >= tree.size {
            return None;
        }
        let new = from_expr(g, &best).filter(|&new| new != original)?;
        if self.probe.same(g, new, original) {
            report.improved += 1;
            report.saved += tree.size - cost;
            Some(new)
        } else {
            report.rejected += 1;
            None
        }
    }
}

fn finish_report(g: &Graph, report: &mut Report) {
    if report.timed_out > 0 {
        report.notes.push(format!(
            "{} ran out during the e-graph polish: {} expressions were left unpolished \
             (correct, less simplified)",
            g.deadline.describe(),
            report.timed_out
        ));
    }
    if report.rejected > 0 {
        report.notes.push(format!(
            "polish: {} rewritten expressions failed the check against the unsimplified \
             expression and were not used (the correct, unsimplified form is emitted)",
            report.rejected
        ));
    }
}

fn to_expr(
    g: &Graph,
    id: Id,
    top: bool,
    uses: &HashMap<Id, usize>,
    outputs: &std::collections::HashSet<Id>,
    map: &HashMap<Id, Id>,
    tree: &mut Tree,
) -> EId {
    let node = g.node(id);
    let leaf = !top
        && (matches!(node, Node::Num(_) | Node::Leaf(_))
            || outputs.contains(&id)
            || uses.get(&id).copied().unwrap_or(0) >= 2
            || tree.size >= MAX_TREE);
    if leaf {
        let id = match map.get(&id) {
            Some(&new) => {
                tree.remapped = true;
                new
            }
            None => id,
        };
        return tree.expr.add(Arith::Leaf(Symbol::from(format!("g{id}"))));
    }
    tree.size += 1;
    let sub = |x: Id, tree: &mut Tree| to_expr(g, x, false, uses, outputs, map, tree);
    // Operands left to right: the term's node order is part of the output.
    let op = match *node {
        Node::Add(a, b) => Arith::Add([sub(a, tree), sub(b, tree)]),
        Node::Sub(a, b) => Arith::Sub([sub(a, tree), sub(b, tree)]),
        Node::Mul(a, b) => Arith::Mul([sub(a, tree), sub(b, tree)]),
        Node::Neg(a) => Arith::Neg(sub(a, tree)),
        Node::Num(_) | Node::Leaf(_) => unreachable!("handled above"),
    };
    tree.expr.add(op)
}

/// Build an extracted expression in the graph (its normal form computed afresh from
/// the structure, never copied from the original).
fn from_expr(g: &mut Graph, expr: &RecExpr<Arith>) -> Option<Id> {
    let mut ids: Vec<Id> = Vec::with_capacity(expr.as_ref().len());
    for node in expr.as_ref() {
        let at = |i: &EId| ids[usize::from(*i)];
        let id = match node {
            Arith::Leaf(s) => s.as_str().strip_prefix('g')?.parse().ok()?,
            Arith::Add([a, b]) => g.add(at(a), at(b)),
            Arith::Sub([a, b]) => g.sub(at(a), at(b)),
            Arith::Mul([a, b]) => g.mul(at(a), at(b)),
            Arith::Neg(a) => g.neg(at(a)),
        };
        ids.push(id);
    }
    ids.last().copied()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A chain with leaves to build expressions from (planar RR: s1, c1, s2, c2, L1, L2).
    fn chain() -> SymbolicChain {
        let src = "name = \"RR\"\nconvention = \"standard\"\n[params]\nL1 = 1.0\nL2 = 0.5\n\
                   [[joints]]\ntype = \"revolute\"\na = \"L1\"\nalpha = 0\nd = 0\n\
                   [[joints]]\ntype = \"revolute\"\na = \"L2\"\nalpha = 0\nd = 0\n";
        let (robot, _) = crate::front::toml_file::load_str(src, "rr.toml").unwrap();
        SymbolicChain::new(&robot.chain(), 1000)
    }

    fn leaves(c: &mut SymbolicChain) -> (Id, Id, Id) {
        let ring = &c.graph.ring;
        let v: Vec<u32> = (0..ring.len() as u32).collect();
        let l1 = v.iter().copied().find(|&x| ring.name(x) == "L1").unwrap();
        let s1 = v.iter().copied().find(|&x| ring.name(x) == "s1").unwrap();
        let c2 = v.iter().copied().find(|&x| ring.name(x) == "c2").unwrap();
        (c.graph.leaf(l1), c.graph.leaf(s1), c.graph.leaf(c2))
    }

    #[test]
    fn factors_a_common_factor_and_checks_it() {
        let mut c = chain();
        let (a, b, d) = leaves(&mut c);
        let ab = c.graph.mul(a, b);
        let ad = c.graph.mul(a, d);
        let e = c.graph.add(ab, ad);
        let mut report = Report::default();
        let out = polish(&mut c, &[e], &Budget::default(), &[], &mut report);
        assert_eq!((report.improved, report.rejected), (1, 0), "{report:?}");
        assert_eq!(c.graph.nf(out[0]), c.graph.nf(e));
        assert!(matches!(c.graph.node(out[0]), Node::Mul(..)));
    }

    #[test]
    fn a_wrong_rule_is_caught_and_the_original_kept() {
        let mut c = chain();
        let (a, b, d) = leaves(&mut c);
        let ab = c.graph.mul(a, b);
        let e = c.graph.add(ab, d);
        let mut report = Report::default();
        // Wrong: drops a term, and is cheaper, so the extraction picks it.
        let wrong = [("(+ ?x ?y)".to_string(), "?x".to_string())];
        let out = polish(&mut c, &[e], &Budget::default(), &wrong, &mut report);
        assert_eq!(report.rejected, 1, "{report:?}");
        assert_eq!(out[0], e, "the unsimplified expression is kept");
        assert!(report.notes.iter().any(|n| n.contains("failed the check")));
    }

    #[test]
    fn past_the_deadline_expressions_are_kept_with_a_note() {
        let mut c = chain();
        let (a, b, d) = leaves(&mut c);
        let ab = c.graph.mul(a, b);
        let ad = c.graph.mul(a, d);
        let e = c.graph.add(ab, ad);
        c.graph.deadline = crate::model::options::Deadline::after_ms(0);
        let mut report = Report::default();
        let out = polish(&mut c, &[e], &Budget::default(), &[], &mut report);
        assert_eq!((report.improved, report.timed_out), (0, 1), "{report:?}");
        assert_eq!(out[0], e, "the expression is kept as it was");
        assert!(
            report
                .notes
                .iter()
                .any(|n| n.contains("during the e-graph polish")),
            "{report:?}"
        );
    }

    #[test]
    fn built_in_rules_parse_and_extra_rules_report_errors() {
        assert!(rules().len() >= 10);
        assert!(extra_rules(&[("(+ ?a".into(), "?a".into())]).is_err());
        assert_eq!(
            extra_rules(&[("(+ ?a ?b)".into(), "(+ ?b ?a)".into())])
                .unwrap()
                .len(),
            1
        );
    }
}
