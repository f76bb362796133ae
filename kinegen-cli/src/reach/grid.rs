//! The voxel grid of a reachability map, and the sphere outside which an arm provably
//! reaches nothing (so its voxels are skipped without changing the map).

use kinegen_core::kinematics::program::Program;
use kinegen_core::model::robot::JointKind;
use kinegen_core::{Chain, Derived};

use crate::error::CliError;

/// The most voxels a map may have.
pub const MAX_VOXELS: usize = 10_000_000;

/// Voxel centres on a regular grid: `min + i·resolution` along each axis, up to `max`.
#[derive(Clone, Debug, PartialEq)]
pub struct Grid {
    /// The box's lower corner (the first centre).
    pub min: [f64; 3],
    /// The box's upper corner (no centre beyond it).
    pub max: [f64; 3],
    /// Spacing of the centres (metres).
    pub resolution: f64,
    /// Centres along x, y, z.
    pub dims: [usize; 3],
}

impl Grid {
    /// The grid of `[min, max]` at `resolution`, or why not (exit 2).
    pub fn new(min: [f64; 3], max: [f64; 3], resolution: f64) -> Result<Grid, CliError> {
        check_resolution(resolution)?;
        let mut dims = [0; 3];
        for k in 0..3 {
            if !(min[k].is_finite() && max[k].is_finite() && min[k] <= max[k]) {
                return Err(CliError::Usage(format!(
                    "--box: axis {} runs from {} to {}: expected finite numbers, min ≤ max",
                    ["x", "y", "z"][k],
                    min[k],
                    max[k]
                )));
            }
            // A centre on the upper face counts despite rounding of the division.
            dims[k] = ((max[k] - min[k]) / resolution * (1.0 + 1e-12)).floor() as usize + 1;
        }
        let voxels = dims.iter().try_fold(1usize, |a, &d| a.checked_mul(d));
        match voxels {
            // Each voxel keeps its measures in memory (~100 bytes): 10 million is ~1 GB.
            Some(v) if v <= MAX_VOXELS => Ok(Grid {
                min,
                max,
                resolution,
                dims,
            }),
            _ => Err(CliError::Usage(format!(
                "--resolution {resolution}: {}×{}×{} voxels is more than 10 million; choose a coarser resolution or a smaller --box",
                dims[0], dims[1], dims[2]
            ))),
        }
    }

    /// Reuleaux's box: the 3 m cube centred on the base.
    pub fn reuleaux(resolution: f64) -> Result<Grid, CliError> {
        Grid::new([-1.5; 3], [1.5; 3], resolution)
    }

    /// How many voxels.
    pub fn len(&self) -> usize {
        self.dims.iter().product()
    }

    /// No voxels (never: every axis has one centre at least).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The centre of voxel `i` (x fastest, then y, then z).
    pub fn centre(&self, i: usize) -> [f64; 3] {
        let [nx, ny, _] = self.dims;
        let idx = [i % nx, (i / nx) % ny, i / (nx * ny)];
        let mut c = [0.0; 3];
        for k in 0..3 {
            c[k] = self.min[k] + idx[k] as f64 * self.resolution;
        }
        c
    }
}

/// `--resolution` (a spacing of voxels or of base positions): a positive number.
pub fn check_resolution(resolution: f64) -> Result<(), CliError> {
    if resolution.is_finite() && resolution > 0.0 {
        Ok(())
    } else {
        Err(CliError::Usage(format!(
            "--resolution {resolution}: must be a positive number of metres"
        )))
    }
}

/// A sphere no configuration takes the tool outside: centre and radius.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ReachSphere {
    /// The point of joint 1's axis nearest the world origin.
    pub centre: [f64; 3],
    /// `‖o₁ − c‖ + Σ‖oᵢ − oᵢ₋₁‖ + ‖p − o_N‖` over the joint frames' origins `oᵢ` and the
    /// tool point `p`.
    pub radius: f64,
}

impl ReachSphere {
    /// The sphere of an all-revolute arm whose frame origins lie on their joints' axes
    /// (checked: the distances are the same at two configurations), else `None` (no
    /// voxel is skipped). Each distance is then fixed by the link geometry and `c` is a
    /// fixed point of joint 1's axis, so by the triangle inequality the tool never leaves
    /// the sphere: a voxel all of whose poses lie outside it is unreachable.
    pub fn of(chain: &Chain, derived: &Derived) -> Option<ReachSphere> {
        if chain.dof() == 0 || chain.kinds().any(|k| k != JointKind::Revolute) {
            return None;
        }
        let model = &derived.model;
        let mut ids = Vec::new();
        for f in &model.frame_rows {
            ids.extend([f[0][3], f[1][3], f[2][3]]);
        }
        ids.extend([
            model.fk_rows[0][3],
            model.fk_rows[1][3],
            model.fk_rows[2][3],
        ]);
        // Joint 1's axis: its Jacobian column's angular part and a point of it.
        let (axis, point) = &model.sym.axes[0];
        ids.extend(axis.iter().chain(point));
        let program = Program::new(&model.sym, chain, &ids);
        let mut regs = program.registers();
        let mut out = vec![0.0; program.outputs()];
        let n = chain.dof();
        let sphere = |q: &[f64], regs: &mut Vec<f64>, out: &mut Vec<f64>| {
            program.eval(q, regs, out);
            let pts: Vec<[f64; 3]> = out.chunks(3).map(|c| [c[0], c[1], c[2]]).collect();
            let (z, p) = (pts[n + 1], pts[n + 2]);
            let along = dot(&z, &p);
            let centre = [
                p[0] - z[0] * along,
                p[1] - z[1] * along,
                p[2] - z[2] * along,
            ];
            let mut radius = 0.0;
            let mut prev = centre;
            for o in &pts[..=n] {
                radius += dist(o, &prev);
                prev = *o;
            }
            (centre, radius)
        };
        let q0 = vec![0.0; n];
        let q1: Vec<f64> = (0..n).map(|i| 0.7 + 0.37 * i as f64).collect();
        let (c0, r0) = sphere(&q0, &mut regs, &mut out);
        let (c1, r1) = sphere(&q1, &mut regs, &mut out);
        let tol = 1e-9 * (1.0 + r0);
        ((r0 - r1).abs() <= tol && dist(&c0, &c1) <= tol).then_some(ReachSphere {
            centre: c0,
            // Rounding of the distances: a margin far below any resolution.
            radius: r0 + tol,
        })
    }

    /// Every point within `spread` of `centre` lies outside the sphere.
    pub fn excludes(&self, centre: &[f64; 3], spread: f64) -> bool {
        dist(centre, &self.centre) - spread > self.radius
    }
}

fn dot(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn dist(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    let d = [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    dot(&d, &d).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reuleaux_box_has_38_centres_per_axis_at_8_cm() {
        let g = Grid::reuleaux(0.08).unwrap();
        assert_eq!(g.dims, [38, 38, 38]);
        assert_eq!(g.centre(0), [-1.5; 3]);
        let last = g.centre(g.len() - 1);
        assert!(last.iter().all(|x| (x - 1.46).abs() < 1e-12), "{last:?}");
        assert_eq!(Grid::reuleaux(0.5).unwrap().dims, [7, 7, 7]);
        for bad in [0.0, -0.1, f64::NAN, f64::INFINITY] {
            assert!(Grid::reuleaux(bad).is_err());
        }
        assert!(Grid::reuleaux(1e-4).is_err(), "30 000³ voxels");
        assert!(Grid::new([0.0; 3], [-1.0, 1.0, 1.0], 0.1).is_err());
    }
}
