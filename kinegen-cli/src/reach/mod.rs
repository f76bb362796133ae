//! `kinegen reach`: where the arm can go and how well — a reachability map solved with
//! the closed-form IK at every pose of every voxel, all solutions, and for each voxel the
//! distance of its solutions from every named singular factor.
//!
//! - [`grid`]: the voxels, and the sphere outside which nothing is reachable.
//! - [`orientations`]: the poses each voxel tries (Reuleaux's 50, or approach × roll).
//! - [`map`]: solving every pose, voxel by voxel, on all cores.
//! - [`measures`]: each solution's manipulability and singular factors' values.
//! - [`npz`]: the map as NumPy arrays.
//! - [`hdf5`]: the map in Reuleaux's HDF5 layout.
//! - [`slices`]: planes of the map as PNG pictures.
//! - [`inverse`]: where to put the base so that every pose of a task is reachable.

pub mod grid;
pub mod hdf5;
pub mod inverse;
pub mod map;
pub mod measures;
pub mod npz;
pub mod orientations;
pub mod slices;

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use kinegen_core::{Chain, Derived};

use crate::error::CliError;
pub use grid::Grid;
pub use map::{Map, Settings, Voxel};
pub use orientations::Orientations;

/// `--orientations` by default: Reuleaux's 50 poses per voxel.
pub const DEFAULT_ORIENTATIONS: &str = "50";

/// `--free-samples` by default: values of a 7-joint arm's locked joint tried per pose.
pub const DEFAULT_FREE_SAMPLES: usize = 8;

/// What `kinegen reach` was asked.
#[derive(Clone, Debug)]
pub struct Request {
    /// Voxel spacing (m).
    pub resolution: f64,
    /// `--orientations`.
    pub orientations: String,
    /// `--box xmin,ymin,zmin,xmax,ymax,zmax` (default: Reuleaux's 3 m cube).
    pub bounds: Option<Vec<f64>>,
    /// Samples of a 7-joint arm's locked joint.
    pub free_samples: usize,
    /// Solve voxels outside the reach sphere too.
    pub no_skip: bool,
    /// Worker threads (default: every core).
    pub threads: Option<usize>,
    /// `-o`: the map (`.npz`), or with `--inverse` the ranked bases (`.json`).
    pub output: Option<PathBuf>,
    /// `--slices DIR`: PNG pictures of planes of the map.
    pub slices: Option<PathBuf>,
    /// Heights of the xy slices (default: joint 1's shoulder height).
    pub slice_z: Option<Vec<f64>>,
    /// `--inverse TASK.json`: base placement for the task's poses.
    pub inverse: Option<PathBuf>,
    /// Height of the plane the base may stand on (`--inverse`).
    pub plane_z: f64,
    /// Draw a progress bar on a terminal.
    pub progress: bool,
    /// Solve every roll about the approach axis, even where they share solutions.
    pub every_roll: bool,
}

/// `kinegen reach`: the report to print; files written as asked (none when it fails).
pub fn run(chain: &Chain, derived: &Derived, req: &Request) -> Result<String, CliError> {
    let orientations = Orientations::parse(&req.orientations)?;
    if req.free_samples == 0 {
        return Err(CliError::Usage("--free-samples: at least 1".into()));
    }
    if req.threads == Some(0) {
        return Err(CliError::Usage("--threads: at least 1".into()));
    }
    if let Some(task) = &req.inverse {
        return inverse::run(chain, derived, task, req);
    }
    let grid = match &req.bounds {
        None => Grid::reuleaux(req.resolution)?,
        Some(b) if b.len() == 6 => {
            Grid::new([b[0], b[1], b[2]], [b[3], b[4], b[5]], req.resolution)?
        }
        Some(b) => {
            return Err(CliError::Usage(format!(
                "--box: expected 6 numbers xmin,ymin,zmin,xmax,ymax,zmax, got {}",
                b.len()
            )))
        }
    };
    // Refuse a file we cannot write before spending the time.
    let output = req.output.as_deref().map(check_output).transpose()?;
    if let Some(dir) = &req.slices {
        std::fs::create_dir_all(dir).map_err(|e| {
            CliError::Usage(format!("--slices: cannot create {}: {e}", dir.display()))
        })?;
    }
    let settings = Settings {
        grid,
        orientations,
        free_samples: req.free_samples,
        skip: !req.no_skip,
        threads: req.threads,
        progress: req.progress,
        roll_symmetry: !req.every_roll,
    };
    let map = map::compute(chain, derived, &settings)?;
    let mut report = map.summary();
    if let Some(path) = output {
        write_atomically(&path, |f| {
            if is_hdf5(&path) {
                use std::io::Write;
                f.write_all(&hdf5::bytes(&map)?).map_err(|e| e.to_string())
            } else {
                npz::write(f, &map.arrays())
                    .map(|_| ())
                    .map_err(|e| e.to_string())
            }
        })?;
        let _ = writeln!(report, "map written to {}", path.display());
    }
    if let Some(dir) = &req.slices {
        let heights = req
            .slice_z
            .clone()
            .unwrap_or_else(|| vec![map.shoulder_height()]);
        for file in slices::draw(&map, dir, &heights)? {
            let _ = writeln!(report, "slice {}", file.display());
        }
    }
    Ok(report)
}

fn is_hdf5(path: &Path) -> bool {
    matches!(
        path.extension().and_then(|e| e.to_str()),
        Some("h5" | "hdf5")
    )
}

/// The worker threads of a map or a placement (`None`: one per core).
fn pool(threads: Option<usize>) -> Result<rayon::ThreadPool, CliError> {
    let mut b = rayon::ThreadPoolBuilder::new();
    if let Some(t) = threads {
        b = b.num_threads(t);
    }
    b.build()
        .map_err(|e| CliError::Usage(format!("--threads: {e}")))
}

/// `path` if a map can be written there: an `.npz` or `.h5` in an existing directory
/// (exit 2 otherwise, before any work).
fn check_output(path: &Path) -> Result<PathBuf, CliError> {
    let ext = path.extension().and_then(|e| e.to_str()).unwrap_or("");
    if !(ext == "npz" || is_hdf5(path)) {
        return Err(CliError::Usage(format!(
            "-o {}: the map is written as .npz (NumPy) or .h5 (Reuleaux's HDF5 layout)",
            path.display()
        )));
    }
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    if !dir.is_dir() {
        return Err(CliError::Usage(format!(
            "-o {}: no directory {}",
            path.display(),
            dir.display()
        )));
    }
    Ok(path.to_path_buf())
}

/// Write through a temporary file in the same directory, renamed into place once
/// complete: a failure (or an interrupt) never leaves a partial map under `path`.
pub fn write_atomically(
    path: &Path,
    write: impl FnOnce(&mut std::fs::File) -> Result<(), String>,
) -> Result<(), CliError> {
    let name = path.file_name().and_then(|n| n.to_str()).unwrap_or("map");
    let tmp = path.with_file_name(format!(".{name}.{}.tmp", std::process::id()));
    let fail = |e: String| {
        let _ = std::fs::remove_file(&tmp);
        CliError::Usage(format!("-o {}: cannot write: {e}", path.display()))
    };
    let mut f = std::fs::File::create(&tmp).map_err(|e| fail(e.to_string()))?;
    write(&mut f).map_err(fail)?;
    f.sync_all().map_err(|e| fail(e.to_string()))?;
    std::fs::rename(&tmp, path).map_err(|e| fail(e.to_string()))
}
