//! **General 6R**: six revolute axes in no special position (the Kinova Jaco's 60° wrist,
//! the FANUC CRX, a calibrated arm whose axes miss by a hair) — Raghavan and Roth's
//! elimination (1990, 1993) in Manocha and Canny's eigenvalue form (1994), on the
//! product-of-exponentials geometry.
//!
//! Write the arm as `e^{ξ1 q1} ⋯ e^{ξ6 q6} = T M⁻¹`. A point `p6` on axis 6 and its
//! direction `h6` do not move with joint 6, so
//!
//! ```text
//! e^{ξ3 q3} e^{ξ4 q4} e^{ξ5 q5} (p6, h6) = e^{−ξ2 q2} e^{−ξ1 q1} (pT, lT)
//! ```
//!
//! with `pT = T M⁻¹ p6`, `lT = R06 h6`, points seen from a point `o` on axis 3. Of each
//! side's point `p` and direction `l` Raghavan and Roth take fourteen quantities — `p`,
//! `l`, `p·p`, `p·l`, `p × l`, `(p·p) l − 2 (p·l) p` — that are linear in the nine
//! products `{1, cos q4, sin q4} ⊗ {1, cos q5, sin q5}` with coefficients linear in `(1,
//! cos q3, sin q3)` on the left, and linear in `{1, cos q1, sin q1} ⊗ {1, cos q2, sin q2}`
//! on the right (the cubic terms of the last three cancel). So:
//!
//! 1. the coefficients are read off the geometry: each side sampled on a grid of thirds
//!    of a turn, where `{1, cos, sin}` are recovered exactly by a three-point Fourier sum;
//! 2. the eight products of (q1, q2) are eliminated: Householder reflections of their
//!    14 × 8 coefficient matrix leave six equations in (q3, q4, q5);
//! 3. with `x = tan(q/2)` those are polynomials of degree 2 in each of x3, x4, x5;
//!    multiplied by x4 they give twelve equations linear in the twelve monomials
//!    `x4^i x5^j` (i ≤ 3, j ≤ 2): `(A x3² + B x3 + C) v = 0`, a quadratic eigenproblem;
//! 4. its 24 eigenvalues (a 24 × 24 companion matrix) are x3's candidates: eight of
//!    them are always `±i` (the determinant's factor `(1 + x²)⁴`), taken out first by an
//!    orthogonal similarity read off the equations at `x = i` (`spurious.rs`); the
//!    other sixteen by Francis's QR on the 16 × 16 matrix left (`eigenvalues.rs`) — at
//!    most 16 real solutions, the other roots complex;
//! 5. for each real x3 the null vector `v` of the 12 × 12 matrix gives x4, x5; the eight
//!    products give q1, q2 (the triangular factor of step 2); q6 by SP1;
//! 6. each branch is polished by Newton steps on `fk` and checked there
//!    ([`Fit::Checked`]): the eigenvalues carry rounding the back-substitution amplifies.
//!
//! That is Raghavan and Roth's own form; the loop can be carried round from any joint and
//! split after two joints or three — twelve forms ([`FORMULATIONS`], `formulation.rs`).
//! Special geometry makes some of them degenerate for every pose (the Jaco: ten of
//! twelve), and special poses (joints at right angles, the tool along axis 1) all of them
//! or nearly: the first form well conditioned at a reference pose is the arm's, read once
//! with the ones degenerate for every pose and kept ([`Hint`]); where it is ill
//! conditioned for a pose, the next well conditioned, else the best conditioned; where a
//! value of its eigen joint is shared by more solutions than the null space separates
//! (the CRX at q2 = 0, where two pairs share it: found by a split root, an odd number of
//! solutions, or roots that give none), the forms with other eigen joints too; where
//! every form degenerates, the solutions of the pose moved off by ±1e-5, ±1e-4 and ±1e-3,
//! tracked back by Newton steps. Damped steps follow wherever Gauss–Newton stalls beside a
//! close pair of solutions or stops short of a singular one.
//! Branches within 2e-6 rad are one double root (merged, flagged singular), as is a branch
//! whose Jacobian is singular to rounding (Hadamard's ratio below 1e-7). Where the
//! solutions form a continuum (axes that coincide at a special pose), the eigenvalues are
//! any of its points: singular branches joined by a segment of solutions are one, the
//! caller's configuration where it is on it; and the regular solutions take the 16 places
//! first.
//!
//! Everything here runs on the numbers of the geometry: the engine's part, at expansion
//! time, is to prove that no family of subproblems fits (either way round) and that every
//! joint is revolute. No allocation: every matrix is on the stack (the 24 × 24 companion
//! is 4.6 kB, reduced in place).

mod eigenvalues;
mod elimination;
mod formulation;
mod roots;
mod spurious;

use crate::ik::double_root::{apart, merge_double_roots, within, DOUBLE_ROOT};
use crate::ik::geometry::{orthogonal, rot, Geometry, Pose, M3, V3};
use crate::ik::polish::{hadamard_ratio, levenberg_marquardt, polish, pose_miss, DAMPED_ROUNDS};
use crate::ik::solutions::{pose_matrix, residual, Candidates};
use crate::ik::subproblems::{sp1_angle, wrap, Fit};
use crate::math::abs;
use core::cell::UnsafeCell;
use core::sync::atomic::{AtomicBool, Ordering};
use elimination::System;
pub use formulation::{Formulation, FORMULATIONS};
use roots::{REAL, SPLIT};

/// A branch whose Jacobian's Hadamard ratio is below this is flagged singular
/// ([`Fit::Double`]): `finish` then names the vanishing factors.
const NEAR_SINGULAR: f64 = 1e-7;

/// The general 6R solver (see the module): every real solution of `pose`, at most 16,
/// each polished on `fk` and flagged [`Fit::Checked`] (a double root: [`Fit::Double`]).
///
/// ```
/// use kinegen::ik::families::{general_6r, Hint};
/// use kinegen::ik::geometry::{Geometry, M3, V3};
/// use kinegen::ik::solutions::Candidates;
/// // Six axes in general position (no two parallel, none meeting).
/// let unit = |x: f64, y: f64, z: f64| V3::new(x, y, z).normalize();
/// let g = Geometry {
///     h: [unit(0.0, 0.0, 1.0), unit(0.1, 1.0, 0.2), unit(0.3, 0.9, -0.1),
///         unit(1.0, 0.2, 0.1), unit(0.2, 1.0, -0.3), unit(0.9, 0.1, 0.4)],
///     p: [V3::zeros(), V3::new(0.05, 0.0, 0.3), V3::new(0.4, 0.1, 0.35),
///         V3::new(0.5, 0.05, 0.6), V3::new(0.7, 0.12, 0.55), V3::new(0.8, 0.0, 0.6)],
///     prismatic: [false; 6],
///     r_tool: M3::identity(),
///     p_tool: V3::new(0.9, 0.0, 0.65),
/// };
/// let q = [0.3, -0.7, 0.4, 1.1, -0.5, 0.8];
/// let mut out = Candidates::<6, 16>::default();
/// general_6r(&g, &g.fk(&q), &[0.0; 6], &Hint::new(), &mut out);
/// assert!(out.as_slice().iter().any(|c| (0..6).all(|i| (c.q[i] - q[i]).abs() < 1e-9)));
/// ```
pub fn general_6r<const K: usize>(
    g: &Geometry<6>,
    pose: &Pose,
    free: &[f64; 6],
    hint: &Hint,
    out: &mut Candidates<6, K>,
) {
    let mut found = Found::default();
    let reached = |q: &[f64; 6]| reaches(g, q, pose);
    let start = hint.start(g);
    let (conditioning, shared) = eliminate_and_solve(g, pose, free, start, &mut found);
    // A value of the eigen joint shared by more solutions than read that no other eigen
    // joint separates either: the pose moved off, as for a degenerate one.
    let unresolved =
        shared.is_some() && !with_other_eigen_joints(g, pose, free, start, shared, &mut found);
    if unresolved
        || conditioning < WELL_CONDITIONED
        || !found.as_slice().iter().any(|c| reached(&c.q))
    {
        // Every form's pencil singular or nearly so for this pose (special poses: the
        // tool along axis 1, joints at right angles — the elimination loses roots there,
        // though the solutions are isolated), or no branch reaches the pose (out of reach,
        // or a singular pose whose solutions form a continuum): the solutions of poses
        // moved off it, brought back onto it by Newton steps, added.
        // Both ways: a pose on the boundary where two solutions are born (a singular
        // one) has them on one side only; and three sizes, for the moved poses' pencils are
        // still ill-conditioned (pivot ratio ~1e-7 to ~1e-5), and a branch one misses
        // another finds (the self-tests' degenerate poses of the Jaco and the CRX; the
        // Gen3's at q2 = 0, q4 = q5 = π/2, where ±1e-5 gives four of its twelve solutions
        // the other sizes lose).
        for size in [
            0.1 * NUDGE,
            -0.1 * NUDGE,
            NUDGE,
            -NUDGE,
            10.0 * NUDGE,
            -10.0 * NUDGE,
        ] {
            let mut seeds = Found::default();
            let _ = eliminate_and_solve(g, &nudged(pose, size), free, start, &mut seeds);
            for s in seeds.as_slice() {
                // Tracked back in steps of a tenth: near-singular poses have solutions
                // ~NUDGE / σ apart, and one Newton run from the nudged pose's could land
                // on a neighbour's.
                let mut q = s.q;
                let mut step = size;
                while abs(step) > 1e-8 {
                    step /= 10.0;
                    q = polish(g, q, &nudged(pose, step));
                }
                let q = polish(g, q, pose);
                // Gauss–Newton stalls near two solutions close together (the Gen3's pairs
                // 0.03–0.06 rad apart, |det J| ~1e-6: 5e-8 off after its rounds), and
                // converges only linearly onto a singular one (the Jaco at q2 = … = q5 = 0:
                // 1e-10 off).
                let q = settle(g, q, pose, pose_miss(g, pose, &q)).map(wrap);
                let room = found.as_slice().len() < FOUND;
                if room && !found.as_slice().iter().any(|c| same(&c.q, &q)) {
                    // Out of reach (or a workspace-boundary pose Newton cannot settle on):
                    // the nearest, flagged so; `finish` drops them where a branch reaches.
                    // A singular one (a continuum's point) is flagged so, and yields its
                    // place to the isolated solutions.
                    let fit = match reached(&q) {
                        false => Fit::LeastSquares,
                        true if hadamard_ratio(g, &q) < NEAR_SINGULAR => Fit::Double,
                        true => Fit::Free,
                    };
                    found.push(q, fit);
                }
            }
        }
    }
    merge_double_roots(g, pose, &mut found);
    // The caller's configuration, where it solves the pose: it replaces a branch within
    // a double root's spread of it (at a singular pose Newton stops ~1e-7 away along the
    // direction the pose does not see), else it is added — a point of a continuum of
    // solutions. Either way `ik_near` stays where it is.
    let here = free.map(wrap);
    if reached(&here) {
        let room = found.as_slice().len() < FOUND;
        match found
            .as_mut_slice()
            .iter_mut()
            .find(|c| within(&c.q, &here, DOUBLE_ROOT))
        {
            Some(c) => c.q = here,
            None if room => found.push(here, Fit::Free),
            // Full (a continuum's samples): it takes the place of the farthest branch.
            None => {
                if let Some(c) = found
                    .as_mut_slice()
                    .iter_mut()
                    .max_by(|a, b| miss(g, &a.q, pose).total_cmp(&miss(g, &b.q, pose)))
                {
                    (c.q, c.fit) = (here, Fit::Free);
                }
            }
        }
    }
    one_per_self_motion(g, pose, &here, &mut found);
    // Spurious real roots (the pencil's rounding) polish to nowhere: the closest first,
    // and of those reaching the pose the regular ones first (the isolated solutions; a
    // continuum's points, singular, can number more than the room for them).
    let mut order: [(bool, f64, usize); FOUND] = [(true, f64::INFINITY, 0); FOUND];
    for (i, c) in found.as_slice().iter().enumerate() {
        let m = miss(g, &c.q, pose);
        let regular = m <= REACHES * (1.0 + pose.p.amax()) && c.fit != Fit::Double;
        order[i] = (!regular, m, i);
    }
    let m = found.as_slice().len();
    order[..m].sort_unstable_by(|a, b| a.0.cmp(&b.0).then(a.1.total_cmp(&b.1)));
    for &(_, _, i) in order[..m].iter().take(K) {
        let c = found.as_slice()[i];
        out.push(c.q, c.fit);
    }
}

/// Keeps one solution of each self-motion: at a singular pose whose solutions form a
/// continuum (the CRX with q2 = 0 and q3 = −π/2, where axes 1 and 4 coincide and only
/// q1 + q4 is fixed), the eigenvalues are any points of it, and up to 24 of them would
/// crowd the isolated solutions out. Two singular branches are on one self-motion where
/// the segment between them solves the pose too (three points of it: coincident axes
/// make such a continuum a straight line in joint space; a curved one keeps its samples).
/// Of each, the caller's configuration where it is one, else the point nearest to it.
fn one_per_self_motion(g: &Geometry<6>, pose: &Pose, here: &[f64; 6], found: &mut Found) {
    let all = *found;
    let items = all.as_slice();
    // A `Checked` branch was found regular (`solve_with` measured its Hadamard ratio).
    let singular: [bool; FOUND] = core::array::from_fn(|i| {
        i < items.len()
            && items[i].fit != Fit::Checked
            && reaches(g, &items[i].q, pose)
            && hadamard_ratio(g, &items[i].q) < NEAR_SINGULAR
    });
    if singular.iter().filter(|&&s| s).count() < 2 {
        return;
    }
    // Each branch's group: the first member's index (the groups are unions of pairs).
    let mut group: [usize; FOUND] = core::array::from_fn(|i| i);
    for i in 0..items.len() {
        for j in i + 1..items.len() {
            if !singular[i] || !singular[j] || group[j] == group[i] {
                continue;
            }
            let (a, b) = (&items[i].q, &items[j].q);
            // To the ends' own rounding: two distinct solutions near a fold, a few 1e-6
            // apart, have a chord that misses by ~1e-12 (the curvature), a line none.
            let ends = miss(g, a, pose).max(miss(g, b, pose));
            let on_line = [0.25, 0.5, 0.75].iter().all(|t| {
                let q: [f64; 6] = core::array::from_fn(|k| a[k] + t * wrap(b[k] - a[k]));
                miss(g, &q, pose) <= 2.0 * ends + 1e-14 * (1.0 + pose.p.amax())
            });
            if on_line {
                let (from, to) = (group[j], group[i]);
                for gk in group.iter_mut().take(items.len()) {
                    if *gk == from {
                        *gk = to;
                    }
                }
            }
        }
    }
    let gap = |q: &[f64; 6]| apart(q, here);
    let mut kept = Found::default();
    for i in 0..items.len() {
        // The group's member nearest the caller's configuration stands for it.
        let nearest = (0..items.len())
            .filter(|&j| group[j] == group[i])
            .min_by(|&x, &y| gap(&items[x].q).total_cmp(&gap(&items[y].q)))
            .unwrap_or(i);
        if nearest == i {
            kept.push(items[i].q, items[i].fit);
        }
    }
    *found = kept;
}

/// Room for the branches the solver keeps: 24 eigenvalues, a second configuration for
/// some, the caller's (more are not kept: a real 6R has at most 16 solutions).
const FOUND: usize = 40;
type Found = Candidates<6, FOUND>;

/// A branch within this of the pose (relative to its position's size; position plus
/// rotation norm) reaches it; `finish` then measures it against `EXACT_TOLERANCE`.
const REACHES: f64 = 1e-9;

/// A branch tracked back onto the pose that misses it by more than this (the largest
/// entry, as `finish` measures against `EXACT_TOLERANCE`, 1e-10) is taken on by damped
/// steps.
const SETTLED: f64 = 1e-11;

/// `q` where Newton's steps left it, unless it misses `pose` by more than [`SETTLED`]
/// (`m`, its largest entry, as [`pose_miss`] measures it): then Levenberg–Marquardt's
/// damped steps from it, kept only where they reach the pose closer (a branch that cannot
/// does not move). Gauss–Newton stalls beside two solutions close together (each full
/// step overshoots along the near-null direction) and converges only linearly onto a
/// singular one; damped steps still converge there.
fn settle(g: &Geometry<6>, q: [f64; 6], pose: &Pose, m: f64) -> [f64; 6] {
    if m <= SETTLED {
        return q;
    }
    let damped = levenberg_marquardt(g, q, pose, DAMPED_ROUNDS).map(wrap);
    if reaches(g, &damped, pose) && pose_miss(g, pose, &damped) < m {
        damped
    } else {
        q
    }
}

/// How far a pose the elimination is degenerate for is moved ([`nudged`]), both ways:
/// far enough that the moved pose's pencil is regular (pivot ratio ~1e-6), near enough
/// that tracking back is a few Newton runs.
const NUDGE: f64 = 1e-4;

/// `pose` turned by `size` radians about a generic axis and moved by `size` per metre of
/// its distance from the base (plus one): off any special pose.
fn nudged(pose: &Pose, size: f64) -> Pose {
    let axis = V3::new(0.267, -0.535, 0.802).normalize();
    let scale = 1.0 + pose.p.amax();
    Pose {
        r: rot(&axis, size) * pose.r,
        p: pose.p + V3::new(-0.62, 0.41, 0.67) * (size * scale),
    }
}

/// Steps 1–6 on a formulation regular for this arm and pose (the arm's first if it is
/// well conditioned, else the next that is, else the best conditioned); the branches into
/// `found`, that pencil's pivot ratio (0: none regular, nothing found) and, where a value
/// of its eigen joint was shared by more solutions than the back-substitution separates,
/// that joint.
fn eliminate_and_solve(
    g: &Geometry<6>,
    pose: &Pose,
    free: &[f64; 6],
    start: Start,
    found: &mut Found,
) -> (f64, Option<usize>) {
    // The arm's first formulation where it is well conditioned for this pose; else the
    // next that is, else the best conditioned of all (a pose near a degenerate one for
    // some of them).
    // The best so far by its ratio and index only, built again at the end: one system on
    // the stack at a time (9 kB each; the Cortex-M4F's stack), and the rebuild is rare.
    let mut best: Option<(f64, usize)> = None;
    for i in 0..FORMULATIONS.len() {
        let k = (start.first + i) % FORMULATIONS.len();
        if start.regular & (1 << k) == 0 {
            continue;
        }
        let Some(sys) = System::new(g, pose, FORMULATIONS[k]) else {
            continue;
        };
        if sys.ratio >= WELL_CONDITIONED {
            let shared = solve_with(g, pose, free, &sys, found);
            return (sys.ratio, shared.then_some(sys.joints[0]));
        }
        if best.is_none_or(|(ratio, _)| sys.ratio > ratio) {
            best = Some((sys.ratio, k));
        }
    }
    match best.and_then(|(_, k)| System::new(g, pose, FORMULATIONS[k])) {
        Some(sys) => {
            let shared = solve_with(g, pose, free, &sys, found);
            (sys.ratio, shared.then_some(sys.joints[0]))
        }
        None => (0.0, None),
    }
}

/// Where several solutions share a value of the eigen joint (the CRX at q2 = 0: four
/// solutions, two pairs, share it), the eigenvalue is multiple: rounding splits it by up
/// to ε^(1/4), and the null space of `M(x)` has more dimensions than the back-substitution
/// separates (two) — solutions go missing, and the ones found look like a double root, a
/// singular configuration they are not. Solutions are intrinsic, the eigen joint is not:
/// the formulations with other eigen joints, well conditioned for this pose, are solved
/// too until one sees no shared value; their solutions are added, and a branch one of
/// them finds as a simple root is not a double one (at a singular configuration, where
/// two solutions meet, every projection of it is a double root). Whether one did.
fn with_other_eigen_joints(
    g: &Geometry<6>,
    pose: &Pose,
    free: &[f64; 6],
    start: Start,
    mut shared: Option<usize>,
    found: &mut Found,
) -> bool {
    let mut tried = [false; 6];
    for (k, form) in FORMULATIONS.into_iter().enumerate() {
        let Some(joint) = shared else {
            return true;
        };
        tried[joint] = true;
        if tried[form.eigen_joint()] || start.regular & (1 << k) == 0 {
            continue;
        }
        let Some(sys) = System::new(g, pose, form) else {
            continue;
        };
        if sys.ratio < WELL_CONDITIONED {
            continue;
        }
        debug_assert_eq!(sys.joints[0], form.eigen_joint());
        let mut more = Found::default();
        shared = solve_with(g, pose, free, &sys, &mut more).then_some(form.eigen_joint());
        for c in more.as_slice() {
            let room = found.as_slice().len() < FOUND;
            match found.as_mut_slice().iter_mut().find(|f| same(&f.q, &c.q)) {
                Some(f) if f.fit == Fit::Double && c.fit == Fit::Checked => f.fit = c.fit,
                Some(_) => {}
                None if room => found.push(c.q, c.fit),
                None => {}
            }
        }
        if shared.is_none() {
            return true;
        }
    }
    false
}

/// A formulation whose pencil's pivot ratio is at least this is used without looking at
/// the others (regular poses of the Jaco: 1e-5 to 1).
const WELL_CONDITIONED: f64 = 1e-3;

/// Which formulation ([`FORMULATIONS`]) an arm's poses start with, and which are regular
/// at all: special geometry (two parallel axes, a 60° wrist) makes some of them
/// degenerate for every pose, and finding that out costs an elimination each (~10 µs;
/// ten of the Jaco's twelve). Both are read once per arm at a reference pose (the product
/// of exponentials at a fixed configuration in no special position, the tool left out)
/// and kept: a pure function of the arm's axes, so a pose's solutions do not depend on
/// the poses solved before it, in which order, or on which thread. A generated `ik` keeps
/// one in a `static`; a hint handed another arm's geometry (a 7-joint arm with a middle
/// joint locked at another value) reads that arm's again.
///
/// ```
/// use kinegen::ik::families::{general_6r, Hint};
/// use kinegen::ik::geometry::{Geometry, M3, V3};
/// use kinegen::ik::solutions::Candidates;
/// let unit = |x: f64, y: f64, z: f64| V3::new(x, y, z).normalize();
/// let g = Geometry {
///     h: [unit(0.0, 0.0, 1.0), unit(0.1, 1.0, 0.2), unit(0.3, 0.9, -0.1),
///         unit(1.0, 0.2, 0.1), unit(0.2, 1.0, -0.3), unit(0.9, 0.1, 0.4)],
///     p: [V3::zeros(), V3::new(0.05, 0.0, 0.3), V3::new(0.4, 0.1, 0.35),
///         V3::new(0.5, 0.05, 0.6), V3::new(0.7, 0.12, 0.55), V3::new(0.8, 0.0, 0.6)],
///     prismatic: [false; 6],
///     r_tool: M3::identity(),
///     p_tool: V3::new(0.9, 0.0, 0.65),
/// };
/// let (a, b) = (g.fk(&[0.3, -0.7, 0.4, 1.1, -0.5, 0.8]), g.fk(&[1.0; 6]));
/// // Solving another pose first changes nothing, to the bit.
/// let (kept, fresh) = (Hint::new(), Hint::new());
/// let (mut x, mut y) = (Candidates::<6, 16>::default(), Candidates::<6, 16>::default());
/// general_6r(&g, &b, &[0.0; 6], &kept, &mut x);
/// x = Candidates::default();
/// general_6r(&g, &a, &[0.0; 6], &kept, &mut x);
/// general_6r(&g, &a, &[0.0; 6], &fresh, &mut y);
/// assert_eq!(x.as_slice(), y.as_slice());
/// ```
#[derive(Debug)]
pub struct Hint {
    /// A start fixed by [`Hint::at`], every formulation tried; else the arm's.
    fixed: Option<usize>,
    /// Held while `arm` is read or written; a caller that finds it held (another
    /// thread, an interrupt) reads its arm's start itself instead of waiting.
    busy: AtomicBool,
    /// The last arm's axes and its start.
    arm: UnsafeCell<Option<([u64; 36], Start)>>,
}

// `arm` is only touched by the caller that set `busy`.
unsafe impl Sync for Hint {}

impl Default for Hint {
    fn default() -> Hint {
        Hint::new()
    }
}

impl Hint {
    /// The arm's own start, read at the reference pose on first use.
    pub const fn new() -> Hint {
        Hint {
            fixed: None,
            busy: AtomicBool::new(false),
            arm: UnsafeCell::new(None),
        }
    }

    /// Start with formulation `k` of [`FORMULATIONS`] (modulo their number) and try every
    /// one where it is ill conditioned: how a test makes each formulation solve a pose.
    pub const fn at(k: usize) -> Hint {
        Hint {
            fixed: Some(k % FORMULATIONS.len()),
            busy: AtomicBool::new(false),
            arm: UnsafeCell::new(None),
        }
    }

    /// Where `g`'s poses start (see the type).
    fn start(&self, g: &Geometry<6>) -> Start {
        if let Some(first) = self.fixed {
            return Start {
                first,
                regular: ALL,
            };
        }
        let axes = axes_bits(g);
        if self.busy.swap(true, Ordering::Acquire) {
            return Start::of(g);
        }
        // SAFETY: `busy` was false and is now ours: no other reference to `arm` exists
        // until it is released below.
        let arm = unsafe { &mut *self.arm.get() };
        let start = match arm {
            Some((bits, start)) if *bits == axes => *start,
            _ => {
                let start = Start::of(g);
                *arm = Some((axes, start));
                start
            }
        };
        self.busy.store(false, Ordering::Release);
        start
    }
}

/// The bits of an arm's axes and their points: what its formulations' regularity depends
/// on (the tool only moves the target).
fn axes_bits(g: &Geometry<6>) -> [u64; 36] {
    core::array::from_fn(|i| {
        let v = if i < 18 {
            g.h[i / 3]
        } else {
            g.p[(i - 18) / 3]
        };
        v[i % 3].to_bits()
    })
}

/// Every formulation (a bit each).
const ALL: u16 = (1 << FORMULATIONS.len()) - 1;

/// A configuration in no special position (no joint at a multiple of π/4), where an
/// arm's formulations are tried once ([`Hint`]).
const REFERENCE: [f64; 6] = [0.37, -1.13, 0.71, 1.29, -0.53, 2.03];

/// Where an arm's poses start: the first formulation well conditioned at the reference
/// pose (else its best conditioned), and the formulations regular there — the others are
/// degenerate for every pose of the arm, and are not tried.
#[derive(Clone, Copy, Debug)]
struct Start {
    first: usize,
    regular: u16,
}

impl Start {
    fn of(g: &Geometry<6>) -> Start {
        let axes = Geometry {
            r_tool: M3::identity(),
            p_tool: V3::zeros(),
            ..*g
        };
        let pose = axes.fk(&REFERENCE);
        let (mut regular, mut first, mut best) = (0, None, None::<(f64, usize)>);
        for (k, &form) in FORMULATIONS.iter().enumerate() {
            let Some(sys) = System::new(&axes, &pose, form) else {
                continue;
            };
            regular |= 1 << k;
            if first.is_none() && sys.ratio >= WELL_CONDITIONED {
                first = Some(k);
            }
            if best.is_none_or(|(ratio, _)| sys.ratio > ratio) {
                best = Some((sys.ratio, k));
            }
        }
        match first.or(best.map(|(_, k)| k)) {
            Some(first) => Start { first, regular },
            // None regular at a generic pose: try them all, pose by pose.
            None => Start {
                first: 0,
                regular: ALL,
            },
        }
    }
}

/// Steps 4–6 on one regular formulation; whether solutions may be missing because a
/// value of the eigen joint is shared by more of them than the back-substitution
/// separates: a real root whose null space it could not read or has more than two
/// dimensions, a real root none of whose branches reaching the pose keeps its value of
/// the eigen joint, a solution read off a root split from the real line with a single
/// null vector, or roots near the real line none of which gave a branch.
fn solve_with(
    g: &Geometry<6>,
    pose: &Pose,
    free: &[f64; 6],
    sys: &System,
    found: &mut Found,
) -> bool {
    let mut shared = false;
    let before = found.as_slice().len();
    let mut roots = [(0.0, 0.0); 2 * 12];
    let n = sys.real_roots(&mut roots);
    let r06 = pose.r * g.r_tool.transpose();
    let f = sys.eliminated;
    let xf = orthogonal(&g.h[f]);
    for &(x, im) in &roots[..n] {
        let (branches, count, wider) = sys.back_substitute(x);
        // Whether a branch keeps this root's value of the eigen joint (see the end).
        let (eigen, mut kept) = (sys.joints[0], false);
        shared |= (wider || count == 0) && im <= REAL;
        for mut q in branches.into_iter().take(count) {
            // The root's value, as the back-substitution set it.
            let value = q[eigen];
            // The eliminated joint by SP1: rot(h_f, q_f) = (R before f)ᵀ R06 (R after f)ᵀ.
            let turn = |j: usize| rot(&g.h[j], q[j]);
            let before = (0..f).fold(M3::identity(), |r, j| r * turn(j));
            let after = (f + 1..6).fold(M3::identity(), |r, j| r * turn(j));
            let target = before.tr_mul(&r06) * after.transpose();
            let (qf, ff) = sp1_angle(&xf, &(target * xf), &g.h[f], free[f]);
            q[f] = qf.theta;
            // Newton on `fk` where the back-substitution left more than rounding.
            let close = miss(g, &q, pose) <= POLISHED * (1.0 + pose.p.amax());
            let q = if close { q } else { polish(g, q, pose) }.map(wrap);
            // Gauss–Newton converges only linearly onto a singular solution and stops
            // short (the Jaco at q2 = q3 = 0: 1.4e-10 off, over `EXACT_TOLERANCE`). One
            // `fk` tells both whether the branch reaches the pose and by how much it misses.
            let (q, reached) = if close {
                (q, true)
            } else {
                let at = g.fk(&q);
                match distance(&at, pose) <= REACHES * (1.0 + pose.p.amax()) {
                    true => (settle(g, q, pose, residual(&pose_matrix(&at), pose)), true),
                    false => (q, false),
                }
            };
            kept |= abs(wrap(q[eigen] - value)) <= KEPT && reached;
            // A solution read as a root split off the real line with one null vector:
            // two met there, or more share the value (then some are missing).
            shared |= im > SPLIT && count == 1 && reached;
            // Two eigenvalues of one solution (a double root split by rounding) polish to
            // it twice.
            if found.as_slice().iter().any(|c| same(&c.q, &q)) {
                continue;
            }
            // A root off the real line, or a vector of a two-dimensional null space (one
            // of them may be a neighbouring root's), is a solution only where it reaches
            // the pose.
            if (im > REAL || count == 2) && !reached {
                continue;
            }
            // A split root with one null vector is one configuration where two solutions
            // meet: a singular one (two null vectors: two solutions sharing a joint); so
            // is a branch whose Jacobian is singular to rounding.
            let fit = if (im > SPLIT && count == 1) || hadamard_ratio(g, &q) < NEAR_SINGULAR {
                Fit::Double
            } else {
                Fit::Checked
            };
            if found.as_slice().len() < FOUND {
                found.push(q, fit.and(ff));
            }
        }
        // A real root none of whose branches keeps its value of the eigen joint: Newton
        // took each to a solution at another value — the null vectors were read wrong
        // (a fold's double root beside two solutions whose eigen joint is near: the Jaco
        // at q4 = q5 = 0), and the solution at this value is missing.
        shared |= !kept && im <= REAL;
    }
    // Roots near the real line but no branch from any: a value shared by four solutions
    // splits by ~ε^(1/4), and none of its null vectors is read right.
    shared || (n > 0 && found.as_slice().len() == before)
}

/// A branch within this of its root's value of the eigen joint (radians) is that root's:
/// Newton moves a back-substituted branch by its rounding (a quadruple root's split,
/// ε^(1/4), at most), a wrongly read one to another solution (~1e-2 away in the Jaco's
/// cases).
const KEPT: f64 = 1e-3;

/// A back-substituted branch this close to the pose (relative to its position's size) is
/// not polished: `finish` checks it against `EXACT_TOLERANCE` (1e-10) anyway.
const POLISHED: f64 = 1e-13;

/// Two configurations within rounding of each other (whole turns apart counts as one).
fn same(a: &[f64; 6], b: &[f64; 6]) -> bool {
    within(a, b, 1e-7)
}

/// `q` reaches `pose`: [`miss`] within [`REACHES`] of the pose's size.
fn reaches(g: &Geometry<6>, q: &[f64; 6], pose: &Pose) -> bool {
    miss(g, q, pose) <= REACHES * (1.0 + pose.p.amax())
}

/// How far `fk(q)` is from `pose`: position (in the arm's units) plus rotation.
fn miss(g: &Geometry<6>, q: &[f64; 6], pose: &Pose) -> f64 {
    distance(&g.fk(q), pose)
}

/// [`miss`] of the pose `at`.
fn distance(at: &Pose, pose: &Pose) -> f64 {
    (at.p - pose.p).norm() + (at.r - pose.r).norm()
}
