//! SVG line plots drawn with plotters: time series of ω, drifts, sweeps, and stacked panels
//! (a scene's energies, momenta and positions).

use plotters::prelude::*;

/// Why a plot could not be drawn: nothing finite to draw, or plotters failed (the message).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{0}")]
pub struct PlotError(pub String);

impl From<&str> for PlotError {
    fn from(message: &str) -> Self {
        PlotError(message.to_string())
    }
}

/// Turns a plotters error into a [`PlotError`].
fn failed(e: impl std::fmt::Debug) -> PlotError {
    PlotError(format!("{e:?}"))
}

/// One named curve.
#[derive(Clone, Debug, PartialEq)]
pub struct Series {
    /// The legend entry, e.g. `ω₁₂`.
    pub name: String,
    /// The points (x, y); non-finite points are skipped.
    pub points: Vec<(f64, f64)>,
}

/// What a plot shows.
#[derive(Clone, Debug, PartialEq)]
pub struct PlotSpec<'a> {
    /// The title above the plot.
    pub title: &'a str,
    /// The label of the horizontal axis.
    pub x_label: &'a str,
    /// The label of the vertical axis.
    pub y_label: &'a str,
    /// A logarithmic vertical axis (values ≤ 0 are drawn at the floor 1e-17).
    pub log_y: bool,
    /// Draw a marker at every point (for sweeps with few points).
    pub markers: bool,
}

/// The smallest value a logarithmic axis shows.
const LOG_FLOOR: f64 = 1e-17;

/// Returns the subscript form of a 1-based plane name: "12" → "₁₂", "1_10" → "₁,₁₀".
pub fn subscript(plane: &str) -> String {
    plane
        .chars()
        .map(|c| match c {
            '0'..='9' => char::from_u32(0x2080 + c as u32 - '0' as u32).unwrap_or(c),
            '_' => ',',
            other => other,
        })
        .collect()
}

fn range(values: impl Iterator<Item = f64>) -> Option<(f64, f64)> {
    let (lo, hi) = values
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
            (a.min(v), b.max(v))
        });
    (lo <= hi).then_some((lo, hi))
}

fn padded(lo: f64, hi: f64) -> (f64, f64) {
    if hi - lo <= 1e-12 * (lo.abs() + hi.abs()).max(1e-300) {
        let d = lo.abs().max(1.0) * 0.5;
        (lo - d, hi + d)
    } else {
        let d = (hi - lo) * 0.05;
        (lo - d, hi + d)
    }
}

/// Returns the SVG text of a line plot of `series`.
///
/// # Errors
/// [`PlotError`] if plotters fails (it does not for finite input) or nothing is finite.
pub fn line_plot(spec: &PlotSpec<'_>, series: &[Series]) -> Result<String, PlotError> {
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (960, 540)).into_drawing_area();
        root.fill(&WHITE).map_err(failed)?;
        chart(&root, spec, series)?;
        root.present().map_err(failed)?;
    }
    Ok(svg)
}

/// Returns the SVG text of plots stacked one above the other under one `title`, sharing
/// nothing but the page: one panel per `(spec, series)`, each with its own axes and legend.
///
/// # Errors
/// As [`line_plot`], for any panel.
pub fn stacked_plot(
    title: &str,
    panels: &[(PlotSpec<'_>, Vec<Series>)],
) -> Result<String, PlotError> {
    let height = 48 + 400 * panels.len().max(1) as u32;
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (960, height)).into_drawing_area();
        root.fill(&WHITE).map_err(failed)?;
        let body = root.titled(title, ("sans-serif", 24)).map_err(failed)?;
        for (area, (spec, series)) in body.split_evenly((panels.len(), 1)).iter().zip(panels) {
            chart(area, spec, series)?;
        }
        root.present().map_err(failed)?;
    }
    Ok(svg)
}

/// Draws one chart of `series` into `area`: axes, curves and legend.
fn chart<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    spec: &PlotSpec<'_>,
    series: &[Series],
) -> Result<(), PlotError> {
    let all = || series.iter().flat_map(|s| s.points.iter());
    let (x0, x1) = range(all().map(|p| p.0)).ok_or("nothing to plot")?;
    let (x0, x1) = if x1 > x0 { (x0, x1) } else { padded(x0, x1) };
    let mut builder = ChartBuilder::on(area);
    builder
        .caption(spec.title, ("sans-serif", 22))
        .margin(16)
        .x_label_area_size(48)
        .y_label_area_size(84);
    if spec.log_y {
        // The range of the positive values; zeros are drawn on the bottom edge.
        let (y0, y1) =
            range(all().map(|p| p.1).filter(|y| *y >= LOG_FLOOR)).unwrap_or((LOG_FLOOR, 1.0));
        let (y0, y1) = (y0 / 3.0, (y1 * 3.0).max(y0 * 10.0));
        let mut chart = builder
            .build_cartesian_2d(x0..x1, (y0..y1).log_scale())
            .map_err(failed)?;
        chart
            .configure_mesh()
            .x_desc(spec.x_label)
            .y_desc(spec.y_label)
            .y_label_formatter(&|y| format!("{y:.0e}"))
            .draw()
            .map_err(failed)?;
        curves(&mut chart, spec, series, |y| y.max(y0))
    } else {
        let (y0, y1) = range(all().map(|p| p.1)).ok_or("nothing to plot")?;
        let (y0, y1) = padded(y0, y1);
        let mut chart = builder.build_cartesian_2d(x0..x1, y0..y1).map_err(failed)?;
        chart
            .configure_mesh()
            .x_desc(spec.x_label)
            .y_desc(spec.y_label)
            .draw()
            .map_err(failed)?;
        curves(&mut chart, spec, series, |y| y)
    }
}

/// Draws the curves of `series` (their finite points, `y` mapped by `clamp`) and the legend.
fn curves<'a, DB, X, Y>(
    chart: &mut ChartContext<'a, DB, Cartesian2d<X, Y>>,
    spec: &PlotSpec<'_>,
    series: &[Series],
    clamp: impl Fn(f64) -> f64,
) -> Result<(), PlotError>
where
    DB: DrawingBackend + 'a,
    X: Ranged<ValueType = f64>,
    Y: Ranged<ValueType = f64>,
{
    for (k, s) in series.iter().enumerate() {
        let color = Palette99::pick(k).to_rgba();
        let pts: Vec<(f64, f64)> = s
            .points
            .iter()
            .filter(|p| p.0.is_finite() && p.1.is_finite())
            .map(|p| (p.0, clamp(p.1)))
            .collect();
        if spec.markers {
            chart
                .draw_series(pts.iter().map(|&p| Circle::new(p, 4, color.filled())))
                .map_err(failed)?;
        }
        chart
            .draw_series(LineSeries::new(pts, color.stroke_width(2)))
            .map_err(failed)?
            .label(s.name.clone())
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
            });
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .draw()
        .map_err(failed)?;
    Ok(())
}
