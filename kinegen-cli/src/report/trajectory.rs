//! A trajectory: each joint's rest-to-rest quintic (the runtime's
//! `kinegen::trajectory::Quintic`) from the first IK solution of the report's pose to
//! the second — the arm changing its configuration for the same tool pose.

use kinegen::trajectory::{Profile, Quintic};
use kinegen_core::Chain;

use super::html::{self, Section};
use super::ik::Solutions;
use super::svg::{Plot, COLOURS};

/// Seconds the motion takes.
const DURATION: f64 = 2.0;
/// Samples drawn per joint.
const SAMPLES: usize = 101;

/// The joint positions over time, `[joint][sample]`, and the sample times; `None`
/// without two solutions or when a quintic cannot be built (non-finite values).
pub fn quintics(from: &[f64], to: &[f64]) -> Option<(Vec<f64>, Vec<Vec<f64>>)> {
    let times: Vec<f64> = (0..SAMPLES)
        .map(|k| DURATION * k as f64 / (SAMPLES - 1) as f64)
        .collect();
    let mut joints = Vec::new();
    for (&a, &b) in from.iter().zip(to) {
        let p = Quintic::new([a, 0.0, 0.0], [b, 0.0, 0.0], DURATION).ok()?;
        joints.push(times.iter().map(|&t| p.position(t)).collect());
    }
    Some((times, joints))
}

/// The section.
pub fn section(chain: &Chain, s: &Solutions) -> Section {
    let pair = match s.solutions.as_slice() {
        [a, b, ..] => Some((&a.0, &b.0)),
        _ => None,
    };
    let body = match pair.and_then(|(a, b)| quintics(a, b)) {
        Some((times, joints)) => {
            let lo = joints.iter().flatten().copied().fold(f64::MAX, f64::min);
            let hi = joints.iter().flatten().copied().fold(f64::MIN, f64::max);
            let pad = 0.05 * (hi - lo).max(1e-3);
            let mut plot = Plot::new(640.0, 360.0, (0.0, DURATION), (lo - pad, hi + pad));
            plot.axes("t (s)", "q (rad, m)");
            for (k, q) in joints.iter().enumerate() {
                let pts: Vec<(f64, f64)> = times.iter().copied().zip(q.iter().copied()).collect();
                let colour = COLOURS[k % COLOURS.len()];
                plot.line(&pts, colour, 2.0);
                let (x, y) = (plot.px(DURATION) - 8.0, plot.py(q[q.len() - 1]) - 4.0);
                plot.text(x, y, "end", &format!("q{}", k + 1));
            }
            html::figure(
                &plot.finish("Joint positions of a quintic between two IK solutions"),
                &format!(
                    "{}: each joint's rest-to-rest quintic (zero velocity and acceleration at \
                     both ends) over {DURATION} s, from IK solution #1 to #2 of the same pose.",
                    chain.name
                ),
            )
        }
        None => html::note("Fewer than two IK solutions: no motion between them to draw."),
    };
    Section {
        id: "trajectory",
        title: "Trajectory".into(),
        body,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_quintic_starts_and_ends_at_the_solutions() {
        let (t, q) = quintics(&[0.0, 1.0], &[2.0, -1.0]).unwrap();
        assert_eq!(t.len(), SAMPLES);
        assert_eq!((q[0][0], q[0][SAMPLES - 1]), (0.0, 2.0));
        assert_eq!((q[1][0], q[1][SAMPLES - 1]), (1.0, -1.0));
        // Half way at half time (the quintic is symmetric).
        assert!((q[0][SAMPLES / 2] - 1.0).abs() < 1e-12);
    }
}
