//! Singular poses of each kind — wrist, elbow (the boundary of the workspace: the arm
//! stretched or folded), shoulder (the wrist centre on axis 1) — of the UR5 and the PUMA
//! 560, built by putting each generated singular factor exactly (to rounding) at zero:
//! `ik` has an exact solution and flags the branch, `ik_near(pose, q)` returns `q`, and
//! `ik_near` is continuous in `q_current` (a perturbation of `q_current` by δ moves the
//! answer by at most a few δ, never to another branch).

use kinegen::ik::XorShift64;
use kinegen::Kinematics;
use kinegen_robots::{Puma560, Ur5};

const TAU: f64 = std::f64::consts::TAU;

fn gap(a: &[f64; 6], b: &[f64; 6]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| {
            let d = x - y;
            (d - TAU * (d / TAU).round()).abs()
        })
        .fold(0.0, f64::max)
}

fn pose_gap(a: &[[f64; 4]; 4], b: &[[f64; 4]; 4]) -> f64 {
    (0..3)
        .flat_map(|r| (0..4).map(move |c| (a[r][c] - b[r][c]).abs()))
        .fold(0.0, f64::max)
}

/// `q` with joint `j` moved to a zero of `f` (bisection from a sign change found by a
/// scan over one turn): an exact singular configuration of the factor `f`.
fn on_zero(q: [f64; 6], j: usize, f: impl Fn(&[f64; 6]) -> f64) -> [f64; 6] {
    let at = |x: f64| {
        let mut p = q;
        p[j] = x;
        f(&p)
    };
    let n = 720;
    let (mut lo, mut hi) = (0..n)
        .map(|i| {
            (
                -TAU / 2.0 + TAU * i as f64 / n as f64,
                -TAU / 2.0 + TAU * (i + 1) as f64 / n as f64,
            )
        })
        .find(|&(a, b)| at(a).signum() != at(b).signum())
        .expect("the factor changes sign over a turn of this joint");
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if at(mid).signum() == at(lo).signum() {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let mut p = q;
    p[j] = 0.5 * (lo + hi);
    p
}

/// The checks for one singular configuration `q` of factor `factor` (index into
/// `SINGULARITIES`).
fn check<R: Kinematics<6>>(
    name: &str,
    robot: &R,
    q: [f64; 6],
    factor: usize,
    factors: impl Fn(&[f64; 6]) -> Vec<f64>,
    ik: impl Fn(&[[f64; 4]; 4]) -> Vec<kinegen::ik::IkBranch<6>>,
    ik_near: impl Fn(&[[f64; 4]; 4], &[f64; 6]) -> Option<[f64; 6]>,
) {
    let f = factors(&q)[factor];
    assert!(f.abs() < 1e-12, "{name}: the factor is {f:e} at {q:?}");
    let pose = robot.fk(&q);
    let sols = ik(&pose);
    let exact: Vec<_> = sols.iter().filter(|b| b.exact).collect();
    assert!(!exact.is_empty(), "{name}: no exact solution at {q:?}");
    for b in &exact {
        assert!(
            pose_gap(&robot.fk(&b.q), &pose) < 1e-10,
            "{name}: {:?} misses the pose",
            b.q
        );
    }
    assert!(
        sols.iter()
            .any(|b| b.at_singularity || b.singular & (1 << factor) != 0),
        "{name}: no branch flagged singular at {q:?}: {sols:?}"
    );
    let near = ik_near(&pose, &q).unwrap_or_else(|| panic!("{name}: ik_near found nothing"));
    assert!(
        gap(&near, &q) < 1e-6,
        "{name}: ik_near(fk(q), q) = {near:?}, q = {q:?}"
    );
    // Continuity in q_current: 50 seeded perturbations of size δ.
    let mut rng = XorShift64::new(17 + factor as u64);
    for delta in [1e-3, 1e-5] {
        for _ in 0..50 {
            let d: [f64; 6] = std::array::from_fn(|_| delta * (2.0 * rng.next_f64() - 1.0));
            let current: [f64; 6] = std::array::from_fn(|i| q[i] + d[i]);
            let moved = ik_near(&pose, &current).expect("still reachable");
            assert!(
                pose_gap(&robot.fk(&moved), &pose) < 1e-10,
                "{name}: the answer misses the pose"
            );
            // Two joints can share a free sum (θ4 + θ6 at a wrist singularity): each
            // moves by at most the perturbation of the one kept, the other compensates.
            let step = gap(&moved, &near);
            assert!(
                step <= 4.0 * delta + 1e-9,
                "{name}, δ = {delta:e}: ik_near jumps {step:e}"
            );
        }
    }
}

#[test]
fn ur5_wrist_elbow_shoulder() {
    let r = Ur5::default();
    let factors = |q: &[f64; 6]| r.singular_factors(q).to_vec();
    let ik = |p: &[[f64; 4]; 4]| r.ik(p).iter().copied().collect::<Vec<_>>();
    let near = |p: &[[f64; 4]; 4], q: &[f64; 6]| r.ik_near(p, q);
    let base = [0.4, -1.1, 1.3, -0.8, 1.2, 0.3];
    let idx = |c: &str| {
        Ur5::SINGULARITIES
            .iter()
            .position(|s| s.condition == c)
            .unwrap()
    };
    // Wrist: θ5 = 0 (θ4 + θ6 determined, not each).
    let mut q = base;
    q[4] = 0.0;
    check("UR5 wrist", &r, q, idx("sin(q5) = 0"), factors, ik, near);
    // Elbow, stretched (the workspace boundary) and folded.
    for q3 in [0.0, std::f64::consts::PI] {
        let mut q = base;
        q[2] = q3;
        check("UR5 elbow", &r, q, idx("sin(q3) = 0"), factors, ik, near);
    }
    // Shoulder: the wrist centre on axis 1, by moving q2.
    let k = idx("a2*cos(q2) + a3*cos(q2+q3) + d5*sin(q2+q3+q4) = 0");
    let q = on_zero(base, 1, |q| r.singular_factors(q)[k]);
    check("UR5 shoulder", &r, q, k, factors, ik, near);
}

#[test]
fn puma560_wrist_elbow_shoulder() {
    let r = Puma560::default();
    let factors = |q: &[f64; 6]| r.singular_factors(q).to_vec();
    let ik = |p: &[[f64; 4]; 4]| r.ik(p).iter().copied().collect::<Vec<_>>();
    let near = |p: &[[f64; 4]; 4], q: &[f64; 6]| r.ik_near(p, q);
    let base = [0.3, 0.5, -0.4, 0.6, 0.8, -0.2];
    let idx = |c: &str| {
        Puma560::SINGULARITIES
            .iter()
            .position(|s| s.condition == c)
            .unwrap()
    };
    let mut q = base;
    q[4] = 0.0;
    check("PUMA wrist", &r, q, idx("sin(q5) = 0"), factors, ik, near);
    // Elbow: a3 sin q3 + d4 cos q3 = 0, the arm stretched (boundary).
    let k = idx("a3*sin(q3) + d4*cos(q3) = 0");
    let q = on_zero(base, 2, |q| r.singular_factors(q)[k]);
    check("PUMA elbow", &r, q, k, factors, ik, near);
    let k = idx("a2*cos(q2) + a3*cos(q2+q3) - d4*sin(q2+q3) = 0");
    let q = on_zero(base, 1, |q| r.singular_factors(q)[k]);
    check("PUMA shoulder", &r, q, k, factors, ik, near);
}
