//! **SP5** — `(θ1, θ2, θ3)` with `p0 + rot(k1, θ1) p1 = rot(k2, θ2) (p2 + rot(k3, θ3) p3)`:
//! a point carried by three rotations onto a point (IK-Geo's statement). A rotation about
//! `k2` keeps a vector's component along `k2` and its length, so
//!
//! `k2ᵀ rot(k1, θ1) p1 − k2ᵀ rot(k3, θ3) p3 = k2ᵀ (p2 − p0)`,
//! `p0ᵀ rot(k1, θ1) p1 − p2ᵀ rot(k3, θ3) p3 = (‖p2‖² + ‖p3‖² − ‖p0‖² − ‖p1‖²) / 2`
//!
//! is SP6 in `(θ1, θ3)` (up to four solutions, `sp6.rs`), and θ2 then comes from SP1:
//! `rot(k2, θ2) (p2 + R3 p3) = p0 + R1 p1`.

use super::sp1::sp1_angle;
use super::sp6::sp6;
use super::FourRoots;
use crate::ik::geometry::{Angle, V3};

/// Up to four solutions `[θ1, θ2, θ3]` of SP5, each with how it fits (SP6's root with
/// SP1's fit).
pub type Sp5Roots = FourRoots<[Angle; 3]>;

/// **SP5** — `p0 + rot(k1, θ1) p1 = rot(k2, θ2) (p2 + rot(k3, θ3) p3)`; `free` is θ2 where
/// both sides lie on `k2` (it turns nothing then).
#[allow(clippy::too_many_arguments)]
pub fn sp5(p0: &V3, k1: &V3, p1: &V3, k2: &V3, p2: &V3, k3: &V3, p3: &V3, free: f64) -> Sp5Roots {
    let d = [
        k2.dot(&(p2 - p0)),
        0.5 * (p2.norm_squared() + p3.norm_squared() - p0.norm_squared() - p1.norm_squared()),
    ];
    let pairs = sp6(
        [*k2, -k2, *p0, -p2],
        [*k1, *k3, *k1, *k3],
        [*p1, *p3, *p1, *p3],
        d,
    );
    let mut out = Sp5Roots::empty([Angle::new(0.0); 3]);
    for ((t1, t3), fit) in pairs.iter() {
        let (t2, f2) = sp1_angle(&(p2 + t3.rot(k3) * p3), &(p0 + t1.rot(k1) * p1), k2, free);
        out.push([t1, t2, t3], fit.and(f2));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::super::tests::unit;
    use super::super::wrap;
    use super::*;
    use crate::ik::geometry::rot;

    #[test]
    fn sp5_recovers_the_generating_angles() {
        let (k1, k2, k3) = (
            unit(0.1, 0.2, 1.0),
            unit(1.0, -0.3, 0.2),
            unit(0.3, 1.0, 0.4),
        );
        let p0 = V3::new(0.2, -0.1, 0.3);
        let p1 = V3::new(0.5, 0.4, -0.2);
        let (p2, p3) = (V3::new(-0.1, 0.3, 0.2), V3::new(0.6, -0.2, 0.1));
        for t in [[0.3, -0.8, 1.9], [-2.5, 3.0, -0.1], [1.0, 0.0, 0.0]] {
            // Choose p1's image so the equation holds: p1 = R1ᵀ (R2 (p2 + R3 p3) − p0).
            let lhs = rot(&k2, t[1]) * (p2 + rot(&k3, t[2]) * p3) - p0;
            let p1 = rot(&k1, t[0]).transpose() * lhs + 0.0 * p1;
            let r = sp5(&p0, &k1, &p1, &k2, &p2, &k3, &p3, 0.0);
            for (a, _) in r.iter() {
                let l = p0 + a[0].rot(&k1) * p1;
                let rr = a[1].rot(&k2) * (p2 + a[2].rot(&k3) * p3);
                assert!((l - rr).norm() < 1e-12, "{a:?}");
            }
            assert!(
                r.iter()
                    .any(|(a, _)| (0..3).all(|i| wrap(a[i].theta - t[i]).abs() < 1e-10)),
                "{t:?} not among {r:?}"
            );
        }
    }
}
