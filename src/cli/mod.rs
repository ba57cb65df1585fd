//! Command-line definitions and dispatch. Errors are mapped to messages and exit codes here only:
//! 0 all checks pass, 1 a check fails, 2 bad input or a numerical failure.

use clap::{Parser, Subcommand};

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
enum Command {}

pub fn run() -> i32 {
    let cli = Cli::parse();
    match cli.command {}
}
