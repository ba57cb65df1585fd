//! Shared by the figure examples (`examples/figNN.rs`): compute a figure of
//! `coatcheck::figures` at full resolution, write `<out>/figNN.csv` (series, x, y, y_err in
//! the axes' display units, named in the header) and `<out>/figNN.svg` (plotters, SVG backend:
//! log axes where the figure's are, axis titles with units, a legend). The output directory is
//! the first argument (default `target/figures`); each file is written to a temporary file in
//! the same directory and renamed into place, so no half-written file is ever left.

use coatcheck::figures::{Axis, Figure};
use plotters::coord::ranged1d::{AsRangedCoord, ValueFormatter};
use plotters::prelude::*;
use std::error::Error;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Width and height of the SVG, px.
const SIZE: (u32, u32) = (800, 600);
/// A log axis shows at most this many decades below the largest value (curves that fall
/// further, e.g. interface stresses of thick films, leave the plot at its bottom).
const LOG_DECADES: f64 = 6.0;

/// Where the legend goes (chosen per figure so it does not cover the curves).
pub use plotters::chart::SeriesLabelPosition as Legend;

/// Compute the figure with `n` points per series, write its CSV and SVG, print where and how
/// long it took; on failure print the error and exit with status 1.
pub fn run(
    make: impl Fn(usize) -> Result<Figure, coatcheck::Error>,
    n: usize,
    colors: &[RGBColor],
    legend: Legend,
) {
    let dir = std::env::args_os()
        .nth(1)
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from("target/figures"));
    let started = Instant::now();
    let result = make(n).map_err(Box::<dyn Error>::from).and_then(|fig| {
        let seconds = started.elapsed().as_secs_f64();
        let [csv, svg] = write(&fig, &dir, colors, legend)?;
        println!(
            "{}: {} series x {n} points computed in {seconds:.3} s; wrote {} and {}",
            fig.name,
            fig.series.len(),
            csv.display(),
            svg.display()
        );
        Ok(())
    });
    if let Err(e) = result {
        eprintln!("error: {e}");
        std::process::exit(1);
    }
}

/// Write `<dir>/<name>.csv` and `<dir>/<name>.svg` (creating `dir`); returns their paths.
pub fn write(
    fig: &Figure,
    dir: &Path,
    colors: &[RGBColor],
    legend: Legend,
) -> Result<[PathBuf; 2], Box<dyn Error>> {
    std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let csv = dir.join(format!("{}.csv", fig.name));
    let svg = dir.join(format!("{}.svg", fig.name));
    write_atomically(&csv, csv_text(fig)?.as_bytes())?;
    write_atomically(&svg, svg_text(fig, colors, legend)?.as_bytes())?;
    Ok([csv, svg])
}

/// Write `bytes` to a temporary file next to `path`, then rename it over `path`.
fn write_atomically(path: &Path, bytes: &[u8]) -> Result<(), Box<dyn Error>> {
    let name = path.file_name().ok_or("output path has no file name")?;
    let tmp = path.with_file_name(format!(".{}.tmp", name.to_string_lossy()));
    let written = std::fs::write(&tmp, bytes)
        .map_err(|e| format!("{}: {e}", tmp.display()))
        .and_then(|()| std::fs::rename(&tmp, path).map_err(|e| format!("{}: {e}", path.display())));
    if written.is_err() {
        // Best effort: a failed write must not leave a partial temporary file behind.
        let _ = std::fs::remove_file(&tmp);
    }
    Ok(written?)
}

/// CSV in display units: `series,<x title>,<y title>,<y title> error`.
fn csv_text(fig: &Figure) -> Result<String, Box<dyn Error>> {
    let mut w = csv::Writer::from_writer(Vec::new());
    let (xt, yt) = (fig.x.title(), fig.y.title());
    w.write_record(["series", &xt, &yt, &format!("{yt} error")])?;
    for s in &fig.series {
        for ((x, y), e) in s.x.iter().zip(&s.y).zip(&s.err) {
            w.write_record([
                s.label.clone(),
                format!("{:e}", x / fig.x.scale),
                format!("{:e}", y / fig.y.scale),
                format!("{:e}", e / fig.y.scale),
            ])?;
        }
    }
    Ok(String::from_utf8(w.into_inner()?)?)
}

/// The range shown on an axis for the values `v` (display units).
fn range(axis: &Axis, v: impl Iterator<Item = f64> + Clone) -> (f64, f64) {
    let max = v.clone().fold(f64::NEG_INFINITY, f64::max);
    if axis.log {
        let floor = max / 10f64.powf(LOG_DECADES);
        let min = v.filter(|&v| v > 0.0).fold(f64::INFINITY, f64::min);
        // Whole decades around the data, widened by a hair so that rounding in the data or in
        // the axis's own key points does not drop the end decades' tick labels.
        (
            10f64.powf(min.max(floor).log10().floor()) * (1.0 - 1e-9),
            10f64.powf(max.log10().ceil()) * (1.0 + 1e-9),
        )
    } else {
        let min = v.fold(f64::INFINITY, f64::min).min(0.0);
        (min, max + 0.05 * (max - min))
    }
}

/// A tick label: `1e-6` on log axes, a short decimal on linear ones.
fn tick(v: f64, log: bool) -> String {
    if log {
        format!("{v:e}")
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

fn svg_text(fig: &Figure, colors: &[RGBColor], legend: Legend) -> Result<String, Box<dyn Error>> {
    let xs = fig
        .series
        .iter()
        .flat_map(|s| s.x.iter())
        .map(|x| x / fig.x.scale);
    let ys = fig
        .series
        .iter()
        .flat_map(|s| s.y.iter())
        .map(|y| y / fig.y.scale);
    let (x0, x1) = range(&fig.x, xs);
    let (y0, y1) = range(&fig.y, ys);
    let mut out = String::new();
    {
        let root = SVGBackend::with_string(&mut out, SIZE).into_drawing_area();
        root.fill(&WHITE)?;
        match (fig.x.log, fig.y.log) {
            (true, true) => draw(
                &root,
                fig,
                (x0..x1).log_scale(),
                (y0..y1).log_scale(),
                colors,
                legend,
            ),
            (true, false) => draw(&root, fig, (x0..x1).log_scale(), y0..y1, colors, legend),
            (false, true) => draw(&root, fig, x0..x1, (y0..y1).log_scale(), colors, legend),
            (false, false) => draw(&root, fig, x0..x1, y0..y1, colors, legend),
        }?;
        root.present()?;
    }
    Ok(out)
}

fn draw<X, Y>(
    root: &DrawingArea<SVGBackend, plotters::coord::Shift>,
    fig: &Figure,
    x: X,
    y: Y,
    colors: &[RGBColor],
    legend: Legend,
) -> Result<(), Box<dyn Error>>
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
        .build_cartesian_2d(x, y)?;
    let (xlog, ylog) = (fig.x.log, fig.y.log);
    chart
        .configure_mesh()
        .x_desc(fig.x.title())
        .y_desc(fig.y.title())
        .x_label_formatter(&|v| tick(*v, xlog))
        .y_label_formatter(&|v| tick(*v, ylog))
        .label_style(("sans-serif", 14))
        .axis_desc_style(("sans-serif", 16))
        .draw()?;
    let (y_lo, y_hi) = {
        let r = chart.y_range();
        (r.start, r.end)
    };
    for (i, s) in fig.series.iter().enumerate() {
        let color = colors[i % colors.len()];
        // Points below a log axis's range are left out (the curve leaves at the bottom).
        let points =
            s.x.iter()
                .zip(&s.y)
                .map(|(x, y)| (x / fig.x.scale, y / fig.y.scale))
                .filter(|&(_, y)| y >= y_lo && y <= y_hi);
        chart
            .draw_series(LineSeries::new(points, color.stroke_width(2)))?
            .label(s.label.as_str())
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
            });
    }
    chart
        .configure_series_labels()
        .position(legend)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .label_font(("sans-serif", 14))
        .draw()?;
    Ok(())
}
