//! |det J| over two joints, the others at the report's configuration: a heat map
//! (log scale, viridis; dark where the Jacobian is singular) evaluated with the engine's
//! own determinant node.

use kinegen_core::kinematics::program::Program;
use kinegen_core::model::robot::JointKind;
use kinegen_core::{Chain, Derived};

use super::html::{self, Section};
use super::ik::Solutions;
use super::svg::{viridis, Plot};
use crate::det_hook::Determinants;

/// Cells per axis.
const CELLS: usize = 72;
/// Decades of |det J| below its maximum the colours span.
const DECADES: f64 = 4.0;

/// The two joints drawn (0-based): the two of the most joints' factor that come first,
/// so the map crosses an arm singularity (joints 2 and 3 of a 6R arm); else 1 and 2.
fn joints(dets: &Determinants, n: usize) -> (usize, usize) {
    let d = dets.det.as_ref().or(dets.det_task.as_ref());
    let widest = d.and_then(|d| d.factors.iter().max_by_key(|f| f.joints.len()));
    match widest.map(|f| f.joints.as_slice()) {
        Some([a, b, ..]) => (a - 1, b - 1),
        _ => (0, 1.min(n.saturating_sub(1))),
    }
}

/// The section, or a note when there is no closed-form determinant or fewer than two
/// joints.
pub fn section(chain: &Chain, derived: &Derived, dets: &Determinants, s: &Solutions) -> Section {
    let d = dets.det.as_ref().or(dets.det_task.as_ref());
    let body = match d {
        Some(d) if chain.dof() >= 2 => {
            let (i, j) = joints(dets, chain.dof());
            let program = Program::new(&derived.model.sym, chain, &[d.node]);
            let svg = map(chain, &program, &s.q0, i, j);
            html::figure(
                &svg,
                &format!(
                    "|det J| over q{} and q{} (the other joints at q = [{}]), log scale over {} \
                     decades below its largest value (32 colours): dark where the Jacobian is singular.",
                    i + 1,
                    j + 1,
                    super::ik::list(&s.q0),
                    DECADES
                ),
            )
        }
        _ => html::note(&format!(
            "No closed-form determinant to map: {}",
            dets.missing
        )),
    };
    Section {
        id: "singularity-map",
        title: "Singularity map".into(),
        body,
    }
}

/// The range a joint is drawn over: its limits, at most ±π for a revolute joint.
fn range(chain: &Chain, k: usize) -> (f64, f64) {
    let l = &chain.links[k];
    let (lo, hi) = match l.motion.kind {
        JointKind::Revolute => (-std::f64::consts::PI, std::f64::consts::PI),
        JointKind::Prismatic => (0.0, 0.5),
    };
    match l.limits {
        Some([a, b]) if a.is_finite() && b.is_finite() && b > a => (a.max(lo), b.min(hi)),
        _ => (lo, hi),
    }
}

/// The heat map of |det| over joints `i`, `j`.
pub fn map(chain: &Chain, program: &Program, q0: &[f64], i: usize, j: usize) -> String {
    let (ri, rj) = (range(chain, i), range(chain, j));
    let mut registers = program.registers();
    let mut out = [0.0];
    let mut q = q0.to_vec();
    let mut values = vec![0.0; CELLS * CELLS];
    let at = |r: (f64, f64), k: usize| r.0 + (k as f64 + 0.5) / CELLS as f64 * (r.1 - r.0);
    for (iy, row) in values.chunks_mut(CELLS).enumerate() {
        for (ix, v) in row.iter_mut().enumerate() {
            q[i] = at(ri, ix);
            q[j] = at(rj, iy);
            program.eval(&q, &mut registers, &mut out);
            *v = out[0].abs();
        }
    }
    let max = values.iter().copied().fold(0.0, f64::max);
    let mut plot = Plot::new(460.0, 420.0, ri, rj);
    let wi = (ri.1 - ri.0) / CELLS as f64;
    let wj = (rj.1 - rj.0) / CELLS as f64;
    // One rectangle per run of equal colour along a row: the page stays small.
    let colour = |v: f64| {
        // 0 at DECADES below the maximum (and below), 1 at the maximum.
        let t = if max > 0.0 && v > 0.0 {
            1.0 + (v / max).log10() / DECADES
        } else {
            0.0
        };
        viridis((t * 32.0).round() / 32.0)
    };
    for (iy, row) in values.chunks(CELLS).enumerate() {
        let mut ix = 0;
        while ix < CELLS {
            let c = colour(row[ix]);
            let mut end = ix + 1;
            while end < CELLS && colour(row[end]) == c {
                end += 1;
            }
            let x = ri.0 + ix as f64 * wi;
            let y = rj.0 + iy as f64 * wj;
            // A hair wider than the cells: no seams between neighbours.
            plot.rect(
                (x, x + (end - ix) as f64 * wi * 1.01),
                (y, y + wj * 1.04),
                &c,
            );
            ix = end;
        }
    }
    plot.axes(&format!("q{} (rad)", i + 1), &format!("q{} (rad)", j + 1));
    plot.finish(&format!("|det J| over q{} and q{}", i + 1, j + 1))
}
