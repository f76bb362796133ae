//! The spherical wrist — joints 4, 5, 6 meet in one point — that the spherical-wrist
//! families end in (`spherical_two_parallel.rs`, `spherical_two_intersecting.rs`): for the
//! rotation `R36` it must make, q5 from SP4 (`h4ᵀ rot(h5, q5) h6 = h4ᵀ R36 h6`), q4 and q6
//! from SP1; at `h4 ∥ R5 h6` q4 is free. With [`WristPair::HalfTurn`] the second root of
//! q5 takes q4 and q6 from the first by half turns.

use super::WristPair;
use crate::ik::geometry::{orthogonal, rot, Geometry, Orbit, M3, V3};
use crate::ik::solutions::Candidates;
use crate::ik::subproblems::{sp1, sp1_angles_2, sp1_sides, wrap, Fit, Sp4};
use core::f64::consts::PI;

/// The spherical wrist (joints 4, 5, 6 meet in a point), set up once per solve: its axes,
/// the circle SP4 cuts for q5 (the same for every arm branch), how the second root is
/// found.
pub(super) struct Wrist {
    pub(super) h: [V3; 3],
    q5: Sp4,
    pair: WristPair,
    /// `R5 h6` and `R5ᵀ h4`: h6's and h4's orbits about h5.
    h6_about_h5: Orbit,
    h4_about_h5: Orbit,
}

impl Wrist {
    pub(super) fn new(g: &Geometry<6>, pair: WristPair) -> Wrist {
        Wrist::of_axes([g.h[3], g.h[4], g.h[5]], pair)
    }

    /// Any three axes meeting in one point (an S-R-S arm's shoulder too).
    pub(super) fn of_axes(h: [V3; 3], pair: WristPair) -> Wrist {
        // h4ᵀ rot(h5, q5) h6 = h4ᵀ R36 h6.
        let q5 = Sp4::new(&h[0], &h[2], &h[1]);
        Wrist {
            h,
            q5,
            pair,
            h6_about_h5: Orbit::new(&h[1], &h[2]),
            h4_about_h5: Orbit::new(&h[1], &h[0]),
        }
    }

    /// `(q4, q5, q6)` with `R4 R5 R6 = R36`, from what the wrist needs of `R36`:
    /// `target = (R36 h6, R36ᵀ h4)`; the whole `r36()` only at `h4 ∥ R5 h6`. SP4 for
    /// q5, SP1 for q4 and q6; at `h4 ∥ R5 h6` (q5 at its singular value) q4 is free and q6
    /// is taken from the whole rotation. With [`WristPair::HalfTurn`] the second root of
    /// q5 takes `(q4 + π, q6 + π)` from the first.
    #[inline]
    pub(super) fn solve(
        &self,
        (r36_h6, r36t_h4): (V3, V3),
        r36: impl Fn() -> M3,
        free: [f64; 2],
        out: &mut [([f64; 3], Fit); 2],
    ) -> usize {
        let [h4, h5, h6] = &self.h;
        let t5 = self.q5.solve(h4.dot(&r36_h6), 0.0);
        if self.pair == WristPair::HalfTurn && t5.n == 2 {
            let q5 = t5.angles[0];
            let sides4 = sp1_sides(&self.h6_about_h5.at(&q5), &r36_h6, h4);
            // Two distinct roots: h4 ∦ R5 h6, so q4 is not free.
            if sides4.is_some() {
                // q4 and q6 side by side (q6's SP1 does not need q4).
                let sides6 = sp1_sides(&r36t_h4, &self.h4_about_h5.back(&q5), h6);
                let [(q4, f4), (q6, f6)] = sp1_angles_2([sides4, sides6], free);
                let fit = t5.fit.and(f4).and(f6);
                out[0] = ([q4, q5.theta, q6], fit);
                out[1] = ([wrap(q4 + PI), t5.angles[1].theta, wrap(q6 + PI)], fit);
                return 2;
            }
        }
        for (o, q5) in out.iter_mut().zip(t5.as_slice()) {
            let (q4, f4) = sp1(&self.h6_about_h5.at(q5), &r36_h6, h4, free[0]);
            let (q6, f6) = if f4 == Fit::Free {
                // Only q4 ± q6 is determined: q4 = free, q6 from R6 = (R4 R5)ᵀ R36.
                let m = (rot(h4, q4) * q5.rot(h5)).transpose() * r36();
                let x = orthogonal(h6);
                sp1(&x, &(m * x), h6, free[1])
            } else {
                // R6 (R36ᵀ h4) = R5ᵀ h4, since R36ᵀ h4 = R6ᵀ R5ᵀ h4.
                sp1(&r36t_h4, &self.h4_about_h5.back(q5), h6, free[1])
            };
            *o = ([q4, q5.theta, q6], t5.fit.and(f4).and(f6));
        }
        t5.n
    }

    /// What [`Wrist::solve`] needs of the rotation `r36`.
    #[inline]
    pub(super) fn target(&self, r36: &M3) -> (V3, V3) {
        (r36 * self.h[2], r36.transpose() * self.h[0])
    }
}

/// Adds the wrist solutions for the arm joints `q123` to `out`; `R36 = (R1 R2 R3)ᵀ R06` is
/// the rotation the wrist must make (a prismatic joint turns nothing), given as
/// `target = (R36 h6, R36ᵀ h4)` and, for a wrist singularity, `r36()`.
#[inline]
pub(super) fn with_wrist(
    wrist: &Wrist,
    q123: [f64; 3],
    (target, r36): ((V3, V3), impl Fn() -> M3),
    fit: Fit,
    free: &[f64; 6],
    out: &mut Candidates<6, 8>,
) {
    let mut w = [([0.0; 3], Fit::Exact); 2];
    let n = wrist.solve(target, r36, [free[3], free[5]], &mut w);
    for &(q456, f) in &w[..n] {
        let q = [q123[0], q123[1], q123[2], q456[0], q456[1], q456[2]];
        out.push(q, fit.and(f));
    }
}
