//! The spherical wrist — joints 4, 5, 6 meet in one point — that the spherical-wrist
//! families end in (`spherical_two_parallel.rs`, `spherical_two_intersecting.rs`): for the
//! rotation `R36` it must make, q5 from SP4 (`h4ᵀ rot(h5, q5) h6 = h4ᵀ R36 h6`), q4 and q6
//! from SP1; at `h4 ∥ R5 h6` q4 is free. With [`WristPair::HalfTurn`] the second root of
//! q5 takes q4 and q6 from the first by half turns.

use super::WristPair;
use crate::ik::geometry::{orthogonal, rot, Angle, Geometry, Orbit, Pose, M3, V3};
use crate::ik::polish::{polish, pose_miss};
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
    /// Whether the caller brings a merged branch that misses `R36` onto the pose on the
    /// whole arm ([`with_wrist`]) where rounding hides the two roots of q5, rather than
    /// [`Wrist::split`] splitting it about the merged root.
    on_arm: bool,
}

impl Wrist {
    pub(super) fn new(g: &Geometry<6>, pair: WristPair) -> Wrist {
        Wrist {
            on_arm: true,
            ..Wrist::of_axes([g.h[3], g.h[4], g.h[5]], pair)
        }
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
            on_arm: false,
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
        target: (V3, V3),
        r36: impl Fn() -> M3,
        free: [f64; 2],
        out: &mut [([f64; 3], Fit); 2],
    ) -> usize {
        let t5 = self.q5.solve(self.h[0].dot(&target.0), 0.0);
        let n = self.solve_roots(t5, target, &r36, free, out);
        // Two roots of q5 within NEAR_DOUBLE of each other: each carries SP4's rounding
        // amplified by 1/|q5 − q5*|, and q4, q6 after it; polished on the whole rotation
        // (their fit stays: the polish only takes rounding out).
        if t5.n == 2 && wrap(t5.angles[0].theta - t5.angles[1].theta).abs() < NEAR_DOUBLE {
            let m = r36();
            for (q, _) in &mut out[..n] {
                *q = self.polish(*q, &m);
            }
        }
        n
    }

    #[inline(always)]
    fn solve_roots(
        &self,
        t5: crate::ik::subproblems::Roots,
        (r36_h6, r36t_h4): (V3, V3),
        r36: &impl Fn() -> M3,
        free: [f64; 2],
        out: &mut [([f64; 3], Fit); 2],
    ) -> usize {
        let [h4, h5, h6] = &self.h;
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
        if t5.fit == Fit::Double {
            if let Some(n) = self.split(out[0].0, (r36_h6, r36t_h4), r36(), free, out) {
                return n;
            }
        }
        t5.n
    }

    /// A q5 merged into a double root (two roots closer than SP4's merge distance,
    /// `2√1e-11 ≈ 6e-6` rad) whose branch `merged` (as [`Wrist::solve`] found it) misses
    /// `R36` (`m`) by more than rounding: the two roots were both real — the wrist a few
    /// µrad from its singularity, not at it — so both are solved (q4, q6 by SP1, then
    /// [`Wrist::polish`]) and flagged `Double`, for `finish` to check against `fk`. `None`
    /// — the merged branch stays — where it makes `R36` to rounding (the wrist is at its
    /// singularity, where the merged branch, with q4 free, is the answer) or either split
    /// branch misses `R36` by as much. Where rounding hid the two roots (|q5 − q5*| below
    /// ~1e-8: the discriminant is lost), [`Wrist::split_about`] — but a wrist whose caller
    /// holds the whole arm leaves that to [`with_wrist`].
    #[cold]
    fn split(
        &self,
        merged: [f64; 3],
        targets: (V3, V3),
        m: M3,
        free: [f64; 2],
        out: &mut [([f64; 3], Fit); 2],
    ) -> Option<usize> {
        let merged_miss = self.miss(merged, &m);
        if merged_miss <= MERGED_WRIST {
            return None;
        }
        match self.q5.split(self.h[0].dot(&targets.0)) {
            Some(roots) => self.split_at(roots, merged_miss, targets, m, free, out),
            None if self.on_arm => None,
            None => self.split_about(merged, merged_miss, targets, m, free, out),
        }
    }

    /// [`Wrist::split`] where rounding hid the two roots: q5 moved from the merged root
    /// either way by the merged branch's miss `merged_miss`.
    #[cold]
    fn split_about(
        &self,
        merged: [f64; 3],
        merged_miss: f64,
        targets: (V3, V3),
        m: M3,
        free: [f64; 2],
        out: &mut [([f64; 3], Fit); 2],
    ) -> Option<usize> {
        let roots = [merged_miss, -merged_miss].map(|d| Angle::new(merged[1] + d));
        self.split_at(roots, merged_miss, targets, m, free, out)
    }

    /// The branches of the two roots of q5 (see [`Wrist::split`]), where both make `R36`
    /// better than the merged branch's `merged_miss`.
    #[cold]
    fn split_at(
        &self,
        roots: [Angle; 2],
        merged_miss: f64,
        (r36_h6, r36t_h4): (V3, V3),
        m: M3,
        free: [f64; 2],
        out: &mut [([f64; 3], Fit); 2],
    ) -> Option<usize> {
        let [h4, _, h6] = &self.h;
        let mut split = [([0.0; 3], Fit::Double); 2];
        for (o, q5) in split.iter_mut().zip(&roots) {
            let (q4, f4) = sp1(&self.h6_about_h5.at(q5), &r36_h6, h4, free[0]);
            let (q6, f6) = sp1(&r36t_h4, &self.h4_about_h5.back(q5), h6, free[1]);
            let q = self.polish([q4, q5.theta, q6], &m);
            *o = (q, Fit::Double.and(f4).and(f6));
        }
        // The split pair only where both its branches make R36 better than the merged one.
        if split.iter().any(|(q, _)| self.miss(*q, &m) >= merged_miss) {
            return None;
        }
        *out = split;
        Some(2)
    }

    /// The largest entry of `R4 R5 R6 − m`.
    fn miss(&self, [q4, q5, q6]: [f64; 3], m: &M3) -> f64 {
        let [h4, h5, h6] = &self.h;
        (rot(h4, q4) * rot(h5, q5) * rot(h6, q6) - m).amax()
    }

    /// `(q4, q5, q6)` moved by Gauss–Newton on `R4 R5 R6 = R36` (`m`): near the wrist's
    /// singularity the subproblems' angles carry rounding amplified by the inverse of the
    /// distance to it; the Jacobian's weak direction (q4 against q6) barely moves the
    /// rotation, so what rounding leaves there costs nothing.
    #[cold]
    fn polish(&self, [mut q4, mut q5, mut q6]: [f64; 3], m: &M3) -> [f64; 3] {
        let [h4, h5, h6] = &self.h;
        for _ in 0..ROUNDS {
            let r4 = rot(h4, q4);
            let r45 = r4 * rot(h5, q5);
            // R36 = D R4 R5 R6 with D ≈ I + [e]×: e in the wrist's base frame, where the
            // joint rates turn it by h4 q̇4 + R4 h5 q̇5 + R4 R5 h6 q̇6.
            let d = m * (r45 * rot(h6, q6)).transpose();
            let e = 0.5 * V3::new(d.m32 - d.m23, d.m13 - d.m31, d.m21 - d.m12);
            let j = M3::from_columns(&[*h4, r4 * h5, r45 * h6]);
            // J itself, not JᵀJ: a micro-radian from the singularity JᵀJ's condition
            // (the square of J's) is past what f64 resolves.
            let Some(step) = j.lu().solve(&e) else {
                break;
            };
            (q4, q5, q6) = (q4 + step.x, q5 + step.y, q6 + step.z);
        }
        [wrap(q4), wrap(q5), wrap(q6)]
    }

    /// What [`Wrist::solve`] needs of the rotation `r36`.
    #[inline]
    pub(super) fn target(&self, r36: &M3) -> (V3, V3) {
        (r36 * self.h[2], r36.transpose() * self.h[0])
    }
}

/// Largest entry of `R4 R5 R6 − R36` a merged double root of q5 may leave before its two
/// roots are split (`EXACT_TOLERANCE`). A wrist at its singularity, computed in floating
/// point, misses by the rounding upstream (1e-12 on the Panda, 5e-11 where its q5 is 0 as
/// well): the merged branch, with q4 left free, is then the answer. One a micro-radian
/// from it misses by about that.
const MERGED_WRIST: f64 = 1e-10;

/// Largest entry of the pose error at which [`at_singularity_on_arm`] takes the whole
/// arm's polish as converged: to rounding. From a wrist at its singularity (the Panda at
/// q2 = 0 beside its shoulder's tangency) it lands within 2.2e-16; from one nanoradians
/// off it (the q2 = 1.5e-8 and −8.2e-9 of the micro-radian test) it stalls on the fold
/// at 2.1e-13 and 1.05e-10 — a point of the continuum reaching the pose, but not the
/// configuration, which the split finds.
const CONVERGED: f64 = 1e-14;

/// Gauss–Newton rounds of [`Wrist::polish`]. Each squares the error; a start within
/// rounding of the answer needs two, but a nanoradian from the singularity SP1 gives q4
/// only to about 0.1 rad (the wrist's weak direction), and eight rounds bring that in.
const ROUNDS: usize = 8;

/// Two roots of q5 closer than this (rad) are polished ([`Wrist::polish`]): their
/// rounding, amplified by the inverse of the gap, can reach 1e-10 within about 1e-4.
const NEAR_DOUBLE: f64 = 1e-3;

/// Adds the wrist solutions for the arm joints `q123` to `out`; `R36 = (R1 R2 R3)ᵀ R06` is
/// the rotation the wrist must make (a prismatic joint turns nothing), given as
/// `target = (R36 h6, R36ᵀ h4)` and, for a wrist singularity, `r36()`; `arm` is the
/// geometry and the pose the joints solve (see [`at_singularity_on_arm`]).
#[inline]
pub(super) fn with_wrist(
    arm: (&Geometry<6>, &Pose),
    wrist: &Wrist,
    q123: [f64; 3],
    (target, r36): ((V3, V3), impl Fn() -> M3),
    fit: Fit,
    free: &[f64; 6],
    out: &mut Candidates<6, 8>,
) {
    let mut w = [([0.0; 3], Fit::Exact); 2];
    let n = wrist.solve(target, &r36, [free[3], free[5]], &mut w);
    // One branch, not solved exactly: q5 merged into a double root (q6 then from the
    // whole rotation, in least squares where the rotation is off by more than rounding).
    if n == 1 && w[0].1 >= Fit::Double {
        let m = r36();
        let miss = wrist.miss(w[0].0, &m);
        if miss > MERGED_WRIST {
            let free = [free[3], free[5]];
            at_singularity_on_arm(arm, wrist, (q123, w[0], miss), (target, m), fit, free, out);
            return;
        }
    }
    for &(q456, f) in &w[..n] {
        let q = [q123[0], q123[1], q123[2], q456[0], q456[1], q456[2]];
        out.push(q, fit.and(f));
    }
}

/// A wrist at its singularity to the accuracy of `R36` (its two roots of q5 hidden by
/// rounding) whose merged branch `q456`, q4 the caller's, misses `R36` by `miss`: the
/// joints before it carry an error the wrist cannot take out (beside a tangency of the
/// shoulder, as on the Panda at q2 = 0 with its shoulder pair 1.8e-3 apart, 6e-10). Split
/// about the merged root, SP1 would put q4 where that error points — anywhere on the
/// continuum, 1 rad from the configuration there. So the merged branch is brought onto
/// the pose on the whole arm (`polish`) from q4 the caller's: the point of the continuum
/// nearest to it. Where that does not converge ([`CONVERGED`]: the wrist nanoradians from
/// its singularity, not at it, where the way out of it is second order), the split about
/// the merged root.
#[cold]
#[inline(never)]
fn at_singularity_on_arm(
    (g, pose): (&Geometry<6>, &Pose),
    wrist: &Wrist,
    (q123, (q456, f), miss): ([f64; 3], ([f64; 3], Fit), f64),
    (target, m): ((V3, V3), M3),
    fit: Fit,
    free: [f64; 2],
    out: &mut Candidates<6, 8>,
) {
    let joined = |q456: [f64; 3]| [q123[0], q123[1], q123[2], q456[0], q456[1], q456[2]];
    let q = polish(g, joined(q456), pose);
    if pose_miss(g, pose, &q) <= CONVERGED {
        out.push(q, fit.and(f));
        return;
    }
    let mut w = [([0.0; 3], Fit::Exact); 2];
    let n = wrist
        .split_about(q456, miss, target, m, free, &mut w)
        .unwrap_or_else(|| {
            w[0] = (q456, f);
            1
        });
    for &(q456, f) in &w[..n] {
        out.push(joined(q456), fit.and(f));
    }
}
