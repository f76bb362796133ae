//! The reachability map on the page (`kinegen report --reach RESOLUTION`): the xz plane
//! through the base of the map `kinegen reach` computes (Reuleaux's cube and 50 poses
//! per voxel at the given spacing), coloured by the reachability index and by the
//! |factor| of each singular factor that every reachable pose of a voxel can keep — how
//! far from that singularity the arm can work there.

use super::html::{self, Section};
use super::svg::{viridis, Plot};
use crate::reach::Map;

/// The section: the map's planes, or why there are none (not asked for; no closed-form
/// IK to map with).
pub fn section(map: Option<&Result<Map, String>>) -> Section {
    let body = match map {
        None => html::note(
            "Not computed: `kinegen report ROBOT --reach 0.08` adds the reachability map's \
             xz plane (the whole map: `kinegen reach`).",
        ),
        Some(Err(why)) => html::note(&format!("No reachability map: {why}")),
        Some(Ok(map)) => {
            let mut body = html::p(&format!(
                "{} voxels of {:.3} m, {} poses each; the plane y = 0 through the base. \
                 Grey: no pose of the voxel reachable.",
                map.settings.grid.len(),
                map.settings.grid.resolution,
                map.poses_per_voxel()
            ));
            let plane = Plane::through_base(map);
            body.push_str(&html::figure(
                &plane.draw(
                    map,
                    "reachability index (%)",
                    &|i| match map.voxels[i].reachable {
                        0 => f64::NAN,
                        _ => map.reachability(i),
                    },
                ),
                "Reachability index: the share of the voxel's poses with a solution within \
                 the joint limits.",
            ));
            for (k, name) in map.factor_names.iter().enumerate() {
                let title = format!("|{name}| every pose can keep");
                body.push_str(&html::figure(
                    &plane.draw(map, &title, &|i| map.voxels[i].factor_best[k]),
                    &format!(
                        "The largest |{name}| every reachable pose of the voxel can keep \
                         (0: some pose of it is only reached at the singularity {name} = 0)."
                    ),
                ));
            }
            body
        }
    };
    Section {
        id: "reachability",
        title: "Reachability map".into(),
        body,
    }
}

/// The grid's xz plane nearest y = 0.
struct Plane {
    /// Index of the plane along y.
    j: usize,
}

impl Plane {
    fn through_base(map: &Map) -> Plane {
        let g = &map.settings.grid;
        let j = (-g.min[1] / g.resolution).round().max(0.0) as usize;
        Plane {
            j: j.min(g.dims[1] - 1),
        }
    }

    /// The plane's voxels coloured by `value` (linear from 0 to the plane's largest;
    /// NaN grey).
    fn draw(&self, map: &Map, title: &str, value: &dyn Fn(usize) -> f64) -> String {
        let g = &map.settings.grid;
        let (nx, nz) = (g.dims[0], g.dims[2]);
        let index = |i: usize, k: usize| i + nx * (self.j + g.dims[1] * k);
        let max = (0..nx)
            .flat_map(|i| (0..nz).map(move |k| (i, k)))
            .map(|(i, k)| value(index(i, k)))
            .filter(|v| v.is_finite())
            .fold(0.0, f64::max);
        let h = g.resolution / 2.0;
        let x = (g.min[0] - h, g.min[0] + (nx as f64 - 0.5) * g.resolution);
        let z = (g.min[2] - h, g.min[2] + (nz as f64 - 0.5) * g.resolution);
        let mut plot = Plot::new(460.0, 440.0, x, z).equal_aspect();
        let colour = |v: f64| {
            if !v.is_finite() {
                "#e1e1e1".to_string()
            } else if max > 0.0 {
                viridis(v / max)
            } else {
                viridis(0.0)
            }
        };
        for k in 0..nz {
            let cz = g.min[2] + k as f64 * g.resolution;
            // One rectangle per run of equal colour along x: the page stays small.
            let mut i = 0;
            while i < nx {
                let c = colour(value(index(i, k)));
                let mut end = i + 1;
                while end < nx && colour(value(index(end, k))) == c {
                    end += 1;
                }
                let x0 = g.min[0] + i as f64 * g.resolution - h;
                let x1 = g.min[0] + (end - 1) as f64 * g.resolution + h;
                // A hair larger than the voxels: no seams between neighbours.
                plot.rect((x0, x1 + 0.04 * h), (cz - h, cz + h * 1.04), &c);
                i = end;
            }
        }
        plot.axes("x (m)", "z (m)");
        plot.finish(&format!("{title}: 0 (dark) to {max:.3} (yellow)"))
    }
}
