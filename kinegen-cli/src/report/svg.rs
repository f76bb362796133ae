//! Drawing helpers for the inline SVG pictures: a plot area mapping data to pixels,
//! axes with ticks, lines, points and text. Written directly (a few elements per
//! picture): the SVG stays small and readable, with nothing to fetch.

use std::fmt::Write;

use kinegen_core::emit::mathml::escape;

/// Line colours of the series, one per joint or solution (colour-blind safe, Okabe–Ito).
pub const COLOURS: [&str; 8] = [
    "#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#000000", "#F0E442",
];

/// A plot: `width × height` pixels, the data box `[x0, x1] × [y0, y1]` drawn inside the
/// margins, y up.
#[derive(Clone, Debug)]
pub struct Plot {
    /// Pixels.
    pub width: f64,
    /// Pixels.
    pub height: f64,
    /// Data range along x.
    pub x: (f64, f64),
    /// Data range along y.
    pub y: (f64, f64),
    /// The elements drawn so far.
    pub body: String,
}

const LEFT: f64 = 56.0;
const RIGHT: f64 = 12.0;
const TOP: f64 = 12.0;
const BOTTOM: f64 = 40.0;

impl Plot {
    /// An empty plot of the data box `x × y` (a zero range is widened by 1).
    pub fn new(width: f64, height: f64, x: (f64, f64), y: (f64, f64)) -> Plot {
        let widen = |(a, b): (f64, f64)| if b > a { (a, b) } else { (a - 0.5, a + 0.5) };
        Plot {
            width,
            height,
            x: widen(x),
            y: widen(y),
            body: String::new(),
        }
    }

    /// The same data scale along x and y (a stick figure keeps its shape): the smaller
    /// scale for both, each range centred.
    pub fn equal_aspect(mut self) -> Plot {
        let sx = (self.width - LEFT - RIGHT) / (self.x.1 - self.x.0);
        let sy = (self.height - TOP - BOTTOM) / (self.y.1 - self.y.0);
        let s = sx.min(sy);
        let grow = |(a, b): (f64, f64), pixels: f64| {
            let half = pixels / s / 2.0;
            let c = (a + b) / 2.0;
            (c - half, c + half)
        };
        self.x = grow(self.x, self.width - LEFT - RIGHT);
        self.y = grow(self.y, self.height - TOP - BOTTOM);
        self
    }

    /// Pixel x of data x.
    pub fn px(&self, x: f64) -> f64 {
        LEFT + (x - self.x.0) / (self.x.1 - self.x.0) * (self.width - LEFT - RIGHT)
    }

    /// Pixel y of data y.
    pub fn py(&self, y: f64) -> f64 {
        self.height - BOTTOM - (y - self.y.0) / (self.y.1 - self.y.0) * (self.height - TOP - BOTTOM)
    }

    /// A data-space rectangle filled with `fill`.
    pub fn rect(&mut self, x: (f64, f64), y: (f64, f64), fill: &str) {
        let (a, b) = (self.px(x.0), self.px(x.1));
        let (c, d) = (self.py(y.1), self.py(y.0));
        let _ = write!(
            self.body,
            r#"<rect x="{a:.1}" y="{c:.1}" width="{:.1}" height="{:.1}" fill="{fill}"/>"#,
            b - a,
            d - c
        );
    }

    /// A polyline through data points.
    pub fn line(&mut self, points: &[(f64, f64)], colour: &str, width: f64) {
        let pts: Vec<String> = points
            .iter()
            .map(|&(x, y)| format!("{:.2},{:.2}", self.px(x), self.py(y)))
            .collect();
        let _ = write!(
            self.body,
            r#"<polyline points="{}" fill="none" stroke="{colour}" stroke-width="{width}" stroke-linejoin="round"/>"#,
            pts.join(" ")
        );
    }

    /// A dot at a data point.
    pub fn dot(&mut self, (x, y): (f64, f64), r: f64, colour: &str) {
        let _ = write!(
            self.body,
            r#"<circle cx="{:.2}" cy="{:.2}" r="{r}" fill="{colour}"/>"#,
            self.px(x),
            self.py(y)
        );
    }

    /// Text at pixel coordinates (escaped).
    pub fn text(&mut self, x: f64, y: f64, anchor: &str, text: &str) {
        let _ = write!(
            self.body,
            r#"<text x="{x:.1}" y="{y:.1}" font-size="12" text-anchor="{anchor}" font-family="sans-serif">{}</text>"#,
            escape(text)
        );
    }

    /// The frame, five ticks per axis with their values, and the axis labels.
    pub fn axes(&mut self, x_label: &str, y_label: &str) {
        let (l, r) = (LEFT, self.width - RIGHT);
        let (t, b) = (TOP, self.height - BOTTOM);
        let _ = write!(
            self.body,
            r##"<rect x="{l}" y="{t}" width="{:.1}" height="{:.1}" fill="none" stroke="#333"/>"##,
            r - l,
            b - t
        );
        for k in 0..=4 {
            let f = k as f64 / 4.0;
            let xv = self.x.0 + f * (self.x.1 - self.x.0);
            let yv = self.y.0 + f * (self.y.1 - self.y.0);
            let (xp, yp) = (self.px(xv), self.py(yv));
            let _ = write!(
                self.body,
                r##"<line x1="{xp:.1}" y1="{b}" x2="{xp:.1}" y2="{:.1}" stroke="#333"/><line x1="{l}" y1="{yp:.1}" x2="{:.1}" y2="{yp:.1}" stroke="#333"/>"##,
                b + 4.0,
                l - 4.0
            );
            self.text(xp, b + 16.0, "middle", &tick(xv));
            self.text(l - 6.0, yp + 4.0, "end", &tick(yv));
        }
        self.text((l + r) / 2.0, self.height - 6.0, "middle", x_label);
        let _ = write!(
            self.body,
            r#"<text x="14" y="{:.1}" font-size="12" text-anchor="middle" font-family="sans-serif" transform="rotate(-90 14 {:.1})">{}</text>"#,
            (t + b) / 2.0,
            (t + b) / 2.0,
            escape(y_label)
        );
    }

    /// The `<svg>` element, with a title for screen readers.
    pub fn finish(&self, title: &str) -> String {
        format!(
            r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}" role="img"><title>{}</title>{}</svg>"#,
            escape(title),
            self.body,
            w = self.width,
            h = self.height
        )
    }
}

/// A tick value, short.
fn tick(v: f64) -> String {
    let v = if v.abs() < 1e-9 { 0.0 } else { v };
    format!("{v:.2}")
}

/// Viridis at `t ∈ [0, 1]` (clamped) as `#rrggbb` ([`crate::colour::viridis`]).
pub fn viridis(t: f64) -> String {
    let [r, g, b] = crate::colour::viridis(t);
    format!("#{r:02x}{g:02x}{b:02x}")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn viridis_ends_and_clamps() {
        assert_eq!(viridis(0.0), "#440154");
        assert_eq!(viridis(1.0), "#fde725");
        assert_eq!(viridis(2.0), "#fde725");
        assert_eq!(viridis(f64::NAN), "#440154");
    }

    #[test]
    fn data_maps_into_the_plot_area_y_up() {
        let p = Plot::new(400.0, 300.0, (0.0, 1.0), (0.0, 2.0));
        assert_eq!(p.px(0.0), LEFT);
        assert_eq!(p.px(1.0), 400.0 - RIGHT);
        assert_eq!(p.py(0.0), 300.0 - BOTTOM);
        assert_eq!(p.py(2.0), TOP);
    }
}
