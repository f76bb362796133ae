//! The evaluation order: the same outputs built with the chain's tail in different
//! middle frames ([`crate::kinematics::frames::Pivot`]), each simplified; the one whose
//! `fk` and `jacobian` take the fewest operations after sharing is kept.

use crate::chain::Chain;
use crate::emit::code::Coder;
use crate::kinematics::model::Model;
use crate::model::options::{Deadline, Options};
use crate::simplify::pass::simplify;

/// The cheapest simplified model of `chain`, within `deadline`.
///
/// Candidates: no middle frame, frame 1 (a vertical first axis drops out of every
/// product), frame N−1 (the wrist); trying all N costs N chain builds for little gain.
/// Ties go to the earlier candidate. All compute the same values. Past the deadline no
/// further candidate is tried (with a note), and past the normal-form budget they are
/// not worth comparing.
pub fn cheapest(chain: &Chain, options: &Options, deadline: Deadline) -> Model {
    let n = chain.dof();
    let mut candidates = vec![None, Some(1)];
    if n > 2 {
        candidates.push(Some(n - 1));
    }
    let total = candidates.len();
    let mut best: Option<(usize, Model)> = None;
    for (tried, pivot) in candidates.into_iter().enumerate() {
        if let Some((_, m)) = best.as_mut().filter(|_| deadline.passed()) {
            m.notes.push(format!(
                "{} ran out while comparing evaluation orders (middle frames): \
                 kept the best of {tried} of {total}",
                deadline.describe()
            ));
            break;
        }
        let model = variant(chain, options, pivot, deadline);
        let cost = cost(chain, &model);
        if best.as_ref().is_none_or(|(c, _)| cost < *c) {
            best = Some((cost, model));
        }
        if best
            .as_ref()
            .is_some_and(|(_, m)| m.sym.graph.nf_overflows > 0)
        {
            break;
        }
    }
    best.map(|(_, m)| m).expect("at least one candidate")
}

/// The model of [`cheapest`] with the deadline starting now.
pub fn build(chain: &Chain, options: &Options) -> Model {
    cheapest(chain, options, Deadline::start(&options.budget))
}

/// One candidate, built and simplified: middle frame `pivot` (`None`: none).
pub fn variant(
    chain: &Chain,
    options: &Options,
    pivot: Option<usize>,
    deadline: Deadline,
) -> Model {
    let model = Model::symbolic(chain, options.budget.max_terms(), pivot, deadline);
    simplify(model, options)
}

/// Operations of `fk` plus `jacobian` after sharing.
fn cost(chain: &Chain, model: &Model) -> usize {
    let coder = Coder::new(chain, &model.sym);
    let [fk, _, jacobian, _, _] = model.groups();
    coder.body(&fk).ops.total() + coder.body(&jacobian).ops.total()
}
