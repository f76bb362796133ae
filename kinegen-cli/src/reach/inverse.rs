//! Base placement, the inverse question of a reachability map: given the poses of a task
//! (in the world), where on a plane can the arm's base stand so that it reaches every one
//! of them, and where does it reach them best?
//!
//! Each candidate base position is tried by solving the task's poses seen from it with
//! the closed-form IK (exact, all solutions) rather than looked up in a voxelised map:
//! the closed form is fast enough that the answer needs no discretisation of the poses.
//! Candidates are ranked by the worst, over the task's poses, of the best manipulability
//! of each pose's solutions.

use std::fmt::Write as _;
use std::path::Path;

use kinegen_core::{Chain, Derived};
use rayon::prelude::*;
use serde_json::{json, Value};

use super::grid::{check_resolution, ReachSphere};
use super::map::{locked_values, solutions, Worker};
use super::measures::Measures;
use super::Request;
use crate::error::CliError;
use crate::ik::{read_poses, Solver};

/// One base position that reaches every pose of the task.
#[derive(Clone, Debug, PartialEq)]
pub struct Placement {
    /// Where the base's origin stands (its orientation is the world's).
    pub position: [f64; 3],
    /// The smallest, over the task's poses, of each pose's best manipulability.
    pub worst_manipulability: f64,
    /// Solutions within limits, summed over the task's poses.
    pub solutions: u32,
}

/// Every base position on the plane `z = plane_z`, a square grid of spacing `step`
/// around the task's poses, that reaches every pose; best first.
pub fn placements(
    chain: &Chain,
    derived: &Derived,
    task: &[[[f64; 4]; 4]],
    plane_z: f64,
    step: f64,
    free_samples: usize,
    threads: Option<usize>,
) -> Result<Vec<Placement>, CliError> {
    check_resolution(step)?;
    let solver = Solver::new(chain, derived)?;
    let measures = Measures::of(chain, derived);
    let n = chain.dof();
    let locked = locked_values(&solver, free_samples);
    // The square: the task's extent widened by the arm's reach (2 m without a bound).
    let reach = ReachSphere::of(chain, derived).map_or(2.0, |s| s.radius);
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for t in task {
        for k in 0..2 {
            lo[k] = lo[k].min(t[k][3] - reach);
            hi[k] = hi[k].max(t[k][3] + reach);
        }
    }
    // Positions at whole multiples of the spacing (a base the user measured at 0.4 m is
    // on the 0.1 m grid), covering the square.
    let first = [0, 1].map(|k| (lo[k] / step).floor() as i64);
    let cells = [0, 1].map(|k| ((hi[k] / step).ceil() as i64 - first[k] + 1).max(1) as usize);
    if cells[0].saturating_mul(cells[1]) > 4_000_000 {
        return Err(CliError::Usage(format!(
            "--resolution {step}: {}×{} base positions; choose a coarser one",
            cells[0], cells[1]
        )));
    }
    let pool = super::pool(threads)?;
    let found: Result<Vec<Option<Placement>>, CliError> = pool.install(|| {
        (0..cells[0] * cells[1])
            .into_par_iter()
            .map_init(
                || Worker::new(&solver, &measures),
                |w, c| {
                    let b = [
                        (first[0] + (c % cells[0]) as i64) as f64 * step,
                        (first[1] + (c / cells[0]) as i64) as f64 * step,
                        plane_z,
                    ];
                    let mut worst = f64::INFINITY;
                    let mut count = 0;
                    for t in task {
                        let mut pose = *t;
                        for k in 0..3 {
                            pose[k][3] -= b[k];
                        }
                        let mut best: f64 = -1.0;
                        w.within.clear();
                        for &l in &locked {
                            for q in solutions(&solver, pose, l, &w.ik, &mut w.solutions)? {
                                count += 1;
                                w.within.extend_from_slice(q);
                            }
                        }
                        measures.eval_each(&w.within, n, &mut w.measures, |m, _| {
                            best = best.max(m);
                        });
                        if best < 0.0 {
                            return Ok(None);
                        }
                        worst = worst.min(best);
                    }
                    Ok(Some(Placement {
                        position: b,
                        worst_manipulability: worst,
                        solutions: count,
                    }))
                },
            )
            .collect()
    });
    let mut found: Vec<Placement> = found?.into_iter().flatten().collect();
    // Best first; ties by position, so the order does not depend on the threads.
    found.sort_by(|a, b| {
        b.worst_manipulability
            .total_cmp(&a.worst_manipulability)
            .then(a.position[0].total_cmp(&b.position[0]))
            .then(a.position[1].total_cmp(&b.position[1]))
    });
    Ok(found)
}

/// `kinegen reach ROBOT --inverse TASK.json`.
pub fn run(
    chain: &Chain,
    derived: &Derived,
    task_file: &Path,
    req: &Request,
) -> Result<String, CliError> {
    if let Some(out) = &req.output {
        if out.extension().and_then(|e| e.to_str()) != Some("json") {
            return Err(CliError::Usage(format!(
                "-o {}: with --inverse the ranked base positions are written as .json",
                out.display()
            )));
        }
    }
    let task = read_poses(task_file, "--inverse")?;
    if task.is_empty() {
        return Err(CliError::Usage(format!(
            "--inverse {}: the task has no poses",
            task_file.display()
        )));
    }
    if !req.plane_z.is_finite() {
        return Err(CliError::Usage("--plane-z: must be a finite height".into()));
    }
    let found = placements(
        chain,
        derived,
        &task,
        req.plane_z,
        req.resolution,
        req.free_samples,
        req.threads,
    )?;
    let mut s = String::new();
    let _ = writeln!(
        s,
        "{}: {} base positions on z = {} (spacing {} m) reach all {} task poses",
        chain.name,
        found.len(),
        req.plane_z,
        req.resolution,
        task.len()
    );
    for p in found.iter().take(10) {
        let _ = writeln!(
            s,
            "  base at ({:.3}, {:.3}, {:.3}): worst manipulability {:.6}, {} solutions",
            p.position[0], p.position[1], p.position[2], p.worst_manipulability, p.solutions
        );
    }
    if let Some(path) = &req.output {
        let rows: Vec<Value> = found
            .iter()
            .map(|p| {
                json!({
                    "position": p.position,
                    "worst_manipulability": p.worst_manipulability,
                    "solutions": p.solutions,
                })
            })
            .collect();
        super::write_atomically(path, |f| {
            use std::io::Write;
            writeln!(f, "{}", Value::Array(rows)).map_err(|e| e.to_string())
        })?;
        let _ = writeln!(s, "ranked positions written to {}", path.display());
    }
    Ok(s)
}
