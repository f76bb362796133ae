//! Closed-form IK chosen at run time, for tools that read a robot at run time (the
//! `kinegen` CLI, tests over random tables): the family named by its solver, the joint
//! count a value, results in `Vec`s. Needs `std`. Generated code calls the family
//! solvers directly, on fixed sizes.

use std::string::String;
use std::vec::Vec;

use super::families::{self, WristPair};
use super::geometry::{Geometry, Pose, M3, V3};
use super::reversed::solve_reversed;
use super::solutions::{finish, finish_locked, without, Candidates, Check, IkSolutions};

/// A robot's zero-configuration geometry as numbers (see [`Geometry`]).
#[derive(Clone, Debug, PartialEq)]
pub struct DynGeometry {
    /// Unit joint axes.
    pub h: Vec<[f64; 3]>,
    /// A point on each axis.
    pub p: Vec<[f64; 3]>,
    /// Which joints are prismatic.
    pub prismatic: Vec<bool>,
    /// Tool rotation at `q = 0`, row-major.
    pub r_tool: [[f64; 3]; 3],
    /// Tool position at `q = 0`.
    pub p_tool: [f64; 3],
}

/// Which solver, and its arguments.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct DynPlan {
    /// The function of [`families`] (`"three_parallel_two_intersecting"`, …, `"position_…"`,
    /// `"pitch_roll"`).
    pub solver: String,
    /// For `planar`: the revolute joints (0-based).
    pub revolute: Vec<usize>,
    /// For `planar`: the prismatic joint.
    pub prismatic: Option<usize>,
    /// The locked joint of a 7-joint arm.
    pub locked: Option<usize>,
    /// How the second wrist solution is found (6-joint families).
    pub wrist: WristPair,
    /// The family fits the chain read from the tool to the base ([`super::reversed`]).
    pub reversed: bool,
}

/// One solution (see [`super::IkBranch`]): its joint values and its flags.
#[derive(Clone, Debug, PartialEq)]
pub struct DynBranch {
    /// Joint values.
    pub q: Vec<f64>,
    /// Exact, residual, singular factors, at a singularity, within the limits.
    pub flags: DynFlags,
}

/// The flags of one solution (in [`DynSolutions`], and of a [`DynBranch`]).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct DynFlags {
    /// Reaches the pose.
    pub exact: bool,
    /// Measured `max |fk − pose|` (0 when not measured).
    pub residual: f64,
    /// Vanishing singular factors (bits).
    pub singular: u32,
    /// A subproblem met a singular configuration.
    pub at_singularity: bool,
    /// Within the limits.
    pub within_limits: bool,
}

/// The solutions of one pose in storage a caller keeps from pose to pose: no allocation
/// once it has held the most solutions a pose has ([`solve_into`]).
///
/// ```
/// use kinegen::ik::dispatch::DynSolutions;
/// let s = DynSolutions::default();
/// assert!(s.is_empty() && s.to_branches().is_empty());
/// ```
#[derive(Clone, Debug, Default, PartialEq)]
pub struct DynSolutions {
    /// Joints per solution.
    n: usize,
    /// Joint values, solution after solution.
    q: Vec<f64>,
    flags: Vec<DynFlags>,
}

impl DynSolutions {
    /// Number of solutions.
    #[inline]
    pub fn len(&self) -> usize {
        self.flags.len()
    }

    /// No solution.
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.flags.is_empty()
    }

    /// Joint values of solution `i`.
    // Inlined into other crates: a batch reads every solution through these (the calls
    // cost 64 instructions a UR5 pose in Python's `Robot.ik`, 0.6 %).
    #[inline]
    pub fn q(&self, i: usize) -> &[f64] {
        &self.q[i * self.n..(i + 1) * self.n]
    }

    /// Flags of solution `i`.
    #[inline]
    pub fn flags(&self, i: usize) -> &DynFlags {
        &self.flags[i]
    }

    /// The solutions as [`DynBranch`]es.
    pub fn to_branches(&self) -> Vec<DynBranch> {
        (0..self.len())
            .map(|i| DynBranch {
                q: self.q(i).to_vec(),
                flags: self.flags[i],
            })
            .collect()
    }

    fn clear(&mut self) {
        self.q.clear();
        self.flags.clear();
    }

    fn fill<const N: usize, const K: usize>(&mut self, s: &IkSolutions<N, K>) {
        self.clear();
        self.n = N;
        for b in s.iter() {
            self.q.extend_from_slice(&b.q);
            self.flags.push(DynFlags {
                exact: b.exact,
                residual: b.residual,
                singular: b.singular,
                at_singularity: b.at_singularity,
                within_limits: b.within_limits,
            });
        }
    }
}

/// What the caller evaluates for a candidate.
pub struct Checks<'a> {
    /// `max |fk(q) − pose|` (or the task-row error).
    pub residual: &'a dyn Fn(&[f64]) -> f64,
    /// Bits of the singular factors vanishing at `q`.
    pub singular: &'a dyn Fn(&[f64]) -> u32,
    /// The residuals of a pose's candidates together (their joint values one vector after
    /// another, then where to put each residual), with the values `residual` gives each
    /// alone; `None`: `residual` one by one.
    pub residuals: Option<Residuals<'a>>,
}

/// [`Checks::residuals`]: joint vectors one after another in, a residual each out.
pub type Residuals<'a> = &'a dyn Fn(&[f64], &mut [f64]);

impl<const N: usize> Check<N> for Checks<'_> {
    const BATCHED: bool = true;

    fn residual(&self, q: &[f64; N], _pose: &Pose) -> f64 {
        (self.residual)(q)
    }
    fn singular(&self, q: &[f64; N]) -> u32 {
        (self.singular)(q)
    }
    fn residuals(&self, qs: &[[f64; N]], _pose: &Pose, out: &mut [f64]) {
        match self.residuals {
            Some(all) => all(qs.as_flattened(), out),
            None => {
                for (q, o) in qs.iter().zip(out) {
                    *o = (self.residual)(q);
                }
            }
        }
    }
}

/// The whole input of one solve.
pub struct DynProblem<'a> {
    /// The solver.
    pub plan: &'a DynPlan,
    /// The geometry.
    pub geometry: &'a DynGeometry,
    /// The target, row-major 4×4.
    pub pose: [[f64; 4]; 4],
    /// The locked joint's value (7-joint arms).
    pub q_locked: f64,
    /// Values for the joints a singular pose leaves free (one per joint).
    pub free: &'a [f64],
    /// Which joints are revolute.
    pub revolute: &'a [bool],
    /// Joint limits.
    pub limits: &'a [[f64; 2]],
    /// Only the solutions that reach the pose are wanted (a reachability map, `ik_near`):
    /// at a pose no branch reaches, branches proved to miss it may be left out instead of
    /// reported with their least-squares nearest ([`Candidates::reaching_only`]). The
    /// exact solutions are the same either way.
    pub reaching_only: bool,
    /// The general 6R's [`families::Hint`], kept from call to call for one arm (its
    /// formulations are read once, ~120 µs on the Jaco); `None`: read on every call. The
    /// solutions are the same either way.
    pub hint: Option<&'a families::Hint>,
}

fn geometry<const N: usize>(g: &DynGeometry) -> Geometry<N> {
    let v = |x: &[f64; 3]| V3::new(x[0], x[1], x[2]);
    let r = &g.r_tool;
    Geometry {
        h: core::array::from_fn(|i| v(&g.h[i])),
        p: core::array::from_fn(|i| v(&g.p[i])),
        prismatic: core::array::from_fn(|i| g.prismatic[i]),
        r_tool: M3::new(
            r[0][0], r[0][1], r[0][2], r[1][0], r[1][1], r[1][2], r[2][0], r[2][1], r[2][2],
        ),
        p_tool: v(&g.p_tool),
    }
}

fn finished<const N: usize, const K: usize>(
    c: &Candidates<N, K>,
    pose: &Pose,
    pr: &DynProblem,
    checks: &Checks,
    out: &mut DynSolutions,
) {
    let (revolute, limits) = finish_inputs::<N>(pr);
    out.fill(&finish(c, pose, &revolute, &limits, checks));
}

/// Which joints turn, and the limits, as `finish` takes them for `N` joints.
fn finish_inputs<const N: usize>(pr: &DynProblem) -> ([bool; N], [[f64; 2]; N]) {
    (
        core::array::from_fn(|i| pr.revolute[i]),
        core::array::from_fn(|i| pr.limits[i]),
    )
}

/// The 6-joint family `plan` names, its candidates into `out` (by reference: these sets
/// are ~500 bytes, and moving them in and out cost two copies a pose); `None` for a
/// solver it does not know.
fn six(
    plan: &DynPlan,
    g: &Geometry<6>,
    pose: &Pose,
    free: &[f64; 6],
    out: &mut Candidates<6, 8>,
) -> Option<()> {
    let w = plan.wrist;
    let solver = match plan.solver.as_str() {
        "three_parallel_two_intersecting" => families::three_parallel_two_intersecting,
        "spherical_two_parallel" => families::spherical_two_parallel,
        "spherical_two_intersecting" => families::spherical_two_intersecting,
        "spherical_two_intersecting_prismatic" => families::spherical_two_intersecting_prismatic,
        "spherical" => families::spherical,
        "three_parallel" => families::three_parallel,
        _ => return None,
    };
    if plan.reversed {
        solve_reversed(
            &g.reversed(),
            pose,
            free,
            |g, p, f, o| solver(g, p, f, w, o),
            out,
        );
    } else {
        solver(g, pose, free, w, out);
    }
    Some(())
}

fn planar<const N: usize>(pr: &DynProblem, checks: &Checks, out: &mut DynSolutions) {
    let g = geometry::<N>(pr.geometry);
    let free: [f64; N] = core::array::from_fn(|i| pr.free[i]);
    let pose = Pose::from_matrix(&pr.pose);
    let mut c = Candidates::default();
    families::planar(
        &g,
        &pose,
        &pr.plan.revolute,
        pr.plan.prismatic,
        &free,
        &mut c,
    );
    finished(&c, &pose, pr, checks, out)
}

fn pitch_roll<const N: usize>(pr: &DynProblem, checks: &Checks, out: &mut DynSolutions) {
    let g = geometry::<N>(pr.geometry);
    let free: [f64; N] = core::array::from_fn(|i| pr.free[i]);
    let mut c = Candidates::<N, 4>::default();
    let pose = Pose::from_matrix(&pr.pose);
    families::pitch_roll(&g, &pose, &free, &mut c);
    finished(&c, &pose, pr, checks, out)
}

/// Every solution of `pr.pose`; `Err` for a solver or joint count no family has.
pub fn solve(pr: &DynProblem, checks: &Checks) -> Result<Vec<DynBranch>, &'static str> {
    let mut out = DynSolutions::default();
    solve_into(pr, checks, &mut out)?;
    Ok(out.to_branches())
}

/// [`solve`] into `out` (its solutions replaced), for a caller solving pose after pose.
pub fn solve_into(
    pr: &DynProblem,
    checks: &Checks,
    out: &mut DynSolutions,
) -> Result<(), &'static str> {
    out.clear();
    let n = pr.geometry.h.len();
    if pr.free.len() != n || pr.revolute.len() != n || pr.limits.len() != n {
        return Err("the free values, joint kinds and limits must have one entry per joint");
    }
    let pose = Pose::from_matrix(&pr.pose);
    if !pose.is_finite() || pr.free.iter().any(|x| !x.is_finite()) || !pr.q_locked.is_finite() {
        return Ok(());
    }
    if let Some(case) = pr.plan.solver.strip_prefix("position_") {
        if n != 3 {
            return Err("position IK is for 3 joints");
        }
        let g = geometry::<3>(pr.geometry);
        let free: [f64; 3] = core::array::from_fn(|i| pr.free[i]);
        let mut c = Candidates::<3, 4>::default();
        match case {
            "intersecting" => families::position_intersecting(&g, &pose, &free, &mut c),
            "parallel" => families::position_parallel(&g, &pose, &free, &mut c),
            "intersecting_prismatic" => {
                families::position_intersecting_prismatic(&g, &pose, &free, &mut c)
            }
            // The revolute joint is joint 1 or joint 3: the geometry says which.
            "one_revolute" => {
                families::position_one_revolute(&g, &pose, !g.prismatic[0], &free, &mut c)
            }
            "cartesian" => families::position_cartesian(&g, &pose, &free, &mut c),
            _ => return Err("unknown solver"),
        }
        finished(&c, &pose, pr, checks, out);
        return Ok(());
    }
    if pr.plan.solver == "cartesian_yaw" {
        if n != 4 {
            return Err("the gantry with a yaw axis has 4 joints");
        }
        let g = geometry::<4>(pr.geometry);
        let free: [f64; 4] = core::array::from_fn(|i| pr.free[i]);
        let Some(r) = (0..4).find(|&i| !g.prismatic[i]) else {
            return Err("the gantry with a yaw axis has one revolute joint");
        };
        let mut c = Candidates::<4, 1>::default();
        families::cartesian_yaw(&g, &pose, r, &free, &mut c);
        finished(&c, &pose, pr, checks, out);
        return Ok(());
    }
    if pr.plan.solver == "pitch_roll" {
        match n {
            4 => pitch_roll::<4>(pr, checks, out),
            5 => pitch_roll::<5>(pr, checks, out),
            _ => return Err("the pitch-and-roll arm has 4 or 5 joints"),
        }
        return Ok(());
    }
    if pr.plan.solver == "planar" {
        match n {
            2 => planar::<2>(pr, checks, out),
            3 => planar::<3>(pr, checks, out),
            4 => planar::<4>(pr, checks, out),
            _ => return Err("planar IK is for 2 to 4 joints"),
        }
        return Ok(());
    }
    if pr.plan.solver == "general_6r" {
        let own = families::Hint::new();
        let hint = pr.hint.unwrap_or(&own);
        return six_or_locked::<16>(pr, &pose, false, checks, out, |g, free, c| {
            families::general_6r(g, &pose, free, hint, c);
            Some(())
        });
    }
    six_or_locked::<8>(pr, &pose, pr.reaching_only, checks, out, |g, free, c| {
        six(pr.plan, g, &pose, free, c)
    })
}

/// An empty set of candidates, asking for reaching solutions only with `reaching_only`.
fn candidates<const N: usize, const K: usize>(reaching_only: bool) -> Candidates<N, K> {
    if reaching_only {
        Candidates::reaching_only()
    } else {
        Candidates::default()
    }
}

/// A 6-joint solver's candidates on the robot's six joints, or on a 7-joint arm's six
/// with the locked one at `pr.q_locked`, finished; `solve` adds them to the (empty) set
/// it is given, asking for reaching ones only with `reaching_only`.
fn six_or_locked<const K: usize>(
    pr: &DynProblem,
    pose: &Pose,
    reaching_only: bool,
    checks: &Checks,
    out: &mut DynSolutions,
    solve: impl Fn(&Geometry<6>, &[f64; 6], &mut Candidates<6, K>) -> Option<()>,
) -> Result<(), &'static str> {
    let mut c = candidates(reaching_only);
    match (pr.geometry.h.len(), pr.plan.locked) {
        (6, None) => {
            let g = geometry::<6>(pr.geometry);
            let free: [f64; 6] = core::array::from_fn(|i| pr.free[i]);
            solve(&g, &free, &mut c).ok_or("unknown solver")?;
            finished(&c, pose, pr, checks, out);
            Ok(())
        }
        (7, Some(k)) => {
            let g7 = geometry::<7>(pr.geometry);
            let g: Geometry<6> = g7.lock(k, pr.q_locked);
            let free7: [f64; 7] = core::array::from_fn(|i| pr.free[i]);
            let free: [f64; 6] = without(&free7, k);
            solve(&g, &free, &mut c).ok_or("unknown solver")?;
            // The locked joint put back as each candidate is settled.
            let (revolute, limits) = finish_inputs::<7>(pr);
            let s = finish_locked(&c, k, pr.q_locked, pose, &revolute, &limits, checks);
            out.fill(&s);
            Ok(())
        }
        _ => Err("closed-form IK is for 6 joints, or 7 with one locked"),
    }
}

/// Every solution of `pr.pose` whose arm angle is `psi`, for a 7-joint S-R-S arm with an
/// orthogonal shoulder and wrist (the engine decides it: `IkPlan::arm_angle`); see
/// [`families::srs_arm_angle`]. `pr.q_locked` is not used.
pub fn solve_arm_angle(
    pr: &DynProblem,
    psi: f64,
    checks: &Checks,
) -> Result<Vec<DynBranch>, &'static str> {
    let mut out = DynSolutions::default();
    solve_arm_angle_into(pr, psi, checks, &mut out)?;
    Ok(out.to_branches())
}

/// [`solve_arm_angle`] into `out` (its solutions replaced).
pub fn solve_arm_angle_into(
    pr: &DynProblem,
    psi: f64,
    checks: &Checks,
    out: &mut DynSolutions,
) -> Result<(), &'static str> {
    out.clear();
    let n = pr.geometry.h.len();
    if n != 7 {
        return Err("the arm angle is for 7-joint S-R-S arms");
    }
    if pr.free.len() != n || pr.revolute.len() != n || pr.limits.len() != n {
        return Err("the free values, joint kinds and limits must have one entry per joint");
    }
    let pose = Pose::from_matrix(&pr.pose);
    if !pose.is_finite() || pr.free.iter().any(|x| !x.is_finite()) || !psi.is_finite() {
        return Ok(());
    }
    let g = geometry::<7>(pr.geometry);
    let free: [f64; 7] = core::array::from_fn(|i| pr.free[i]);
    let mut c = Candidates::<7, 8>::default();
    families::srs_arm_angle(&g, &pose, psi, WristPair::HalfTurn, &free, &mut c);
    finished(&c, &pose, pr, checks, out);
    Ok(())
}
