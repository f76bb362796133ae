//! UR5 straight lines through a wrist singularity (θ5 = 0 at their midpoint), sampled at
//! 500 Hz: the closed form (`track_closed_form`, the nearest exact solution of every
//! sample) and the numerical tracker (`track_ik`, Newton–Raphson on the SVD
//! pseudo-inverse seeded with the previous sample), both run on the same lines.

use kinegen::adapters::{fk_isometry, pose_matrix};
use kinegen::ik::IkOptions;
use kinegen::trajectory::{CartesianLine, IkTrackError, Trapezoid};
use kinegen_robots::Ur5;
use nalgebra::{Isometry3, Translation3, Unit, UnitQuaternion, Vector3};

const RATE: f64 = 500.0; // 2 ms per sample
const MAX_STEP: f64 = 0.05; // rad per sample

/// Singular configurations (θ5 = 0) the lines pass through.
const SINGULAR: [[f64; 6]; 3] = [
    [0.3, -1.2, 1.4, -0.3, 0.0, 0.2],
    [-0.8, -1.7, 1.9, 0.4, 0.0, -1.0],
    [1.9, -1.6, 1.1, 2.0, 0.0, 2.5],
];

/// From `T_s·Rot(−θ)` shifted by −d to `T_s·Rot(θ)` shifted by +d: the position passes
/// through the singular pose's halfway, and slerp passes its orientation there too.
fn line(
    ur5: &Ur5,
    q_s: &[f64; 6],
    d: [f64; 3],
    axis: Vector3<f64>,
    theta: f64,
) -> CartesianLine<Trapezoid> {
    let t = fk_isometry(ur5, q_s);
    let r = UnitQuaternion::from_axis_angle(&Unit::new_normalize(axis), theta);
    let mut a = Translation3::new(-d[0], -d[1], -d[2]) * t;
    a.rotation = t.rotation * r.inverse();
    let mut b = Translation3::new(d[0], d[1], d[2]) * t;
    b.rotation = t.rotation * r;
    CartesianLine::with_limits(a, b, 0.25, 1.0, 1.0, 2.0).unwrap()
}

/// Every line: three singular configurations × a pure translation and rotations about
/// the world axes.
fn lines(ur5: &Ur5) -> Vec<([f64; 6], CartesianLine<Trapezoid>)> {
    let mut out = Vec::new();
    for (q_s, d) in SINGULAR
        .iter()
        .zip([[0.06, 0.04, -0.03], [0.0, 0.08, 0.02], [0.05, 0.0, 0.0]])
    {
        out.push((*q_s, line(ur5, q_s, d, Vector3::z(), 0.0)));
        for axis in [Vector3::x(), Vector3::y(), Vector3::z()] {
            out.push((*q_s, line(ur5, q_s, d, axis, 0.2)));
        }
    }
    out
}

fn max_step(a: &[f64; 6], b: &[f64; 6]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

fn miss(ur5: &Ur5, q: &[f64; 6], target: &Isometry3<f64>) -> f64 {
    let p = fk_isometry(ur5, q);
    (p.translation.vector - target.translation.vector).norm()
        + p.rotation.angle_to(&target.rotation)
}

/// The closed form's joint path along `line` from the branch through `q_s`.
fn closed_form_path(ur5: &Ur5, q_s: &[f64; 6], line: &CartesianLine<Trapezoid>) -> Vec<[f64; 6]> {
    let q0 = ur5
        .ik_near(&pose_matrix(line.start()), q_s)
        .expect("the start is reachable");
    let samples: Vec<_> = line.sample(RATE).unwrap().collect();
    let mut path = Vec::new();
    for (step, (t, target)) in line.track_closed_form(ur5, RATE, q0).unwrap().zip(&samples) {
        let (_, q) = step.unwrap_or_else(|e| panic!("t = {t}: {e}"));
        assert!(miss(ur5, &q, target) < 1e-9, "t = {t}: misses the line");
        path.push(q);
    }
    assert_eq!(path.len(), samples.len());
    path
}

#[test]
fn closed_form_crosses_the_wrist_singularity_without_a_jump_or_flip() {
    let ur5 = Ur5::default();
    for (q_s, line) in lines(&ur5) {
        let path = closed_form_path(&ur5, &q_s, &line);
        let worst = path
            .windows(2)
            .map(|w| max_step(&w[0], &w[1]))
            .fold(0.0, f64::max);
        let min_s5 = path
            .iter()
            .map(|q| q[4].sin().abs())
            .fold(f64::INFINITY, f64::min);
        // θ5 = 0 lies between two samples, each within one step of it.
        assert!(
            min_s5 <= worst,
            "{q_s:?}: the line misses the singularity (min |sin θ5| = {min_s5})"
        );
        assert!(
            worst <= MAX_STEP,
            "{q_s:?}: a joint jumps {worst} rad in 2 ms"
        );
        // Halfway the sample is (within a sample's travel) the singular pose. At a UR
        // wrist singularity h6 ∥ h2 ∥ h3 ∥ h4: the configurations of that pose form a
        // one-parameter family, and the path passes through the member continuous with
        // its start (q6 kept from the previous sample), not necessarily q_s itself.
        let mid = &path[((line.duration() / 2.0) * RATE).round() as usize];
        assert!(mid[4].sin().abs() <= worst, "{q_s:?}: halfway at {mid:?}");
        println!("closed form through {q_s:?}: {} samples, largest step {worst:.4} rad, min |sin θ5| {min_s5:.1e}", path.len());
    }
}

/// The numerical tracker on the same lines, compared sample by sample with the closed
/// form wherever it gives an answer: it must be the same configuration (no other branch),
/// and when it stops, it says why.
#[test]
fn numerical_tracker_on_the_same_lines_agrees_or_reports() {
    let ur5 = Ur5::default();
    let mut followed = 0;
    for (q_s, line) in lines(&ur5) {
        let path = closed_form_path(&ur5, &q_s, &line);
        let mut stopped = None;
        for (i, step) in line
            .track_ik(&ur5, RATE, path[0], &IkOptions::default(), MAX_STEP)
            .unwrap()
            .enumerate()
        {
            match step {
                Ok((_, sol)) => {
                    let d = max_step(&sol.q, &path[i]);
                    assert!(
                        d < 1e-6,
                        "{q_s:?}, sample {i}: numerical {:?} vs closed form {:?}",
                        sol.q,
                        path[i]
                    );
                }
                Err(e) => {
                    stopped = Some(match e {
                        IkTrackError::Jump { t, joint, step } => {
                            format!("jumps at t = {t:.3} s (joint {joint}: {step:.3} rad)")
                        }
                        IkTrackError::Ik { t, error } => {
                            format!("fails at t = {t:.3} s: {error:?}")
                        }
                    });
                    break;
                }
            }
        }
        match stopped {
            None => followed += 1,
            Some(why) => println!("numerical through {q_s:?}: {why}"),
        }
    }
    println!(
        "numerical tracker followed {followed} of {} lines",
        lines(&ur5).len()
    );
}

/// A line that leaves the workspace (into the cylinder around axis 1 the wrist centre
/// cannot enter): the closed form follows it without a jump up to the boundary and then
/// reports `OutOfReach` instead of commanding a wrong configuration.
#[test]
fn closed_form_stops_with_out_of_reach_at_the_workspace_boundary() {
    let ur5 = Ur5::default();
    let q_s = [0.0, -2.0, 1.0, -1.0, 0.0, 0.0];
    let line = line(&ur5, &q_s, [0.06, 0.04, -0.03], Vector3::z(), 0.0);
    let q0 = ur5.ik_near(&pose_matrix(line.start()), &q_s).unwrap();
    let samples: Vec<_> = line.sample(RATE).unwrap().collect();
    let mut last = q0;
    let mut reached = 0;
    let mut out = None;
    for (step, (t, target)) in line
        .track_closed_form(&ur5, RATE, q0)
        .unwrap()
        .zip(&samples)
    {
        match step {
            Ok((_, q)) => {
                assert!(miss(&ur5, &q, target) < 1e-9);
                assert!(max_step(&last, &q) <= MAX_STEP, "t = {t}");
                last = q;
                reached += 1;
            }
            Err(e) => {
                out = Some((*t, e));
                break;
            }
        }
    }
    let (t, _) = out.expect("the line leaves the workspace");
    assert!(reached > 0 && reached < samples.len());
    // Truly out of reach there: no exact solution of that sample.
    assert!(ur5.ik(&pose_matrix(&line.pose(t))).exact().next().is_none());
}
