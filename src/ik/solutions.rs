//! Solution sets of closed-form IK, fixed-size, and the last step every solver shares:
//! wrapping into the joint limits, checking least-squares and singular branches against
//! the forward kinematics, removing duplicates.

use super::geometry::Pose;
use super::subproblems::{wrap, Fit};
use core::borrow::Borrow;
use core::f64::consts::{PI, TAU};

/// A candidate from a family solver: joint values and how the subproblems fitted.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Candidate<const N: usize> {
    /// Joint values.
    pub q: [f64; N],
    /// The weakest fit of the subproblems that produced it.
    pub fit: Fit,
}

/// Up to `K` candidates.
#[derive(Clone, Copy, Debug)]
pub struct Candidates<const N: usize, const K: usize> {
    items: [Candidate<N>; K],
    len: usize,
    /// The caller keeps only the solutions that reach the pose (see
    /// [`Candidates::reaching_only`]).
    reaching_only: bool,
}

impl<const N: usize, const K: usize> Default for Candidates<N, K> {
    fn default() -> Self {
        Candidates {
            items: [Candidate {
                q: [0.0; N],
                fit: Fit::Exact,
            }; K],
            len: 0,
            reaching_only: false,
        }
    }
}

impl<const N: usize, const K: usize> Candidates<N, K> {
    /// An empty set for a caller that keeps only the solutions that reach the pose — a
    /// reachability map counting them, `ik_near` choosing among them. At a pose that no
    /// branch reaches, a solver may then leave out the branches it proves to miss it by
    /// more than [`NEAR_MISS`] (the lanes solvers of `ik::regular`: an elbow or shoulder
    /// out of reach, the rest of the branch exact) instead of handing on each one's
    /// least-squares nearest for `finish` to check with `fk` — none of which could be
    /// exact. The solutions that reach the pose are the same either way.
    ///
    /// ```
    /// use kinegen::ik::solutions::Candidates;
    /// assert!(Candidates::<6, 8>::reaching_only().wants_reaching_only());
    /// assert!(!Candidates::<6, 8>::default().wants_reaching_only());
    /// ```
    pub fn reaching_only() -> Self {
        Candidates {
            reaching_only: true,
            ..Default::default()
        }
    }

    /// Whether the caller keeps only the solutions that reach the pose
    /// ([`Candidates::reaching_only`]).
    pub fn wants_reaching_only(&self) -> bool {
        self.reaching_only
    }

    /// The first `len` only (a solver taking back what it pushed last).
    #[cfg_attr(feature = "small-ik", allow(dead_code))]
    pub(crate) fn truncate(&mut self, len: usize) {
        self.len = self.len.min(len);
    }

    /// Add one (ignored when `K` are there already: a solver bug, never silent in tests).
    pub fn push(&mut self, q: [f64; N], fit: Fit) {
        debug_assert!(self.len < K, "more than {K} IK candidates");
        if self.len < K {
            self.items[self.len] = Candidate { q, fit };
            self.len += 1;
        }
    }

    /// The candidates.
    pub fn as_slice(&self) -> &[Candidate<N>] {
        // `len ≤ K` always (`push`); saying so keeps a panic path (and, on a
        // microcontroller, the formatting machinery it pulls in) out of every `ik`.
        &self.items[..self.len.min(K)]
    }

    /// The candidates, to be changed in place (a family polishing its branches).
    pub fn as_mut_slice(&mut self) -> &mut [Candidate<N>] {
        &mut self.items[..self.len.min(K)]
    }
}

/// One IK solution (a branch: shoulder, elbow, wrist choice), in the robot's scalar `T`
/// (`f64`, or `f32` for a `scalar: f32` robot, whose solve runs in f64 and is rounded
/// once at the end: [`IkSolutions::to_f32`]).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct IkBranch<const N: usize, T = f64> {
    /// Joint values (revolute joints wrapped by whole turns into the limits where that
    /// helps, else into `(−π, π]`).
    #[cfg_attr(feature = "serde", serde(with = "serde_big_array::BigArray"))]
    pub q: [T; N],
    /// `fk(q)` reaches the pose (to [`EXACT_TOLERANCE`]). `false`: the pose is out of
    /// reach and `q` is the nearest the solver found (least squares), see `residual` —
    /// or, where other branches reach the pose, this one misses it by at most
    /// [`NEAR_MISS`] (a near-tangency).
    pub exact: bool,
    /// `max |fk(q) − pose|` over the 12 entries of the top three rows, when it was
    /// measured: for least-squares branches and singular ones. `0.0` for the branches
    /// every subproblem solved exactly (their error is rounding only). Measured in f64
    /// for every robot (see [`Check`]).
    pub residual: T,
    /// Bit `i` set: entry `i` of the robot's `SINGULARITIES` vanishes at `q` (to
    /// [`SINGULAR_TOLERANCE`]); checked for the branches a subproblem found singular.
    pub singular: u32,
    /// A subproblem met a double root or left a joint free: `q` is a singular
    /// configuration (also for robots without `SINGULARITIES`, such as 7-joint arms).
    pub at_singularity: bool,
    /// Every joint within the robot's `LIMITS`.
    pub within_limits: bool,
}

/// All solutions of one pose: at most `K`, no allocation; joint values in `T` (`f64`, or
/// `f32` for a `scalar: f32` robot).
///
/// With the `serde` feature it is a sequence of its branches (reading back more than `K`
/// is an error); with `defmt`, firmware logs it as that list.
#[derive(Clone, Copy, Debug)]
pub struct IkSolutions<const N: usize, const K: usize, T = f64> {
    items: [IkBranch<N, T>; K],
    len: usize,
}

/// Largest `max |fk(q) − pose|` entry of a branch that counts as exact.
pub const EXACT_TOLERANCE: f64 = 1e-10;

/// Largest residual of a branch that misses a pose another branch reaches and is still
/// returned (flagged inexact): a near-tangency, which an f32 robot's solutions count as
/// exact ([`EXACT_TOLERANCE_F32`]). A branch that misses by more is no answer to a pose
/// the arm reaches; its least-squares configuration is returned only for a pose out of
/// every branch's reach.
pub const NEAR_MISS: f64 = EXACT_TOLERANCE_F32;

/// Largest `|factor(q)|` at which a singular factor counts as vanishing.
pub const SINGULAR_TOLERANCE: f64 = 1e-9;

/// Largest joint difference (radians or metres, after whole turns) of two branches that
/// are the same configuration.
pub const SAME_CONFIGURATION: f64 = 1e-9;

impl<const N: usize, const K: usize, T: Copy + Default> IkSolutions<N, K, T> {
    /// No solutions.
    #[inline]
    pub fn empty() -> Self {
        IkSolutions {
            items: [IkBranch {
                q: [T::default(); N],
                exact: false,
                residual: T::default(),
                singular: 0,
                at_singularity: false,
                within_limits: false,
            }; K],
            len: 0,
        }
    }

    /// Number of solutions.
    pub fn len(&self) -> usize {
        self.len
    }

    /// Whether there is none.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The solutions.
    pub fn as_slice(&self) -> &[IkBranch<N, T>] {
        // `len ≤ K` always; no panic path (see `Candidates::as_slice`).
        &self.items[..self.len.min(K)]
    }

    /// Adds `b` (never more than `K`: `finish` adds at most one per candidate).
    #[inline(always)]
    fn push(&mut self, b: IkBranch<N, T>) {
        // As `Candidates::push`: more than `K` would be a solver bug, never silent in tests.
        debug_assert!(self.len < K, "more than {K} IK solutions");
        // `get_mut`, not indexing: no panic path (see `Candidates::as_slice`).
        if let Some(slot) = self.items.get_mut(self.len) {
            *slot = b;
            self.len += 1;
        }
    }

    /// Keeps the solutions `keep` says yes to, in order.
    fn retain(&mut self, keep: impl Fn(&IkBranch<N, T>) -> bool) {
        let mut len = 0;
        for i in 0..self.len.min(K) {
            if keep(&self.items[i]) {
                if len < i {
                    // A swap of two places known apart: a copy within one array is a
                    // `memmove`, 1.5 KB of a microcontroller's flash that nothing else in
                    // `ik` needs.
                    let (front, back) = self.items.split_at_mut(i);
                    core::mem::swap(&mut front[len], &mut back[0]);
                }
                len += 1;
            }
        }
        self.len = len;
    }

    /// The solutions, in order.
    pub fn iter(&self) -> core::slice::Iter<'_, IkBranch<N, T>> {
        self.as_slice().iter()
    }

    /// The exact solutions.
    pub fn exact(&self) -> impl Iterator<Item = &IkBranch<N, T>> {
        self.iter().filter(|b| b.exact)
    }
}

impl<const N: usize, const K: usize> IkSolutions<N, K> {
    /// The exact solution nearest to `q` (joint-space distance, whole turns of revolute
    /// joints chosen nearest to `q` within `limits`), as joint values; `None` when there
    /// is no exact solution.
    pub fn nearest(
        &self,
        q: &[f64; N],
        revolute: &[bool; N],
        limits: &[[f64; 2]; N],
    ) -> Option<[f64; N]> {
        nearest_of(self.exact().map(|b| b.q), q, revolute, limits)
    }
}

/// The one of `candidates` nearest to `q` (see [`IkSolutions::nearest`]).
fn nearest_of<const N: usize>(
    candidates: impl Iterator<Item = [f64; N]>,
    q: &[f64; N],
    revolute: &[bool; N],
    limits: &[[f64; 2]; N],
) -> Option<[f64; N]> {
    let mut best: Option<([f64; N], f64)> = None;
    for mut x in candidates {
        let mut d2 = 0.0;
        for i in 0..N {
            if revolute[i] {
                x[i] = turn_near(x[i], q[i], limits[i]);
            }
            d2 += (x[i] - q[i]) * (x[i] - q[i]);
        }
        if best.is_none_or(|(_, d)| d2 < d) {
            best = Some((x, d2));
        }
    }
    best.map(|(x, _)| x)
}

/// `x + k·2π` nearest to `target` within `[lo, hi]` (or nearest overall if none is).
fn turn_near(x: f64, target: f64, [lo, hi]: [f64; 2]) -> f64 {
    let k = libm::round((target - x) / TAU);
    let mut best = x;
    let mut best_d = f64::INFINITY;
    for dk in [-1.0, 0.0, 1.0] {
        let y = x + (k + dk) * TAU;
        let inside = y >= lo && y <= hi;
        let d = (y - target).abs() + if inside { 0.0 } else { 1e3 };
        if d < best_d {
            best = y;
            best_d = d;
        }
    }
    best
}

/// `θ` wrapped into `(−π, π]`, then moved by a whole turn into `[lo, hi]` if that is
/// where it fits.
#[inline]
fn into_limits(theta: f64, [lo, hi]: [f64; 2]) -> f64 {
    let t = wrap(theta);
    if t >= lo && t <= hi {
        return t;
    }
    for y in [t + TAU, t - TAU] {
        if y >= lo && y <= hi {
            return y;
        }
    }
    t
}

/// What the robot's generated code evaluates for a candidate that a subproblem solved in
/// least squares or found singular. Generated types implement it with their own `fk` and
/// `singular_factors`.
pub trait Check<const N: usize> {
    /// How far `fk(q)` is from `pose` (see [`residual`], [`task_residual`]).
    fn residual(&self, q: &[f64; N], pose: &Pose) -> f64;
    /// Bit `i` set when singular factor `i` vanishes at `q` (see [`vanishing`]).
    fn singular(&self, q: &[f64; N]) -> u32;

    /// Whether [`finish`] asks [`Check::residuals`] once per pose, for every candidate
    /// that needs a residual, instead of [`Check::residual`] one by one: for a checker
    /// that evaluates several joint vectors side by side (the run-time solvers' register
    /// programs in lanes). Generated code checks one by one, and its `finish` has no
    /// trace of the batch.
    const BATCHED: bool = false;

    /// [`Check::residual`] of each of `qs`, into `out` (as long as `qs`), with the
    /// values `residual` gives for each alone.
    fn residuals(&self, qs: &[[f64; N]], pose: &Pose, out: &mut [f64]) {
        for (q, o) in qs.iter().zip(out) {
            *o = self.residual(q, pose);
        }
    }
}

/// The robot's solution set from a solver's candidates: joint values wrapped into
/// `limits`, least-squares and singular branches checked against `check`, duplicates
/// removed; where some branch reaches the pose, the branches that miss it by more than
/// [`NEAR_MISS`] left out.
#[inline]
pub fn finish<const N: usize, const K: usize, C: Check<N>>(
    candidates: &Candidates<N, K>,
    pose: &Pose,
    revolute: &[bool; N],
    limits: &[[f64; 2]; N],
    check: &C,
) -> IkSolutions<N, K> {
    // The joint values by reference: copied out of the candidates by value, a Cortex-M
    // build moved them with a `memmove` (1.5 KB of flash with its routine).
    let each = candidates.as_slice().iter().map(|c| (&c.q, c.fit));
    finish_each(each, pose, revolute, limits, check)
}

/// [`finish`] for the candidates of the arm with joint `k` locked at `q_k` (`N = M + 1`
/// joints in all): each candidate gets the locked joint put back as it is settled, with
/// no second candidate set ([`with_locked`]) between.
#[inline]
pub fn finish_locked<const M: usize, const N: usize, const K: usize, C: Check<N>>(
    candidates: &Candidates<M, K>,
    k: usize,
    q_k: f64,
    pose: &Pose,
    revolute: &[bool; N],
    limits: &[[f64; 2]; N],
    check: &C,
) -> IkSolutions<N, K> {
    let each = candidates
        .as_slice()
        .iter()
        .map(|c| (with_joint(&c.q, k, q_k), c.fit));
    finish_each(each, pose, revolute, limits, check)
}

/// What [`finish`] and [`finish_locked`] do, on the candidates' joint values and fits.
#[inline(always)]
fn finish_each<const N: usize, const K: usize, C: Check<N>, Q: Borrow<[f64; N]>>(
    candidates: impl Iterator<Item = (Q, Fit)> + Clone,
    pose: &Pose,
    revolute: &[bool; N],
    limits: &[[f64; 2]; N],
    check: &C,
) -> IkSolutions<N, K> {
    // A batching checker measures, up front and together, the candidates the loop below
    // will ask about, in the order it asks.
    let mut batched = [0.0; K];
    let mut next = 0;
    // (Most poses' candidates are all exact: nothing to measure, nothing set up.)
    if C::BATCHED && candidates.clone().any(|(_, fit)| fit != Fit::Exact) {
        let mut qs = [[0.0; N]; K];
        let mut m = 0;
        for (c_q, c_fit) in candidates.clone() {
            if c_fit != Fit::Exact
                && m < K
                && settle(c_q.borrow(), &mut qs[m], revolute, limits).is_some()
            {
                m += 1;
            }
        }
        check.residuals(&qs[..m], pose, &mut batched[..m]);
    }
    let mut out = IkSolutions::empty();
    // `unchecked[i]`: solution i came from a candidate some subproblem did not solve
    // exactly.
    let mut unchecked = [false; K];
    let mut any_unchecked = false;
    for (c_q, c_fit) in candidates {
        let mut q = [0.0; N];
        let Some(within_limits) = settle(c_q.borrow(), &mut q, revolute, limits) else {
            continue;
        };
        // A quartic's simple root (`Checked`) is no more singular than an exact
        // subproblem's: only its accuracy is measured.
        let (residual, singular) = match c_fit {
            Fit::Exact => (0.0, 0),
            fit => (
                if C::BATCHED && next < K {
                    next += 1;
                    batched[next - 1]
                } else {
                    check.residual(&q, pose)
                },
                if fit == Fit::Checked {
                    0
                } else {
                    check.singular(&q)
                },
            ),
        };
        // Unchecked branches have residual 0: every subproblem solved exactly.
        let exact = residual <= EXACT_TOLERANCE;
        let branch = IkBranch {
            q,
            exact,
            residual,
            singular,
            // A least-squares step that still reaches the pose met a tangency: a double
            // root that rounding pushed just outside.
            at_singularity: match c_fit {
                Fit::Double | Fit::Free => true,
                Fit::LeastSquares => exact,
                Fit::Exact | Fit::Checked => false,
            },
            within_limits,
        };
        // Two candidates every subproblem solved exactly are distinct: where their
        // branches split, a subproblem gave two roots at least its merge distance apart
        // (≥ 6e-6 rad for SP3/SP4, ≳ 1e-7 for SP2 and the prismatic quadratic; see
        // `subproblems`), far above SAME_CONFIGURATION. Only pairs with a singular or
        // least-squares candidate can be one configuration twice (the self-tests check
        // that no solution set holds a duplicate). So an exact candidate with no
        // checked one before it is a new solution, as it is.
        if c_fit == Fit::Exact && !any_unchecked {
            out.push(branch);
            continue;
        }
        let n = out.len;
        let copy = out
            .items
            .iter_mut()
            .zip(unchecked.iter_mut())
            .take(n)
            .filter(|(_, u)| c_fit != Fit::Exact || **u)
            .find(|(b, _)| same(&b.q, &q, revolute));
        if let Some((b, u)) = copy {
            // Keep the better of two copies of one configuration.
            if exact && !b.exact {
                *b = branch;
                *u = c_fit != Fit::Exact;
            }
            continue;
        }
        if let Some(u) = unchecked.get_mut(out.len) {
            *u = c_fit != Fit::Exact;
        }
        any_unchecked |= c_fit != Fit::Exact;
        out.push(branch);
    }
    // Only a checked branch can miss.
    if any_unchecked && out.iter().any(|b| b.exact) {
        out.retain(|b| b.exact || b.residual <= NEAR_MISS);
    }
    out
}

/// A candidate's joint values as a solution: revolute joints wrapped into `(−π, π]`, then
/// by a whole turn into their limits where that helps; with whether every joint is within
/// its limits, into `out`. `None` for a non-finite value.
// `out`, not a returned `([f64; N], bool)`: moving the returned array out of the `Option`
// was a `memmove` on a Cortex-M (1.5 KB of flash with its routine).
#[inline(always)]
fn settle<const N: usize>(
    q: &[f64; N],
    out: &mut [f64; N],
    revolute: &[bool; N],
    limits: &[[f64; 2]; N],
) -> Option<bool> {
    // As the solvers almost always give it — revolute joints within (−π, π], every joint
    // finite — a candidate stays as it is: one branch-free test of all joints. A wrapped
    // value is moved by a whole turn only into limits that reach past ±π and leave it
    // out: limits that hold a whole turn hold every wrapped value, and limits within
    // [−π, π] (the iiwa's, all of the Panda's but joint 6's) hold `t ± 2π` never —
    // constant tests where `limits` is the robot's `LIMITS`. (About half the Panda's
    // candidates lie outside its limits: this keeps them off the joint-by-joint path.)
    let (mut settled, mut within_limits) = (true, true);
    for i in 0..N {
        let (t, [lo, hi]) = (q[i], limits[i]);
        // (|t| < π: ±π itself, and NaN, go joint by joint.)
        let wrapped = t.abs() < PI;
        let inside = (t >= lo) & (t <= hi);
        let turn_moves = (lo < -PI && hi < PI) || (lo > -PI && hi > PI);
        settled &= match (revolute[i], turn_moves) {
            (true, false) => wrapped,
            (true, true) => wrapped & inside,
            (false, _) => t.is_finite(),
        };
        within_limits &= inside;
    }
    if settled {
        *out = *q;
        return Some(within_limits);
    }
    settle_by_joint(*q, out, revolute, limits)
}

/// [`settle`] joint by joint: each revolute joint wrapped, then moved by a whole turn into
/// its limits where that fits.
#[inline(always)]
fn settle_by_joint<const N: usize>(
    mut q: [f64; N],
    out: &mut [f64; N],
    revolute: &[bool; N],
    limits: &[[f64; 2]; N],
) -> Option<bool> {
    // One pass; the flags with `&=`, not `&&`.
    let (mut finite, mut within_limits) = (true, true);
    for i in 0..N {
        let [lo, hi] = limits[i];
        if revolute[i] && lo <= -PI && hi >= PI {
            // Wrapped into (−π, π], a value is within such limits, and only a non-finite
            // one comes out as NaN.
            q[i] = wrap(q[i]);
            finite &= !q[i].is_nan();
            continue;
        }
        if revolute[i] {
            q[i] = into_limits(q[i], limits[i]);
        }
        finite &= q[i].is_finite();
        within_limits &= (q[i] >= lo) & (q[i] <= hi);
    }
    *out = q;
    finite.then_some(within_limits)
}

/// `max |fk − pose|` over the top three rows (a NaN entry of `t` is passed over, as
/// `f64::max` would).
pub fn residual(t: &[[f64; 4]; 4], pose: &Pose) -> f64 {
    // `if d > e` rather than `f64::max`: the same value for `d ≥ 0` or NaN, without
    // `max`'s NaN and signed-zero handling — one `maxsd` an entry, not six instructions
    // (a solver measuring every solution calls this twelve times a solution).
    let mut e: f64 = 0.0;
    for (i, row) in t.iter().take(3).enumerate() {
        for (j, x) in row.iter().enumerate() {
            let target = if j < 3 { pose.r[(i, j)] } else { pose.p[i] };
            let d = (x - target).abs();
            if d > e {
                e = d;
            }
        }
    }
    e
}

/// [`residual`] of `L` tool poses side by side: lane `l` of `t[4 * i + j]` is entry
/// `(i, j)` of pose `l`'s top three rows (`t` holds 12 entries, row by row, as a batch of
/// forward kinematics gives them). Lane `l` of the result has the bits of [`residual`]
/// of pose `l`: the same comparisons in the same order, each entry taken for all lanes at
/// once (a solver's eight solutions measured in a few vector instructions an entry).
///
/// ```
/// use kinegen::ik::geometry::Pose;
/// use kinegen::ik::solutions::{residual, residual_lanes};
/// let pose = Pose::from_matrix(&[[1.0, 0.0, 0.0, 0.5], [0.0, 1.0, 0.0, 0.0],
///                                [0.0, 0.0, 1.0, 2.0], [0.0, 0.0, 0.0, 1.0]]);
/// let t = [[1.0, 0.0, 0.0, 0.5], [0.0, 1.0, 0.0, 1e-9], [0.0, 0.0, 1.0, 2.0], [0.0, 0.0, 0.0, 1.0]];
/// let lanes: Vec<[f64; 2]> = t.iter().take(3).flatten().map(|&x| [x, 0.0]).collect();
/// let e = residual_lanes::<2>(&lanes, &pose);
/// assert_eq!(e[0], residual(&t, &pose));
/// assert_eq!(e[0], 1e-9);
/// ```
///
/// # Panics
/// If `t` has fewer than 12 entries.
#[inline]
pub fn residual_lanes<const L: usize>(t: &[[f64; L]], pose: &Pose) -> [f64; L] {
    let mut e = [0.0; L];
    for i in 0..3 {
        for j in 0..4 {
            let target = if j < 3 { pose.r[(i, j)] } else { pose.p[i] };
            let x = &t[4 * i + j];
            // A select, not a branch: one `maxpd` for two lanes (its operand order keeps
            // `e` where `d` is NaN, as `if d > e` does).
            let d: [f64; L] = core::array::from_fn(|l| (x[l] - target).abs());
            e = core::array::from_fn(|l| if d[l] > e[l] { d[l] } else { e[l] });
        }
    }
    e
}

/// `max` over `rows` (indices into `[x y z rx ry rz]`) of the task error: position
/// entries, and for `rz` the wrapped difference of the angles about z. (Planar arms: only
/// their task rows are solved.)
pub fn task_residual(t: &[[f64; 4]; 4], pose: &Pose, rows: &[usize]) -> f64 {
    let mut e: f64 = 0.0;
    for &r in rows {
        let d = match r {
            0..=2 => t[r][3] - pose.p[r],
            5 => wrap(libm::atan2(t[1][0], t[0][0]) - libm::atan2(pose.r[(1, 0)], pose.r[(0, 0)])),
            _ => 0.0,
        };
        e = e.max(d.abs());
    }
    e
}

/// Bit `i` set for each `factors[i]` within [`SINGULAR_TOLERANCE`] of zero.
pub fn vanishing<const F: usize>(factors: &[f64; F]) -> u32 {
    factors
        .iter()
        .enumerate()
        .take(32)
        .filter(|(_, f)| f.abs() <= SINGULAR_TOLERANCE)
        .fold(0, |bits, (i, _)| bits | (1 << i))
}

/// `q` without entry `k`; `M` must be `N − 1`.
// Inlined: with `k` a constant where the generated code calls it, six moves.
#[inline]
pub fn without<const N: usize, const M: usize>(q: &[f64; N], k: usize) -> [f64; M] {
    let mut out = [0.0; M];
    for (o, (_, x)) in out
        .iter_mut()
        .zip(q.iter().enumerate().filter(|(i, _)| *i != k))
    {
        *o = *x;
    }
    out
}

/// The candidates of the arm with joint `k` locked, as candidates of the whole arm (joint
/// `k` at `q_k`); `M` must be `N + 1`.
pub fn with_locked<const N: usize, const M: usize, const K: usize>(
    c: &Candidates<N, K>,
    k: usize,
    q_k: f64,
) -> Candidates<M, K> {
    let mut out = Candidates::default();
    for x in c.as_slice() {
        out.push(with_joint(&x.q, k, q_k), x.fit);
    }
    out
}

/// `q` with joint `k` at `q_k` put in (`M = N + 1` joints).
#[inline(always)]
fn with_joint<const N: usize, const M: usize>(q: &[f64; N], k: usize, q_k: f64) -> [f64; M] {
    // A caller naming the wrong arm does not build.
    const {
        assert!(
            M == N + 1,
            "the whole arm has one joint more than the locked one"
        )
    };
    debug_assert!(k < M, "the locked joint is one of the arm's");
    let mut out = [q_k; M];
    for (i, x) in q.iter().enumerate() {
        // Joints after `k` move one place on (`k` is a constant where this is inlined).
        if let Some(slot) = out.get_mut(if i < k { i } else { i + 1 }) {
            *slot = *x;
        }
    }
    out
}

#[inline]
fn same<const N: usize>(a: &[f64; N], b: &[f64; N], revolute: &[bool; N]) -> bool {
    (0..N).all(|i| {
        let d = a[i] - b[i];
        let d = if revolute[i] { wrap(d) } else { d };
        d.abs() <= SAME_CONFIGURATION
    })
}

// Single precision: a `scalar: f32` robot solves in f64 and rounds once.
//
// Its generated `ik` widens the pose, evaluates `ik_geometry` in f64 from the widened
// parameters, runs the same family solver and `finish` (with a `Check` that measures the
// residual on the geometry's product of exponentials in f64, not with the f32 `fk`), and
// only then rounds: the subproblems' double-root and on-axis tests need f64 (in f32 a
// singular pose's double root would split by ~1e-3 rad), and the exactness test
// ([`EXACT_TOLERANCE`], 1e-10) is far below f32's rounding (~1e-7).

/// Largest residual (measured in f64) of a branch that counts as exact for an f32 robot.
///
/// An f32 pose is not a pose to 1e-10: its rotation is orthonormal and its position
/// consistent only to f32 rounding, about `4 ε · reach` when it comes from the f32 `fk`
/// (5.7e-7 for the UR5, `robots/tests/f32_error.rs`; ε = 2⁻²³). A singular or
/// least-squares branch of such a pose meets it to that amplified by the tangency, not to
/// [`EXACT_TOLERANCE`]: over 10 000 f32 UR5 poses (`tests/ik_closed_form_f32.rs`) the
/// largest f64 residual of a branch that should be exact was 4.7e-6, so 1e-5 leaves a
/// margin of about 2. The price: a pose out of reach by less than 1e-5 (m, or the rotation
/// entries) counts as reached.
pub const EXACT_TOLERANCE_F32: f64 = 1e-5;

impl<const N: usize, const K: usize> IkSolutions<N, K> {
    /// The same solutions with joint values and residuals rounded to `f32` (round to
    /// nearest), for an f32 robot: a branch is exact when its residual is within
    /// [`EXACT_TOLERANCE_F32`], and one that became exact only so (a least-squares fit of
    /// an f32 pose at a tangency) is flagged `at_singularity`. Rounding is monotone, so a
    /// value within f32 limits (widened) stays within them.
    /// Two branches closer than f32 can tell apart become one (the first).
    pub fn to_f32(&self) -> IkSolutions<N, K, f32> {
        let mut out: IkSolutions<N, K, f32> = IkSolutions::empty();
        for b in self.as_slice() {
            let q = b.q.map(|x| x as f32);
            if out.as_slice().iter().any(|o| o.q == q) {
                continue;
            }
            let exact = b.exact || b.residual <= EXACT_TOLERANCE_F32;
            let Some(slot) = out.items.get_mut(out.len) else {
                break;
            };
            *slot = IkBranch {
                q,
                exact,
                residual: b.residual as f32,
                singular: b.singular,
                at_singularity: b.at_singularity || (exact && !b.exact),
                within_limits: b.within_limits,
            };
            out.len += 1;
        }
        out
    }
}

impl<const N: usize, const K: usize> IkSolutions<N, K, f32> {
    /// The exact solution nearest to `q` (see [`IkSolutions::nearest`]): chosen in f64
    /// from the widened values, then rounded to `f32`.
    pub fn nearest(
        &self,
        q: &[f32; N],
        revolute: &[bool; N],
        limits: &[[f32; 2]; N],
    ) -> Option<[f32; N]> {
        let limits = limits.map(|l| l.map(f64::from));
        let q = q.map(f64::from);
        nearest_of(
            self.exact().map(|b| b.q.map(f64::from)),
            &q,
            revolute,
            &limits,
        )
        .map(|x| x.map(|v| v as f32))
    }
}

/// `pose` with its rotation replaced by the nearest rotation (two steps of the polar
/// iteration `R ← (R + R⁻ᵀ)/2`, quadratic: a rotation off by 1e-7 comes out orthonormal
/// to f64 rounding). For an f32 pose, widened: its rotation is orthonormal only to f32
/// rounding, and a wrist solved on a non-orthonormal rotation (`h2ᵀ R h6` a little over 1)
/// turns that ~1e-7 into a least-squares angle of ~2e-4 rad. A matrix without an inverse
/// is left as it is (the solvers then fit it in least squares).
pub fn orthonormalized(pose: &Pose) -> Pose {
    let mut r = pose.r;
    for _ in 0..2 {
        match r.try_inverse() {
            Some(inv) => r = (r + inv.transpose()) * 0.5,
            None => break,
        }
    }
    Pose { r, p: pose.p }
}

/// The pose an f64 robot's `Check::residual` measures a branch at: the generated `fk`
/// (`generated`), or with the `small-ik` feature the product of exponentials of its IK
/// geometry (`poe`) — the same pose to rounding, read by the runtime's one `Geometry::fk`
/// instead of a second copy of the generated `fk` inlined into every `ik` (about 5 KB of
/// soft-float code on a Cortex-M4F; examples/firmware/README.md).
///
/// ```
/// use kinegen::ik::geometry::{Geometry, M3, V3};
/// use kinegen::ik::solutions::{checked_pose, residual};
/// let g = Geometry {
///     h: [V3::z()],
///     p: [V3::zeros()],
///     prismatic: [false],
///     r_tool: M3::identity(),
///     p_tool: V3::new(1.0, 0.0, 0.0),
/// };
/// let (c, s) = (0.3f64.cos(), 0.3f64.sin());
/// let fk = [[c, -s, 0.0, c], [s, c, 0.0, s], [0.0, 0.0, 1.0, 0.0], [0.0, 0.0, 0.0, 1.0]];
/// let t = checked_pose(|| fk, || g.fk(&[0.3]));
/// assert!(residual(&t, &g.fk(&[0.3])) < 1e-15);
/// ```
#[inline(always)]
pub fn checked_pose(
    generated: impl FnOnce() -> [[f64; 4]; 4],
    poe: impl FnOnce() -> Pose,
) -> [[f64; 4]; 4] {
    if cfg!(feature = "small-ik") {
        pose_matrix(&poe())
    } else {
        generated()
    }
}

/// `pose` as a row-major homogeneous transform (bottom row `0 0 0 1`): what [`residual`]
/// and [`task_residual`] read, for a pose from [`Geometry::fk`](super::geometry::Geometry::fk).
pub fn pose_matrix(pose: &Pose) -> [[f64; 4]; 4] {
    let (r, p) = (&pose.r, &pose.p);
    [
        [r[(0, 0)], r[(0, 1)], r[(0, 2)], p[0]],
        [r[(1, 0)], r[(1, 1)], r[(1, 2)], p[1]],
        [r[(2, 0)], r[(2, 1)], r[(2, 2)], p[2]],
        [0.0, 0.0, 0.0, 1.0],
    ]
}

#[cfg(feature = "serde")]
impl<const N: usize, const K: usize, T: serde::Serialize> serde::Serialize
    for IkSolutions<N, K, T>
{
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.collect_seq(&self.items[..self.len])
    }
}

#[cfg(feature = "serde")]
impl<'de, const N: usize, const K: usize, T> serde::Deserialize<'de> for IkSolutions<N, K, T>
where
    T: serde::Deserialize<'de> + Copy + Default,
{
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct Branches<const N: usize, const K: usize, T>(core::marker::PhantomData<T>);
        impl<'de, const N: usize, const K: usize, T> serde::de::Visitor<'de> for Branches<N, K, T>
        where
            T: serde::Deserialize<'de> + Copy + Default,
        {
            type Value = IkSolutions<N, K, T>;
            fn expecting(&self, f: &mut core::fmt::Formatter) -> core::fmt::Result {
                write!(f, "a sequence of at most {K} IK branches")
            }
            fn visit_seq<A: serde::de::SeqAccess<'de>>(
                self,
                mut seq: A,
            ) -> Result<Self::Value, A::Error> {
                let mut out = IkSolutions::empty();
                while let Some(branch) = seq.next_element::<IkBranch<N, T>>()? {
                    if out.len == K {
                        return Err(serde::de::Error::invalid_length(K + 1, &self));
                    }
                    out.items[out.len] = branch;
                    out.len += 1;
                }
                Ok(out)
            }
        }
        deserializer.deserialize_seq(Branches::<N, K, T>(core::marker::PhantomData))
    }
}

#[cfg(feature = "defmt")]
impl<const N: usize, const K: usize, T: defmt::Format> defmt::Format for IkSolutions<N, K, T> {
    fn format(&self, f: defmt::Formatter) {
        defmt::write!(f, "{}", &self.items[..self.len])
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ik::geometry::{M3, V3};

    /// A solution set with the given `(q, exact, residual)` branches.
    fn solutions(branches: &[([f64; 2], bool, f64)]) -> IkSolutions<2, 4> {
        let mut s = IkSolutions::empty();
        for (slot, &(q, exact, residual)) in s.items.iter_mut().zip(branches) {
            *slot = IkBranch {
                q,
                exact,
                residual,
                singular: 0,
                at_singularity: false,
                within_limits: true,
            };
        }
        s.len = branches.len();
        s
    }

    /// `settle`'s one test of all joints keeps the values and the flag that the joint-by-
    /// joint path gives (wrap, a whole turn into the limits where that fits): for limits
    /// that hold a whole turn, lie within [−π, π], or reach past one end, and a prismatic
    /// joint, at values about ±π, the limits, NaN and infinities.
    #[test]
    fn settling_in_one_test_is_settling_joint_by_joint() {
        let limits = [
            [-TAU, TAU],
            [-PI, PI],
            [-2.9, 2.9],
            [-0.02, 3.75],
            [-3.07, -0.07],
            [-3.5, 2.0],
            [-PI, 4.0],
            [0.0, 1.0],
        ];
        let eps = 1e-12;
        let about = [
            PI, 2.0, 2.9, 3.07, 3.5, 3.75, 4.0, 0.02, 0.07, 1.0, 6.0, 7.0,
        ];
        let near = about
            .iter()
            .flat_map(|&x| [x - eps, x, x + eps, eps - x, -x, -x - eps]);
        let special = [f64::NAN, f64::INFINITY, f64::NEG_INFINITY, 0.0, -0.0];
        for &lim in &limits {
            for revolute in [true, false] {
                for t in special.into_iter().chain(near.clone()) {
                    let (mut got_q, mut want_q) = ([f64::NAN], [f64::NAN]);
                    let got = settle(&[t], &mut got_q, &[revolute], &[lim]);
                    let want = settle_by_joint([t], &mut want_q, &[revolute], &[lim]);
                    assert_eq!(got, want, "t = {t}, revolute {revolute}, limits {lim:?}");
                    if want.is_some() {
                        let bits = |q: [f64; 1]| q[0].to_bits();
                        assert_eq!(bits(got_q), bits(want_q), "t = {t}, limits {lim:?}");
                    }
                }
            }
        }
        // Values the joint-by-joint path moves: the comparison is not of identities.
        let mut q = [0.0];
        assert_eq!(
            settle(&[-2.9], &mut q, &[true], &[[-0.02, 3.75]]),
            Some(true)
        );
        assert_eq!(q[0], -2.9 + TAU);
        assert_eq!(settle(&[7.0], &mut q, &[true], &[[-2.9, 2.9]]), Some(true));
        assert_eq!(q[0], 7.0 - TAU);
    }

    #[test]
    fn to_f32_rounds_merges_and_uses_the_f32_tolerance() {
        let s = solutions(&[
            ([0.1, 2.0], true, 0.0),
            // Rounds to the same f32 values as the first: dropped.
            ([0.1 + 1e-12, 2.0], true, 0.0),
            // A least-squares fit within f32 rounding of the pose: exact in f32, singular.
            ([-1.0, 0.5], false, 3e-7),
            // Out of reach.
            ([1.5, -0.5], false, 1e-3),
        ]);
        let t = s.to_f32();
        assert_eq!(t.len(), 3);
        let b = t.as_slice();
        assert_eq!(b[0].q, [0.1f32, 2.0]);
        assert!(b[0].exact && !b[0].at_singularity);
        assert!(b[1].exact && b[1].at_singularity && b[1].residual == 3e-7f32);
        assert!(!b[2].exact && !b[2].at_singularity);
    }

    #[test]
    fn f32_nearest_chooses_in_f64_and_rounds() {
        let s = solutions(&[([0.1, 2.0], true, 0.0), ([3.0, -2.0], true, 0.0)]).to_f32();
        let tau = core::f32::consts::TAU;
        let limits = [[-2.0 * tau, 2.0 * tau]; 2];
        // Whole turns nearest to q: 3.0 − 2π for joint 1.
        let near = s.nearest(&[-3.2, -2.1], &[true, true], &limits).unwrap();
        assert_eq!(near, [(3.0 - TAU) as f32, -2.0]);
        assert!(IkSolutions::<2, 4, f32>::empty()
            .nearest(&[0.0; 2], &[true; 2], &limits)
            .is_none());
    }

    /// A check that reads the residual off the first joint (and no singular factor).
    struct FirstJoint;
    impl Check<3> for FirstJoint {
        fn residual(&self, q: &[f64; 3], _: &Pose) -> f64 {
            q[0].abs()
        }
        fn singular(&self, _: &[f64; 3]) -> u32 {
            0
        }
    }

    #[test]
    fn finish_locked_is_finish_of_the_whole_arms_candidates() {
        // Joint 2 (0-based 1) locked at 0.7; an exact candidate, a least-squares copy of
        // it, a least-squares one off the pose (dropped by the near-miss rule: the
        // compaction moves the last one down), one beyond a whole turn, and one exact.
        let mut c = Candidates::<2, 6>::default();
        c.push([0.0, 1.0], Fit::Exact);
        c.push([1e-12, 1.0], Fit::LeastSquares);
        c.push([0.5, -1.0], Fit::LeastSquares);
        c.push([1e-11, -1.5 + TAU], Fit::LeastSquares);
        c.push([0.0, 2.0], Fit::Exact);
        let pose = Pose {
            r: M3::identity(),
            p: V3::zeros(),
        };
        let (revolute, limits) = ([true; 3], [[-PI, PI]; 3]);
        let locked = finish_locked(&c, 1, 0.7, &pose, &revolute, &limits, &FirstJoint);
        let whole = with_locked::<2, 3, 6>(&c, 1, 0.7);
        let reference = finish(&whole, &pose, &revolute, &limits, &FirstJoint);
        assert_eq!(locked.as_slice(), reference.as_slice());
        let q: [[f64; 3]; 3] = core::array::from_fn(|i| locked.as_slice()[i].q);
        assert_eq!(locked.len(), 3);
        assert_eq!(q, [[0.0, 0.7, 1.0], [1e-11, 0.7, -1.5], [0.0, 0.7, 2.0]]);
    }

    /// [`FirstJoint`] asked for a pose's residuals together, recording what it was asked.
    struct FirstJointBatched(core::cell::RefCell<([[f64; 3]; 8], usize, usize)>);
    impl Check<3> for FirstJointBatched {
        const BATCHED: bool = true;
        fn residual(&self, _: &[f64; 3], _: &Pose) -> f64 {
            panic!("a batching check is asked once per pose")
        }
        fn singular(&self, _: &[f64; 3]) -> u32 {
            0
        }
        fn residuals(&self, qs: &[[f64; 3]], _: &Pose, out: &mut [f64]) {
            let mut asked = self.0.borrow_mut();
            asked.0[..qs.len()].copy_from_slice(qs);
            asked.1 = qs.len();
            asked.2 += 1;
            for (q, o) in qs.iter().zip(out) {
                *o = q[0].abs();
            }
        }
    }

    #[test]
    fn a_batching_check_is_asked_once_for_the_candidates_that_need_it() {
        // Exact candidates need no residual; a non-finite one is never a solution; the
        // least-squares ones are asked about settled (wrapped into the limits), in order.
        let mut c = Candidates::<3, 8>::default();
        c.push([0.0, 1.0, 0.5], Fit::Exact);
        c.push([1e-12, 1.0, 0.5], Fit::LeastSquares);
        c.push([f64::NAN, 0.0, 0.0], Fit::LeastSquares);
        c.push([0.5, -1.0, 0.0], Fit::Double);
        c.push([1e-11, -1.5 + TAU, 0.0], Fit::Checked);
        c.push([0.0, 2.0, 0.0], Fit::Exact);
        let pose = Pose {
            r: M3::identity(),
            p: V3::zeros(),
        };
        let (revolute, limits) = ([true; 3], [[-PI, PI]; 3]);
        let one_by_one = finish(&c, &pose, &revolute, &limits, &FirstJoint);
        let batching = FirstJointBatched(Default::default());
        let together = finish(&c, &pose, &revolute, &limits, &batching);
        assert_eq!(together.as_slice(), one_by_one.as_slice());
        let (asked, count, calls) = *batching.0.borrow();
        assert_eq!((count, calls), (3, 1));
        assert_eq!(
            asked[..3],
            [[1e-12, 1.0, 0.5], [0.5, -1.0, 0.0], [1e-11, -1.5, 0.0]]
        );
    }

    #[test]
    fn pose_matrix_is_row_major_homogeneous() {
        let pose = Pose {
            r: M3::new(0.0, -1.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0),
            p: V3::new(0.5, -0.25, 2.0),
        };
        let t = pose_matrix(&pose);
        assert_eq!(t[0], [0.0, -1.0, 0.0, 0.5]);
        assert_eq!(t[1], [1.0, 0.0, 0.0, -0.25]);
        assert_eq!(t[3], [0.0, 0.0, 0.0, 1.0]);
        assert_eq!(residual(&t, &pose), 0.0);
    }

    /// `residual` is the fold of `f64::max` over the twelve entries' errors, bit for bit,
    /// NaN and infinite entries included.
    #[test]
    fn residual_is_the_largest_entry_error() {
        let pose = Pose {
            r: M3::new(0.0, -1.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0),
            p: V3::new(0.5, -0.25, 2.0),
        };
        let by_max = |t: &[[f64; 4]; 4]| {
            let mut e: f64 = 0.0;
            for (i, row) in t.iter().take(3).enumerate() {
                for (j, x) in row.iter().take(3).enumerate() {
                    e = e.max((x - pose.r[(i, j)]).abs());
                }
                e = e.max((row[3] - pose.p[i]).abs());
            }
            e
        };
        let specials = [
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            -0.0,
            0.0,
            1e-300,
        ];
        let mut x = 0x2545_f491_4f6c_dd1d_u64;
        let mut poses = std::vec::Vec::new();
        for k in 0..2_000 {
            let mut t = pose_matrix(&pose);
            for entry in t.iter_mut().take(3).flatten() {
                x ^= x << 13;
                x ^= x >> 7;
                x ^= x << 17;
                let u = (x >> 11) as f64 / (1u64 << 53) as f64;
                *entry += match (x >> 3) % 8 {
                    0 => 0.0,
                    1 => specials[(x >> 8) as usize % specials.len()],
                    _ => (u - 0.5) * 10f64.powi((k % 30) - 20),
                };
            }
            assert_eq!(residual(&t, &pose).to_bits(), by_max(&t).to_bits(), "{t:?}");
            poses.push(t);
        }
        // Side by side, three lanes at a time: each lane's bits as alone.
        for three in poses.chunks_exact(3) {
            let lanes: std::vec::Vec<[f64; 3]> = (0..12)
                .map(|k| core::array::from_fn(|l| three[l][k / 4][k % 4]))
                .collect();
            let e = residual_lanes(&lanes, &pose);
            for (l, t) in three.iter().enumerate() {
                assert_eq!(e[l].to_bits(), residual(t, &pose).to_bits(), "{t:?}");
            }
        }
    }
}
