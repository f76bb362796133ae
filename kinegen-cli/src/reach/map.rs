//! Solving every pose of every voxel: the closed-form IK (all solutions), then per
//! solution within the limits its manipulability and the values of the determinant's
//! singular factors, gathered per voxel. Voxels are independent: they are spread over
//! the cores and collected in grid order, so the map is the same for any thread count.

use std::cell::RefCell;
use std::fmt::Write as _;
use std::time::Instant;

use kinegen::ik::dispatch::DynSolutions;
use kinegen_core::{Chain, Derived};
use rayon::prelude::*;

use super::grid::{Grid, ReachSphere};
use super::measures::{self, Measures};
use super::npz::Array;
use super::orientations::{Orientations, RelativePose};
use crate::error::CliError;
use crate::ik::{Scratch, Solver};

/// How to build a map.
#[derive(Clone, Debug)]
pub struct Settings {
    /// The voxels.
    pub grid: Grid,
    /// The poses each voxel tries.
    pub orientations: Orientations,
    /// A 7-joint arm: how many values of its locked joint are tried per pose, evenly
    /// spaced over its limits (over [−π, π) without limits).
    pub free_samples: usize,
    /// Skip the voxels outside the arm's reach sphere (the map is the same).
    pub skip: bool,
    /// Worker threads (`None`: every core).
    pub threads: Option<usize>,
    /// Draw a progress bar (on a terminal only).
    pub progress: bool,
    /// Solve one roll per approach direction where the rolls provably share their
    /// solutions (see [`roll_symmetric`]); `false` solves every roll.
    pub roll_symmetry: bool,
}

/// What one voxel's poses gave.
#[derive(Clone, Debug, PartialEq)]
pub struct Voxel {
    /// Poses with a solution within the joint limits.
    pub reachable: u32,
    /// The fewest solutions within limits of any of its poses.
    pub solutions_min: u32,
    /// Solutions within limits over all its poses (the mean is this over the count).
    pub solutions_sum: u32,
    /// The largest manipulability `√det(J Jᵀ)` over its solutions (NaN: none).
    pub manipulability: f64,
    /// For each singular factor, the smallest `|factor|` over its solutions (NaN: none).
    pub factor_min: Vec<f64>,
    /// For each singular factor, the smallest over its reachable poses of the largest
    /// `|factor|` among the pose's solutions: every reachable pose of the voxel has a
    /// solution at least this far from the factor's zero set (NaN: none reachable).
    pub factor_best: Vec<f64>,
    /// Bit k: pose k reachable (poses 0..64; Reuleaux's 50 fit).
    pub mask: u64,
    /// Skipped: provably out of reach, nothing solved.
    pub skipped: bool,
}

/// A reachability map.
#[derive(Clone, Debug)]
pub struct Map {
    /// The robot's name.
    pub robot: String,
    /// How it was built.
    pub settings: Settings,
    /// Each voxel's poses, relative to its centre.
    pub poses: Vec<RelativePose>,
    /// The singular factors' text (`sin(q5)`), in the determinant's order.
    pub factor_names: Vec<String>,
    /// Every voxel of the grid, in its order.
    pub voxels: Vec<Voxel>,
    /// IK solves run (poses × locked-joint samples of the voxels not skipped, one roll
    /// of each approach direction where rolls share their solutions).
    pub ik_calls: u64,
    /// Wall time of the solving (s).
    pub seconds: f64,
    /// Threads that solved.
    pub threads: usize,
    /// The reach sphere used to skip voxels.
    pub sphere: Option<ReachSphere>,
    /// The height of joint 1's frame origin at q = 0 (the shoulder of a DH table).
    pub shoulder: f64,
    /// Rolls solved once for all ([`roll_symmetric`]); 1 when every pose was solved.
    pub rolls_shared: usize,
}

/// Each thread's registers.
pub(super) struct Worker {
    pub(super) ik: RefCell<Scratch>,
    /// A pose's solutions, reused from pose to pose.
    pub(super) solutions: DynSolutions,
    pub(super) measures: measures::Scratch,
    /// A pose's solutions within the limits, one joint vector after another, measured
    /// together.
    pub(super) within: Vec<f64>,
}

impl Worker {
    pub(super) fn new(solver: &Solver, measures: &Measures) -> Worker {
        Worker {
            ik: RefCell::new(solver.scratch()),
            solutions: DynSolutions::default(),
            measures: measures.scratch(),
            within: Vec::new(),
        }
    }
}

/// Solve every pose of the map.
pub fn compute(chain: &Chain, derived: &Derived, settings: &Settings) -> Result<Map, CliError> {
    let solver = Solver::new(chain, derived)?;
    let measures = Measures::of(chain, derived);
    let locked_values = locked_values(&solver, settings.free_samples);
    let poses = settings.orientations.poses();
    // Poses solved per group of rolls: 1 = every pose.
    let rolls = match settings.orientations {
        Orientations::Approach { rolls, .. }
            if settings.roll_symmetry && roll_symmetric(&solver, &measures) =>
        {
            rolls
        }
        _ => 1,
    };
    let spread = settings
        .orientations
        .offset_radius(settings.grid.resolution);
    let sphere = ReachSphere::of(chain, derived);
    let k = measures.names.len();
    let n = chain.dof();
    let grid = &settings.grid;

    let bar = if settings.progress {
        indicatif::ProgressBar::new(grid.len() as u64)
    } else {
        indicatif::ProgressBar::hidden()
    };
    bar.set_style(
        indicatif::ProgressStyle::with_template(
            "{bar:40} {pos}/{len} voxels, {elapsed} elapsed, {eta} left",
        )
        .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
    );
    let new_worker = || Worker::new(&solver, &measures);
    let voxel = |w: &mut Worker, i: usize| -> Result<(Voxel, u64), CliError> {
        let centre = grid.centre(i);
        let mut v = Voxel {
            reachable: 0,
            solutions_min: u32::MAX,
            solutions_sum: 0,
            manipulability: f64::NAN,
            factor_min: vec![f64::NAN; k],
            factor_best: vec![f64::NAN; k],
            mask: 0,
            skipped: false,
        };
        if settings.skip && sphere.is_some_and(|s| s.excludes(&centre, spread)) {
            v.skipped = true;
            v.solutions_min = 0;
            return Ok((v, 0));
        }
        let mut calls = 0;
        let mut best = vec![f64::NAN; k];
        for (j, rel) in poses.iter().enumerate().step_by(rolls) {
            let mut pose = [[0.0, 0.0, 0.0, 1.0]; 4];
            for r in 0..3 {
                pose[r][..3].copy_from_slice(&rel.rotation[r]);
                pose[r][3] = centre[r] + spread * rel.offset[r];
            }
            let mut count = 0u32;
            // Per factor, the largest |value| among this pose's solutions.
            best.iter_mut().for_each(|b| *b = f64::NAN);
            w.within.clear();
            for &locked in &locked_values {
                calls += 1;
                for q in solutions(&solver, pose, locked, &w.ik, &mut w.solutions)? {
                    count += 1;
                    w.within.extend_from_slice(q);
                }
            }
            measures.eval_each(&w.within, n, &mut w.measures, |m, values| {
                // `f64::max`/`min` skip a NaN operand: NaN is "none yet".
                v.manipulability = v.manipulability.max(m);
                for ((f, b), x) in v.factor_min.iter_mut().zip(best.iter_mut()).zip(values) {
                    *f = f.min(x.abs());
                    *b = b.max(x.abs());
                }
            });
            // The pose stands for itself and the `rolls − 1` rolls after it.
            if count > 0 {
                for (f, b) in v.factor_best.iter_mut().zip(&best) {
                    *f = f.min(*b);
                }
                v.reachable += rolls as u32;
                for k in j..(j + rolls).min(64) {
                    v.mask |= 1 << k;
                }
            }
            v.solutions_min = v.solutions_min.min(count);
            v.solutions_sum += count * rolls as u32;
        }
        Ok((v, calls))
    };

    let start = Instant::now();
    let pool = super::pool(settings.threads)?;
    let threads = pool.current_num_threads();
    let results: Result<Vec<(Voxel, u64)>, CliError> = pool.install(|| {
        (0..grid.len())
            .into_par_iter()
            .map_init(new_worker, |w, i| {
                let r = voxel(w, i);
                bar.inc(1);
                r
            })
            .collect()
    });
    bar.finish_and_clear();
    let results = results?;
    let seconds = start.elapsed().as_secs_f64();
    let ik_calls = results.iter().map(|(_, c)| c).sum();
    Ok(Map {
        robot: chain.name.clone(),
        settings: settings.clone(),
        poses,
        factor_names: measures.names.clone(),
        voxels: results.into_iter().map(|(v, _)| v).collect(),
        ik_calls,
        seconds,
        threads,
        sphere,
        rolls_shared: rolls,
        shoulder: {
            let frame = &derived.model.frame_rows;
            let z = frame.first().map(|f| f[2][3]);
            z.map_or(0.0, |z| {
                let p = kinegen_core::kinematics::program::Program::new(
                    &derived.model.sym,
                    chain,
                    &[z],
                );
                let mut out = [0.0];
                p.eval(&vec![0.0; chain.dof()], &mut p.registers(), &mut out);
                out[0]
            })
        },
    })
}

/// Rolls about the tool's z axis provably share their solutions: the last joint turns
/// the tool about that axis over a whole turn ([`Solver::tool_rolls`]), so a pose
/// rolled by θ is solved by the same `q1…q_{N−1}` with `q_N ± θ` — reachable alike, with
/// as many solutions — and no measure reads `q_N` (world-frame manipulability and the
/// determinant's factors do not depend on a roll of the tool about its own axis).
pub fn roll_symmetric(solver: &Solver, measures: &Measures) -> bool {
    let n = solver.chain().dof();
    n > 0
        && solver.tool_rolls()
        && solver.locked_joint() != Some(n - 1)
        && !measures.reads_joint(n - 1)
}

/// The values a 7-joint arm's locked joint takes: `samples` evenly spaced over its
/// limits (over [−π, π) without), cell midpoints; `[None]` for a 6-joint arm.
pub(super) fn locked_values(solver: &Solver, samples: usize) -> Vec<Option<f64>> {
    match solver.locked_joint() {
        None => vec![None],
        Some(k) => {
            let [lo, hi] = solver.limits()[k];
            let (lo, hi) = if lo.is_finite() && hi.is_finite() {
                (lo, hi)
            } else {
                (-std::f64::consts::PI, std::f64::consts::PI)
            };
            (0..samples)
                .map(|i| Some(lo + (i as f64 + 0.5) * (hi - lo) / samples as f64))
                .collect()
        }
    }
}

/// The solutions of `pose` that reach it within the joint limits (solved into `out`).
pub(super) fn solutions<'a>(
    solver: &Solver,
    pose: [[f64; 4]; 4],
    locked: Option<f64>,
    scratch: &RefCell<Scratch>,
    out: &'a mut DynSolutions,
) -> Result<impl Iterator<Item = &'a [f64]>, CliError> {
    solver.reaching_into(pose, locked, scratch, out)?;
    let out = &*out;
    Ok((0..out.len())
        .filter(|&i| out.flags(i).exact && out.flags(i).within_limits)
        .map(|i| out.q(i)))
}

impl Map {
    /// Poses tried per voxel.
    pub fn poses_per_voxel(&self) -> usize {
        self.poses.len()
    }

    /// The reachability index of voxel `i`: the percentage of its poses reachable.
    pub fn reachability(&self, i: usize) -> f64 {
        100.0 * f64::from(self.voxels[i].reachable) / self.poses.len() as f64
    }

    /// The height of joint 1's frame origin at q = 0 (the shoulder of a DH table):
    /// where a horizontal slice shows the most.
    pub fn shoulder_height(&self) -> f64 {
        self.shoulder
    }

    /// The terminal report.
    pub fn summary(&self) -> String {
        let g = &self.settings.grid;
        let reachable = self.voxels.iter().filter(|v| v.reachable > 0).count();
        let skipped = self.voxels.iter().filter(|v| v.skipped).count();
        let mut s = String::new();
        let _ = writeln!(
            s,
            "{}: {}×{}×{} voxels at {} m, {} poses each ({}); {} reachable, {} skipped outside the reach sphere{}",
            self.robot,
            g.dims[0],
            g.dims[1],
            g.dims[2],
            g.resolution,
            self.poses.len(),
            self.settings.orientations.label(),
            reachable,
            skipped,
            self.sphere
                .map(|s| format!(" (radius {:.4} m)", s.radius))
                .unwrap_or_default()
        );
        let per_core = self.ik_calls as f64 / self.seconds.max(1e-9) / self.threads as f64;
        let _ = writeln!(
            s,
            "{} IK calls in {:.3} s on {} threads: {:.0} per second per thread",
            self.ik_calls, self.seconds, self.threads, per_core
        );
        if self.rolls_shared > 1 {
            let _ = writeln!(
                s,
                "the last joint turns the tool about its approach axis: one solve stands for each direction's {} rolls (--every-roll solves them all)",
                self.rolls_shared
            );
        }
        if !self.factor_names.is_empty() {
            let _ = writeln!(s, "singular factors: {}", self.factor_names.join(", "));
        }
        s
    }

    /// The arrays of the `.npz` file, for the reachable voxels (reachability > 0), as
    /// Reuleaux lists its spheres:
    ///
    /// - `spheres` (V×4, f64): centre x, y, z and the reachability index (%), Reuleaux's
    ///   `/Spheres/sphere_dataset`;
    /// - `poses` (P×10, f32, Reuleaux's 50 only): the voxel's centre, the pose's
    ///   position and quaternion (x, y, z, w) of every reachable pose, Reuleaux's
    ///   `/Poses/poses_dataset`;
    /// - `solutions_min`, `solutions_mean` (V): solutions within limits per pose;
    /// - `manipulability` (V): the best `√det(J Jᵀ)` over the voxel's solutions;
    /// - `factor_min` (V×K): per singular factor, the smallest |factor| over the
    ///   voxel's solutions; `factor_best` (V×K): the smallest over its reachable poses of
    ///   the largest |factor| among a pose's solutions; `factor_names` (K): the factors
    ///   that depend on a joint, as text;
    /// - `resolution`, `box` (min then max corner), `dims` (centres per axis).
    pub fn arrays(&self) -> Vec<(&'static str, Array)> {
        let keep: Vec<usize> = (0..self.voxels.len())
            .filter(|&i| self.voxels[i].reachable > 0)
            .collect();
        let g = &self.settings.grid;
        let n = self.poses.len() as f64;
        let mut spheres = Vec::with_capacity(4 * keep.len());
        let mut poses = Vec::new();
        let reuleaux = self.settings.orientations == Orientations::Reuleaux;
        let spread = self.settings.orientations.offset_radius(g.resolution);
        for &i in &keep {
            let c = g.centre(i);
            spheres.extend([c[0], c[1], c[2], self.reachability(i)]);
            if reuleaux {
                for (j, rel) in self.poses.iter().enumerate() {
                    if self.voxels[i].mask & (1 << j) != 0 {
                        let q = quaternion(&rel.rotation);
                        poses.extend(
                            [
                                c[0],
                                c[1],
                                c[2],
                                c[0] + spread * rel.offset[0],
                                c[1] + spread * rel.offset[1],
                                c[2] + spread * rel.offset[2],
                                q[0],
                                q[1],
                                q[2],
                                q[3],
                            ]
                            .map(|x| x as f32),
                        );
                    }
                }
            }
        }
        let k = self.factor_names.len();
        let v = keep.len();
        let mut out = vec![
            ("spheres", Array::F64(vec![v, 4], spheres)),
            (
                "solutions_min",
                Array::U32(
                    vec![v],
                    keep.iter().map(|&i| self.voxels[i].solutions_min).collect(),
                ),
            ),
            (
                "solutions_mean",
                Array::F64(
                    vec![v],
                    keep.iter()
                        .map(|&i| f64::from(self.voxels[i].solutions_sum) / n)
                        .collect(),
                ),
            ),
            (
                "manipulability",
                Array::F64(
                    vec![v],
                    keep.iter()
                        .map(|&i| self.voxels[i].manipulability)
                        .collect(),
                ),
            ),
            (
                "factor_min",
                Array::F64(
                    vec![v, k],
                    keep.iter()
                        .flat_map(|&i| self.voxels[i].factor_min.iter().copied())
                        .collect(),
                ),
            ),
            (
                "factor_best",
                Array::F64(
                    vec![v, k],
                    keep.iter()
                        .flat_map(|&i| self.voxels[i].factor_best.iter().copied())
                        .collect(),
                ),
            ),
            ("factor_names", Array::Str(self.factor_names.clone())),
            ("resolution", Array::F64(vec![], vec![g.resolution])),
            ("box", Array::F64(vec![6], [g.min, g.max].concat())),
            (
                "dims",
                Array::U32(vec![3], g.dims.map(|d| d as u32).to_vec()),
            ),
        ];
        if reuleaux {
            out.insert(1, ("poses", Array::F32(vec![poses.len() / 10, 10], poses)));
        }
        out
    }
}

/// The unit quaternion (x, y, z, w) of a rotation matrix (Shepperd's method: the
/// largest of the four candidates, so no cancellation).
fn quaternion(r: &[[f64; 3]; 3]) -> [f64; 4] {
    let t = r[0][0] + r[1][1] + r[2][2];
    let q = if t > r[0][0].max(r[1][1]).max(r[2][2]) {
        let s = (1.0 + t).sqrt() * 2.0;
        [
            (r[2][1] - r[1][2]) / s,
            (r[0][2] - r[2][0]) / s,
            (r[1][0] - r[0][1]) / s,
            s / 4.0,
        ]
    } else if r[0][0] >= r[1][1] && r[0][0] >= r[2][2] {
        let s = (1.0 + r[0][0] - r[1][1] - r[2][2]).sqrt() * 2.0;
        [
            s / 4.0,
            (r[0][1] + r[1][0]) / s,
            (r[0][2] + r[2][0]) / s,
            (r[2][1] - r[1][2]) / s,
        ]
    } else if r[1][1] >= r[2][2] {
        let s = (1.0 + r[1][1] - r[0][0] - r[2][2]).sqrt() * 2.0;
        [
            (r[0][1] + r[1][0]) / s,
            s / 4.0,
            (r[1][2] + r[2][1]) / s,
            (r[0][2] - r[2][0]) / s,
        ]
    } else {
        let s = (1.0 + r[2][2] - r[0][0] - r[1][1]).sqrt() * 2.0;
        [
            (r[0][2] + r[2][0]) / s,
            (r[1][2] + r[2][1]) / s,
            s / 4.0,
            (r[1][0] - r[0][1]) / s,
        ]
    };
    // q and −q are the same rotation: the one with w ≥ 0.
    if q[3] < 0.0 {
        q.map(|x| -x)
    } else {
        q
    }
}
