//! Command-line definitions and dispatch. Errors are mapped to messages and exit codes here only:
//! 0 all checks pass, 1 a check fails, 2 bad input or a numerical failure.

mod check;
mod check_args;
mod check_stack;
mod materials;

use clap::{Parser, Subcommand};

mod psd;
mod response;
mod response_stack;
mod synth;
mod verify;
mod verify_stack;

#[derive(Parser)]
#[command(
    name = "coatcheck",
    version,
    about = "Qualify soft coatings on hard substrates against surface roughness"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Judge a coating design: contact area, interface stresses, pass/fail checks, d_min.
    Check(Box<check::CheckArgs>),
    /// List the materials library (bundled, plus --materials DIR).
    Materials(materials::MaterialsArgs),
    /// Layer response S, f, g over q·d (eq. 7 and the static App. B kernels; Fig. 14), or over q
    /// at every interface of a layer stack (`--layer`).
    Response(response::ResponseArgs),
    /// Heights (line scans or a height map) → power spectrum C(q), with a summary.
    Psd(psd::PsdArgs),
    /// Write a synthetic self-affine surface (fixed seed) as a height map or line scans.
    Synth(synth::SynthArgs),
    /// Exact contact on a height map (FFT boundary elements) beside Persson's estimate.
    Verify(verify::VerifyArgs),
}

/// `--format` of `check`: the report's formats as a command-line value.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum OutputFormat {
    Table,
    Json,
    Csv,
}

impl From<OutputFormat> for coatcheck::report::Format {
    fn from(f: OutputFormat) -> Self {
        match f {
            OutputFormat::Table => Self::Table,
            OutputFormat::Json => Self::Json,
            OutputFormat::Csv => Self::Csv,
        }
    }
}

pub fn run() -> i32 {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Check(args) => check::run(*args),
        Command::Materials(args) => materials::run(args),
        Command::Response(a) => response::run(a),
        Command::Psd(a) => psd::run(a),
        Command::Synth(a) => synth::run(a),
        Command::Verify(a) => verify::run(a),
    };
    match result {
        Ok(code) => code,
        // The reader went away (`| head`): end quietly, as coreutils and ripgrep do.
        Err(e) if coatcheck::report::is_broken_pipe(&e) => 0,
        Err(e) => {
            eprintln!("coatcheck: {e}");
            2
        }
    }
}
