//! The evaluation order: the same outputs built with the chain's tail in different
//! middle frames ([`crate::kinematics::frames::Pivot`]), those that can still win
//! simplified; the one whose `fk` and `jacobian` take the fewest operations after sharing
//! is kept.

use crate::chain::Chain;
use crate::emit::code::Coder;
use crate::kinematics::model::Model;
use crate::model::options::{Deadline, Options};
use crate::simplify::pass::simplify;

/// How much costlier than the cheapest unsimplified candidate another may be and still
/// be simplified and compared: the polish and the sign pass change a candidate's count
/// by at most 7 % on the robots of `robots/` (UR5 frame 1: 152 → 141), so one more than
/// 1/8 costlier cannot overtake; simplifying it anyway cost two thirds of a 6-axis
/// arm's evaluation-order search (the e-graph runs at the proc-macro's opt-level 0).
const SIMPLIFY_MARGIN: (usize, usize) = (9, 8);

/// The cheapest simplified model of `chain`, within `deadline`.
///
/// Candidates: no middle frame, frame 1 (a vertical first axis drops out of every
/// product), frame N−1 (the wrist); trying all N costs N chain builds for little gain.
/// Each is built and counted unsimplified; those within 1/8 (`SIMPLIFY_MARGIN`) of the
/// cheapest are simplified, cheapest first, and compared again. Ties go to the earlier
/// candidate. All compute the same values. Past the deadline no further candidate is
/// built or simplified (with a note), and past the normal-form budget they are not worth
/// comparing.
pub fn cheapest(chain: &Chain, options: &Options, deadline: Deadline) -> Model {
    let n = chain.dof();
    let mut candidates = vec![None, Some(1)];
    if n > 2 {
        candidates.push(Some(n - 1));
    }
    let total = candidates.len();
    let mut built: Vec<(usize, Model)> = Vec::new();
    let mut notes = Vec::new();
    for (tried, pivot) in candidates.into_iter().enumerate() {
        if tried > 0 && deadline.passed() {
            notes.push(format!(
                "{} ran out while comparing evaluation orders (middle frames): \
                 kept the best of {tried} of {total}",
                deadline.describe()
            ));
            break;
        }
        let model = Model::candidate(chain, options.budget.max_terms(), pivot, deadline);
        let overflowed = model.sym.graph.nf_overflows > 0;
        built.push((tried, model));
        if overflowed {
            break;
        }
    }
    // Counting a candidate's operations is writing its code (a long chain's `fk` and
    // `jacobian`: 1.8 s of 2 000 joints' 14 s): done only where there is a choice.
    let mut built: Vec<(usize, usize, Model)> = match built.len() {
        1 => built.into_iter().map(|(tried, m)| (0, tried, m)).collect(),
        _ => built
            .into_iter()
            .map(|(tried, m)| (cost(chain, &m), tried, m))
            .collect(),
    };
    // Cheapest unsimplified first; ties keep the candidates' order.
    built.sort_by_key(|&(c, tried, _)| (c, tried));
    let limit = built[0].0 * SIMPLIFY_MARGIN.0 / SIMPLIFY_MARGIN.1;
    // The best simplified so far: its count (once a second one is there to compare),
    // its place among the candidates, the model.
    let mut best: Option<(Option<usize>, usize, Model)> = None;
    let compared = built.len();
    for (simplified, (raw, tried, model)) in built.into_iter().enumerate() {
        if best.is_some() && raw > limit {
            break;
        }
        if best.is_some() && deadline.passed() {
            notes.push(format!(
                "{} ran out while simplifying evaluation orders (middle frames): \
                 kept the best of {simplified} of {compared}",
                deadline.describe()
            ));
            break;
        }
        let model = simplify(model.with_tool_frame(chain), options);
        best = match best {
            None => Some((None, tried, model)),
            Some((b, t, m)) => {
                let b = b.unwrap_or_else(|| cost(chain, &m));
                let c = cost(chain, &model);
                if (c, tried) < (b, t) {
                    Some((Some(c), tried, model))
                } else {
                    Some((Some(b), t, m))
                }
            }
        };
    }
    let mut model = best.map(|(_, _, m)| m).expect("at least one candidate");
    model.notes.extend(notes);
    model
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
    simplify(
        Model::symbolic(chain, options.budget.max_terms(), pivot, deadline),
        options,
    )
}

/// Operations of `fk` plus `jacobian` after sharing.
fn cost(chain: &Chain, model: &Model) -> usize {
    let coder = Coder::new(chain, &model.sym);
    let [fk, _, jacobian, _, _] = model.groups();
    coder.body(&fk).ops.total() + coder.body(&jacobian).ops.total()
}
