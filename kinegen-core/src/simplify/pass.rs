//! One model through the simplify passes, in order: the e-graph polish of every inline
//! expression, then the sign pass, each result checked before it replaces the original;
//! then the notes on what the exact core could not keep.

use crate::algebra::graph::{Graph, Id};
use crate::kinematics::model::Model;
use crate::kinematics::second_order::SecondOrder;
use crate::model::options::Options;
use crate::simplify::check::Probe;
use crate::simplify::{polish, signs};

/// `model` simplified: same values, fewer operations (or, where a check fails, the
/// unsimplified expressions and a note).
pub fn simplify(mut model: Model, options: &Options) -> Model {
    polish_all(&mut model, options);
    move_signs(&mut model);
    note_lost_normal_forms(&mut model);
    model
}

/// The e-graph polish of every inline expression (checked inside [`polish::polish`]).
fn polish_all(model: &mut Model, options: &Options) {
    let mut report = polish::Report::default();
    let outputs = model.ids();
    let ids = polish::polish(
        &mut model.sym,
        &outputs,
        &options.budget,
        &options.extra_rewrites,
        &mut report,
    );
    model.set_ids(ids);
    model.fused = model.fused_ids();
    model.notes.extend(report.notes.iter().cloned());
    model.polish = report;
}

/// Signs chosen for the fewest negations ([`signs`]), once per generated function: a
/// node the function would compute with both signs would be computed twice, so `frames`
/// is one problem and the fused `fk_and_jacobian` has its own. The pass copies normal
/// forms instead of recomputing them, so it is checked by value.
fn move_signs(model: &mut Model) {
    if model.sym.graph.past_deadline() {
        model.notes.push(format!(
            "{} ran out before the signs were chosen: the expressions are emitted as built",
            model.sym.graph.deadline.describe()
        ));
        return;
    }
    // The fused function's outputs are one more group, signed last.
    let fused_before = model.fused.clone();
    let mut groups = model.groups().to_vec();
    groups.push(fused_before.clone());
    let (g, notes) = (&mut model.sym.graph, &mut model.notes);
    let mut signed = signed_groups(g, &groups, "the signs", notes);
    let fused_after = signed.split_off(signed.len() - fused_before.len());
    let probe = Probe::new(&model.sym);
    let before = model.ids().into_iter().chain(fused_before.iter().copied());
    let after = signed.iter().copied().chain(fused_after.iter().copied());
    let bad = before
        .zip(after)
        .any(|(b, a)| a != b && !probe.same_values(&model.sym.graph, a, b));
    if bad {
        model.notes.push(
            "internal check failed after moving signs: the unsimplified expressions are emitted"
                .into(),
        );
    } else {
        model.set_ids(signed);
        model.fused = fused_after;
    }
}

/// Each group's outputs with their signs chosen ([`signs::assign`]), concatenated; where
/// the deadline cut a group's search short, a note saying so of `what` (once).
fn signed_groups(
    g: &mut Graph,
    groups: &[Vec<Id>],
    what: &str,
    notes: &mut Vec<String>,
) -> Vec<Id> {
    let mut cut = false;
    let mut ids = Vec::new();
    for group in groups {
        let signed = signs::assign(g, group);
        cut |= signed.cut;
        ids.extend(signed.ids);
    }
    if cut {
        notes.push(format!(
            "{} ran out while {what} were chosen: some negations that could be absorbed are left in",
            g.deadline.describe()
        ));
    }
    ids
}

/// Outputs whose expression reached a node without normal form have none: say so.
fn note_lost_normal_forms(model: &mut Model) {
    let lost = model.without_normal_form();
    let g = &model.sym.graph;
    if g.nf_overflows > 0 {
        model.notes.push(format!(
            "{} expressions exceeded the normal-form budget of {} terms: they are shared structurally only{lost}",
            g.nf_overflows, g.max_terms
        ));
    }
    if g.nf_timeouts > 0 {
        model.notes.push(format!(
            "{} ran out while building normal forms: {} were not computed, and what is built on them is shared structurally only{lost}",
            g.deadline.describe(),
            g.nf_timeouts
        ));
    }
}

/// The second-order outputs with signs chosen for the fewest negations, once per
/// generated function, checked by value. (The e-graph polish is not run on them: on UR5
/// and Panda it saved nothing there, and on UR5's `jdot_qdot` its tree-by-tree choices
/// cost 26 operations more after sharing.)
pub fn simplify_second_order(model: &mut Model, second: &mut SecondOrder) {
    if second.at_run_time.is_some() {
        return;
    }
    if model.sym.graph.past_deadline() {
        model.notes.push(format!(
            "{} ran out before the second-order outputs' signs were chosen: they are emitted as built",
            model.sym.graph.deadline.describe()
        ));
        return;
    }
    let groups = second.groups();
    let (g, notes) = (&mut model.sym.graph, &mut model.notes);
    let signed = signed_groups(g, &groups, "the second-order outputs' signs", notes);
    let probe = Probe::new(&model.sym);
    let before = groups.concat();
    let bad = before
        .iter()
        .zip(&signed)
        .any(|(&b, &a)| a != b && !probe.same_values(&model.sym.graph, a, b));
    if bad {
        model.notes.push(
            "internal check failed after moving signs in the second-order outputs: their \
             unsimplified expressions are emitted"
                .into(),
        );
    } else {
        second.set_ids(&signed);
    }
}
