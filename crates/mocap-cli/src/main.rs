//! `mocap`: inspect, validate and convert motion-capture files from the shell.
//!
//! Errors go to stderr as `FILE:LINE:COL: message` with a non-zero exit status.

use mocap_cli::commands;
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
    /// Skeletons, joints, channels, frames, timing, bounding box, units, what the
    /// file says about itself and warnings.
    Info {
        /// The motion file (BVH, BVA, ASF, or an AMC: its .asf is found beside it, or give both), or a Quake 2 .md2 model.
        #[arg(required = true, num_args = 1..=2)]
        files: Vec<PathBuf>,
        /// Print JSON instead of text.
        #[arg(long)]
        json: bool,
    },
    /// World positions of every joint (End Sites included) at one frame.
    Pose {
        /// The motion file (an AMC finds its .asf, or give both).
        #[arg(required = true, num_args = 1..=2)]
        files: Vec<PathBuf>,
        /// Frame index, 0-based.
        #[arg(long, default_value_t = 0)]
        frame: usize,
        /// Print JSON (the only output form; accepted for clarity).
        #[arg(long)]
        json: bool,
    },
    /// Solves IK at one frame: pulls a joint to a target and prints the corrected
    /// pose's world positions (as `pose` does).
    Ik {
        /// The motion file (an AMC finds its .asf, or give both).
        #[arg(required = true, num_args = 1..=2)]
        files: Vec<PathBuf>,
        /// The joint to move (the end effector).
        #[arg(long)]
        joint: String,
        /// Where it should go: x,y,z in the file's units and model space.
        #[arg(long, allow_hyphen_values = true)]
        target: String,
        /// Frame index, 0-based.
        #[arg(long, default_value_t = 0)]
        frame: usize,
        /// Bones in the chain above the joint (default: the limb's two for a hand or
        /// foot of a humanoid, else 2).
        #[arg(long)]
        bones: Option<usize>,
        /// two-bone, ccd or fabrik (default: two-bone for two bones, else fabrik).
        #[arg(long)]
        solver: Option<String>,
        /// Print JSON (the only output form; accepted for clarity).
        #[arg(long)]
        json: bool,
    },
    /// Converts a motion to BVH (every joint position kept) or BVA (each joint's world transform a segment).
    Convert {
        /// Input file(s): one motion file, or an Acclaim skeleton and motion (`SKEL.asf TAKE.amc`).
        #[arg(required = true, num_args = 1..=2)]
        inputs: Vec<PathBuf>,
        /// Output file (.bvh or .bva).
        #[arg(short, long)]
        output: PathBuf,
    },
    /// Renders clips and models to PNG headlessly (wgpu on Vulkan; Mesa lavapipe without a GPU).
    Render {
        /// One or more motion or model files, drawn side by side (Acclaim: skeleton and motions; MD2: the model and its skin image).
        #[arg(required = true)]
        files: Vec<PathBuf>,
        /// A skin image (PCX, BMP, PNG, JPEG) for the MD2 model(s); same as giving it among the files.
        #[arg(long)]
        skin: Vec<PathBuf>,
        /// The animation MD2 models play (`run`, `stand`, …; default `all`, every frame in file order).
        #[arg(long)]
        animation: Option<String>,
        /// Frame to render (in the first file's frame time; default 0).
        #[arg(long, conflicts_with_all = ["time", "frames", "sheet"])]
        frame: Option<usize>,
        /// Time in seconds to render (interpolated).
        #[arg(long, conflicts_with_all = ["frames", "sheet"])]
        time: Option<f64>,
        /// A sequence `a:b:step` (end inclusive, step default 1); --out is a directory.
        #[arg(long, conflicts_with = "sheet")]
        frames: Option<String>,
        /// A contact sheet of evenly spaced frames over the whole clip.
        #[arg(long)]
        sheet: bool,
        /// Columns of the contact sheet (rows follow from the aspect).
        #[arg(long, default_value_t = 4)]
        columns: u32,
        /// Output PNG (or directory for --frames).
        #[arg(long)]
        out: PathBuf,
        /// Image size WIDTHxHEIGHT (the whole sheet for --sheet).
        #[arg(long, default_value = "1280x720")]
        size: String,
        /// Draw mode: capsules (lit solids per bone), sticks (lines and joints) or body (a skinned body around the bones).
        #[arg(long, default_value = "capsules")]
        mode: String,
        /// Camera `yaw,pitch[,distance]` in degrees and metres (default frames the motion).
        #[arg(long, allow_hyphen_values = true)]
        camera: Option<String>,
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
        Command::Info { files, json } => commands::info(&files, json),
        Command::Pose { files, frame, json: _ } => commands::pose(&files, frame),
        Command::Convert { inputs, output } => commands::convert(&inputs, &output),
        Command::Ik { files, joint, target, frame, bones, solver, json: _ } => {
            commands::ik(&files, &commands::IkRequest { joint: &joint, target: &target, frame, bones, solver: solver.as_deref() })
        }
        Command::Validate { paths } => commands::validate(&paths),
        Command::Render { mut files, skin, animation, frame, time, frames, sheet, columns, out, size, mode, camera } => {
            files.extend(skin);
            let shot = match (frame, time, frames, sheet) {
                (_, Some(t), _, _) => commands::Shot::Time(t),
                (_, _, Some(range), _) => commands::Shot::Sequence(range),
                (_, _, _, true) => commands::Shot::Sheet(columns),
                (f, ..) => commands::Shot::Frame(f.unwrap_or(0)),
            };
            let options = commands::RenderOptions { mode: &mode, camera: camera.as_deref(), animation: animation.as_deref() };
            commands::render(&files, shot, &out, &size, &options)
        }
    };
    match result {
        Ok(code) => code,
        Err(message) => {
            eprintln!("{message}");
            ExitCode::FAILURE
        }
    }
}
