//! `mocap`: inspect, validate and convert motion-capture files from the shell.
//!
//! Errors go to stderr as `FILE:LINE:COL: message` with a non-zero exit status.

use clap::{ArgMatches, CommandFactory, FromArgMatches, Parser, Subcommand};
use mocap::ops::edit::{Edit, EditSpec};
use mocap_cli::commands;
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
        /// The motion file (an AMC finds its .asf, or give both; a .gltf finds its .bin).
        #[arg(required = true, num_args = 1..=2)]
        files: Vec<PathBuf>,
        /// Frame index, 0-based.
        #[arg(long, default_value_t = 0, conflicts_with = "time")]
        frame: usize,
        /// Time in seconds instead of a frame (sampled between frames).
        #[arg(long)]
        time: Option<f64>,
        /// The animation of a glTF file (default: its first).
        #[arg(long)]
        animation: Option<String>,
        /// How --time is sampled between frames: nearest, linear (default) or cubic.
        #[arg(long, requires = "time")]
        interpolation: Option<String>,
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
    /// Edits a motion and writes BVH: the edits apply in the order given.
    Edit {
        /// The motion file (an AMC finds its .asf, or give both).
        #[arg(required = true, num_args = 1..=2)]
        files: Vec<PathBuf>,
        /// Output file (.bvh).
        #[arg(short, long)]
        output: PathBuf,
        /// Keep frames a:b (inclusive).
        #[arg(long, value_name = "A:B")]
        trim: Vec<String>,
        /// Resample to this frame rate: N (linear in-betweens) or N:cubic
        /// (Catmull-Rom positions, squad rotations; smooth across frames).
        #[arg(long, value_name = "N[:cubic]")]
        fps: Vec<String>,
        /// Play backward.
        #[arg(long)]
        reverse: bool,
        /// Forward then backward, a seamless loop.
        #[arg(long)]
        ping_pong: bool,
        /// Blend the last N frames into the first so the loop is seamless.
        #[arg(long, value_name = "N")]
        knit: Vec<usize>,
        /// Remove the root's horizontal travel (its height stays).
        #[arg(long)]
        in_place: bool,
        /// Also remove the root's turning (with --in-place's effect).
        #[arg(long)]
        in_place_turning: bool,
        /// The file's up axis (x, y, z, -x, -y, -z): turn it to stand Y-up.
        #[arg(long, allow_hyphen_values = true)]
        up: Vec<String>,
        /// Convert lengths from the guessed unit to m, dm, cm, mm or in.
        #[arg(long)]
        units: Vec<String>,
        /// Multiply every length by this factor.
        #[arg(long)]
        scale: Vec<f32>,
        /// Rename a joint: OLD=NEW.
        #[arg(long, value_name = "OLD=NEW")]
        rename: Vec<String>,
        /// Remove a joint, folding its motion into its children (no position changes).
        #[arg(long, value_name = "JOINT")]
        remove: Vec<String>,
        /// Remove a joint and drop its motion.
        #[arg(long, value_name = "JOINT")]
        drop_joint: Vec<String>,
    },
    /// Layers a second motion on a subtree of a base motion (a wave on the right arm
    /// over a walk) and writes BVH.
    Layer {
        /// The base motion (BVH, BVA, or an Acclaim pair).
        base: PathBuf,
        /// The base joint whose subtree the layer drives.
        #[arg(long)]
        subtree: String,
        /// The layer's motion.
        layer: PathBuf,
        /// 0 (base) to 1 (layer).
        #[arg(long, default_value_t = 1.0)]
        weight: f32,
        /// Add the layer's change from its first frame instead of replacing.
        #[arg(long)]
        additive: bool,
        /// Seconds to fade the layer in from the start.
        #[arg(long, default_value_t = 0.0)]
        fade_in: f64,
        /// Seconds to fade it out before the end.
        #[arg(long, default_value_t = 0.0)]
        fade_out: f64,
        /// Match a base joint to a layer joint by hand: BASE=LAYER (repeatable).
        #[arg(long, value_name = "BASE=LAYER")]
        map: Vec<String>,
        /// Output file (.bvh).
        #[arg(short, long)]
        output: PathBuf,
    },
    /// Puts a motion on another skeleton (retargeting): every mapped bone points
    /// where its source bone points, the root's path scaled by the legs; writes
    /// BVH or glTF on exactly the target's skeleton.
    Retarget {
        /// The motion: one file, or an Acclaim skeleton and motion (`SKEL.asf TAKE.amc`).
        #[arg(required = true, num_args = 1..=2)]
        source: Vec<PathBuf>,
        /// The skeleton that receives it: a motion file (or `SKEL.asf [TAKE.amc]`).
        #[arg(long, required = true, num_args = 1..=2)]
        onto: Vec<PathBuf>,
        /// Joint pairs by hand: a JSON object `{"TARGET": "SOURCE", …}` ("" leaves a joint out).
        #[arg(long, value_name = "MAP.json")]
        map: Option<PathBuf>,
        /// Save the pairs used, in the same form.
        #[arg(long, value_name = "MAP.json")]
        save_map: Option<PathBuf>,
        /// The pose the two skeletons are matched in: `first-frame` or `rest`.
        #[arg(long, default_value = "first-frame")]
        reference: String,
        /// The source's animation, when it is a glTF file with several (default: its first).
        #[arg(long)]
        animation: Option<String>,
        /// Output file (.bvh, .glb or .gltf).
        #[arg(short, long)]
        output: PathBuf,
    },
    /// Compares two takes (a prediction with ground truth, two captures): B sampled at A's frame
    /// times, both in metres with Y up; MPJPE and per-joint errors in A's file units and metres,
    /// per-frame error, per-joint angle differences.
    Compare {
        /// The first take (the reference; an .amc finds its .asf).
        a: PathBuf,
        /// The second take (same skeleton, or matched by joint names and tree shape).
        b: PathBuf,
        /// `none`, `root` (each frame: roots to the origin, B turned to A's heading),
        /// `procrustes` (each frame: B's best rigid fit onto A), or `root-once` /
        /// `procrustes-once` (the same once for the whole take).
        #[arg(long, default_value = "none")]
        align: String,
        /// Joint pairs by hand: a JSON object `{"A_JOINT": "B_JOINT", …}`.
        #[arg(long, value_name = "MAP.json")]
        map: Option<PathBuf>,
        /// Print JSON: `mpjpe`, `mpjpe_m`, `joints: [{name, mean, max, angle}]`, `frames`, `worst_frame`.
        #[arg(long)]
        json: bool,
    },
    /// Captures skeletal motion from a Quake 2 MD2 model's vertex animation:
    /// joints where four tracked vertices' spheres meet, bone spins from tracked
    /// triangles; prints each joint's residuals; writes BVH.
    Capture {
        /// The model (.md2).
        model: PathBuf,
        /// The rig (JSON: skeleton in the set-up frame, spins, binding); without
        /// it a humanoid (or --skeleton) is fitted and bound automatically.
        #[arg(long)]
        rig: Option<PathBuf>,
        /// Fit this motion file's skeleton (BVH, BVA, or ASF) instead of the
        /// built-in humanoid (without --rig).
        #[arg(long)]
        skeleton: Option<PathBuf>,
        /// Write only this animation's frames (the model's frame names: run, stand…).
        #[arg(long)]
        animation: Option<String>,
        /// Also write one BVH per animation beside the output (OUT-run.bvh, …).
        #[arg(long)]
        split: bool,
        /// Vertices tracked per joint (four is the source's method; more average out noise).
        #[arg(long, default_value_t = 4)]
        vertices: usize,
        /// Use each tracked vertex's stored (8-bit) place as it is, not the best
        /// fit of its rigid part averaged over all frames (the source's method; noisier).
        #[arg(long)]
        raw_vertices: bool,
        /// Save the rig used (JSON), to adjust it and capture again with --rig.
        #[arg(long)]
        save_rig: Option<PathBuf>,
        /// Also write the capture in the source's per-frame layout (frame name,
        /// bone translations, bone rotations in radians, doubles).
        #[arg(long)]
        frames_out: Option<PathBuf>,
        /// Output file (.bvh).
        #[arg(short, long)]
        output: PathBuf,
    },
    /// Converts a motion to BVH (every joint position kept) or BVA (each joint's world transform a segment).
    Convert {
        /// Input file(s): one motion file, or an Acclaim skeleton and motion (`SKEL.asf TAKE.amc`).
        #[arg(required = true, num_args = 1..=2)]
        inputs: Vec<PathBuf>,
        /// Output file (.bvh, .bva, .glb or .gltf).
        #[arg(short, long)]
        output: PathBuf,
        /// The animation of a glTF file to write (default: its first).
        #[arg(long)]
        animation: Option<String>,
    },
    /// Renders clips and models to PNG or video headlessly (wgpu on Vulkan; Mesa lavapipe without a GPU).
    Render {
        /// One or more motion or model files, drawn side by side (Acclaim: skeleton and motions; MD2: the model and its skin image).
        #[arg(required = true)]
        files: Vec<PathBuf>,
        /// A skin image (PCX, BMP, PNG, JPEG, TGA) for the MD2 model(s); same as giving it among the files.
        #[arg(long)]
        skin: Vec<PathBuf>,
        /// The animation MD2 models play (`run`, `stand`, …; default `all`, every frame in file order).
        #[arg(long)]
        animation: Option<String>,
        /// Frame to render (in the first file's frame time; default 0).
        #[arg(long, conflicts_with_all = ["time", "frames", "sheet", "video"])]
        frame: Option<usize>,
        /// Time in seconds to render (interpolated).
        #[arg(long, conflicts_with_all = ["frames", "sheet", "video"])]
        time: Option<f64>,
        /// A sequence `a:b:step` (end inclusive, step default 1); --out is a directory.
        #[arg(long, conflicts_with_all = ["sheet", "video"])]
        frames: Option<String>,
        /// A contact sheet of evenly spaced frames over the whole clip.
        #[arg(long, conflicts_with = "video")]
        sheet: bool,
        /// A video of the whole clip (or --from/--to): OUT.mp4 (H.264), OUT.webm (AV1) or OUT.gif;
        /// frame k shows the time from + k/fps, as --time draws it.
        #[arg(long, value_name = "OUT", conflicts_with = "out")]
        video: Option<PathBuf>,
        /// Video frames per second (default: the first clip's rate; a GIF at most 50).
        #[arg(long)]
        fps: Option<f64>,
        /// The video's first time in seconds (default 0).
        #[arg(long)]
        from: Option<f64>,
        /// The video's last time in seconds (default: the end of the longest clip).
        #[arg(long)]
        to: Option<f64>,
        /// No progress bar or summary for --video.
        #[arg(long, short)]
        quiet: bool,
        /// Columns of the contact sheet (rows follow from the aspect).
        #[arg(long, default_value_t = 4)]
        columns: u32,
        /// Output PNG (or directory for --frames).
        #[arg(long, required_unless_present = "video")]
        out: Option<PathBuf>,
        /// Image size WIDTHxHEIGHT (the whole sheet for --sheet).
        #[arg(long, default_value = "1280x720")]
        size: String,
        /// Draw mode: capsules (lit solids per bone), sticks (lines and joints) or body (a skinned body around the bones).
        #[arg(long, default_value = "capsules")]
        mode: String,
        /// Camera `yaw,pitch[,distance]` in degrees and metres (default frames the motion).
        #[arg(long, allow_hyphen_values = true)]
        camera: Option<String>,
        /// The file axis that points up in every clip, `y` or `z` (default: guessed per clip from its motion).
        #[arg(long)]
        up: Option<String>,
        /// Sampling between frames (--time, --video): nearest, linear (default) or cubic.
        #[arg(long)]
        interpolation: Option<String>,
        /// Draw this joint's path over the whole clip (the root's on the floor), a tick each
        /// second and the current point.
        #[arg(long, value_name = "JOINT")]
        trail: Option<String>,
    },
    /// Checks files or directories (recursively): one line per file.
    Validate {
        /// Files or directories.
        #[arg(required = true)]
        paths: Vec<PathBuf>,
    },
    /// A whole dataset at once: every motion file under DIR (or listed in a text file, one
    /// path a line) validated, summarised or converted, with a JSON-lines manifest
    /// (file, sha256, status, error with its location or the figures); resumable, never
    /// stopped by a bad file, on every core.
    Batch {
        /// A folder (walked recursively) or a text file listing paths.
        source: PathBuf,
        /// Only read each file (the default).
        #[arg(long, conflicts_with = "to")]
        validate: bool,
        /// `json` (a summary line per file: frames, fps, joints, units, up axis, duration,
        /// bounds, warnings), `bvh` or `glb` (converted into --out, same relative paths), or
        /// `png` (a contact sheet of each, as render --sheet draws it).
        #[arg(long)]
        to: Option<String>,
        /// Where converted files go (and the manifest, by default).
        #[arg(long)]
        out: Option<PathBuf>,
        /// The manifest (default: OUT/manifest.jsonl, else ./manifest.jsonl); files it lists
        /// with the same sha256 are skipped.
        #[arg(long)]
        manifest: Option<PathBuf>,
        /// Threads (default: every core).
        #[arg(long)]
        jobs: Option<usize>,
        /// No progress bar.
        #[arg(long, short)]
        quiet: bool,
    },
}

/// The edits of `mocap edit` as the core's edit specs, in the order they appear
/// on the command line (`--NAME V` is the spec `NAME:V`, [`commands::flag_spec`]).
fn edit_specs(matches: &ArgMatches) -> Result<Vec<EditSpec>, String> {
    let mut specs: Vec<(usize, EditSpec)> = Vec::new();
    let values = |id: &str| -> Vec<(usize, String)> {
        match (matches.indices_of(id), matches.get_raw(id)) {
            (Some(i), Some(v)) => i.zip(v.map(|x| x.to_string_lossy().into_owned())).collect(),
            _ => Vec::new(),
        }
    };
    let flag = |id: &str| -> Option<usize> { matches.get_flag(id).then(|| matches.index_of(id)).flatten() };
    for name in ["trim", "fps", "knit", "up", "units", "scale"] {
        for (i, v) in values(name) {
            specs.push((i, commands::flag_spec(name, &v)?));
        }
    }
    // Joint names are taken as given (a `:` in one is no separator here).
    for (i, v) in values("rename") {
        let (from, to) = v.split_once('=').ok_or_else(|| format!("--rename {v}: expected OLD=NEW"))?;
        specs.push((i, Edit::Rename { from: from.to_owned(), to: to.to_owned() }.into()));
    }
    for (id, fold) in [("remove", true), ("drop_joint", false)] {
        for (i, name) in values(id) {
            specs.push((i, Edit::RemoveJoint { name, fold }.into()));
        }
    }
    for (id, edit) in [
        ("reverse", Edit::Reverse),
        ("ping_pong", Edit::PingPong),
        ("in_place", Edit::InPlace { remove_turning: false }),
        ("in_place_turning", Edit::InPlace { remove_turning: true }),
    ] {
        if let Some(i) = flag(id) {
            specs.push((i, edit.into()));
        }
    }
    specs.sort_by_key(|(i, _)| *i);
    Ok(specs.into_iter().map(|(_, spec)| spec).collect())
}

fn main() -> ExitCode {
    let matches = Cli::command().get_matches();
    let cli = match Cli::from_arg_matches(&matches) {
        Ok(cli) => cli,
        Err(e) => e.exit(),
    };
    let result = match cli.command {
        Command::Info { files, json } => commands::info(&files, json),
        Command::Pose { files, frame, time, animation, interpolation, json: _ } => {
            commands::pose(&files, frame, time, animation.as_deref(), interpolation.as_deref())
        }
        Command::Convert { inputs, output, animation } => commands::convert(&inputs, &output, animation.as_deref()),
        Command::Compare { a, b, align, map, json } => commands::compare(&a, &b, &align, map.as_deref(), json),
        Command::Retarget { source, onto, map, save_map, reference, animation, output } => {
            commands::retarget(&commands::RetargetRequest {
                animation: animation.as_deref(),
                source: &source,
                onto: &onto,
                map: map.as_deref(),
                save_map: save_map.as_deref(),
                reference: &reference,
                output: &output,
            })
        }
        Command::Layer { base, subtree, layer, weight, additive, fade_in, fade_out, map, output } => {
            let request = commands::LayerRequest { subtree: &subtree, weight, additive, fade_in, fade_out, map: &map };
            commands::layer(&base, &layer, &request, &output)
        }
        Command::Edit { files, output, .. } => match matches.subcommand_matches("edit").map(edit_specs) {
            Some(Ok(specs)) => commands::edit(&files, &specs, &output),
            Some(Err(e)) => Err(e),
            None => Err("edit: no arguments".into()),
        },
        Command::Ik { files, joint, target, frame, bones, solver, json: _ } => commands::ik(
            &files,
            &commands::IkRequest { joint: &joint, target: &target, frame, bones, solver: solver.as_deref() },
        ),
        Command::Validate { paths } => commands::validate(&paths),
        Command::Batch { source, validate: _, to, out, manifest, jobs, quiet } => {
            commands::batch(&source, to.as_deref(), out.as_deref(), manifest.as_deref(), jobs, quiet)
        }
        Command::Capture {
            model,
            rig,
            skeleton,
            animation,
            split,
            vertices,
            raw_vertices,
            save_rig,
            frames_out,
            output,
        } => commands::capture(&commands::CaptureRequest {
            model: &model,
            rig: rig.as_deref(),
            skeleton: skeleton.as_deref(),
            animation: animation.as_deref(),
            split,
            vertices,
            raw_vertices,
            save_rig: save_rig.as_deref(),
            frames_out: frames_out.as_deref(),
            output: &output,
        }),
        Command::Render {
            mut files,
            skin,
            animation,
            frame,
            time,
            frames,
            sheet,
            video,
            fps,
            from,
            to,
            quiet,
            columns,
            out,
            size,
            mode,
            camera,
            up,
            interpolation,
            trail,
        } => {
            files.extend(skin);
            let is_video = video.is_some();
            let shot = match (&video, frame, time, frames, sheet) {
                (Some(_), ..) => commands::Shot::Video(commands::VideoRequest { fps, from, to, quiet }),
                (_, _, Some(t), _, _) => commands::Shot::Time(t),
                (_, _, _, Some(range), _) => commands::Shot::Sequence(range),
                (_, _, _, _, true) => commands::Shot::Sheet(columns),
                (_, f, ..) => commands::Shot::Frame(f.unwrap_or(0)),
            };
            let options = commands::RenderOptions {
                mode: &mode,
                camera: camera.as_deref(),
                animation: animation.as_deref(),
                up: up.as_deref(),
                interpolation: interpolation.as_deref(),
                trail: trail.as_deref(),
            };
            match video.or(out) {
                Some(_) if !is_video && (fps.is_some() || from.is_some() || to.is_some()) => {
                    Err("--fps, --from and --to are for --video".into())
                }
                Some(out) => commands::render(&files, shot, &out, &size, &options),
                None => Err("mocap render: give --out FILE (or --video FILE)".into()),
            }
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
