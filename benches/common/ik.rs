//! What the closed-form IK benches share (`#[path]`-included by `benches/ik_closed_form.rs`,
//! `benches/ik_quartic.rs`, `benches/ik_general.rs` and `benches/ik-geo/benches/ik_geo.rs`): the poses every contender solves, and how a
//! solution is judged, for any joint count (six-joint arms, the seven-joint Panda).

use std::f64::consts::PI;

use kinegen::ik::XorShift64;
use kinegen::Kinematics;

/// `count` poses of configurations drawn within the limits (seeded), with the
/// configurations.
pub fn poses<const N: usize, R: Kinematics<N>>(
    robot: &R,
    seed: u64,
    count: usize,
) -> Vec<([[f64; 4]; 4], [f64; N])> {
    let limits = robot.limits();
    let mut rng = XorShift64::new(seed);
    (0..count)
        .map(|_| {
            let q = rng.configuration(&limits);
            (robot.fk(&q), q)
        })
        .collect()
}

/// `max |fk(q) − pose|` over the top three rows.
pub fn miss<const N: usize, R: Kinematics<N>>(
    robot: &R,
    q: &[f64; N],
    pose: &[[f64; 4]; 4],
) -> f64 {
    let t = robot.fk(q);
    (0..3)
        .flat_map(|r| (0..4).map(move |c| (r, c)))
        .map(|(r, c)| (t[r][c] - pose[r][c]).abs())
        .fold(0.0, f64::max)
}

/// The same configuration, modulo whole turns (1e-6 rad).
pub fn same<const N: usize>(a: &[f64; N], b: &[f64; N]) -> bool {
    a.iter().zip(b).all(|(x, y)| {
        let d = x - y;
        (d - 2.0 * PI * (d / (2.0 * PI)).round()).abs() < 1e-6
    })
}

/// 1 000 poses when timing (`cargo bench`), 50 when CI runs the bench once as a test.
pub fn poses_count() -> usize {
    if std::env::args().any(|a| a == "--bench") {
        1000
    } else {
        50
    }
}

/// A bench's one-off check of a closed-form `ik(pose, q)` (`q` the generating
/// configuration) on `set`: every exact solution within 1e-10 of its pose, the counts
/// printed (solutions, exact ones, poses by exact count, poses whose generating
/// configuration is found), and at most `most_missed` poses without it.
pub fn check_solutions<const N: usize, const K: usize, R: Kinematics<N>>(
    name: &str,
    robot: &R,
    ik: impl Fn(&[[f64; 4]; 4], &[f64; N]) -> kinegen::ik::IkSolutions<N, K>,
    set: &[([[f64; 4]; 4], [f64; N])],
    most_missed: usize,
) {
    let (mut all, mut exact, mut found) = (0, 0, 0);
    let mut counts = [0usize; 17];
    for (pose, q) in set {
        let sols = ik(pose, q);
        all += sols.len();
        counts[sols.exact().count().min(16)] += 1;
        for b in sols.exact() {
            let e = miss(robot, &b.q, pose);
            assert!(e <= 1e-10, "{name}: an exact solution {e:e} off");
            exact += 1;
        }
        if sols.exact().any(|b| same(&b.q, q)) {
            found += 1;
        }
    }
    println!(
        "{name}: {} poses, {all} solutions, {exact} exact, generating configuration found \
         {found}/{}; poses by exact count (0..16): {counts:?}",
        set.len(),
        set.len()
    );
    assert!(
        set.len() - found <= most_missed,
        "{name}: {} generating configurations not found",
        set.len() - found
    );
}
