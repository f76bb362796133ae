//! Singularity maps as PNGs in `docs/img/` (or the directory given as the first argument):
//!
//! - `singularity_ur5.png`: UR5 `|det J|` over (q2, q3) and over (q3, q5), the other joints
//!   fixed, with the zero sets of the generated `singular_factors` drawn on top;
//! - `singularity_planar_rr.png`: the planar RR arm's workspace, every reachable point
//!   coloured by `|det J|` at its inverse-kinematics solution, with the images of the
//!   singular sets (the boundary circles `r = L1 + L2` and `r = |L1 − L2|`).
//!
//! Every value drawn comes from the generated code (`jacobian_det`, `singular_factors`,
//! `fk`); the curves are traced from the factors numerically, not drawn from known answers.
//!
//! ```text
//! cargo run --example singularity_map
//! ```
//!
//! Text is drawn with DejaVu Sans read at run time (Debian/Ubuntu package
//! `fonts-dejavu-core`); set `KINEGEN_FONT=/path/to/font.ttf` to use another TrueType font.

#[path = "common/plots.rs"]
mod plots;

#[path = "../kinegen-cli/src/colour.rs"]
mod colour;

use std::error::Error;
use std::f64::consts::PI;
use std::path::Path;

use kinegen_robots::{PlanarRr, Ur5};
use plotters::coord::Shift;
use plotters::prelude::*;

/// Grid cells per axis of the heat maps.
const CELLS: usize = 320;
/// Decades of `|det J|` the colour scale spans below its maximum.
const DECADES: f64 = 4.0;

fn main() -> Result<(), Box<dyn Error>> {
    plots::load_font()?;
    let out = plots::output_dir()?;
    ur5_map(&out.join("singularity_ur5.png"))?;
    planar_rr_map(&out.join("singularity_planar_rr.png"))?;
    println!("wrote 2 maps to {}", out.display());
    Ok(())
}

/// A sampled function on a square grid of cell centres over `range × range`.
struct Grid {
    range: (f64, f64),
    values: Vec<f64>, // row-major, `CELLS × CELLS`, index [iy * CELLS + ix]
}

impl Grid {
    fn sample(range: (f64, f64), f: impl Fn(f64, f64) -> f64) -> Grid {
        let mut values = Vec::with_capacity(CELLS * CELLS);
        for iy in 0..CELLS {
            for ix in 0..CELLS {
                values.push(f(coord(range, ix), coord(range, iy)));
            }
        }
        Grid { range, values }
    }

    fn at(&self, ix: usize, iy: usize) -> f64 {
        self.values[iy * CELLS + ix]
    }

    /// The zero set as line segments (marching squares with linear interpolation).
    fn zero_set(&self) -> Vec<[(f64, f64); 2]> {
        let mut segs = Vec::new();
        for iy in 0..CELLS - 1 {
            for ix in 0..CELLS - 1 {
                let corners = [(ix, iy), (ix + 1, iy), (ix + 1, iy + 1), (ix, iy + 1)];
                let mut hits = Vec::new();
                for k in 0..4 {
                    let (a, b) = (corners[k], corners[(k + 1) % 4]);
                    let (fa, fb) = (self.at(a.0, a.1), self.at(b.0, b.1));
                    // A crossing on this edge: a sign change, or an exact zero at its start.
                    if fa == 0.0 || (fa < 0.0) != (fb < 0.0) && fb != 0.0 {
                        let t = if fa == fb { 0.0 } else { fa / (fa - fb) };
                        let x = coord(self.range, a.0)
                            + t * step(self.range) * (b.0 as f64 - a.0 as f64);
                        let y = coord(self.range, a.1)
                            + t * step(self.range) * (b.1 as f64 - a.1 as f64);
                        hits.push((x, y));
                    }
                }
                for pair in hits.chunks(2) {
                    if let [p, q] = pair {
                        segs.push([*p, *q]);
                    }
                }
            }
        }
        segs
    }
}

fn step(range: (f64, f64)) -> f64 {
    (range.1 - range.0) / CELLS as f64
}

fn coord(range: (f64, f64), i: usize) -> f64 {
    range.0 + (i as f64 + 0.5) * step(range)
}

/// Viridis: the colour scale of every picture the `kinegen` command draws (one table,
/// `kinegen-cli/src/colour.rs`, included below).
fn viridis(t: f64) -> RGBColor {
    let [r, g, b] = colour::viridis(t);
    RGBColor(r, g, b)
}

/// Colour of `|det J|` on a log scale spanning [`DECADES`] below `max`.
fn shade(det_abs: f64, max: f64) -> RGBColor {
    let t = if det_abs > 0.0 {
        1.0 + (det_abs / max).log10() / DECADES
    } else {
        0.0
    };
    viridis(t)
}

/// Line colours of the singular factors, by index.
const FACTOR_COLORS: [RGBColor; 4] = [
    RGBColor(230, 30, 30),
    RGBColor(255, 255, 255),
    RGBColor(255, 140, 0),
    RGBColor(0, 200, 255),
];

/// One UR5 panel: `|det J|` over joints `(jx, jy)` (0-based) with `q` elsewhere.
fn ur5_panel(
    area: &DrawingArea<BitMapBackend, Shift>,
    ur5: &Ur5,
    q: [f64; 6],
    (jx, jy): (usize, usize),
) -> Result<(), Box<dyn Error>> {
    // A little past ±π so that zero sets at ±π fall inside the grid.
    let range = (-3.2, 3.2);
    let at = |x: f64, y: f64| {
        let mut q = q;
        q[jx] = x;
        q[jy] = y;
        q
    };
    let det = Grid::sample(range, |x, y| ur5.jacobian_det(&at(x, y)).abs());
    let max = det.values.iter().copied().fold(0.0, f64::max);
    let fixed: Vec<String> = (0..6)
        .filter(|&j| j != jx && j != jy)
        .map(|j| format!("q{} = {}", j + 1, fmt_angle(q[j])))
        .collect();
    let mut chart = ChartBuilder::on(area)
        .caption(
            format!(
                "UR5 |det J| over (q{}, q{}); {}",
                jx + 1,
                jy + 1,
                fixed.join(", ")
            ),
            ("sans-serif", 16),
        )
        .margin(10)
        .x_label_area_size(40)
        .y_label_area_size(50)
        .build_cartesian_2d(range.0..range.1, range.0..range.1)?;
    chart
        .configure_mesh()
        .disable_mesh()
        .x_desc(format!("q{} [rad]", jx + 1))
        .y_desc(format!("q{} [rad]", jy + 1))
        .label_style(("sans-serif", 13))
        .axis_desc_style(("sans-serif", 14))
        .draw()?;
    let h = step(range) / 2.0;
    chart.draw_series((0..CELLS * CELLS).map(|k| {
        let (ix, iy) = (k % CELLS, k / CELLS);
        let (x, y) = (coord(range, ix), coord(range, iy));
        Rectangle::new(
            [(x - h, y - h), (x + h, y + h)],
            shade(det.at(ix, iy), max).filled(),
        )
    }))?;
    // The zero set of each factor that depends on a joint (parameter factors never vanish).
    let mut color = 0;
    for (k, s) in Ur5::SINGULARITIES.iter().enumerate() {
        if s.joints.is_empty() {
            continue;
        }
        let factor = Grid::sample(range, |x, y| ur5.singular_factors(&at(x, y))[k]);
        let segs = factor.zero_set();
        let c = FACTOR_COLORS[color % FACTOR_COLORS.len()];
        color += 1;
        if segs.is_empty() {
            continue; // constant on this slice (its joints are all fixed): nothing to draw
        }
        chart
            .draw_series(
                segs.into_iter()
                    .map(move |s| PathElement::new(s.to_vec(), c.stroke_width(2))),
            )?
            .label(s.condition)
            .legend(move |(x, y)| PathElement::new([(x, y), (x + 18, y)], c.stroke_width(3)));
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::LowerLeft)
        .label_font(("sans-serif", 12))
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK.mix(0.4))
        .draw()?;
    Ok(())
}

fn ur5_map(path: &Path) -> Result<(), Box<dyn Error>> {
    let root = BitMapBackend::new(path, (1400, 760)).into_drawing_area();
    root.fill(&WHITE)?;
    let (body, bar) = root.split_vertically(690);
    let panels = body.split_evenly((1, 2));
    let ur5 = Ur5::default();
    ur5_panel(
        &panels[0],
        &ur5,
        [0.0, 0.0, 0.0, -PI / 2.0, 0.8, 0.0],
        (1, 2),
    )?;
    ur5_panel(
        &panels[1],
        &ur5,
        [0.0, -1.2, 0.0, -PI / 2.0, 0.0, 0.0],
        (2, 4),
    )?;
    colour_bar(
        &bar,
        "log scale: |det J| relative to its maximum on each panel",
        260,
        (-DECADES, 0.0),
    )?;
    root.present()?;
    Ok(())
}

/// A horizontal colour bar for the [`shade`] scale.
fn colour_bar(
    area: &DrawingArea<BitMapBackend, Shift>,
    label: &str,
    side_margin: u32,
    (lo, hi): (f64, f64),
) -> Result<(), Box<dyn Error>> {
    // A negative lower end means decades (the log scale of [`shade`]).
    let log = lo < 0.0;
    let mut chart = ChartBuilder::on(area)
        .margin_left(side_margin)
        .margin_right(side_margin)
        .margin_bottom(4)
        .x_label_area_size(22)
        .caption(label, ("sans-serif", 13))
        .build_cartesian_2d(lo..hi, 0.0..1.0)?;
    chart
        .configure_mesh()
        .disable_mesh()
        .disable_y_axis()
        .x_labels(if log { (hi - lo) as usize + 1 } else { 6 })
        .x_label_formatter(&|x| {
            if log {
                format!("1e{}", x.round() as i32)
            } else {
                format!("{x:.2}")
            }
        })
        .label_style(("sans-serif", 12))
        .draw()?;
    let n = 200;
    chart.draw_series((0..n).map(|i| {
        let x0 = lo + (hi - lo) * i as f64 / n as f64;
        let x1 = x0 + (hi - lo) / n as f64;
        Rectangle::new(
            [(x0, 0.0), (x1, 1.0)],
            viridis(i as f64 / (n - 1) as f64).filled(),
        )
    }))?;
    Ok(())
}

fn planar_rr_map(path: &Path) -> Result<(), Box<dyn Error>> {
    // Unequal links, so that the inner boundary is a circle rather than the origin.
    let arm = PlanarRr { L1: 1.0, L2: 0.6 };
    let reach = arm.L1 + arm.L2;
    let range = (-1.1 * reach, 1.1 * reach);
    // Each reachable (x, y): elbow angle from the law of cosines, shoulder from atan2;
    // the colour is the generated `jacobian_det` there, after checking `fk` lands on (x, y).
    let det = Grid::sample(range, |x, y| {
        let c2 = (x * x + y * y - arm.L1 * arm.L1 - arm.L2 * arm.L2) / (2.0 * arm.L1 * arm.L2);
        if !(-1.0..=1.0).contains(&c2) {
            return f64::NAN; // outside the workspace
        }
        let q2 = c2.acos();
        let q1 = y.atan2(x) - (arm.L2 * q2.sin()).atan2(arm.L1 + arm.L2 * c2);
        let q = [q1, q2];
        let t = arm.fk(&q);
        assert!(
            (t[0][3] - x).abs() < 1e-9 && (t[1][3] - y).abs() < 1e-9,
            "inverse kinematics missed ({x}, {y})"
        );
        arm.jacobian_det(&q).abs()
    });
    let max = det
        .values
        .iter()
        .copied()
        .filter(|v| v.is_finite())
        .fold(0.0, f64::max);

    let root = BitMapBackend::new(path, (820, 860)).into_drawing_area();
    root.fill(&WHITE)?;
    let (body, bar) = root.split_vertically(790);
    let mut chart = ChartBuilder::on(&body)
        .caption(
            format!(
                "Planar RR (L1 = {}, L2 = {}) over its workspace: det J = {}",
                arm.L1,
                arm.L2,
                PlanarRr::DET
            ),
            ("sans-serif", 16),
        )
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(50)
        .build_cartesian_2d(range.0..range.1, range.0..range.1)?;
    chart
        .configure_mesh()
        .light_line_style(WHITE.mix(0.0))
        .bold_line_style(BLACK.mix(0.08))
        .x_desc("x [m]")
        .y_desc("y [m]")
        .label_style(("sans-serif", 13))
        .axis_desc_style(("sans-serif", 14))
        .draw()?;
    let h = step(range) / 2.0;
    chart.draw_series(
        (0..CELLS * CELLS)
            .filter(|&k| det.values[k].is_finite())
            .map(|k| {
                let (ix, iy) = (k % CELLS, k / CELLS);
                let (x, y) = (coord(range, ix), coord(range, iy));
                Rectangle::new(
                    [(x - h, y - h), (x + h, y + h)],
                    viridis(det.at(ix, iy) / max).filled(),
                )
            }),
    )?;

    // Singular sets: the roots of each joint-dependent factor in q2, found by bisection
    // on the generated `singular_factors`, then mapped through `fk` with q1 swept.
    let mut color = 0;
    for (k, s) in PlanarRr::SINGULARITIES.iter().enumerate() {
        if s.joints.is_empty() {
            continue;
        }
        let f = |q2: f64| arm.singular_factors(&[0.0, q2])[k];
        let c = FACTOR_COLORS[color % FACTOR_COLORS.len()];
        color += 1;
        let mut labelled = false;
        for q2 in roots(f, -PI, PI) {
            let curve: Vec<(f64, f64)> = (0..=360)
                .map(|i| {
                    let t = arm.fk(&[2.0 * PI * i as f64 / 360.0, q2]);
                    (t[0][3], t[1][3])
                })
                .collect();
            let series = chart.draw_series([PathElement::new(curve, c.stroke_width(3))])?;
            if !labelled {
                series
                    .label(format!(
                        "{} (q2 = 0: r = L1 + L2; q2 = ±π: r = |L1 − L2|)",
                        s.condition
                    ))
                    .legend(move |(x, y)| {
                        PathElement::new([(x, y), (x + 18, y)], c.stroke_width(3))
                    });
                labelled = true;
            }
        }
    }
    // One arm pose for scale.
    let q = [0.5, 1.3];
    let frames = arm.frames(&q);
    let pts = vec![
        (0.0, 0.0),
        (frames[0][0][3], frames[0][1][3]),
        (frames[1][0][3], frames[1][1][3]),
    ];
    chart
        .draw_series([PathElement::new(pts.clone(), BLACK.stroke_width(3))])?
        .label("the arm at q = (0.5, 1.3)")
        .legend(|(x, y)| PathElement::new([(x, y), (x + 18, y)], BLACK.stroke_width(3)));
    chart.draw_series(pts.iter().map(|&p| Circle::new(p, 5, BLACK.filled())))?;
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperLeft)
        .label_font(("sans-serif", 12))
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK.mix(0.4))
        .draw()?;
    colour_bar(
        &bar,
        "linear scale: |det J| (white: out of reach)",
        120,
        (0.0, max),
    )?;
    root.present()?;
    Ok(())
}

/// Roots of `f` on `[lo, hi]`: sign changes on a fine grid refined by bisection, plus
/// the ends when `f` vanishes there.
fn roots(f: impl Fn(f64) -> f64, lo: f64, hi: f64) -> Vec<f64> {
    let n = 720;
    let x = |i: usize| lo + (hi - lo) * i as f64 / n as f64;
    let mut out = Vec::new();
    for i in 0..n {
        let (mut a, mut b) = (x(i), x(i + 1));
        let (fa, fb) = (f(a), f(b));
        if fa.abs() < 1e-12 {
            out.push(a);
            continue;
        }
        if i + 1 == n && fb.abs() < 1e-12 {
            out.push(b);
        }
        if (fa < 0.0) == (fb < 0.0) || fb.abs() < 1e-12 {
            continue;
        }
        for _ in 0..60 {
            let m = 0.5 * (a + b);
            if (f(m) < 0.0) == (fa < 0.0) {
                a = m;
            } else {
                b = m;
            }
        }
        out.push(0.5 * (a + b));
    }
    out
}

fn fmt_angle(x: f64) -> String {
    if (x + PI / 2.0).abs() < 1e-12 {
        "−π/2".into()
    } else {
        format!("{x}")
    }
}
