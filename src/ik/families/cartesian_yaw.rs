//! **A Cartesian gantry with a turn about z** — three prismatic joints and one revolute
//! joint whose axis is vertical, in any order (P P P R: the pick-and-place gantry with a
//! rotary tool axis; R P P P: the same on a turntable). Task rows x, y, z and the angle
//! about z: the yaw fixes the revolute joint, then the position is linear in the slides.

use super::planar::yaw;
use super::position::cramer;
use crate::ik::geometry::{Geometry, Pose};
use crate::ik::solutions::Candidates;
use crate::ik::subproblems::{wrap, Fit};

/// **Position and yaw, P P P R in any order** (`r` the revolute joint, its axis `±z`;
/// the engine proved the slides' axes independent at every yaw):
///
/// 1. `ψ = φ − φ0` (the tool's angle about z, minus its angle at `q = 0`): `q_r = ±ψ`
/// 2. the slides — with `q_r` known, `p = c + Σ q_i a_i` (`c` the tool point with the
///    slides at 0, `a_i` their axes, turned by `q_r` where they come after it): a 3 × 3
///    linear system, Cramer's rule.
///
/// One solution.
pub fn cartesian_yaw<const K: usize>(
    g: &Geometry<4>,
    pose: &Pose,
    r: usize,
    _free: &[f64; 4],
    out: &mut Candidates<4, K>,
) {
    let mut q = [0.0; 4];
    q[r] = wrap(g.h[r].z.signum() * yaw(g, pose));
    let (at, axes, _) = g.frames(&q);
    let d = pose.p - at.p;
    let slides: [usize; 3] = core::array::from_fn(|k| k + usize::from(k >= r));
    let x = cramer(slides.map(|i| axes[i]), &d);
    for (i, xi) in slides.into_iter().zip(x) {
        q[i] = xi;
    }
    out.push(q, Fit::Exact);
}

#[cfg(test)]
mod tests {
    use super::super::tests::unit;
    use super::*;
    use crate::ik::geometry::{rot, V3};
    use crate::ik::XorShift64;

    /// Random gantries with the yaw joint first, last, or third (the slide after it
    /// vertical), random points and tool; every pose of their own `fk` solved back to its
    /// configuration, the yaw and the point to rounding.
    #[test]
    fn the_yaw_then_the_slides() {
        let mut rng = XorShift64::new(4);
        for case in 0..400 {
            let r = [0, 2, 3][case % 3];
            let z = V3::z() * if rng.next_f64() < 0.5 { 1.0 } else { -1.0 };
            let h: [V3; 4] = core::array::from_fn(|i| match i {
                _ if i == r => z,
                _ if i > r && r > 0 => V3::z(),
                _ => unit(&mut rng),
            });
            let g = Geometry {
                h,
                p: core::array::from_fn(|_| unit(&mut rng) * 0.3),
                prismatic: core::array::from_fn(|i| i != r),
                r_tool: rot(&unit(&mut rng), 0.4),
                p_tool: unit(&mut rng) * 0.2,
            };
            let q: [f64; 4] = core::array::from_fn(|i| {
                if i == r {
                    (2.0 * rng.next_f64() - 1.0) * 3.0
                } else {
                    rng.next_f64() - 0.5
                }
            });
            let pose = g.fk(&q);
            let mut out = Candidates::<4, 1>::default();
            cartesian_yaw(&g, &pose, r, &[0.0; 4], &mut out);
            let c = out.as_slice()[0];
            let gap =
                c.q.iter()
                    .zip(&q)
                    .map(|(a, b)| (a - b).abs())
                    .fold(0.0, f64::max);
            assert!(gap <= 1e-12, "case {case}: {:?} for {q:?}", c.q);
        }
    }
}
