//! Position, velocity and acceleration plots of the trajectory profiles, as PNGs in
//! `docs/img/` (or the directory given as the first argument).
//!
//! ```text
//! cargo run --example trajectory_plots
//! ```
//!
//! Text is drawn with DejaVu Sans read at run time (Debian/Ubuntu package
//! `fonts-dejavu-core`); set `KINEGEN_FONT=/path/to/font.ttf` to use another TrueType font.

#[path = "common/plots.rs"]
mod plots;

use std::error::Error;
use std::path::Path;

use kinegen::trajectory::{Cubic, Profile, Quintic, StopAtVias, ThroughVias, Trapezoid};
use plotters::prelude::*;

/// One curve: a label, a colour and its samples `(t, q, q̇, q̈)`.
struct Curve {
    label: &'static str,
    color: RGBColor,
    samples: Vec<(f64, f64, f64, f64)>,
}

impl Curve {
    fn new<P: Profile>(label: &'static str, color: RGBColor, profile: &P) -> Self {
        let samples = profile.sample(400.0).expect("valid rate").collect();
        Self {
            label,
            color,
            samples,
        }
    }
}

/// Horizontal reference lines: `±v_max` on the velocity plot, `±a_max` on the acceleration plot.
#[derive(Clone, Copy)]
struct Limits {
    v_max: f64,
    a_max: f64,
}

const BLUE_: RGBColor = RGBColor(31, 119, 180);
const ORANGE_: RGBColor = RGBColor(230, 110, 20);
const GREY: RGBColor = RGBColor(150, 150, 150);

fn main() -> Result<(), Box<dyn Error>> {
    plots::load_font()?;
    let out = plots::output_dir()?;

    let (v_max, a_max) = (0.5, 1.0);
    let limits = Some(Limits { v_max, a_max });

    let trap = Trapezoid::new(0.0, 1.0, v_max, a_max)?;
    plot(
        &out.join("trajectory_trapezoid.png"),
        &format!(
            "Trapezoid 0 → 1 rad, v_max = {v_max}, a_max = {a_max}: t_a = {:.2} s, T = {:.2} s",
            trap.accel_time(),
            trap.duration()
        ),
        &[Curve::new("trapezoid", BLUE_, &trap)],
        limits,
    )?;

    let tri = Trapezoid::new(0.0, 0.15, v_max, a_max)?;
    plot(
        &out.join("trajectory_triangle.png"),
        &format!(
            "Triangle 0 → 0.15 rad (< v_max²/a_max = {:.2}): peak {:.3} rad/s, T = {:.3} s",
            v_max * v_max / a_max,
            tri.peak_velocity(),
            tri.duration()
        ),
        &[Curve::new("triangle", BLUE_, &tri)],
        limits,
    )?;

    let cubic = Cubic::rest_to_rest(0.0, 1.0, v_max, a_max)?;
    plot(
        &out.join("trajectory_cubic.png"),
        &format!(
            "Cubic 0 → 1 rad at rest, shortest T within limits: T = {:.2} s (jerk constant)",
            cubic.duration()
        ),
        &[Curve::new("cubic", BLUE_, &cubic)],
        limits,
    )?;

    let quintic = Quintic::rest_to_rest(0.0, 1.0, v_max, a_max)?;
    plot(
        &out.join("trajectory_quintic.png"),
        &format!(
            "Quintic 0 → 1 rad, zero v and a at both ends: T = {:.2} s",
            quintic.duration()
        ),
        &[Curve::new("quintic", BLUE_, &quintic)],
        limits,
    )?;

    let points = [0.0, 1.0, 1.6, 0.6, 1.2];
    let stop = StopAtVias::new(points, v_max, a_max)?;
    // Arrive at the same times as the stopping path, without stopping.
    let through = ThroughVias::new(points, *stop.arrival_times())?;
    plot(
        &out.join("trajectory_multi_segment.png"),
        "Via points 0, 1, 1.6, 0.6, 1.2 at the same times: stop at each vs pass through (cubics ignore the limits)",
        &[
            Curve::new("stop at each (trapezoids)", GREY, &stop),
            Curve::new("pass through (cubics, heuristic via velocities)", ORANGE_, &through),
        ],
        limits,
    )?;

    println!("wrote 5 plots to {}", out.display());
    Ok(())
}

/// Three stacked panels, position / velocity / acceleration over time.
fn plot(
    path: &Path,
    title: &str,
    curves: &[Curve],
    limits: Option<Limits>,
) -> Result<(), Box<dyn Error>> {
    let root = BitMapBackend::new(path, (900, 780)).into_drawing_area();
    root.fill(&WHITE)?;
    let (header, body) = root.split_vertically(34);
    header.titled(title, ("sans-serif", 17))?;
    let panels = body.split_evenly((3, 1));
    let t_end = curves
        .iter()
        .flat_map(|c| c.samples.last().map(|s| s.0))
        .fold(0.0, f64::max);
    let names = [
        "position q [rad]",
        "velocity dq/dt [rad/s]",
        "acceleration d²q/dt² [rad/s²]",
    ];
    for (k, panel) in panels.iter().enumerate() {
        let value = |s: &(f64, f64, f64, f64)| [s.1, s.2, s.3][k];
        let mut lo = curves
            .iter()
            .flat_map(|c| c.samples.iter().map(value))
            .fold(0.0, f64::min);
        let mut hi = curves
            .iter()
            .flat_map(|c| c.samples.iter().map(value))
            .fold(0.0, f64::max);
        let limit = limits
            .map(|l| [f64::NAN, l.v_max, l.a_max][k])
            .filter(|x| x.is_finite());
        if let Some(l) = limit {
            lo = lo.min(-l);
            hi = hi.max(l);
        }
        let pad = 0.08 * (hi - lo).max(1e-9);
        let mut chart = ChartBuilder::on(panel)
            .margin_left(10)
            .margin_right(20)
            .margin_top(6)
            .x_label_area_size(if k == 2 { 36 } else { 18 })
            .y_label_area_size(60)
            .build_cartesian_2d(0.0..t_end, (lo - pad)..(hi + pad))?;
        chart
            .configure_mesh()
            .light_line_style(WHITE.mix(0.0))
            .bold_line_style(BLACK.mix(0.08))
            .x_desc(if k == 2 { "time t [s]" } else { "" })
            .y_desc(names[k])
            .y_label_formatter(&|y| tick(*y, hi - lo))
            .x_label_formatter(&|x| tick(*x, t_end))
            .label_style(("sans-serif", 13))
            .axis_desc_style(("sans-serif", 14))
            .draw()?;
        if let Some(l) = limit {
            for y in [-l, l] {
                chart.draw_series(LineSeries::new(
                    [(0.0, y), (t_end, y)],
                    RED.mix(0.45).stroke_width(1),
                ))?;
            }
        }
        for c in curves {
            let series = chart.draw_series(LineSeries::new(
                c.samples.iter().map(|s| (s.0, value(s))),
                c.color.stroke_width(2),
            ))?;
            if curves.len() > 1 && k == 0 {
                let color = c.color;
                series.label(c.label).legend(move |(x, y)| {
                    PathElement::new([(x, y), (x + 18, y)], color.stroke_width(2))
                });
            }
        }
        if curves.len() > 1 && k == 0 {
            chart
                .configure_series_labels()
                .position(SeriesLabelPosition::LowerRight)
                .label_font(("sans-serif", 13))
                .background_style(WHITE.mix(0.85))
                .border_style(BLACK.mix(0.3))
                .draw()?;
        }
    }
    root.present()?;
    Ok(())
}

/// A tick label with enough decimals for an axis spanning `range`, and no "-0.00" for
/// values that are zero up to rounding.
fn tick(x: f64, range: f64) -> String {
    let decimals = (-(range / 8.0).log10()).ceil().clamp(0.0, 4.0) as usize;
    let s = format!("{x:.decimals$}");
    match s.strip_prefix('-') {
        Some(rest) if rest.chars().all(|c| c == '0' || c == '.') => rest.to_string(),
        _ => s,
    }
}
