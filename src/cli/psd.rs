//! `coatcheck psd FILE`: heights (line scans or a height map) → power spectrum.
//!
//! Writes `q (1/m), C (m^4)` (plus `C1D (m^3)` for line scans, on the same q) as CSV, through
//! a temporary file and a rename, and prints the processing steps and a summary (h_rms, rms
//! slope, rms curvature, kept q-range, share of h_rms² outside it).

use coatcheck::Error;
use coatcheck::psd::abel::Conversion;
use coatcheck::report::finite::Finite;
use coatcheck::report::{sig, table, um};
use coatcheck::topography::io::HeightKind;
use coatcheck::topography::spectrum::{Detrend, PsdOptions, TopographyPsd, Window};
use coatcheck::topography::{FileInfo, HeightFileOptions, psd_of_file};
use coatcheck::units::{Dim, parse_quantity};
use std::io::Write;
use std::path::PathBuf;

#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum KindArg {
    /// Decide from the file: its metadata comment, a header line (line scans), --dx (line
    /// scans) or --pixel-size (map).
    Auto,
    Lines,
    Map,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum WindowArg {
    Hann,
    None,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum DetrendArg {
    Mean,
    Tilt,
    Curvature,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum ConversionArg {
    /// Exact: inverse Abel transform of the 1D PSD.
    InverseAbel,
    /// C = C1D/(πq), exact only for H = 1.
    PiQShortcut,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum FormatArg {
    Table,
    Csv,
    Json,
}

/// Heights → PSD. Height units: --z-unit (default m, or the file's header or metadata).
/// Exit code 0 on success; 2 on bad input, with one line on stderr naming the file and line,
/// and no output file written.
#[derive(Debug, clap::Args)]
#[command(after_help = "Exit codes: 0 success, 2 bad input or a numerical failure.")]
pub struct PsdArgs {
    /// An instrument file (x3p, sdf, sur, gwy, …), line scans (`x,z…` columns, or `z…` with
    /// --dx) or a height map (CSV matrix).
    pub file: PathBuf,
    /// What the file holds.
    #[arg(long, value_enum, default_value = "auto")]
    pub kind: KindArg,
    /// Line scans: sample spacing (e.g. 0.5um) for files without an x column.
    #[arg(long)]
    pub dx: Option<String>,
    /// Height map: pixel size (e.g. 1um), or the x size when --pixel-size-y differs.
    #[arg(long)]
    pub pixel_size: Option<String>,
    /// Height map: pixel size along y (between lines), if different from x.
    #[arg(long)]
    pub pixel_size_y: Option<String>,
    /// Unit of the heights (m, um, nm).
    #[arg(long)]
    pub z_unit: Option<String>,
    /// Unit of the x column of line scans.
    #[arg(long)]
    pub x_unit: Option<String>,
    /// The data are one period of a periodic surface (default window: none).
    #[arg(long)]
    pub periodic: bool,
    /// Window (default: hann, or none for periodic data).
    #[arg(long, value_enum)]
    pub window: Option<WindowArg>,
    /// Trend removed first (default: tilt, or mean for periodic data).
    #[arg(long, value_enum)]
    pub detrend: Option<DetrendArg>,
    /// Log-spaced q bins per decade.
    #[arg(long, default_value_t = 10)]
    pub points_per_decade: usize,
    /// Shortest wavelength kept, in pixels (2 = Nyquist).
    #[arg(long, default_value_t = 4.0)]
    pub cutoff_pixels: f64,
    /// Line scans: how the 1D PSD becomes the 2D PSD.
    #[arg(long, value_enum, default_value = "inverse-abel")]
    pub conversion: ConversionArg,
    /// Write the PSD as CSV here (atomically).
    #[arg(long, short)]
    pub output: Option<PathBuf>,
    /// Instrument files: the channel to use, by name or 1-based number (default: the first
    /// height channel).
    #[arg(long)]
    pub channel: Option<String>,
    /// What to print: summary table, CSV, or one JSON object.
    #[arg(long, value_enum, default_value = "table")]
    pub format: FormatArg,
}

fn length(flag: &'static str, v: &Option<String>) -> Result<Option<f64>, Error> {
    v.as_deref()
        .map(|s| {
            let x = parse_quantity(s, Dim::Length(1)).map_err(|e| {
                Error::invalid(flag, format!("'{s}' ({e})"), "a length such as 0.5um")
            })?;
            if x.is_finite() && x > 0.0 {
                Ok(x)
            } else {
                Err(Error::invalid(flag, s, "a length > 0"))
            }
        })
        .transpose()
}

/// Run `coatcheck psd`; returns the exit code (0) or an error (exit code 2).
pub fn run(a: PsdArgs) -> Result<i32, Error> {
    let dx = length("--dx", &a.dx)?;
    let px = length("--pixel-size", &a.pixel_size)?;
    let py = length("--pixel-size-y", &a.pixel_size_y)?;
    let periodic = a.periodic.then_some(true);
    let opts = PsdOptions {
        detrend: a.detrend.map(|d| match d {
            DetrendArg::Mean => Detrend::Mean,
            DetrendArg::Tilt => Detrend::Tilt,
            DetrendArg::Curvature => Detrend::Curvature,
        }),
        window: a.window.map(|w| match w {
            WindowArg::Hann => Window::Hann,
            WindowArg::None => Window::None,
        }),
        points_per_decade: a.points_per_decade,
        cutoff_pixels: a.cutoff_pixels,
        conversion: match a.conversion {
            ConversionArg::InverseAbel => Conversion::InverseAbel,
            ConversionArg::PiQShortcut => Conversion::PiQShortcut,
        },
    };
    let file = HeightFileOptions {
        kind: match a.kind {
            KindArg::Auto => None,
            KindArg::Lines => Some(HeightKind::Lines),
            KindArg::Map => Some(HeightKind::Map),
        },
        dx,
        pixel_size: px,
        pixel_size_y: py,
        x_unit: a.x_unit.clone(),
        z_unit: a.z_unit.clone(),
        periodic,
        channel: a.channel.clone(),
    };
    let (info, result) = psd_of_file(&a.file, &file, &opts)?;
    let input = a.file.display().to_string();
    // The summary numbers every format shows, checked as text first (JSON shows a NaN as null,
    // and the CSV's comment line is prose); the data rows are checked as they are written.
    let mut summary = Vec::new();
    write_summary_csv(&mut summary, &result).map_err(|source| Error::Io {
        path: PathBuf::from("<memory>"),
        source,
    })?;
    coatcheck::report::finite_only(&String::from_utf8_lossy(&summary))?;
    if let Some(out) = &a.output {
        coatcheck::report::write_with(out, |w| write_csv(w, &input, &info, &result))?;
    }
    let mut stdout = Finite::new(std::io::stdout().lock());
    let printed = match a.format {
        FormatArg::Table => {
            writeln!(
                stdout,
                "{}",
                summary_table(&input, &info, &result, a.output.as_ref())
            )
        }
        FormatArg::Csv => match &a.output {
            None => write_csv(&mut stdout, &input, &info, &result),
            Some(_) => write_summary_csv(&mut stdout, &result).and_then(|()| {
                info.warnings
                    .iter()
                    .try_for_each(|w| writeln!(stdout, "# warning: {w}"))
            }),
        },
        FormatArg::Json => writeln!(stdout, "{}", json(&input, &info, &result)),
    };
    printed
        .and_then(|()| stdout.finish())
        .map_err(|source| Error::Io {
            path: PathBuf::from("<stdout>"),
            source,
        })?;
    Ok(0)
}

fn write_csv(
    w: &mut dyn Write,
    input: &str,
    info: &FileInfo,
    r: &TopographyPsd,
) -> std::io::Result<()> {
    writeln!(w, "# coatcheck psd of {input}")?;
    for s in &r.steps {
        writeln!(w, "# {s}")?;
    }
    for warning in &info.warnings {
        writeln!(w, "# warning: {warning}")?;
    }
    let s = r.summary;
    writeln!(
        w,
        "# h_rms = {:e} m, rms slope = {:e}, rms curvature = {:e} 1/m, kept q = [{:e}, {:e}] 1/m, outside fraction of h_rms^2 = {:e}",
        s.h_rms, s.rms_slope, s.rms_curvature, s.q_min, s.q_max, s.outside_fraction
    )?;
    match &r.c1d {
        None => {
            writeln!(w, "q (1/m),C (m^4)")?;
            for (q, c) in r.c2d.q().iter().zip(r.c2d.c_values()) {
                writeln!(w, "{q:e},{c:e}")?;
            }
        }
        Some(c1d) => {
            writeln!(w, "q (1/m),C (m^4),C1D (m^3)")?;
            for ((q, c), c1) in r.c2d.q().iter().zip(r.c2d.c_values()).zip(c1d.c_values()) {
                writeln!(w, "{q:e},{c:e},{c1:e}")?;
            }
        }
    }
    Ok(())
}

/// The summary as CSV, `quantity,value,unit`, the quantities named as in the JSON's `summary`.
fn write_summary_csv(w: &mut dyn Write, r: &TopographyPsd) -> std::io::Result<()> {
    let s = r.summary;
    writeln!(w, "quantity,value,unit")?;
    for (key, value, unit) in [
        ("h_rms_m", s.h_rms, "m"),
        ("h_rms_kept_m", s.h_rms_kept, "m"),
        ("rms_slope", s.rms_slope, "1"),
        ("rms_curvature_per_m", s.rms_curvature, "1/m"),
        ("q_min_per_m", s.q_min, "1/m"),
        ("q_max_per_m", s.q_max, "1/m"),
        ("outside_fraction", s.outside_fraction, "1"),
    ] {
        writeln!(w, "{key},{value:e},{unit}")?;
    }
    Ok(())
}

fn summary_table(input: &str, info: &FileInfo, r: &TopographyPsd, out: Option<&PathBuf>) -> String {
    let s = r.summary;
    let mut steps = table(&["step"]);
    for st in &r.steps {
        steps.add_row(vec![st.clone()]);
    }
    let mut t = table(&["quantity", "value"]);
    t.add_row(vec![
        "input".to_string(),
        format!(
            "{input} ({})",
            if info.kind == HeightKind::Map {
                "height map"
            } else {
                "line scans"
            }
        ),
    ]);
    if let Some(ch) = &info.channel {
        t.add_row(vec![
            "format, channel".to_string(),
            format!(
                "{}, {ch} (channels: {})",
                info.format,
                info.channels.join(", ")
            ),
        ]);
        t.add_row(vec![
            "grid used".to_string(),
            format!(
                "{} points ({:.3} % of the channel; {:.3} % not measured, {:.3} % filled)",
                info.grid
                    .iter()
                    .map(|n| n.to_string())
                    .collect::<Vec<_>>()
                    .join("×"),
                100.0 * info.used_fraction,
                100.0 * info.missing_fraction,
                100.0 * info.filled_fraction
            ),
        ]);
    }
    t.add_row(vec![
        "h_rms (all wavelengths)".into(),
        format!("{} µm", um(s.h_rms)),
    ]);
    t.add_row(vec![
        "h_rms (kept q-range)".into(),
        format!("{} µm", um(s.h_rms_kept)),
    ]);
    t.add_row(vec!["rms slope (kept)".into(), sig(s.rms_slope, 4)]);
    t.add_row(vec![
        "rms curvature (kept)".into(),
        format!("{} 1/µm", sig(s.rms_curvature * 1e-6, 4)),
    ]);
    t.add_row(vec![
        "kept q-range".into(),
        format!("{} – {} 1/m", sig(s.q_min, 4), sig(s.q_max, 4)),
    ]);
    t.add_row(vec![
        "share of h_rms² outside".into(),
        format!("{} %", sig(100.0 * s.outside_fraction, 3)),
    ]);
    t.add_row(vec![
        "PSD points".into(),
        match out {
            Some(p) => format!("{} (written to {})", r.c2d.q().len(), p.display()),
            None => format!("{} (use --output FILE to save them)", r.c2d.q().len()),
        },
    ]);
    let warnings: String = info
        .warnings
        .iter()
        .map(|w| format!("\nwarning: {w}"))
        .collect();
    format!("{steps}\n{t}{warnings}")
}

/// The JSON object (schema `src/report/schema/psd.schema.json`; SI, the unit in each key).
fn json(input: &str, info: &FileInfo, r: &TopographyPsd) -> serde_json::Value {
    let s = r.summary;
    serde_json::json!({
        "schema_version": coatcheck::report::SCHEMA_VERSION,
        "coatcheck_version": env!("CARGO_PKG_VERSION"),
        "input": input,
        "kind": if info.kind == HeightKind::Map { "map" } else { "lines" },
        "format": info.format,
        "channel": info.channel,
        "channels": info.channels,
        "grid": info.grid,
        "size_m": info.size(),
        "pixel_size_m": info.pixel_size,
        "height_unit_in_file": info.height_unit_in_file,
        "missing_fraction": info.missing_fraction,
        "used_fraction": info.used_fraction,
        "filled_fraction": info.filled_fraction,
        "steps": r.steps,
        "warnings": info.warnings,
        "summary": {
            "h_rms_m": s.h_rms,
            "h_rms_kept_m": s.h_rms_kept,
            "rms_slope": s.rms_slope,
            "rms_curvature_per_m": s.rms_curvature,
            "q_min_per_m": s.q_min,
            "q_max_per_m": s.q_max,
            "outside_fraction": s.outside_fraction,
        },
        "q_per_m": r.c2d.q(),
        "c_m4": r.c2d.c_values(),
        "c1d_m3": r.c1d.as_ref().map(|t| t.c_values()),
    })
}
