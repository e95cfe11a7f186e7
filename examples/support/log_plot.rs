//! The log-log plots of the book's generated figures (`examples/book_literature.rs`,
//! `examples/book_integrators.rs`): one SVG frame with decade grid lines, axis titles, and
//! lines with their points and a legend on the right.

use std::fmt::Write as _;

/// A plot being drawn: the SVG so far and the frame's geometry.
pub struct LogPlot {
    svg: String,
    size: (f64, f64),
    /// Left, right, top and bottom margins.
    margins: (f64, f64, f64, f64),
    /// The decades (log₁₀) at the ends of each axis.
    x_decades: (f64, f64),
    y_decades: (f64, f64),
    lines: usize,
}

impl LogPlot {
    /// A white frame of `size` (width, height) with `margins` (left, right, top, bottom;
    /// the legend sits in the right one), whose axes run over the decades `x_decades` and
    /// `y_decades` (log₁₀ of their ends), in sans-serif of `font_size`.
    pub fn new(
        size: (f64, f64),
        margins: (f64, f64, f64, f64),
        x_decades: (f64, f64),
        y_decades: (f64, f64),
        font_size: u32,
    ) -> LogPlot {
        let (w, h) = size;
        let mut svg = String::new();
        let _ = writeln!(
            svg,
            r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}" font-family="sans-serif" font-size="{font_size}">"#
        );
        let _ = writeln!(
            svg,
            r#"<rect x="0" y="0" width="{w}" height="{h}" fill="white"/>"#
        );
        LogPlot {
            svg,
            size,
            margins,
            x_decades,
            y_decades,
            lines: 0,
        }
    }

    /// The horizontal position of the value x.
    pub fn px(&self, x: f64) -> f64 {
        let (left, right, _, _) = self.margins;
        let (x0, x1) = self.x_decades;
        left + (x.log10() - x0) / (x1 - x0) * (self.size.0 - left - right)
    }

    /// The vertical position of the value y, held inside the frame (and 1e-16 and below at
    /// 1e-16).
    pub fn py(&self, y: f64) -> f64 {
        let (_, _, top, bottom) = self.margins;
        let (y0, y1) = self.y_decades;
        let e = y.max(1e-16).log10().clamp(y0, y1);
        top + (y1 - e) / (y1 - y0) * (self.size.1 - top - bottom)
    }

    /// Horizontal grid lines at 10^k for each k of `exponents`, labelled 1e{k}.
    pub fn y_grid(&mut self, exponents: impl IntoIterator<Item = i32>) {
        let (left, right, _, _) = self.margins;
        for k in exponents {
            let y = self.py(10f64.powi(k));
            let _ = writeln!(
                self.svg,
                r##"<line x1="{left}" y1="{y:.1}" x2="{:.1}" y2="{y:.1}" stroke="#ddd"/><text x="{:.1}" y="{:.1}" text-anchor="end">1e{k}</text>"##,
                self.size.0 - right,
                left - 6.0,
                y + 4.0
            );
        }
    }

    /// Vertical grid lines at the values of `ticks`, each with its label.
    pub fn x_grid(&mut self, ticks: impl IntoIterator<Item = (f64, String)>) {
        let (_, _, top, bottom) = self.margins;
        let h = self.size.1;
        for (value, label) in ticks {
            let x = self.px(value);
            let _ = writeln!(
                self.svg,
                r##"<line x1="{x:.1}" y1="{top}" x2="{x:.1}" y2="{:.1}" stroke="#ddd"/><text x="{x:.1}" y="{:.1}" text-anchor="middle">{label}</text>"##,
                h - bottom,
                h - bottom + 16.0
            );
        }
    }

    /// The axis titles: below the frame and turned along its left side.
    pub fn titles(&mut self, x_title: &str, y_title: &str) {
        let (left, right, top, bottom) = self.margins;
        let (w, h) = self.size;
        let _ = writeln!(
            self.svg,
            r#"<text x="{:.1}" y="{:.1}" text-anchor="middle">{x_title}</text>"#,
            (left + w - right) / 2.0,
            h - 10.0
        );
        let _ = writeln!(
            self.svg,
            r#"<text x="14" y="{:.1}" transform="rotate(-90 14 {:.1})" text-anchor="middle">{y_title}</text>"#,
            (top + h - bottom) / 2.0,
            (top + h - bottom) / 2.0
        );
    }

    /// A line through `points` (values, in the order given) in `colour`, dashed or not,
    /// with a dot at each point and `name` as the next entry of the legend.
    pub fn line(&mut self, points: &[(f64, f64)], colour: &str, dashed: bool, name: &str) {
        let (_, right, top, _) = self.margins;
        let placed: Vec<(f64, f64)> = points
            .iter()
            .map(|&(x, y)| (self.px(x), self.py(y)))
            .collect();
        let dash = if dashed {
            r#" stroke-dasharray="5,3""#
        } else {
            ""
        };
        let path: Vec<String> = placed
            .iter()
            .map(|(x, y)| format!("{x:.1},{y:.1}"))
            .collect();
        let _ = writeln!(
            self.svg,
            r#"<polyline fill="none" stroke="{colour}" stroke-width="1.5"{dash} points="{}"/>"#,
            path.join(" ")
        );
        for (x, y) in &placed {
            let _ = writeln!(
                self.svg,
                r#"<circle cx="{x:.1}" cy="{y:.1}" r="2" fill="{colour}"/>"#
            );
        }
        let x = self.size.0 - right;
        let ly = top + 8.0 + 16.0 * self.lines as f64;
        let _ = writeln!(
            self.svg,
            r#"<line x1="{:.1}" y1="{ly:.1}" x2="{:.1}" y2="{ly:.1}" stroke="{colour}" stroke-width="2"{dash}/><text x="{:.1}" y="{:.1}">{}</text>"#,
            x + 8.0,
            x + 24.0,
            x + 28.0,
            ly + 4.0,
            name.replace('&', "&amp;").replace('<', "&lt;")
        );
        self.lines += 1;
    }

    /// The finished SVG.
    pub fn finish(mut self) -> String {
        self.svg.push_str("</svg>\n");
        self.svg
    }
}
