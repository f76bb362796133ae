//! Solution sets of closed-form IK, fixed-size, and the last step every solver shares:
//! wrapping into the joint limits, checking least-squares and singular branches against
//! the forward kinematics, removing duplicates.

use super::geometry::Pose;
use super::subproblems::{wrap, Fit};
use core::f64::consts::TAU;

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
}

impl<const N: usize, const K: usize> Default for Candidates<N, K> {
    fn default() -> Self {
        Candidates {
            items: [Candidate {
                q: [0.0; N],
                fit: Fit::Exact,
            }; K],
            len: 0,
        }
    }
}

impl<const N: usize, const K: usize> Candidates<N, K> {
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
        &self.items[..self.len]
    }
}

/// One IK solution (a branch: shoulder, elbow, wrist choice).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct IkBranch<const N: usize> {
    /// Joint values (revolute joints wrapped by whole turns into the limits where that
    /// helps, else into `(−π, π]`).
    pub q: [f64; N],
    /// `fk(q)` reaches the pose (to [`EXACT_TOLERANCE`]). `false`: the pose is out of
    /// reach and `q` is the nearest the solver found (least squares), see `residual`.
    pub exact: bool,
    /// `max |fk(q) − pose|` over the 12 entries of the top three rows, when it was
    /// measured: for least-squares branches and singular ones. `0.0` for the branches
    /// every subproblem solved exactly (their error is rounding only).
    pub residual: f64,
    /// Bit `i` set: entry `i` of the robot's `SINGULARITIES` vanishes at `q` (to
    /// [`SINGULAR_TOLERANCE`]); checked for the branches a subproblem found singular.
    pub singular: u32,
    /// A subproblem met a double root or left a joint free: `q` is a singular
    /// configuration (also for robots without `SINGULARITIES`, such as 7-joint arms).
    pub at_singularity: bool,
    /// Every joint within the robot's `LIMITS`.
    pub within_limits: bool,
}

/// All solutions of one pose: at most `K`, no allocation.
#[derive(Clone, Copy, Debug)]
pub struct IkSolutions<const N: usize, const K: usize> {
    items: [IkBranch<N>; K],
    len: usize,
}

/// Largest `max |fk(q) − pose|` entry of a branch that counts as exact.
pub const EXACT_TOLERANCE: f64 = 1e-10;

/// Largest `|factor(q)|` at which a singular factor counts as vanishing.
pub const SINGULAR_TOLERANCE: f64 = 1e-9;

/// Largest joint difference (radians or metres, after whole turns) of two branches that
/// are the same configuration.
pub const SAME_CONFIGURATION: f64 = 1e-9;

impl<const N: usize, const K: usize> IkSolutions<N, K> {
    /// No solutions.
    pub fn empty() -> Self {
        IkSolutions {
            items: [IkBranch {
                q: [0.0; N],
                exact: false,
                residual: 0.0,
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
    pub fn as_slice(&self) -> &[IkBranch<N>] {
        &self.items[..self.len]
    }

    /// The solutions, in order.
    pub fn iter(&self) -> core::slice::Iter<'_, IkBranch<N>> {
        self.as_slice().iter()
    }

    /// The exact solutions.
    pub fn exact(&self) -> impl Iterator<Item = &IkBranch<N>> {
        self.iter().filter(|b| b.exact)
    }

    /// The exact solution nearest to `q` (joint-space distance, whole turns of revolute
    /// joints chosen nearest to `q` within `limits`), as joint values; `None` when there
    /// is no exact solution.
    pub fn nearest(
        &self,
        q: &[f64; N],
        revolute: &[bool; N],
        limits: &[[f64; 2]; N],
    ) -> Option<[f64; N]> {
        let mut best: Option<([f64; N], f64)> = None;
        for b in self.exact() {
            let mut x = b.q;
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
}

/// The robot's solution set from a solver's candidates: joint values wrapped into
/// `limits`, least-squares and singular branches checked against `check`, duplicates
/// removed.
pub fn finish<const N: usize, const K: usize, C: Check<N>>(
    candidates: &Candidates<N, K>,
    pose: &Pose,
    revolute: &[bool; N],
    limits: &[[f64; 2]; N],
    check: &C,
) -> IkSolutions<N, K> {
    let mut out = IkSolutions::empty();
    // `unchecked[i]`: solution i came from a candidate some subproblem did not solve
    // exactly.
    let mut unchecked = [false; K];
    for c in candidates.as_slice() {
        let mut q = c.q;
        for i in 0..N {
            if revolute[i] {
                q[i] = into_limits(q[i], limits[i]);
            }
        }
        if q.iter().any(|x| !x.is_finite()) {
            continue;
        }
        let (residual, singular) = match c.fit {
            Fit::Exact => (0.0, 0),
            _ => (check.residual(&q, pose), check.singular(&q)),
        };
        // Unchecked branches have residual 0: every subproblem solved exactly.
        let exact = residual <= EXACT_TOLERANCE;
        let within_limits = (0..N).all(|i| q[i] >= limits[i][0] && q[i] <= limits[i][1]);
        let branch = IkBranch {
            q,
            exact,
            residual,
            singular,
            // A least-squares step that still reaches the pose met a tangency: a double
            // root that rounding pushed just outside.
            at_singularity: match c.fit {
                Fit::Double | Fit::Free => true,
                Fit::LeastSquares => exact,
                Fit::Exact => false,
            },
            within_limits,
        };
        // Two candidates every subproblem solved exactly are distinct: where their
        // branches split, a subproblem gave two roots at least its merge distance apart
        // (≥ 6e-6 rad for SP3/SP4, ≳ 1e-7 for SP2 and the prismatic quadratic; see
        // `subproblems`), far above SAME_CONFIGURATION. Only pairs with a singular or
        // least-squares candidate can be one configuration twice (the self-tests check
        // that no solution set holds a duplicate).
        let copy = (0..out.len)
            .filter(|&i| c.fit != Fit::Exact || unchecked[i])
            .find(|&i| same(&out.items[i].q, &q, revolute));
        if let Some(i) = copy {
            // Keep the better of two copies of one configuration.
            if exact && !out.items[i].exact {
                out.items[i] = branch;
                unchecked[i] = c.fit != Fit::Exact;
            }
            continue;
        }
        unchecked[out.len] = c.fit != Fit::Exact;
        out.items[out.len] = branch;
        out.len += 1;
    }
    out
}

/// `max |fk − pose|` over the top three rows.
pub fn residual(t: &[[f64; 4]; 4], pose: &Pose) -> f64 {
    let mut e: f64 = 0.0;
    for (i, row) in t.iter().take(3).enumerate() {
        for (j, x) in row.iter().take(3).enumerate() {
            e = e.max((x - pose.r[(i, j)]).abs());
        }
        e = e.max((row[3] - pose.p[i]).abs());
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
        let mut q = [0.0; M];
        let mut it = x.q.iter();
        for (i, slot) in q.iter_mut().enumerate() {
            *slot = if i == k {
                q_k
            } else {
                *it.next().unwrap_or(&0.0)
            };
        }
        out.push(q, x.fit);
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
