//! What the closed-form IK benches share (`#[path]`-included by `benches/ik_closed_form.rs`
//! and `benches/ik-geo/benches/ik_geo.rs`): the poses every contender solves, and how a
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
