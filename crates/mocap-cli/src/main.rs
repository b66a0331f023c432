//! `mocap`: inspect, validate and convert motion-capture files from the shell.
//!
//! Errors go to stderr as `FILE:LINE:COL: message` with a non-zero exit status.

mod commands;

use clap::{Parser, Subcommand};
use std::path::PathBuf;
use std::process::ExitCode;

/// Motion-capture files: info, poses, validation and conversion.
#[derive(Parser)]
#[command(name = "mocap", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Skeletons, joints, channels, frames, timing, bounding box, units and warnings.
    Info {
        /// The motion file.
        file: PathBuf,
        /// Print JSON instead of text.
        #[arg(long)]
        json: bool,
    },
    /// World positions of every joint (End Sites included) at one frame.
    Pose {
        /// The motion file.
        file: PathBuf,
        /// Frame index, 0-based.
        #[arg(long, default_value_t = 0)]
        frame: usize,
        /// Print JSON (the only output form; accepted for clarity).
        #[arg(long)]
        json: bool,
    },
    /// Converts a motion file to BVH.
    Convert {
        /// Input file.
        input: PathBuf,
        /// Output file (.bvh).
        #[arg(short, long)]
        output: PathBuf,
    },
    /// Checks files or directories (recursively): one line per file.
    Validate {
        /// Files or directories.
        #[arg(required = true)]
        paths: Vec<PathBuf>,
    },
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Info { file, json } => commands::info(&file, json),
        Command::Pose { file, frame, json: _ } => commands::pose(&file, frame),
        Command::Convert { input, output } => commands::convert(&input, &output),
        Command::Validate { paths } => commands::validate(&paths),
    };
    match result {
        Ok(code) => code,
        Err(message) => {
            eprintln!("{message}");
            ExitCode::FAILURE
        }
    }
}
