//! Planes of a reachability map as PNG pictures: xy planes at chosen heights and the xz
//! plane through the base, one picture per measure (reachability index, best
//! manipulability, and the smallest |factor| of each singular factor).
//!
//! Labels are drawn with DejaVu Sans read at run time (Debian's `fonts-dejavu-core`;
//! `KINEGEN_FONT` names another TrueType font); without a font the pictures have no text.

use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use plotters::prelude::*;
use plotters::style::register_font;

use super::map::Map;
use crate::error::CliError;

/// Which value a picture shows, per voxel (NaN: unreachable, drawn grey).
struct Measure<'a> {
    /// File-name part.
    slug: String,
    /// Title.
    title: String,
    value: Box<dyn Fn(usize) -> f64 + 'a>,
}

/// Draw every measure on the xy planes at `heights` and on the xz plane at y = 0 into
/// `dir`; the files written.
pub fn draw(map: &Map, dir: &Path, heights: &[f64]) -> Result<Vec<PathBuf>, CliError> {
    let font = font();
    let g = &map.settings.grid;
    let mut measures = vec![
        Measure {
            slug: "reachability".into(),
            title: "reachability index (%)".into(),
            value: Box::new(|i| match map.voxels[i].reachable {
                0 => f64::NAN,
                _ => map.reachability(i),
            }),
        },
        Measure {
            slug: "manipulability".into(),
            title: "best manipulability √det(J Jᵀ)".into(),
            value: Box::new(|i| map.voxels[i].manipulability),
        },
    ];
    for (k, name) in map.factor_names.iter().enumerate() {
        measures.push(Measure {
            slug: format!("factor{}_min", k + 1),
            title: format!("smallest |{name}| of any solution"),
            value: Box::new(move |i| map.voxels[i].factor_min[k]),
        });
        measures.push(Measure {
            slug: format!("factor{}_best", k + 1),
            title: format!("|{name}| every pose can keep"),
            value: Box::new(move |i| map.voxels[i].factor_best[k]),
        });
    }
    let plane = |axis: usize, at: f64| -> usize {
        let i = ((at - g.min[axis]) / g.resolution).round();
        (i.max(0.0) as usize).min(g.dims[axis] - 1)
    };
    // The xy planes at the heights, then the xz plane through the base: (fixed axis, at).
    let planes: Vec<(usize, f64)> = heights.iter().map(|&z| (2, z)).chain([(1, 0.0)]).collect();
    let mut files = Vec::new();
    for m in &measures {
        for &(axis, at) in &planes {
            let k = plane(axis, at);
            let at = g.min[axis] + k as f64 * g.resolution;
            // The picture's vertical axis: y on an xy plane, z on the xz plane.
            let (up, name, fixed) = if axis == 2 {
                (1, "xy", "z")
            } else {
                (2, "xz", "y")
            };
            let path = dir.join(format!(
                "{}_{}_{name}_{fixed}{at:+.3}.png",
                map.robot, m.slug
            ));
            let cells = |i: usize, j: usize| {
                let mut c = [i, 0, 0];
                c[up] = j;
                c[axis] = k;
                (m.value)(c[0] + g.dims[0] * (c[1] + g.dims[1] * c[2]))
            };
            picture(
                &path,
                font,
                &format!("{} — {}, {fixed} = {at:.3} m", map.robot, m.title),
                ("x (m)", ["x (m)", "y (m)", "z (m)"][up]),
                [(g.min[0], g.dims[0]), (g.min[up], g.dims[up])],
                g.resolution,
                &cells,
            )?;
            files.push(path);
        }
    }
    Ok(files)
}

/// One heat map: cell `(i, j)` of `axes` (start, count) coloured by `cells(i, j)` on a
/// linear scale from 0 to the plane's largest value.
fn picture(
    path: &Path,
    font: bool,
    title: &str,
    labels: (&str, &str),
    axes: [(f64, usize); 2],
    step: f64,
    cells: &dyn Fn(usize, usize) -> f64,
) -> Result<(), CliError> {
    let err = |e: &dyn std::fmt::Display| {
        CliError::Usage(format!("--slices: cannot draw {}: {e}", path.display()))
    };
    let [(x0, nx), (y0, ny)] = axes;
    let max = (0..nx)
        .flat_map(|i| (0..ny).map(move |j| (i, j)))
        .map(|(i, j)| cells(i, j))
        .filter(|v| v.is_finite())
        .fold(0.0, f64::max);
    let root = BitMapBackend::new(path, (760, 640)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| err(&e))?;
    let (plot, bar) = root.split_horizontally(640);
    let h = step / 2.0;
    let x_range = (x0 - h)..(x0 + (nx as f64 - 0.5) * step);
    let y_range = (y0 - h)..(y0 + (ny as f64 - 0.5) * step);
    let mut builder = ChartBuilder::on(&plot);
    builder.margin(12);
    if font {
        builder
            .caption(title, ("sans-serif", 16))
            .x_label_area_size(40)
            .y_label_area_size(50);
    }
    let mut chart = builder
        .build_cartesian_2d(x_range, y_range)
        .map_err(|e| err(&e))?;
    if font {
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc(labels.0)
            .y_desc(labels.1)
            .label_style(("sans-serif", 13))
            .draw()
            .map_err(|e| err(&e))?;
    }
    chart
        .draw_series((0..nx * ny).map(|k| {
            let (i, j) = (k % nx, k / nx);
            let (x, y) = (x0 + i as f64 * step, y0 + j as f64 * step);
            let v = cells(i, j);
            let colour = if v.is_finite() && max > 0.0 {
                viridis(v / max)
            } else {
                RGBColor(225, 225, 225)
            };
            Rectangle::new([(x - h, y - h), (x + h, y + h)], colour.filled())
        }))
        .map_err(|e| err(&e))?;
    // The colour bar: 0 at the bottom, the largest value at the top.
    let (_, bar_h) = bar.dim_in_pixel();
    let (top, bottom) = (60i32, bar_h as i32 - 60);
    for y in top..bottom {
        let t = f64::from(bottom - y) / f64::from(bottom - top);
        bar.draw(&Rectangle::new([(20, y), (50, y + 1)], viridis(t).filled()))
            .map_err(|e| err(&e))?;
    }
    if font {
        for (y, v) in [(top, max), (bottom, 0.0)] {
            bar.draw(&Text::new(
                format!("{v:.3}"),
                (55, y - 6),
                ("sans-serif", 12),
            ))
            .map_err(|e| err(&e))?;
        }
    }
    root.present().map_err(|e| err(&e))
}

/// Viridis ([`crate::colour::viridis`]) as a plotters colour.
fn viridis(t: f64) -> RGBColor {
    let [r, g, b] = crate::colour::viridis(t);
    RGBColor(r, g, b)
}

/// Register a TrueType font for the labels, once; whether one was found.
fn font() -> bool {
    static FOUND: OnceLock<bool> = OnceLock::new();
    *FOUND.get_or_init(|| {
        let candidates = std::env::var_os("KINEGEN_FONT")
            .map(PathBuf::from)
            .into_iter()
            .chain(
                [
                    "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf",
                    "/usr/share/fonts/TTF/DejaVuSans.ttf",
                    "/usr/share/fonts/dejavu-sans-fonts/DejaVuSans.ttf",
                    "/Library/Fonts/Arial.ttf",
                    "/System/Library/Fonts/Supplemental/Arial.ttf",
                    "C:\\Windows\\Fonts\\arial.ttf",
                ]
                .map(PathBuf::from),
            );
        for path in candidates {
            if let Ok(bytes) = std::fs::read(&path) {
                // plotters keeps the font for the whole run.
                let bytes: &'static [u8] = Box::leak(bytes.into_boxed_slice());
                if register_font("sans-serif", FontStyle::Normal, bytes).is_ok() {
                    return true;
                }
            }
        }
        false
    })
}
