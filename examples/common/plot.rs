//! Shared by the figure examples (`examples/figNN.rs`): compute a figure of
//! `coatcheck::figures` at full resolution, write `<out>/figNN.csv` (series, x, y, y_err in
//! the axes' display units, named in the header) and `<out>/figNN.svg` (plotters, SVG backend:
//! log axes where the figure's are, axis titles with units, a legend). The output directory is
//! the first argument (default `target/figures`); each file goes through the library's one
//! writer (`coatcheck::report::write_file`), so no half-written file is ever left.

use coatcheck::figures::Figure;
use coatcheck::report::plot::{Extras, RGBColor};
use std::error::Error;
use std::path::{Path, PathBuf};
use std::time::Instant;

pub use coatcheck::report::plot::Legend;

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
    coatcheck::report::write_file(&csv, &csv_text(fig)?)?;
    coatcheck::report::write_file(&svg, &svg_text(fig, colors, legend)?)?;
    Ok([csv, svg])
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

fn svg_text(fig: &Figure, colors: &[RGBColor], legend: Legend) -> Result<String, Box<dyn Error>> {
    let extras = Extras {
        legend,
        colors: colors.to_vec(),
        ..Extras::default()
    };
    Ok(coatcheck::report::plot::svg(fig, &extras)?)
}
