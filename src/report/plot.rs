//! Figures as SVG text (plotters' SVG backend): log or linear axes with titles and units, one
//! line per series with a legend, vertical and horizontal reference lines with labels (limits,
//! d_min, ε), and shaded x-ranges (the measured band, the lowest octave). Used by the HTML
//! report (inline SVG) and the figure examples. Values are SI; each axis shows `si / scale`.
//! The SVG's text uses the generic `sans-serif` family, so no font is embedded or fetched.

use crate::Error;
use crate::figures::{Axis, Figure};
use plotters::coord::Shift;
use plotters::coord::ranged1d::{AsRangedCoord, ValueFormatter};
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

/// By default a log axis shows at most this many decades below the largest value (curves that
/// fall further, e.g. interface stresses of thick films, leave the plot at its bottom).
pub const LOG_DECADES: f64 = 6.0;

/// The default line colours.
pub const PALETTE: [RGBColor; 5] = [
    RGBColor(200, 30, 30),
    RGBColor(30, 70, 200),
    RGBColor(20, 140, 60),
    RGBColor(150, 60, 170),
    RGBColor(230, 130, 0),
];

/// Where the legend goes (chosen per figure so it does not cover the curves).
pub use plotters::chart::SeriesLabelPosition as Legend;
pub use plotters::style::RGBColor;

/// A reference line: `x = at` (vertical) or `y = at` (horizontal), SI, with a label.
#[derive(Debug, Clone, PartialEq)]
pub struct Marker {
    pub at: f64,
    pub vertical: bool,
    pub label: String,
}

/// A shaded x-range `[from, to]` (SI) with a label.
#[derive(Debug, Clone, PartialEq)]
pub struct Band {
    pub from: f64,
    pub to: f64,
    pub label: String,
}

/// What to draw besides the figure's series.
#[derive(Debug, Clone, PartialEq)]
pub struct Extras {
    pub markers: Vec<Marker>,
    pub bands: Vec<Band>,
    pub legend: Legend,
    /// Line colours of the series, in order (repeated past the last).
    pub colors: Vec<RGBColor>,
    /// Width and height, px.
    pub size: (u32, u32),
    /// Decades a log value axis shows below its largest value.
    pub log_decades: f64,
}

impl Default for Extras {
    fn default() -> Self {
        Extras {
            markers: Vec::new(),
            bands: Vec::new(),
            legend: Legend::UpperRight,
            colors: PALETTE.to_vec(),
            size: (800, 600),
            log_decades: LOG_DECADES,
        }
    }
}

fn plot_error(e: impl std::fmt::Display) -> Error {
    Error::Numerical {
        what: "plot",
        detail: e.to_string(),
    }
}

/// The range shown on an axis for the values `v` (display units).
fn range(axis: &Axis, v: impl Iterator<Item = f64> + Clone, decades: f64) -> (f64, f64) {
    let v = v.filter(|v| v.is_finite());
    let max = v.clone().fold(f64::NEG_INFINITY, f64::max);
    if axis.log {
        let floor = max / 10f64.powf(decades);
        let min = v.filter(|&v| v > 0.0).fold(f64::INFINITY, f64::min);
        // Whole decades around the data, widened by a hair so that rounding in the data or in
        // the axis's own key points does not drop the end decades' tick labels.
        let (lo, hi) = (min.max(floor).log10().floor(), max.log10().ceil());
        let hi = if hi > lo { hi } else { lo + 1.0 };
        (10f64.powf(lo) * (1.0 - 1e-9), 10f64.powf(hi) * (1.0 + 1e-9))
    } else {
        let min = v.fold(f64::INFINITY, f64::min).min(0.0);
        let span = if max > min { max - min } else { 1.0 };
        (min, max + 0.05 * span)
    }
}

/// A tick label: `1e-6` (or `2.5e-6`) on log axes, a short decimal on linear ones.
fn tick(v: f64, log: bool) -> String {
    if log {
        let e = v.abs().log10().floor();
        let m = v / 10f64.powf(e);
        // Ticks are nice numbers; the axis ends are widened by 1e-9, so round the mantissa.
        let m = (m * 100.0).round() / 100.0;
        let (m, e) = if m >= 10.0 {
            (m / 10.0, e + 1.0)
        } else {
            (m, e)
        };
        if (m - 1.0).abs() < 1e-9 {
            format!("1e{e}")
        } else {
            format!("{m}e{e}")
        }
    } else {
        let s = format!("{v:.6}");
        let s = s.trim_end_matches('0').trim_end_matches('.');
        if s == "-0" {
            "0".to_string()
        } else {
            s.to_string()
        }
    }
}

/// The figure with its extras as an SVG document.
pub fn svg(fig: &Figure, extras: &Extras) -> Result<String, Error> {
    if fig.series.iter().all(|s| s.x.is_empty()) || extras.colors.is_empty() {
        return Err(plot_error(format!(
            "{}: no points to plot, or no colours",
            fig.name
        )));
    }
    let xs = fig
        .series
        .iter()
        .flat_map(|s| s.x.iter())
        .chain(extras.markers.iter().filter(|m| m.vertical).map(|m| &m.at))
        .map(|x| x / fig.x.scale);
    let ys = fig
        .series
        .iter()
        .flat_map(|s| s.y.iter())
        .chain(extras.markers.iter().filter(|m| !m.vertical).map(|m| &m.at))
        .map(|y| y / fig.y.scale);
    let (x0, x1) = range(&fig.x, xs, f64::INFINITY);
    let (y0, y1) = range(&fig.y, ys, extras.log_decades);
    let mut out = String::new();
    {
        let root = SVGBackend::with_string(&mut out, extras.size).into_drawing_area();
        root.fill(&WHITE).map_err(plot_error)?;
        match (fig.x.log, fig.y.log) {
            (true, true) => draw(
                &root,
                fig,
                extras,
                (x0..x1).log_scale(),
                (y0..y1).log_scale(),
            ),
            (true, false) => draw(&root, fig, extras, (x0..x1).log_scale(), y0..y1),
            (false, true) => draw(&root, fig, extras, x0..x1, (y0..y1).log_scale()),
            (false, false) => draw(&root, fig, extras, x0..x1, y0..y1),
        }?;
        root.present().map_err(plot_error)?;
    }
    Ok(out)
}

fn draw<X, Y>(
    root: &DrawingArea<SVGBackend, Shift>,
    fig: &Figure,
    extras: &Extras,
    x: X,
    y: Y,
) -> Result<(), Error>
where
    X: AsRangedCoord<Value = f64>,
    Y: AsRangedCoord<Value = f64>,
    X::CoordDescType: ValueFormatter<f64>,
    Y::CoordDescType: ValueFormatter<f64>,
{
    let mut chart = ChartBuilder::on(root)
        .caption(fig.title, ("sans-serif", 20))
        .margin(15)
        .x_label_area_size(50)
        .y_label_area_size(80)
        .build_cartesian_2d(x, y)
        .map_err(plot_error)?;
    let (xlog, ylog) = (fig.x.log, fig.y.log);
    chart
        .configure_mesh()
        .x_desc(fig.x.title())
        .y_desc(fig.y.title())
        .x_label_formatter(&|v| tick(*v, xlog))
        .y_label_formatter(&|v| tick(*v, ylog))
        .label_style(("sans-serif", 14))
        .axis_desc_style(("sans-serif", 16))
        .draw()
        .map_err(plot_error)?;
    let (x_lo, x_hi) = {
        let r = chart.x_range();
        (r.start, r.end)
    };
    let (y_lo, y_hi) = {
        let r = chart.y_range();
        (r.start, r.end)
    };
    let grey = RGBColor(120, 120, 120);
    for (i, b) in extras.bands.iter().enumerate() {
        let (a, z) = (
            (b.from / fig.x.scale).clamp(x_lo, x_hi),
            (b.to / fig.x.scale).clamp(x_lo, x_hi),
        );
        let shade = if i % 2 == 0 {
            RGBColor(200, 215, 240)
        } else {
            RGBColor(245, 215, 170)
        };
        chart
            .draw_series(std::iter::once(Rectangle::new(
                [(a, y_lo), (z, y_hi)],
                shade.mix(0.5).filled(),
            )))
            .map_err(plot_error)?
            .label(b.label.as_str())
            .legend(move |(x, y)| Rectangle::new([(x, y - 5), (x + 20, y + 5)], shade.filled()));
    }
    for (i, s) in fig.series.iter().enumerate() {
        let color = extras.colors[i % extras.colors.len().max(1)];
        // Points outside the value axis's range are left out (the curve leaves the plot).
        let points =
            s.x.iter()
                .zip(&s.y)
                .map(|(x, y)| (x / fig.x.scale, y / fig.y.scale))
                .filter(|&(_, y)| y.is_finite() && y >= y_lo && y <= y_hi);
        chart
            .draw_series(LineSeries::new(points, color.stroke_width(2)))
            .map_err(plot_error)?
            .label(s.label.as_str())
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
            });
    }
    let mut verticals = 0;
    for m in &extras.markers {
        let line = if m.vertical {
            let v = m.at / fig.x.scale;
            if !(x_lo..=x_hi).contains(&v) {
                continue;
            }
            [(v, y_lo), (v, y_hi)]
        } else {
            let v = m.at / fig.y.scale;
            if !(y_lo..=y_hi).contains(&v) {
                continue;
            }
            [(x_lo, v), (x_hi, v)]
        };
        chart
            .draw_series(DashedLineSeries::new(line, 6, 4, grey.stroke_width(2)))
            .map_err(plot_error)?;
        // Vertical lines are labelled just right of their top end, every second one at its
        // bottom end so that neighbours do not overlap; horizontal ones just above their right
        // end (clear of the axes' tick labels).
        let style = ("sans-serif", 13).into_font().color(&BLACK);
        let (anchor, offset, pos) = if m.vertical {
            verticals += 1;
            // A line in the right quarter of the plot is labelled on its left, so that the
            // label stays inside the plot.
            let frac = if fig.x.log {
                (line[0].0 / x_lo).ln() / (x_hi / x_lo).ln()
            } else {
                (line[0].0 - x_lo) / (x_hi - x_lo)
            };
            let (dx, h) = if frac > 0.75 {
                (-4, HPos::Right)
            } else {
                (4, HPos::Left)
            };
            if verticals % 2 == 1 {
                ((line[0].0, y_hi), (dx, 4), Pos::new(h, VPos::Top))
            } else {
                ((line[0].0, y_lo), (dx, -4), Pos::new(h, VPos::Bottom))
            }
        } else {
            (
                (x_hi, line[0].1),
                (-4, -4),
                Pos::new(HPos::Right, VPos::Bottom),
            )
        };
        chart
            .draw_series(std::iter::once(
                EmptyElement::at(anchor) + Text::new(m.label.clone(), offset, style.pos(pos)),
            ))
            .map_err(plot_error)?;
    }
    chart
        .configure_series_labels()
        .position(extras.legend.clone())
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .label_font(("sans-serif", 14))
        .draw()
        .map_err(plot_error)?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::figures::Series;

    fn figure(log: bool) -> Figure {
        let axis = |label| Axis {
            label,
            unit: "MPa",
            scale: 1e6,
            log,
        };
        Figure {
            name: "t",
            title: "Test figure",
            x: axis("thickness"),
            y: axis("stress"),
            series: vec![Series {
                label: "curve".into(),
                x: vec![1e6, 1e7, 1e8],
                y: vec![2e6, 3e6, 5e6],
                err: vec![0.0; 3],
            }],
        }
    }

    #[test]
    fn svg_has_axes_titles_markers_and_bands() {
        let extras = Extras {
            markers: vec![
                Marker {
                    at: 4e6,
                    vertical: false,
                    label: "limit 4 MPa".into(),
                },
                Marker {
                    at: 3e7,
                    vertical: true,
                    label: "d_min".into(),
                },
            ],
            bands: vec![Band {
                from: 1e6,
                to: 2e6,
                label: "lowest octave".into(),
            }],
            ..Extras::default()
        };
        for log in [true, false] {
            let s = svg(&figure(log), &extras).unwrap();
            assert!(s.starts_with("<svg"), "{}", &s[..40]);
            for text in [
                "Test figure",
                "thickness [MPa]",
                "stress [MPa]",
                "limit 4 MPa",
                "d_min",
                "lowest octave",
                "curve",
            ] {
                assert!(s.contains(text), "log = {log}: no '{text}'");
            }
            assert!(s.contains("<polyline"), "no line drawn");
            assert!(s.contains("stroke-dasharray") || s.matches("<polyline").count() >= 3);
        }
    }

    #[test]
    fn a_figure_without_points_is_an_error() {
        let mut f = figure(true);
        f.series[0].x.clear();
        f.series[0].y.clear();
        assert!(svg(&f, &Extras::default()).is_err());
    }

    #[test]
    fn log_range_covers_whole_decades_and_a_constant_gets_one() {
        let a = Axis {
            label: "x",
            unit: "",
            scale: 1.0,
            log: true,
        };
        let (lo, hi) = range(&a, [2.0, 30.0].into_iter(), LOG_DECADES);
        assert!((lo - 1.0).abs() < 1e-8 && (hi - 100.0).abs() < 1e-6);
        let (lo, hi) = range(&a, [1e-20, 1.0].into_iter(), LOG_DECADES);
        assert!((lo - 1e-6).abs() < 1e-14, "{lo}");
        let (lo, hi2) = range(&a, [10.0, 10.0].into_iter(), LOG_DECADES);
        assert!(hi < 1.0 + 1e-6 && hi2 > 99.0);
        assert!(lo < 10.0 + 1e-6, "{lo}");
    }

    #[test]
    fn ticks_read_as_people_write_them() {
        assert_eq!(tick(1e-5 * (1.0 - 1e-9), true), "1e-5");
        assert_eq!(tick(9.999999999e-6, true), "1e-5");
        assert_eq!(tick(2.5e-6, true), "2.5e-6");
        assert_eq!(tick(100.0, true), "1e2");
        assert_eq!(tick(0.25, false), "0.25");
        assert_eq!(tick(-0.0, false), "0");
    }
}
