//! The poses tried in each voxel of a reachability map: Reuleaux's 50 poses on a small
//! sphere around the voxel's centre, or a Zacharias-style set (approach directions
//! spread evenly over the sphere, each with rolls about the approach axis).

use std::f64::consts::PI;

use crate::error::CliError;

/// Which poses each voxel tries.
#[derive(Clone, Debug, PartialEq)]
pub enum Orientations {
    /// Reuleaux's map creator: 10 azimuths φ = kπ/5 × 5 elevations θ = kπ/5 (θ < π);
    /// the tool at `centre + r·(cos φ sin θ, sin φ sin θ, cos θ)` with `r` the
    /// resolution, turned `R = Rz(φ)·Ry(π/2 + θ)` (roll 0, pitch π/2 + θ, yaw φ), which
    /// points the tool's x axis at the centre.
    Reuleaux,
    /// `directions` approach directions on a Fibonacci sphere, each with `rolls`
    /// turns about it (k·2π/rolls): the tool at the centre with its z axis along the
    /// direction into the centre (Zacharias et al.: frames on a sphere pointing inward).
    Approach {
        /// Directions on the sphere.
        directions: usize,
        /// Rolls about each.
        rolls: usize,
    },
}

/// One pose of a voxel, relative to its centre: an offset and a rotation (row-major).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RelativePose {
    /// Where the tool is, from the voxel's centre (in units of the resolution for
    /// [`Orientations::Reuleaux`], zero otherwise).
    pub offset: [f64; 3],
    /// The tool's orientation.
    pub rotation: [[f64; 3]; 3],
}

impl Orientations {
    /// `--orientations`: `50` (Reuleaux's), or `DxR` (D directions, R rolls; `200x12` is
    /// the Zacharias density, 2 400 per voxel).
    pub fn parse(text: &str) -> Result<Self, CliError> {
        let bad = || {
            CliError::Usage(format!(
                "--orientations `{text}`: expected 50 (Reuleaux's poses) or DxR (D approach directions times R rolls about each, e.g. 200x12)"
            ))
        };
        if text.trim() == "50" {
            return Ok(Orientations::Reuleaux);
        }
        let (d, r) = text.split_once(['x', 'X']).ok_or_else(bad)?;
        let directions: usize = d.trim().parse().map_err(|_| bad())?;
        let rolls: usize = r.trim().parse().map_err(|_| bad())?;
        if directions == 0 || rolls == 0 || directions.saturating_mul(rolls) > 100_000 {
            return Err(CliError::Usage(format!(
                "--orientations `{text}`: between 1 and 100 000 poses per voxel"
            )));
        }
        Ok(Orientations::Approach { directions, rolls })
    }

    /// The poses of one voxel, relative to its centre.
    pub fn poses(&self) -> Vec<RelativePose> {
        match *self {
            Orientations::Reuleaux => {
                let mut out = Vec::with_capacity(50);
                for i in 0..10 {
                    let phi = f64::from(i) * PI / 5.0;
                    for k in 0..5 {
                        let theta = f64::from(k) * PI / 5.0;
                        let (sp, cp) = phi.sin_cos();
                        let (st, ct) = theta.sin_cos();
                        out.push(RelativePose {
                            offset: [cp * st, sp * st, ct],
                            rotation: mul(&rot_z(phi), &rot_y(PI / 2.0 + theta)),
                        });
                    }
                }
                out
            }
            Orientations::Approach { directions, rolls } => {
                let mut out = Vec::with_capacity(directions * rolls);
                for u in fibonacci_sphere(directions) {
                    // z along −u (into the centre), x any unit vector normal to it.
                    let z = [-u[0], -u[1], -u[2]];
                    let helper = if z[2].abs() < 0.9 {
                        [0.0, 0.0, 1.0]
                    } else {
                        [1.0, 0.0, 0.0]
                    };
                    let x = unit(cross(&helper, &z));
                    let y = cross(&z, &x);
                    let frame = [[x[0], y[0], z[0]], [x[1], y[1], z[1]], [x[2], y[2], z[2]]];
                    for k in 0..rolls {
                        let roll = k as f64 * 2.0 * PI / rolls as f64;
                        out.push(RelativePose {
                            offset: [0.0; 3],
                            rotation: mul(&frame, &rot_z(roll)),
                        });
                    }
                }
                out
            }
        }
    }

    /// How far a pose's position is from its voxel's centre, for a resolution.
    pub fn offset_radius(&self, resolution: f64) -> f64 {
        match self {
            Orientations::Reuleaux => resolution,
            Orientations::Approach { .. } => 0.0,
        }
    }

    /// As the map's files and reports name it.
    pub fn label(&self) -> String {
        match self {
            Orientations::Reuleaux => "reuleaux-50".into(),
            Orientations::Approach { directions, rolls } => {
                format!("approach-{directions}x{rolls}")
            }
        }
    }
}

/// `n` unit vectors spread evenly over the sphere (the golden-angle spiral).
fn fibonacci_sphere(n: usize) -> Vec<[f64; 3]> {
    let golden = PI * (3.0 - 5f64.sqrt());
    (0..n)
        .map(|i| {
            let z = 1.0 - (2.0 * i as f64 + 1.0) / n as f64;
            let r = (1.0 - z * z).max(0.0).sqrt();
            let (s, c) = (golden * i as f64).sin_cos();
            [r * c, r * s, z]
        })
        .collect()
}

fn rot_z(t: f64) -> [[f64; 3]; 3] {
    let (s, c) = t.sin_cos();
    [[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]]
}

fn rot_y(t: f64) -> [[f64; 3]; 3] {
    let (s, c) = t.sin_cos();
    [[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]]
}

fn mul(a: &[[f64; 3]; 3], b: &[[f64; 3]; 3]) -> [[f64; 3]; 3] {
    let mut m = [[0.0; 3]; 3];
    for (i, row) in m.iter_mut().enumerate() {
        for (j, x) in row.iter_mut().enumerate() {
            *x = (0..3).map(|k| a[i][k] * b[k][j]).sum();
        }
    }
    m
}

fn cross(a: &[f64; 3], b: &[f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn unit(v: [f64; 3]) -> [f64; 3] {
    let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    [v[0] / n, v[1] / n, v[2] / n]
}

#[cfg(test)]
mod tests {
    use super::*;

    fn is_rotation(r: &[[f64; 3]; 3]) -> bool {
        let rt_r = mul(
            &[
                [r[0][0], r[1][0], r[2][0]],
                [r[0][1], r[1][1], r[2][1]],
                [r[0][2], r[1][2], r[2][2]],
            ],
            r,
        );
        let det = r[0][0] * (r[1][1] * r[2][2] - r[1][2] * r[2][1])
            - r[0][1] * (r[1][0] * r[2][2] - r[1][2] * r[2][0])
            + r[0][2] * (r[1][0] * r[2][1] - r[1][1] * r[2][0]);
        (0..3).all(|i| (0..3).all(|j| (rt_r[i][j] - f64::from(u8::from(i == j))).abs() < 1e-14))
            && (det - 1.0).abs() < 1e-14
    }

    /// Reuleaux's 50: on the unit sphere, x axis pointing at the centre.
    #[test]
    fn reuleaux_poses_point_their_x_axis_at_the_centre() {
        let poses = Orientations::Reuleaux.poses();
        assert_eq!(poses.len(), 50);
        for p in &poses {
            assert!(is_rotation(&p.rotation));
            let x = [p.rotation[0][0], p.rotation[1][0], p.rotation[2][0]];
            for (x, o) in x.iter().zip(&p.offset) {
                assert!((x + o).abs() < 1e-14, "{p:?}");
            }
        }
    }

    /// Zacharias-style: D × R rotations, z axes into the centre, rolls distinct.
    #[test]
    fn approach_poses_cover_directions_and_rolls() {
        let o = Orientations::parse("200x12").unwrap();
        let poses = o.poses();
        assert_eq!(poses.len(), 2400);
        assert!(poses.iter().all(|p| is_rotation(&p.rotation)));
        // The mean approach direction of an even spread is near zero.
        let mut mean = [0.0; 3];
        for p in &poses {
            for (k, m) in mean.iter_mut().enumerate() {
                *m += p.rotation[k][2] / poses.len() as f64;
            }
        }
        assert!(mean.iter().all(|m| m.abs() < 1e-2), "{mean:?}");
        for bad in ["0x3", "12", "ax2", "1000x1000"] {
            assert!(Orientations::parse(bad).is_err(), "{bad}");
        }
    }
}
