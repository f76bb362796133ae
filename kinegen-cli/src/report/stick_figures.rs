//! Every IK solution of the report's pose as a stick figure — the frame origins joined
//! base to tool — in two views: the xz plane (side) and the xy plane (top). All
//! solutions end at the same tool point; that they do is the picture's check.

use kinegen_core::Chain;

use super::frames::origins;
use super::html::{self, Section};
use super::ik::Solutions;
use super::svg::{Plot, COLOURS};

/// The section (a note instead when there are no solutions to draw).
pub fn section(chain: &Chain, s: &Solutions) -> Section {
    let body = if s.solutions.is_empty() {
        html::note("No IK solutions to draw (see Inverse kinematics).")
    } else {
        let figures: Vec<Vec<[f64; 3]>> = s
            .solutions
            .iter()
            .map(|(q, _, _)| origins(chain, q))
            .collect();
        let mut b = String::new();
        for (a, c, name) in [(0, 2, "side view, xz plane"), (0, 1, "top view, xy plane")] {
            b.push_str(&html::figure(
                &view(&figures, a, c, name),
                &format!(
                    "The {} solutions of the pose, {name}: frame origins from the base (dot) \
                     to the tool point (ring), one colour per solution (# as in the table above).",
                    figures.len()
                ),
            ));
        }
        b
    };
    Section {
        id: "stick-figures",
        title: "IK solutions drawn".into(),
        body,
    }
}

/// One projection (`a`, `c`: the coordinates drawn as x and y).
pub fn view(figures: &[Vec<[f64; 3]>], a: usize, c: usize, name: &str) -> String {
    let all = figures.iter().flatten();
    let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for p in all {
        x0 = x0.min(p[a]);
        x1 = x1.max(p[a]);
        y0 = y0.min(p[c]);
        y1 = y1.max(p[c]);
    }
    let pad = 0.08 * (x1 - x0).max(y1 - y0).max(1e-3);
    let mut plot =
        Plot::new(460.0, 400.0, (x0 - pad, x1 + pad), (y0 - pad, y1 + pad)).equal_aspect();
    let axis = ["x (m)", "y (m)", "z (m)"];
    plot.axes(axis[a], axis[c]);
    for (i, f) in figures.iter().enumerate() {
        let colour = COLOURS[i % COLOURS.len()];
        let pts: Vec<(f64, f64)> = f.iter().map(|p| (p[a], p[c])).collect();
        plot.line(&pts, colour, 2.5);
        for &p in &pts {
            plot.dot(p, 3.0, colour);
        }
        let px = plot.width - 20.0;
        plot.text(px, 26.0 + 15.0 * i as f64, "end", &format!("#{}", i + 1));
        let y = 22.0 + 15.0 * i as f64;
        plot.body.push_str(&format!(
            r#"<rect x="{:.1}" y="{y:.1}" width="8" height="8" fill="{colour}"/>"#,
            px + 2.0
        ));
    }
    if let Some(f) = figures.first() {
        let base = f[0];
        plot.dot((base[a], base[c]), 5.0, "#333");
        let tip = f[f.len() - 1];
        let (tx, ty) = (plot.px(tip[a]), plot.py(tip[c]));
        plot.body.push_str(&format!(
            r##"<circle cx="{tx:.2}" cy="{ty:.2}" r="7" fill="none" stroke="#333" stroke-width="1.5"/>"##
        ));
    }
    plot.finish(&format!("IK solutions, {name}"))
}
