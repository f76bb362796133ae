//! `kinegen ik`: every closed-form solution of one pose or of a file of poses, the same
//! solver the generated `ik` calls (through `kinegen::ik::dispatch`), fed the geometry
//! the engine derives; residuals and singular factors evaluated on the engine's own
//! `fk` and determinant nodes.

use std::fmt::Write;

use kinegen::ik::dispatch::{
    solve_arm_angle_into, solve_into, Checks, DynBranch, DynGeometry, DynPlan, DynProblem,
    DynSolutions,
};
use kinegen::ik::families::WristPair;
use kinegen::ik::geometry::Pose;
use kinegen_core::kinematics::ik::family::Family;
use kinegen_core::kinematics::ik::IkModel;
use kinegen_core::kinematics::program::{Program, LANES};
use kinegen_core::model::robot::JointKind;
use kinegen_core::{Chain, Derived};
use serde_json::{json, Value};

use crate::error::CliError;

/// The solutions of one pose.
#[derive(Clone, Debug)]
pub struct PoseResult {
    /// Every solution.
    pub branches: Vec<DynBranch>,
    /// `max |fk(q) − pose|` of each (measured for every one here).
    pub residuals: Vec<f64>,
    /// Names of the vanishing singular factors of each (`sin(q5) = 0`): the generated
    /// `ik`'s `singular` bits, measured on the branches a subproblem found singular or
    /// solved in least squares (where a factor vanishes, some subproblem meets a double
    /// root or a free angle).
    pub singular: Vec<Vec<String>>,
    /// The answer of `ik_near`, when a current configuration was given.
    pub near: Option<Option<Vec<f64>>>,
    /// A 7-joint arm: the joint left free (1-based) and the value it was locked at.
    pub free_joint: Option<(usize, f64)>,
    /// An S-R-S arm solved by its arm angle: the angle.
    pub arm_angle: Option<f64>,
}

/// What the CLI needs to solve poses of one robot. It owns what it reads (a copy of the
/// chain and of the IK model), so a caller can keep one beside the robot it was built from
/// and solve pose after pose without building it again.
pub struct Solver {
    chain: Chain,
    ik: IkModel,
    /// `sin(q5) = 0`: the determinant's singular factors, in its order.
    factor_names: Vec<String>,
    plan: DynPlan,
    geometry: DynGeometry,
    revolute: Vec<bool>,
    limits: Vec<[f64; 2]>,
    /// The tool pose's 12 entries (the engine's `fk` nodes).
    fk: Program,
    /// The determinant's singular factors (none without a closed-form determinant).
    factors: Program,
    /// The task rows a planar, position or SCARA-like arm solves (`None`: the pose).
    task_rows: Option<Vec<usize>>,
    /// The free joints' values when the caller gives none.
    zeros: Vec<f64>,
    /// The general 6R's formulations, read on the first pose (shared by threads).
    hint: kinegen::ik::families::Hint,
}

/// Registers of a [`Solver`]'s programs: one per thread, reused from pose to pose.
#[derive(Clone, Debug)]
pub struct Scratch {
    fk: Vec<f64>,
    factors: Vec<f64>,
    values: Vec<f64>,
    /// Lane registers and outputs of `fk` measuring the solutions' residuals, [`LANES`]
    /// at a time.
    fk_lanes: Vec<[f64; LANES]>,
    lane_values: Vec<[f64; LANES]>,
}

impl Solver {
    /// The solver of `chain`, or why it has none (exit 2).
    pub fn new(chain: &Chain, derived: &Derived) -> Result<Self, CliError> {
        let ik = match &derived.ik {
            Ok(ik) => ik,
            Err(why) => {
                return Err(CliError::Usage(format!(
                    "`{}` has no closed-form inverse kinematics: {why}",
                    chain.name
                )))
            }
        };
        let v = ik.values(chain);
        let model = &derived.model;
        let fk_ids: Vec<_> = model.fk_rows.iter().flatten().copied().collect();
        let (factor_ids, factor_names): (Vec<_>, Vec<_>) = match &derived.det {
            Some(Ok(det)) => det
                .factors
                .iter()
                .map(|f| (f.node, format!("{} = 0", f.text)))
                .unzip(),
            _ => (Vec::new(), Vec::new()),
        };
        let (revolute_joints, prismatic) = match &ik.plan.family {
            Family::Planar {
                revolute,
                prismatic,
            } => (revolute.clone(), *prismatic),
            _ => (Vec::new(), None),
        };
        Ok(Solver {
            chain: chain.clone(),
            ik: ik.clone(),
            factor_names,
            plan: DynPlan {
                solver: ik.plan.family.solver().into(),
                revolute: revolute_joints,
                prismatic,
                locked: ik.plan.locked,
                wrist: if ik.plan.wrist_half_turn {
                    WristPair::HalfTurn
                } else {
                    WristPair::Solve
                },
                reversed: ik.plan.reversed,
            },
            geometry: DynGeometry {
                h: v.h,
                p: v.p,
                prismatic: v.prismatic,
                r_tool: v.r_tool,
                p_tool: v.p_tool,
            },
            revolute: chain.kinds().map(|k| k == JointKind::Revolute).collect(),
            limits: chain
                .links
                .iter()
                .map(|l| l.limits.unwrap_or([f64::NEG_INFINITY, f64::INFINITY]))
                .collect(),
            fk: Program::new(&model.sym, chain, &fk_ids),
            factors: Program::new(&model.sym, chain, &factor_ids),
            zeros: vec![0.0; chain.dof()],
            hint: kinegen::ik::families::Hint::new(),
            task_rows: match ik.plan.family {
                Family::Planar { .. } | Family::Position(_) | Family::CartesianYaw { .. } => chain
                    .task
                    .as_ref()
                    .map(|t| t.iter().map(|r| r.index()).collect()),
                _ => None,
            },
        })
    }

    /// Registers for [`Solver::branches`] and [`Solver::factor_values`].
    pub fn scratch(&self) -> Scratch {
        Scratch {
            fk: self.fk.registers(),
            factors: self.factors.registers(),
            values: vec![0.0; self.fk.outputs().max(self.factors.outputs())],
            fk_lanes: self.fk.lane_registers(),
            lane_values: vec![[0.0; LANES]; self.fk.outputs()],
        }
    }

    /// The chain solved.
    pub fn chain(&self) -> &Chain {
        &self.chain
    }

    /// Joint limits (unlimited joints: ±∞).
    pub fn limits(&self) -> &[[f64; 2]] {
        &self.limits
    }

    /// The last joint turns the tool about the tool's own z axis: the last joint is
    /// revolute, its axis is the tool's z axis at q = 0 (either direction, through a
    /// point of it, to 1e-12 of the arm's size) and its limits span a whole turn. Then a
    /// pose turned by θ about its z axis has the same solutions with `q_N ± θ`.
    pub fn tool_rolls(&self) -> bool {
        let n = self.chain.dof();
        let g = &self.geometry;
        if n == 0 || g.prismatic[n - 1] {
            return false;
        }
        let [lo, hi] = self.limits[n - 1];
        if hi - lo < std::f64::consts::TAU {
            return false;
        }
        let h = g.h[n - 1];
        let z = [g.r_tool[0][2], g.r_tool[1][2], g.r_tool[2][2]];
        let dot = h[0] * z[0] + h[1] * z[1] + h[2] * z[2];
        let d = [0, 1, 2].map(|k| g.p_tool[k] - g.p[n - 1][k]);
        let cross = [
            d[1] * h[2] - d[2] * h[1],
            d[2] * h[0] - d[0] * h[2],
            d[0] * h[1] - d[1] * h[0],
        ];
        let size = 1.0
            + g.p
                .iter()
                .chain([&g.p_tool])
                .flatten()
                .fold(0.0f64, |a, x| a.max(x.abs()));
        let off = cross.iter().map(|x| x * x).sum::<f64>().sqrt();
        (dot.abs() - 1.0).abs() < 1e-12 && off < 1e-12 * size
    }

    /// The joint a 7-joint arm's closed form locks (0-based).
    pub fn locked_joint(&self) -> Option<usize> {
        self.plan.locked
    }

    /// `IK_FAMILY`.
    pub fn family(&self) -> &str {
        &self.ik.plan.name
    }

    /// The derivation steps.
    pub fn steps(&self) -> &[String] {
        &self.ik.plan.steps
    }

    /// The tool pose the engine's `fk` gives at `q`, with the sines and cosines of
    /// generated code ([`kinegen::math::sin_cos_n`]): the bits [`Solver::measure`] gives
    /// in lanes.
    fn fk(&self, q: &[f64], s: &mut Scratch) -> [[f64; 4]; 4] {
        self.fk
            .eval_with(q, &mut s.fk, &mut s.values, kinegen::math::sin_cos_n);
        let mut t = [[0.0, 0.0, 0.0, 1.0]; 4];
        for (i, row) in t.iter_mut().take(3).enumerate() {
            row.copy_from_slice(&s.values[4 * i..4 * i + 4]);
        }
        t
    }

    /// The singular factors' values at `q`, in the determinant's order (empty without
    /// a closed-form determinant).
    pub fn factor_values<'s>(&self, q: &[f64], s: &'s mut Scratch) -> &'s [f64] {
        // The generated code's sines and cosines, as for fk.
        self.factors
            .eval_with(q, &mut s.factors, &mut s.values, kinegen::math::sin_cos_n);
        &s.values[..self.factors.outputs()]
    }

    /// Bits of the singular factors that vanish at `q`.
    fn vanishing_bits(&self, q: &[f64], s: &mut Scratch) -> u32 {
        let mut bits = 0;
        for (i, v) in self.factor_values(q, s).iter().enumerate() {
            if v.abs() <= kinegen::ik::solutions::SINGULAR_TOLERANCE {
                bits |= 1 << i.min(31);
            }
        }
        bits
    }

    /// The names of the singular factors set in `bits` (`sin(q5) = 0`), as a
    /// solution's flags ([`kinegen::ik::dispatch::DynFlags::singular`]) give them.
    pub fn names(&self, bits: u32) -> Vec<String> {
        self.factor_names
            .iter()
            .enumerate()
            .filter(|(i, _)| bits & (1 << (*i).min(31)) != 0)
            .map(|(_, f)| f.clone())
            .collect()
    }

    /// The task rows a planar arm solves (`None`: the whole pose).
    fn task_rows(&self) -> Option<&[usize]> {
        self.task_rows.as_deref()
    }

    /// `max |fk(q) − pose|` over the rows the arm solves, from the tool pose `t`.
    fn miss(&self, t: &[[f64; 4]; 4], pose: &Pose) -> f64 {
        match self.task_rows() {
            None => kinegen::ik::solutions::residual(t, pose),
            Some(rows) => kinegen::ik::solutions::task_residual(t, pose, rows),
        }
    }

    /// [`Solver::miss`] of the first `out.len()` lanes of fk's outputs `v` (12 entries,
    /// row by row, as the fk program gives them): the whole pose's residuals all lanes at
    /// once ([`kinegen::ik::solutions::residual_lanes`], the same bits), a planar arm's
    /// task rows lane by lane.
    fn lane_misses(&self, v: &[[f64; LANES]], pose: &Pose, out: &mut [f64]) {
        if self.task_rows().is_none() {
            let e = kinegen::ik::solutions::residual_lanes(v, pose);
            out.copy_from_slice(&e[..out.len()]);
            return;
        }
        for (l, m) in out.iter_mut().enumerate() {
            let mut t = [[0.0, 0.0, 0.0, 1.0]; 4];
            for (i, row) in t.iter_mut().take(3).enumerate() {
                for (j, x) in row.iter_mut().enumerate() {
                    *x = v[4 * i + j][l];
                }
            }
            *m = self.miss(&t, pose);
        }
    }

    fn residual(&self, q: &[f64], pose: &Pose, s: &mut Scratch) -> f64 {
        let t = self.fk(q, s);
        self.miss(&t, pose)
    }

    /// The residuals of the candidates `qs` holds (joint values one vector after
    /// another) into `out`, for `finish` ([`Checks::residuals`]): a few one by one,
    /// more side by side in lanes — the same bits either way.
    fn residuals_into(&self, qs: &[f64], pose: &Pose, s: &mut Scratch, out: &mut [f64]) {
        let n = self.chain.dof();
        let count = qs.len() / n;
        if count < crate::eval::LANES_FROM {
            for (q, o) in qs.chunks_exact(n).zip(out) {
                *o = self.residual(q, pose, s);
            }
            return;
        }
        self.measure(count, |i| &qs[i * n..(i + 1) * n], pose, s, out);
    }

    /// The residual of each of `count` solutions (joint values `q(i)`) into `misses`
    /// (as long): [`LANES`] solutions are evaluated side by side by one program of fk.
    fn measure<'q>(
        &self,
        count: usize,
        q: impl Fn(usize) -> &'q [f64],
        pose: &Pose,
        s: &mut Scratch,
        misses: &mut [f64],
    ) {
        let (registers, v) = (&mut s.fk_lanes, &mut s.lane_values);
        crate::eval::eval_groups(&self.fk, count, q, registers, v, |first, len, v| {
            self.lane_misses(v, pose, &mut misses[first..first + len]);
        });
    }

    /// Every solution of `pose`; with `near`, also the nearest to it (its free joints
    /// from it). `locked` is the locked joint's value of a 7-joint arm.
    pub fn solve(
        &self,
        pose: [[f64; 4]; 4],
        near: Option<&[f64]>,
        locked: Option<f64>,
        arm_angle: Option<f64>,
    ) -> Result<PoseResult, CliError> {
        let scratch = std::cell::RefCell::new(self.scratch());
        self.solve_with(pose, near, locked, arm_angle, true, &scratch)
    }

    /// [`Solver::solve`] with `scratch`'s registers (from [`Solver::scratch`]), for a
    /// caller solving many poses; without `residuals`, the residuals are NaN (not
    /// measured: a check of fk per solution costs more than the solving).
    pub fn solve_with(
        &self,
        pose: [[f64; 4]; 4],
        near: Option<&[f64]>,
        locked: Option<f64>,
        arm_angle: Option<f64>,
        residuals: bool,
        scratch: &std::cell::RefCell<Scratch>,
    ) -> Result<PoseResult, CliError> {
        let mut solutions = DynSolutions::default();
        let mut misses = Vec::new();
        self.measured_into(
            pose,
            near,
            locked,
            arm_angle,
            residuals,
            scratch,
            &mut solutions,
            &mut misses,
        )?;
        let near_q = near.map(|q| nearest(&solutions, q, &self.revolute, &self.limits));
        let branches = solutions.to_branches();
        let residuals = misses;
        let singular = branches
            .iter()
            .map(|b| self.names(b.flags.singular))
            .collect();
        let free_joint = match arm_angle {
            None => match self.plan.locked {
                Some(k) => Some((k + 1, self.q_locked(locked, near, None)?)),
                None => None,
            },
            Some(_) => None,
        };
        Ok(PoseResult {
            free_joint,
            arm_angle,
            branches,
            residuals,
            singular,
            near: near_q,
        })
    }

    /// The locked joint's value the solver uses: `--locked`, else the caller's
    /// configuration's (0 without a locked joint or with an arm angle).
    fn q_locked(
        &self,
        locked: Option<f64>,
        near: Option<&[f64]>,
        arm_angle: Option<f64>,
    ) -> Result<f64, CliError> {
        Ok(match (self.plan.locked, locked, near) {
            _ if arm_angle.is_some() => 0.0,
            (None, _, _) => 0.0,
            (Some(_), Some(x), _) => x,
            (Some(k), None, Some(q)) => q[k],
            (Some(k), None, None) => {
                return Err(CliError::Usage(format!(
                "`{}` locks joint {} for its closed form: give its value with --locked, or --near",
                self.chain.name,
                k + 1
            )))
            }
        })
    }

    /// Every solution of `pose` (as [`Solver::solve`]) without the report around them:
    /// the branches only, evaluated with `scratch`'s registers.
    pub fn branches(
        &self,
        pose: [[f64; 4]; 4],
        near: Option<&[f64]>,
        locked: Option<f64>,
        arm_angle: Option<f64>,
        scratch: &std::cell::RefCell<Scratch>,
    ) -> Result<Vec<DynBranch>, CliError> {
        let mut out = DynSolutions::default();
        self.solutions_into(pose, near, locked, arm_angle, scratch, &mut out)?;
        Ok(out.to_branches())
    }

    /// Every solution of `pose` (as [`Solver::branches`]) with its residual (NaN without
    /// `residuals`), into storage the caller keeps from pose to pose: what
    /// [`Solver::solve_with`] reports, without allocating once the storage has grown.
    /// `misses` is replaced.
    #[allow(clippy::too_many_arguments)]
    pub fn measured_into(
        &self,
        pose: [[f64; 4]; 4],
        near: Option<&[f64]>,
        locked: Option<f64>,
        arm_angle: Option<f64>,
        residuals: bool,
        scratch: &std::cell::RefCell<Scratch>,
        solutions: &mut DynSolutions,
        misses: &mut Vec<f64>,
    ) -> Result<(), CliError> {
        self.solutions_into(pose, near, locked, arm_angle, scratch, solutions)?;
        misses.clear();
        if !residuals {
            misses.resize(solutions.len(), f64::NAN);
            return Ok(());
        }
        let target = Pose::from_matrix(&pose);
        let sols = &*solutions;
        misses.resize(sols.len(), 0.0);
        self.measure(
            sols.len(),
            |i| sols.q(i),
            &target,
            &mut scratch.borrow_mut(),
            misses,
        );
        Ok(())
    }

    /// The exact solution of `pose` nearest to `q` (its free joints from it), as
    /// [`Solver::solve`] gives it with `near`, solved into `out` and nothing else
    /// measured: `ik_near` pose after pose.
    pub fn near_into(
        &self,
        pose: [[f64; 4]; 4],
        q: &[f64],
        scratch: &std::cell::RefCell<Scratch>,
        out: &mut DynSolutions,
    ) -> Result<Option<Vec<f64>>, CliError> {
        // Only an exact solution is ever the nearest.
        self.solve_into(pose, Some(q), None, None, true, scratch, out)?;
        Ok(nearest(out, q, &self.revolute, &self.limits))
    }

    /// [`Solver::branches`] into `out` (its solutions replaced).
    pub fn solutions_into(
        &self,
        pose: [[f64; 4]; 4],
        near: Option<&[f64]>,
        locked: Option<f64>,
        arm_angle: Option<f64>,
        scratch: &std::cell::RefCell<Scratch>,
        out: &mut DynSolutions,
    ) -> Result<(), CliError> {
        self.solve_into(pose, near, locked, arm_angle, false, scratch, out)
    }

    /// The solutions of `pose` that reach it, into `out` (its solutions replaced), for a
    /// caller that keeps no other (a reachability map): the exact solutions of
    /// [`Solver::solutions_into`], without the least-squares branches of a pose out of
    /// reach that the solver proves miss it (`DynProblem::reaching_only`); those it
    /// cannot rule out come flagged inexact as before.
    pub fn reaching_into(
        &self,
        pose: [[f64; 4]; 4],
        locked: Option<f64>,
        scratch: &std::cell::RefCell<Scratch>,
        out: &mut DynSolutions,
    ) -> Result<(), CliError> {
        self.solve_into(pose, None, locked, None, true, scratch, out)
    }

    #[allow(clippy::too_many_arguments)]
    fn solve_into(
        &self,
        pose: [[f64; 4]; 4],
        near: Option<&[f64]>,
        locked: Option<f64>,
        arm_angle: Option<f64>,
        reaching_only: bool,
        scratch: &std::cell::RefCell<Scratch>,
        out: &mut DynSolutions,
    ) -> Result<(), CliError> {
        if arm_angle.is_some() {
            if self.ik.plan.arm_angle.is_none() {
                return Err(CliError::Usage(format!(
                    "`{}` has no arm angle: --arm-angle is for a 7-joint S-R-S arm (axes 1, 2, 3 and 5, 6, 7 meeting, orthogonal shoulder and wrist)",
                    self.chain.name
                )));
            }
            if locked.is_some() {
                return Err(CliError::Usage(
                    "--arm-angle and --locked each fix the arm's self-motion: give one".into(),
                ));
            }
        }
        let q_locked = self.q_locked(locked, near, arm_angle)?;
        let free = near.unwrap_or(&self.zeros);
        let target = Pose::from_matrix(&pose);
        let residual = |q: &[f64]| self.residual(q, &target, &mut scratch.borrow_mut());
        let singular = |q: &[f64]| self.vanishing_bits(q, &mut scratch.borrow_mut());
        let residuals = |qs: &[f64], out: &mut [f64]| {
            self.residuals_into(qs, &target, &mut scratch.borrow_mut(), out)
        };
        let checks = Checks {
            residual: &residual,
            singular: &singular,
            residuals: Some(&residuals),
        };
        let problem = DynProblem {
            plan: &self.plan,
            geometry: &self.geometry,
            pose,
            q_locked,
            free,
            revolute: &self.revolute,
            limits: &self.limits,
            reaching_only,
            hint: Some(&self.hint),
        };
        match arm_angle {
            Some(psi) => solve_arm_angle_into(&problem, psi, &checks, out),
            None => solve_into(&problem, &checks, out),
        }
        .map_err(|e| CliError::Usage(e.into()))
    }
}

/// The exact branch nearest to `q` (whole turns of revolute joints chosen nearest to it
/// within the limits), as `ik_near` picks it.
fn nearest(
    solutions: &DynSolutions,
    q: &[f64],
    revolute: &[bool],
    limits: &[[f64; 2]],
) -> Option<Vec<f64>> {
    use std::f64::consts::TAU;
    let mut best: Option<(Vec<f64>, f64)> = None;
    for j in (0..solutions.len()).filter(|&j| solutions.flags(j).exact) {
        let mut x = solutions.q(j).to_vec();
        let mut d2 = 0.0;
        for i in 0..x.len() {
            if revolute[i] {
                let k = ((q[i] - x[i]) / TAU).round();
                let candidates = [k - 1.0, k, k + 1.0].map(|m| x[i] + m * TAU);
                let inside = |y: &f64| *y >= limits[i][0] && *y <= limits[i][1];
                x[i] = candidates
                    .into_iter()
                    .min_by(|a, b| {
                        let cost = |y: f64| (y - q[i]).abs() + if inside(&y) { 0.0 } else { 1e3 };
                        cost(*a).total_cmp(&cost(*b))
                    })
                    .unwrap_or(x[i]);
            }
            d2 += (x[i] - q[i]) * (x[i] - q[i]);
        }
        if best.as_ref().is_none_or(|(_, d)| d2 < *d) {
            best = Some((x, d2));
        }
    }
    best.map(|(x, _)| x)
}

/// Parse `--pose m00,m01,…,m33`: 16 finite numbers, row-major, a rigid transform.
pub fn parse_pose(text: &str) -> Result<[[f64; 4]; 4], CliError> {
    let values: Vec<f64> = text
        .split(',')
        .map(|s| s.trim().parse::<f64>())
        .collect::<Result<_, _>>()
        .map_err(|_| {
            CliError::Usage(format!(
                "--pose: `{text}` is not 16 comma-separated numbers"
            ))
        })?;
    pose_from(&values, "--pose")
}

/// A 4×4 row-major transform from 16 numbers, checked: finite, last row `0 0 0 1`,
/// rotation orthonormal (to 1e-6).
pub fn pose_from(values: &[f64], what: &str) -> Result<[[f64; 4]; 4], CliError> {
    if values.len() != 16 {
        return Err(CliError::Usage(format!(
            "{what}: a pose is 16 numbers (row-major 4×4), found {}",
            values.len()
        )));
    }
    if values.iter().any(|x| !x.is_finite()) {
        return Err(CliError::Usage(format!(
            "{what}: the pose has a non-finite entry"
        )));
    }
    let t: [[f64; 4]; 4] = std::array::from_fn(|i| std::array::from_fn(|j| values[4 * i + j]));
    if t[3] != [0.0, 0.0, 0.0, 1.0] {
        return Err(CliError::Usage(format!(
            "{what}: the last row of a pose must be 0, 0, 0, 1"
        )));
    }
    let r = nalgebra::Matrix3::from_fn(|i, j| t[i][j]);
    let off = (r.transpose() * r - nalgebra::Matrix3::identity()).amax();
    if off > 1e-6 || r.determinant() < 0.0 {
        return Err(CliError::Usage(format!(
            "{what}: the rotation part is not a rotation (RᵀR − I is {off:.1e} off, det {:.3})",
            r.determinant()
        )));
    }
    Ok(t)
}

/// Parse `--near q1,…,qN`.
pub fn parse_near(text: &str, dof: usize) -> Result<Vec<f64>, CliError> {
    crate::eval::parse_q(text, dof).map_err(|e| match e {
        CliError::Usage(m) => CliError::Usage(m.replacen("--q", "--near", 1)),
        e => e,
    })
}

/// `{"family", "solutions", "exact", "singular", "residual", "within_limits"[, "near"]
/// [, "free_joint", "free_value"][, "arm_angle"]}` (`free_joint` 1-based, for a 7-joint
/// arm; `arm_angle` when it was solved by its arm angle).
pub fn to_json(family: &str, r: &PoseResult) -> Value {
    let mut v = json!({
        "family": family,
        "solutions": r.branches.iter().map(|b| b.q.clone()).collect::<Vec<_>>(),
        "exact": r.branches.iter().map(|b| b.flags.exact).collect::<Vec<_>>(),
        "singular": r.singular,
        "residual": r.residuals,
        "within_limits": r.branches.iter().map(|b| b.flags.within_limits).collect::<Vec<_>>(),
    });
    if let Some(near) = &r.near {
        v["near"] = json!(near);
    }
    if let Some((k, value)) = r.free_joint {
        v["free_joint"] = json!(k);
        v["free_value"] = json!(value);
    }
    if let Some(psi) = r.arm_angle {
        v["arm_angle"] = json!(psi);
    }
    v
}

/// A readable table of one pose's solutions.
pub fn to_table(family: &str, r: &PoseResult) -> String {
    let mut s = format!("family: {family}\n");
    if let Some((k, value)) = r.free_joint {
        let _ = writeln!(s, "joint {k} free, locked at {value}");
    }
    if let Some(psi) = r.arm_angle {
        let _ = writeln!(s, "arm angle {psi}");
    }
    let _ = match r.branches.len() {
        1 => writeln!(s, "1 solution"),
        n => writeln!(s, "{n} solutions"),
    };
    for (i, b) in r.branches.iter().enumerate() {
        let q: Vec<String> = b.q.iter().map(|x| format!("{x:>10.6}")).collect();
        let mut flags = vec![if b.flags.exact { "exact" } else { "nearest" }.to_string()];
        if !b.flags.within_limits {
            flags.push("outside limits".into());
        }
        if !r.singular[i].is_empty() {
            flags.push(format!("singular: {}", r.singular[i].join(", ")));
        } else if b.flags.at_singularity {
            flags.push("singular".into());
        }
        let _ = writeln!(
            s,
            "  {:>2}  q = [{}]  residual {:.1e}  ({})",
            i + 1,
            q.join(", "),
            r.residuals[i],
            flags.join("; ")
        );
    }
    if let Some(near) = &r.near {
        match near {
            Some(q) => {
                let q: Vec<String> = q.iter().map(|x| format!("{x:.6}")).collect();
                let _ = writeln!(s, "nearest to the given configuration: [{}]", q.join(", "));
            }
            None => {
                s.push_str("nearest to the given configuration: none (the pose is out of reach)\n")
            }
        }
    }
    s
}

/// What `kinegen ik` was asked.
pub struct Request<'a> {
    /// `--pose`.
    pub pose: Option<&'a str>,
    /// `--poses`.
    pub poses: Option<&'a std::path::Path>,
    /// `--near`.
    pub near: Option<&'a str>,
    /// `--locked`.
    pub locked: Option<f64>,
    /// `--arm-angle`.
    pub arm_angle: Option<f64>,
    /// `--json`.
    pub json: bool,
}

/// `kinegen ik`: the text to print.
pub fn run(chain: &Chain, derived: &Derived, req: &Request) -> Result<String, CliError> {
    let solver = Solver::new(chain, derived)?;
    let n = chain.dof();
    match (req.pose, req.poses) {
        (Some(text), None) => {
            let pose = parse_pose(text)?;
            let near = req.near.map(|t| parse_near(t, n)).transpose()?;
            let r = solver.solve(pose, near.as_deref(), req.locked, req.arm_angle)?;
            Ok(if req.json {
                format!("{}\n", to_json(solver.family(), &r))
            } else {
                to_table(solver.family(), &r)
            })
        }
        (None, Some(path)) => {
            let poses = read_poses(path, "--poses")?;
            let near: Option<Vec<Vec<f64>>> = match req.near {
                None => None,
                Some(file) => {
                    let v = read_json(std::path::Path::new(file), "--near")?;
                    let rows = v
                        .as_array()
                        .map(|a| a.iter().map(|q| numbers(q, 1, n)).collect::<Vec<_>>());
                    match rows {
                        Some(rows) if rows.len() == poses.len() && rows.iter().all(|r| r.len() == n && r.iter().all(|x| x.is_finite())) => Some(rows),
                        _ => {
                            return Err(CliError::Usage(format!(
                                "{file}: expected a JSON array of {} joint vectors of {n} numbers, one per pose",
                                poses.len()
                            )))
                        }
                    }
                }
            };
            let mut out = Vec::new();
            let mut text = String::new();
            for (i, pose) in poses.iter().enumerate() {
                let q = near.as_ref().map(|rows| rows[i].as_slice());
                let r = solver.solve(*pose, q, req.locked, req.arm_angle)?;
                out.push(to_json(solver.family(), &r));
                let _ = writeln!(text, "pose {i}: {}", to_table(solver.family(), &r));
            }
            Ok(if req.json {
                format!("{}\n", Value::Array(out))
            } else {
                text
            })
        }
        _ => Err(CliError::Usage(
            "give one of --pose m00,…,m33 or --poses FILE.json".into(),
        )),
    }
}

/// A JSON file holding an array of 4×4 poses (arrays of 4 rows of 4 numbers), each
/// checked as `--pose` is.
pub fn read_poses(path: &std::path::Path, what: &str) -> Result<Vec<[[f64; 4]; 4]>, CliError> {
    read_json(path, what)?
        .as_array()
        .ok_or_else(|| {
            CliError::Usage(format!(
                "{}: expected a JSON array of poses",
                path.display()
            ))
        })?
        .iter()
        .enumerate()
        .map(|(i, p)| pose_from(&numbers(p, 4, 4), &format!("{}: pose {i}", path.display())))
        .collect()
}

fn read_json(path: &std::path::Path, what: &str) -> Result<Value, CliError> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| CliError::Usage(format!("{what}: cannot read {}: {e}", path.display())))?;
    serde_json::from_str(&text)
        .map_err(|e| CliError::Usage(format!("{}:{}: not JSON: {e}", path.display(), e.line())))
}

/// The numbers of a JSON `rows × cols` array (`[[…], …]`, or `[…]` for one row), flat;
/// empty when it is not one.
fn numbers(v: &Value, rows: usize, cols: usize) -> Vec<f64> {
    let row = |r: &Value| -> Option<Vec<f64>> {
        let a = r.as_array()?;
        (a.len() == cols).then(|| a.iter().map(|x| x.as_f64().unwrap_or(f64::NAN)).collect())
    };
    if rows == 1 {
        return row(v).unwrap_or_default();
    }
    match v.as_array() {
        Some(a) if a.len() == rows => a
            .iter()
            .map(row)
            .collect::<Option<Vec<_>>>()
            .map(|r| r.concat())
            .unwrap_or_default(),
        _ => Vec::new(),
    }
}

/// `kinegen show ROBOT --what ik`.
pub fn show(chain: &Chain, derived: &Derived) -> String {
    match &derived.ik {
        Ok(ik) => {
            let mut s = format!("{} — closed-form IK: {}\n\n", chain.name, ik.plan.name);
            for (i, step) in ik.plan.steps.iter().enumerate() {
                let _ = writeln!(s, "{}. {step}", i + 1);
            }
            let most = match ik.plan.max_solutions {
                1 => "one solution".to_string(),
                n => format!("at most {n} solutions"),
            };
            let _ = writeln!(
                s,
                "\n{most} per pose; the family was decided exactly from the joint axes at q = 0"
            );
            if let Some(steps) = &ik.plan.arm_angle {
                let _ = writeln!(
                    s,
                    "\nby arm angle ψ (--arm-angle; S-R-S arm with an orthogonal shoulder and wrist):\n"
                );
                for (i, step) in steps.iter().enumerate() {
                    let _ = writeln!(s, "{}. {step}", i + 1);
                }
                s.push('\n');
            }
            if let Some(k) = ik.plan.locked {
                let all: Vec<String> = ik
                    .plan
                    .lockable
                    .iter()
                    .map(|i| (i + 1).to_string())
                    .collect();
                let _ = writeln!(
                    s,
                    "free joint: {} (its value is an input: --locked, or from --near); joints whose locking leaves a family: {} (choose with --free)",
                    k + 1,
                    all.join(", ")
                );
            }
            s
        }
        Err(why) => format!("{} — no closed-form IK: {why}\n", chain.name),
    }
}
