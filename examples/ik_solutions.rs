//! Every closed-form IK solution of one UR5 pose and one PUMA 560 pose, drawn as stick
//! figures: `docs/img/ik_ur5.png`, `docs/img/ik_puma560.png` (or into the directory given
//! as the first argument). Each solution gets two views — front (x–z) and top (x–y) —
//! and its branch: shoulder left/right, elbow up/down, wrist flipped or not.
//!
//! The joints drawn are the origins of the generated `frames(q)`, then the tool point of
//! `fk(q)`; the solutions are the generated `ik`'s. Branch names are read off the
//! figure, not off the solver's order: the shoulder's side is where the wrist centre lies
//! across the plane of axes 1 and 2, the elbow is up when it lies above the line from the
//! shoulder to the wrist centre, and the wrist is flipped when q5 < 0.
//!
//! ```text
//! cargo run --example ik_solutions
//! ```
//!
//! Text is drawn with DejaVu Sans read at run time (Debian/Ubuntu package
//! `fonts-dejavu-core`); set `KINEGEN_FONT=/path/to/font.ttf` to use another TrueType font.

#[path = "common/plots.rs"]
mod plots;

use std::error::Error;
use std::path::Path;

use kinegen::Kinematics;
use kinegen_robots::{Puma560, Ur5};
use plotters::prelude::*;

type P3 = [f64; 3];

fn main() -> Result<(), Box<dyn Error>> {
    plots::load_font()?;
    let out = plots::output_dir()?;
    let ur5 = Ur5::default();
    let q = [0.4, -1.1, 1.3, -0.8, 1.2, 0.3];
    let n = draw(
        &ur5,
        "UR5",
        &ur5.fk(&q),
        |p| ur5.ik(p).iter().filter(|b| b.exact).map(|b| b.q).collect(),
        &out.join("ik_ur5.png"),
    )?;
    println!("UR5: {n} solutions");
    let puma = Puma560::default();
    let q = [0.3, 0.5, -0.4, 0.6, 0.8, -0.2];
    let n = draw(
        &puma,
        "PUMA 560",
        &puma.fk(&q),
        |p| puma.ik(p).iter().filter(|b| b.exact).map(|b| b.q).collect(),
        &out.join("ik_puma560.png"),
    )?;
    println!("PUMA 560: {n} solutions");
    println!("wrote 2 pictures to {}", out.display());
    Ok(())
}

/// The figure's points: the base, every frame origin, the tool point.
fn stick<R: Kinematics<6>>(robot: &R, q: &[f64; 6]) -> Vec<P3> {
    let mut pts = vec![[0.0; 3]];
    pts.extend(robot.frames(q).iter().map(|f| [f[0][3], f[1][3], f[2][3]]));
    let t = robot.fk(q);
    pts.push([t[0][3], t[1][3], t[2][3]]);
    pts
}

fn sub(a: &P3, b: &P3) -> P3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn dot(a: &P3, b: &P3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn cross(a: &P3, b: &P3) -> P3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// Shoulder side, elbow, wrist, read off the figure (see the module docs).
fn branch<R: Kinematics<6>>(robot: &R, q: &[f64; 6]) -> String {
    let f = robot.frames(q);
    let origin = |i: usize| [f[i][0][3], f[i][1][3], f[i][2][3]];
    let z = |i: usize| [f[i][0][2], f[i][1][2], f[i][2][2]];
    let (shoulder, elbow, wrist) = (origin(0), origin(1), origin(3));
    // Axis 2 is frame 1's z; the plane of axes 1 (world z) and 2 has normal z × h2.
    let normal = cross(&[0.0, 0.0, 1.0], &z(0));
    let side = if dot(&normal, &wrist) >= 0.0 {
        "left"
    } else {
        "right"
    };
    let sw = sub(&wrist, &shoulder);
    let t = dot(&sub(&elbow, &shoulder), &sw) / dot(&sw, &sw).max(1e-12);
    let line_z = shoulder[2] + t * sw[2];
    let up = if elbow[2] >= line_z { "up" } else { "down" };
    let wrist_flip = if q[4] < 0.0 { "flipped" } else { "not flipped" };
    format!("shoulder {side}, elbow {up}, wrist {wrist_flip}")
}

fn draw<R: Kinematics<6>>(
    robot: &R,
    name: &str,
    pose: &[[f64; 4]; 4],
    ik: impl Fn(&[[f64; 4]; 4]) -> Vec<[f64; 6]>,
    path: &Path,
) -> Result<usize, Box<dyn Error>> {
    let solutions = ik(pose);
    let figures: Vec<Vec<P3>> = solutions.iter().map(|q| stick(robot, q)).collect();
    // One scale for every panel: the extent of every figure, square.
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for p in figures.iter().flatten() {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let half = (0..3).map(|k| hi[k] - lo[k]).fold(0.0, f64::max) / 2.0 + 0.05;
    let mid: Vec<f64> = (0..3).map(|k| (hi[k] + lo[k]) / 2.0).collect();
    let range = |k: usize| (mid[k] - half)..(mid[k] + half);
    let rows = solutions.len().div_ceil(2).max(1);
    let root = BitMapBackend::new(path, (1400, 330 * rows as u32 + 50)).into_drawing_area();
    root.fill(&WHITE)?;
    let title = format!(
        "{name}: all {} closed-form IK solutions of one pose (tool at [{:.3}, {:.3}, {:.3}] m)",
        solutions.len(),
        pose[0][3],
        pose[1][3],
        pose[2][3]
    );
    let (top, body) = root.split_vertically(50);
    top.titled(&title, ("sans-serif", 24))?;
    let panels = body.split_evenly((rows, 4));
    for (i, (q, fig)) in solutions.iter().zip(&figures).enumerate() {
        let label = branch(robot, q);
        for (v, (a, b, axes)) in [(0usize, 2usize, "front, x–z"), (0, 1, "top, x–y")]
            .into_iter()
            .enumerate()
        {
            let area = &panels[2 * i + v];
            let caption = if v == 0 {
                format!("{}: {label}", i + 1)
            } else {
                format!(
                    "q = [{}]",
                    q.iter()
                        .map(|x| format!("{x:.2}"))
                        .collect::<Vec<_>>()
                        .join(", ")
                )
            };
            let mut chart = ChartBuilder::on(area)
                .caption(caption, ("sans-serif", 14))
                .margin(8)
                .x_label_area_size(34)
                .y_label_area_size(36)
                .build_cartesian_2d(range(a), range(b))?;
            chart
                .configure_mesh()
                .x_labels(5)
                .y_labels(5)
                .x_desc(if a == 0 { "x (m)" } else { "" })
                .y_desc(format!("{} (m) — {axes}", ["x", "y", "z"][b]))
                .label_style(("sans-serif", 11))
                .draw()?;
            let pts: Vec<(f64, f64)> = fig.iter().map(|p| (p[a], p[b])).collect();
            let colour = Palette99::pick(i).to_rgba();
            chart.draw_series(LineSeries::new(pts.clone(), colour.stroke_width(4)))?;
            chart.draw_series(pts.iter().map(|p| Circle::new(*p, 4, BLACK.filled())))?;
            let tool = *pts.last().unwrap_or(&(0.0, 0.0));
            chart.draw_series(std::iter::once(Cross::new(tool, 7, RED.stroke_width(2))))?;
        }
    }
    root.present()?;
    Ok(solutions.len())
}
