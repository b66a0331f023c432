//! The subcommands. Each returns an exit code or a message for stderr.

use mocap::ops::edit::EditSpec;
use mocap::{Asset, Clip, Format, Input, Loaded, Model};
use serde_json::{Value, json};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

fn read(path: &Path) -> Result<Vec<u8>, String> {
    std::fs::read(path).map_err(|e| format!("{}: cannot read: {e}", path.display()))
}

fn stem(path: &Path) -> String {
    path.file_stem().map(|s| s.to_string_lossy().to_ascii_lowercase()).unwrap_or_default()
}

/// The skeleton of an Acclaim motion given alone: in its folder, the `.asf` its
/// name starts with (`01_01.amc` → `01.asf`, the longest such), else the only
/// `.asf` there, else an error that says what is needed.
pub fn find_skeleton(amc: &Path) -> Result<PathBuf, String> {
    let dir = amc.parent().filter(|d| !d.as_os_str().is_empty()).unwrap_or(Path::new("."));
    let mut skeletons: Vec<PathBuf> = std::fs::read_dir(dir)
        .map_err(|e| format!("{}: cannot list {} to find its skeleton: {e}", amc.display(), dir.display()))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().and_then(|e| e.to_str()).is_some_and(|e| e.eq_ignore_ascii_case("asf")))
        .collect();
    skeletons.sort();
    let motion = stem(amc);
    let by_name = skeletons.iter().filter(|s| motion.starts_with(&stem(s))).max_by_key(|s| stem(s).len());
    match (by_name, skeletons.as_slice()) {
        (Some(s), _) => Ok(s.clone()),
        (None, [only]) => Ok(only.clone()),
        (None, []) => Err(format!(
            "{}: an Acclaim motion needs its skeleton, and {} has no .asf file; give it too: mocap … SKELETON.asf {}",
            amc.display(),
            dir.display(),
            amc.display()
        )),
        (None, _) => Err(format!(
            "{}: an Acclaim motion needs its skeleton: no .asf in {} starts its name, and there are {}; give the right one too: mocap … SKELETON.asf {}",
            amc.display(),
            dir.display(),
            skeletons.len(),
            amc.display()
        )),
    }
}

/// Reads a set of files as the viewer does (formats from content, Acclaim motions
/// paired with skeletons); an `.amc` with no `.asf` in the set finds its skeleton
/// with [`find_skeleton`]. Errors read `FILE:LINE:COL: message`.
pub fn read_set(paths: &[PathBuf]) -> Result<Vec<Loaded>, String> {
    load_files(read_all(paths)?)
}

fn read_all(paths: &[PathBuf]) -> Result<Vec<(PathBuf, Vec<u8>)>, String> {
    paths.iter().map(|p| read(p).map(|b| (p.clone(), b))).collect()
}

/// [`read_set`] on files already read.
fn load_files(mut files: Vec<(PathBuf, Vec<u8>)>) -> Result<Vec<Loaded>, String> {
    let formats: Vec<Option<Format>> = files.iter().map(|(p, b)| Format::detect(&p.display().to_string(), b)).collect();
    if !formats.contains(&Some(Format::Asf)) {
        if let Some((amc, _)) = files.iter().zip(&formats).find(|(_, f)| **f == Some(Format::Amc)).map(|(f, _)| f) {
            let skeleton = find_skeleton(amc)?;
            let bytes = read(&skeleton)?;
            files.insert(0, (skeleton, bytes));
        }
    }
    let names: Vec<String> = files.iter().map(|(p, _)| p.display().to_string()).collect();
    let inputs: Vec<Input> = files.iter().zip(&names).map(|((_, bytes), name)| Input { name, bytes }).collect();
    mocap::load(&inputs).into_iter().map(|r| r.map_err(|e| e.to_string())).collect()
}

/// Reads the files of one clip (a motion file, or an Acclaim skeleton with one motion).
fn read_clip(paths: &[PathBuf]) -> Result<Clip, String> {
    match one_asset(read_set(paths)?, paths)? {
        Asset::Clip(clip) => Ok(clip),
        Asset::Model(_) => Err(format!(
            "{}: a model has no skeleton or motion; give a motion file (.bvh, .bva, or .asf with .amc)",
            shown(paths)
        )),
    }
}

/// The one asset of a set read from `paths`, or an error saying what to give.
fn one_asset(mut set: Vec<Loaded>, paths: &[PathBuf]) -> Result<Asset, String> {
    match set.len() {
        1 => Ok(set.remove(0).asset),
        0 => Err(format!("{}: no clip or model in these files", shown(paths))),
        n => Err(format!(
            "{}: these files hold {n} clips or models; give one (an .asf skeleton with one .amc, one .bvh/.bva, or one .md2 with its skin)",
            shown(paths)
        )),
    }
}

fn shown(paths: &[PathBuf]) -> String {
    paths.iter().map(|p| p.display().to_string()).collect::<Vec<_>>().join(" ")
}

/// An f32 as a JSON number with its shortest round-trip digits (not f64 noise).
fn num(v: f32) -> Value {
    let shortest: Option<f64> = ryu::Buffer::new().format(v).parse().ok();
    shortest.and_then(serde_json::Number::from_f64).map_or(Value::Null, Value::Number)
}

fn vec3(v: mocap::glam::Vec3) -> Value {
    json!([num(v.x), num(v.y), num(v.z)])
}

fn print_json(value: &Value) -> Result<ExitCode, String> {
    let text = serde_json::to_string_pretty(value).map_err(|e| e.to_string())?;
    // A closed pipe (`| head`) is not an error worth a panic.
    let _ = writeln!(std::io::stdout().lock(), "{text}");
    Ok(ExitCode::SUCCESS)
}

/// `mocap info` for an MD2 model: frames, vertices, triangles, texture
/// coordinates, skins, animations (`frames` is the same key as for motion files).
fn info_model(path: &str, model: &Model, as_json: bool) -> Result<ExitCode, String> {
    let mesh = &model.mesh;
    let units = mesh.units();
    let counts = mesh.source_counts;
    let animations: Vec<Value> =
        mesh.animations().iter().map(|a| json!({ "name": a.name, "first": a.first, "last": a.last })).collect();
    let skin = model.skin.as_ref().map(|s| s.name.clone());
    if as_json {
        return print_json(&json!({
            "file": path,
            "format": "md2",
            "frames": mesh.frame_count(),
            "vertices": counts.vertices,
            "triangles": counts.triangles,
            "tex_coords": counts.tex_coords,
            "skin_size": mesh.skin_size,
            "skins": mesh.skins,
            "skin": skin,
            "animations": animations,
            "height": num(mesh.height()),
            "units": units.name(),
        }));
    }
    let mut out = std::io::stdout().lock();
    let _ = writeln!(out, "file:       {path}");
    let _ = writeln!(out, "format:     Quake 2 MD2 model");
    let _ = writeln!(out, "frames:     {}", mesh.frame_count());
    let _ = writeln!(out, "vertices:   {}", counts.vertices);
    let _ = writeln!(out, "triangles:  {}", counts.triangles);
    let _ = writeln!(out, "tex coords: {} (skin {}×{})", counts.tex_coords, mesh.skin_size[0], mesh.skin_size[1]);
    let _ = writeln!(
        out,
        "skins:      {}",
        if mesh.skins.is_empty() { "(none named)".to_owned() } else { mesh.skins.join(", ") }
    );
    if let Some(skin) = &skin {
        let _ = writeln!(out, "skin used:  {skin}");
    }
    let _ = writeln!(out, "units:      {} (guessed from a first-frame height of {:.3})", units.name(), mesh.height());
    for a in mesh.animations() {
        let _ = writeln!(out, "animation:  {} (frames {}–{})", a.name, a.first, a.last);
    }
    Ok(ExitCode::SUCCESS)
}

/// `mocap info`.
pub fn info(paths: &[PathBuf], as_json: bool) -> Result<ExitCode, String> {
    let clip = match one_asset(read_set(paths)?, paths)? {
        Asset::Model(model) => return info_model(&shown(paths), &model, as_json),
        Asset::Clip(clip) => clip,
    };
    let path = shown(paths);
    let skeleton = clip.skeleton();
    let roots: Vec<&str> = skeleton.roots().filter_map(|r| skeleton.joints().get(r)).map(|j| j.name.as_str()).collect();
    let joints = skeleton.joint_count();
    let end_sites = skeleton.len() - joints;
    let bounds = clip.bounds();
    let up = clip.up_axis();
    let units = clip.units_along(up);
    let warnings: Vec<String> = clip.warnings.iter().map(ToString::to_string).collect();
    if as_json {
        return print_json(&json!({
            "file": path,
            "skeletons": roots.len(),
            "roots": roots,
            "joints": joints,
            "end_sites": end_sites,
            "channels": skeleton.channel_count(),
            "frames": clip.frame_count(),
            "frame_time": clip.frame_time(),
            "fps": clip.fps(),
            "duration": clip.duration(),
            "bounds": { "min": vec3(bounds.min), "max": vec3(bounds.max) },
            "units": units.name(),
            "up": up.name(),
            "angle_unit": clip.motion().angle_unit().name(),
            "metadata": clip.metadata.iter().map(|(k, v)| json!([k, v])).collect::<Vec<_>>(),
            "warnings": warnings,
        }));
    }
    let mut out = std::io::stdout().lock();
    let _ = writeln!(out, "file:       {path}");
    let _ = writeln!(out, "skeletons:  {} ({})", roots.len(), roots.join(", "));
    let _ = writeln!(out, "joints:     {joints} (+{end_sites} End Sites)");
    let _ = writeln!(out, "channels:   {}", skeleton.channel_count());
    let _ = writeln!(out, "frames:     {}", clip.frame_count());
    let _ = writeln!(out, "frame time: {} s ({:.3} fps)", clip.frame_time(), clip.fps());
    let _ = writeln!(out, "duration:   {:.3} s", clip.duration());
    let _ = writeln!(out, "bounds:     min {:?} max {:?}", bounds.min.to_array(), bounds.max.to_array());
    let _ = writeln!(out, "up:         {} (guessed from the motion)", up.name());
    let _ = writeln!(
        out,
        "units:      {} (guessed from a first-pose height of {:.3})",
        units.name(),
        clip.pose_height_along(up)
    );
    for (k, v) in &clip.metadata {
        let _ = writeln!(out, "{:<11} {}", format!("{k}:"), v.replace('\n', "\n            "));
    }
    for w in &warnings {
        let _ = writeln!(out, "warning:    {w}");
    }
    Ok(ExitCode::SUCCESS)
}

/// `mocap pose`.
pub fn pose(paths: &[PathBuf], frame: usize) -> Result<ExitCode, String> {
    let clip = read_clip(paths)?;
    if frame >= clip.frame_count().max(1) {
        return Err(format!(
            "{}: frame {frame} is out of range (the clip has {} frames)",
            shown(paths),
            clip.frame_count()
        ));
    }
    let mut positions = Vec::new();
    clip.world_positions_into(frame, &mut positions);
    let joints: Vec<Value> = clip
        .skeleton()
        .joints()
        .iter()
        .zip(&positions)
        .map(|(j, p)| json!({ "name": j.name, "parent": j.parent, "end_site": j.is_end_site(), "position": vec3(*p) }))
        .collect();
    let time = clip.timeline().time_of(frame);
    print_json(&json!({ "frame": frame, "time": time, "joints": joints }))
}

/// One edit of `mocap edit`, as written on the command line.
#[derive(Clone, Debug, PartialEq)]
pub enum EditOp {
    /// `--trim a:b`.
    Trim(String),
    /// `--fps N`.
    Fps(String),
    /// `--reverse`.
    Reverse,
    /// `--ping-pong`.
    PingPong,
    /// `--knit N`.
    Knit(String),
    /// `--in-place` (false) or `--in-place-turning` (true).
    InPlace(bool),
    /// `--up z`.
    Up(String),
    /// `--units m`.
    Units(String),
    /// `--scale F`.
    Scale(String),
    /// `--rename OLD=NEW`.
    Rename(String),
    /// `--remove J` (fold, true) or `--drop-joint J` (false).
    Remove(String, bool),
}

impl EditOp {
    /// The core's edit spec for this flag: a value flag's text is read by the
    /// core's reader ([`mocap::ops::edit::EditSpec`]) as the spec of the same name
    /// (`--knit 4` is `knit:4`, `--up -z` is `up:-z`); an error names the flag.
    pub fn spec(&self) -> Result<EditSpec, String> {
        use mocap::ops::edit::Edit;
        // `--NAME V` is the spec `NAME:V`.
        let read = |name: &str, v: &str| {
            format!("{name}:{v}").parse::<EditSpec>().map_err(|e| format!("--{name} {v}: expected {}", e.expected))
        };
        match self {
            EditOp::Trim(v) => read("trim", v),
            EditOp::Fps(v) => read("fps", v),
            EditOp::Reverse => Ok(Edit::Reverse.into()),
            EditOp::PingPong => Ok(Edit::PingPong.into()),
            EditOp::Knit(v) => read("knit", v),
            EditOp::InPlace(turning) => Ok(Edit::InPlace { remove_turning: *turning }.into()),
            EditOp::Up(v) => read("up", v),
            EditOp::Units(v) => read("units", v),
            EditOp::Scale(v) => read("scale", v),
            // Joint names are taken as given (a `:` in one is no separator here).
            EditOp::Rename(v) => {
                let (from, to) = v.split_once('=').ok_or_else(|| format!("--rename {v}: expected OLD=NEW"))?;
                Ok(Edit::Rename { from: from.to_owned(), to: to.to_owned() }.into())
            }
            EditOp::Remove(name, fold) => Ok(Edit::RemoveJoint { name: name.clone(), fold: *fold }.into()),
        }
    }
}

/// `mocap edit`: the edits in order, then BVH.
pub fn edit(inputs: &[PathBuf], ops: &[EditOp], output: &Path) -> Result<ExitCode, String> {
    if output.extension().and_then(|e| e.to_str()).is_none_or(|e| !e.eq_ignore_ascii_case("bvh")) {
        return Err(format!("{}: edit writes .bvh files", output.display()));
    }
    let mut clip = read_clip(inputs)?;
    for op in ops {
        // Units resolve against the clip as edited so far.
        let edit = op.spec()?.resolve(&clip);
        clip = mocap::ops::edit::apply(&clip, &edit).map_err(|e| format!("{}: {e}", shown(inputs)))?;
    }
    let (baked, warnings) = mocap::ops::bake::to_bvh(&clip);
    for w in warnings {
        eprintln!("{}: warning: {w}", output.display());
    }
    std::fs::write(output, mocap::formats::bvh::write(&baked))
        .map_err(|e| format!("{}: cannot write: {e}", output.display()))?;
    Ok(ExitCode::SUCCESS)
}

/// What `mocap layer` is asked.
pub struct LayerRequest<'a> {
    /// The base joint whose subtree the layer drives.
    pub subtree: &'a str,
    /// 0–1.
    pub weight: f32,
    /// Additive instead of override.
    pub additive: bool,
    /// Fade-in seconds.
    pub fade_in: f64,
    /// Fade-out seconds.
    pub fade_out: f64,
    /// `BASE=LAYER` pairs.
    pub map: &'a [String],
}

/// `mocap layer`: a layer on a subtree of the base, as BVH.
pub fn layer(base: &Path, layer: &Path, request: &LayerRequest, output: &Path) -> Result<ExitCode, String> {
    if output.extension().and_then(|e| e.to_str()).is_none_or(|e| !e.eq_ignore_ascii_case("bvh")) {
        return Err(format!("{}: layer writes .bvh files", output.display()));
    }
    let base_clip = read_clip(&[base.to_path_buf()])?;
    let layer_clip = read_clip(&[layer.to_path_buf()])?;
    let map = request
        .map
        .iter()
        .map(|m| {
            m.split_once('=')
                .map(|(b, l)| (b.to_owned(), l.to_owned()))
                .ok_or_else(|| format!("--map {m}: expected BASE=LAYER"))
        })
        .collect::<Result<Vec<_>, _>>()?;
    let settings = mocap::ops::layer::Layer {
        subtree: request.subtree.to_owned(),
        weight: request.weight,
        fade_in: request.fade_in,
        fade_out: request.fade_out,
        blend: if request.additive { mocap::ops::layer::Blend::Additive } else { mocap::ops::layer::Blend::Override },
        map,
    };
    let out = mocap::ops::layer::apply(&base_clip, &layer_clip, &settings)
        .map_err(|e| format!("{} + {}: {e}", base.display(), layer.display()))?;
    std::fs::write(output, mocap::formats::bvh::write(&out))
        .map_err(|e| format!("{}: cannot write: {e}", output.display()))?;
    Ok(ExitCode::SUCCESS)
}

/// What `mocap capture` is asked.
pub struct CaptureRequest<'a> {
    /// The MD2 model.
    pub model: &'a Path,
    /// A rig file, else the automatic fit.
    pub rig: Option<&'a Path>,
    /// A motion file whose skeleton is fitted (without a rig).
    pub skeleton: Option<&'a Path>,
    /// Only this animation.
    pub animation: Option<&'a str>,
    /// One BVH per animation too.
    pub split: bool,
    /// Vertices per joint.
    pub vertices: usize,
    /// Stored vertex places, not their rigid parts' best fit.
    pub raw_vertices: bool,
    /// Where to save the rig used.
    pub save_rig: Option<&'a Path>,
    /// Where to write the per-frame layout.
    pub frames_out: Option<&'a Path>,
    /// The BVH to write.
    pub output: &'a Path,
}

/// `mocap capture`: skeletal motion from an MD2 model's vertex animation.
pub fn capture(request: &CaptureRequest) -> Result<ExitCode, String> {
    let output = request.output;
    if output.extension().and_then(|e| e.to_str()).is_none_or(|e| !e.eq_ignore_ascii_case("bvh")) {
        return Err(format!("{}: capture writes .bvh files", output.display()));
    }
    let model_path = request.model;
    let bytes = std::fs::read(model_path).map_err(|e| format!("{}: cannot read: {e}", model_path.display()))?;
    let md2 = mocap::formats::md2::parse(&bytes)
        .map_err(|e| format!("{}:{}:{}: {}", model_path.display(), e.line, e.column, e.message))?;
    use mocap::capture::{Capturer, RigChoice};
    let given = match request.rig {
        Some(path) => {
            let text = std::fs::read_to_string(path).map_err(|e| format!("{}: cannot read: {e}", path.display()))?;
            Some(mocap::capture::Rig::from_json(&text).map_err(|e| format!("{}: {e}", path.display()))?)
        }
        None => None,
    };
    let template = match (&given, request.skeleton) {
        (None, Some(path)) => {
            let clip = read_clip(&[path.to_path_buf()])?;
            let mut model = Vec::new();
            mocap::local_to_model(clip.skeleton(), &mocap::LocalPose::rest(clip.skeleton()), &mut model);
            Some((clip, model))
        }
        _ => None,
    };
    let choice = match (&given, &template) {
        (Some(rig), _) => RigChoice::Given(rig),
        (None, t) => RigChoice::Fit(t.as_ref().map(|(clip, model)| (clip.skeleton(), model.as_slice()))),
    };
    let options = mocap::capture::Options {
        vertices_per_joint: request.vertices.max(4),
        average_shapes: !request.raw_vertices,
        ..mocap::capture::Options::default()
    };
    let started = std::time::Instant::now();
    let capturer = Capturer::new(&md2, choice, &options).map_err(|e| format!("{}: {e}", model_path.display()))?;
    if let Some(path) = request.save_rig {
        std::fs::write(path, capturer.rig().to_json()).map_err(|e| format!("{}: cannot write: {e}", path.display()))?;
    }
    let cap = capturer.finish().map_err(|e| format!("{}: {e}", model_path.display()))?;
    print!("{}", cap.report.text());
    println!(
        "{}: {} frames, {} joints ({} tracked) in {:.0} ms; animations: {}",
        model_path.display(),
        md2.frames.len(),
        cap.report.joints.len(),
        cap.report.joints.iter().filter(|j| j.tracked.is_ok()).count(),
        started.elapsed().as_secs_f64() * 1000.0,
        cap.animations.iter().map(|a| format!("{} {}–{}", a.name, a.first, a.last)).collect::<Vec<_>>().join(", ")
    );
    let clip = match request.animation {
        Some(name) => cap.animation_clip(name).ok_or_else(|| {
            format!(
                "--animation {name}: {} has {}",
                model_path.display(),
                cap.animations.iter().map(|a| a.name.as_str()).collect::<Vec<_>>().join(", ")
            )
        })?,
        None => cap.clip.clone(),
    };
    std::fs::write(output, mocap::formats::bvh::write(&clip))
        .map_err(|e| format!("{}: cannot write: {e}", output.display()))?;
    if request.split {
        let stem = output.file_stem().and_then(|s| s.to_str()).unwrap_or("capture");
        for a in &cap.animations {
            let Some(part) = cap.animation_clip(&a.name) else { continue };
            let path = output.with_file_name(format!("{stem}-{}.bvh", a.name));
            std::fs::write(&path, mocap::formats::bvh::write(&part))
                .map_err(|e| format!("{}: cannot write: {e}", path.display()))?;
        }
    }
    if let Some(path) = request.frames_out {
        std::fs::write(path, mocap::capture::frames::write(&cap.frames()))
            .map_err(|e| format!("{}: cannot write: {e}", path.display()))?;
    }
    Ok(ExitCode::SUCCESS)
}

/// What `mocap ik` is asked.
pub struct IkRequest<'a> {
    /// The effector's name.
    pub joint: &'a str,
    /// `x,y,z`.
    pub target: &'a str,
    /// Frame index.
    pub frame: usize,
    /// Bones above the effector.
    pub bones: Option<usize>,
    /// Solver name.
    pub solver: Option<&'a str>,
}

/// `mocap ik`: the pose at a frame, its chain solved toward a target.
pub fn ik(paths: &[PathBuf], request: &IkRequest) -> Result<ExitCode, String> {
    let clip = read_clip(paths)?;
    let skeleton = clip.skeleton();
    if request.frame >= clip.frame_count().max(1) {
        return Err(format!(
            "{}: frame {} is out of range (the clip has {} frames)",
            shown(paths),
            request.frame,
            clip.frame_count()
        ));
    }
    let effector =
        skeleton.find(request.joint).ok_or_else(|| format!("{}: no joint named `{}`", shown(paths), request.joint))?;
    let xyz: Vec<f32> = request
        .target
        .split(',')
        .map(|v| v.trim().parse::<f32>())
        .collect::<Result<_, _>>()
        .map_err(|_| format!("--target {}: expected x,y,z (numbers)", request.target))?;
    let target = match xyz.as_slice() {
        &[x, y, z] if xyz.iter().all(|v| v.is_finite()) => mocap::glam::Vec3::new(x, y, z),
        _ => return Err(format!("--target {}: expected x,y,z (three finite numbers)", request.target)),
    };
    let chain = match request.bones {
        Some(bones) => mocap::runtime::ik::Chain::up_from(skeleton, effector, bones.max(1)),
        None => mocap::runtime::ik::Chain::for_joint(skeleton, effector),
    }
    .map_err(|e| e.to_string())?;
    let solver = request.solver.unwrap_or(if chain.joints().len() == 3 { "two-bone" } else { "fabrik" });
    let mut pose = mocap::LocalPose::default();
    clip.local_pose_into(request.frame, &mut pose);
    // Within a ten-thousandth of the chain's length, with passes to spare (CCD
    // converges slowly on some chains; the others stop as soon as they are there).
    let length = chain.rest_length(skeleton);
    let options = mocap::runtime::ik::Options {
        angle_unit: clip.motion().angle_unit(),
        iterations: 2000,
        tolerance: 1e-4 * length.max(1e-6),
        ..Default::default()
    };
    let result = match solver {
        "two-bone" if chain.joints().len() == 3 => {
            // Bend toward where the middle joint points now (keeps the knee forward).
            let mid = mocap::runtime::ik::model_transform(skeleton, &pose, chain.joints()[1]).translation;
            let root = mocap::runtime::ik::model_transform(skeleton, &pose, chain.root()).translation;
            mocap::runtime::ik::two_bone(skeleton, &mut pose, &chain, target, mid + (mid - root), &options)
        }
        "two-bone" => {
            return Err(format!(
                "--solver two-bone needs a chain of two bones (this one has {})",
                chain.joints().len() - 1
            ));
        }
        "ccd" => mocap::runtime::ik::ccd(skeleton, &mut pose, &chain, target, &options),
        "fabrik" => mocap::runtime::ik::fabrik(skeleton, &mut pose, &chain, target, &options),
        other => return Err(format!("--solver {other}: expected two-bone, ccd or fabrik")),
    };
    let mut model = Vec::new();
    mocap::local_to_model(skeleton, &pose, &mut model);
    let name = |j: usize| skeleton.joints().get(j).map_or(String::new(), |x| x.name.clone());
    let joints: Vec<Value> = skeleton
        .joints()
        .iter()
        .zip(&model)
        .map(|(j, t)| json!({ "name": j.name, "parent": j.parent, "end_site": j.is_end_site(), "position": vec3(t.translation) }))
        .collect();
    print_json(&json!({
        "frame": request.frame,
        "time": clip.timeline().time_of(request.frame),
        "joint": request.joint,
        "target": vec3(target),
        "solver": solver,
        "chain": chain.joints().iter().map(|&j| name(j)).collect::<Vec<_>>(),
        "reached": result.reached,
        "distance": num(result.distance),
        "joints": joints,
    }))
}

/// `mocap convert`: to BVH (general clips baked, every position kept) or BVA (each
/// joint's world transform a segment). What the target cannot keep is said on stderr.
pub fn convert(inputs: &[PathBuf], output: &Path) -> Result<ExitCode, String> {
    let ext = output.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    let clip = read_clip(inputs)?;
    let (text, warnings) = match ext.as_deref() {
        Some("bvh") => {
            let (baked, warnings) = mocap::ops::bake::to_bvh(&clip);
            (mocap::formats::bvh::write(&baked), warnings)
        }
        Some("bva") => {
            let (bva, warnings) = mocap::formats::bva::from_clip(&clip);
            (mocap::formats::bva::write(&bva), warnings)
        }
        _ => return Err(format!("{}: can write .bvh or .bva files", output.display())),
    };
    for w in warnings {
        eprintln!("{}: warning: {w}", output.display());
    }
    std::fs::write(output, text).map_err(|e| format!("{}: cannot write: {e}", output.display()))?;
    Ok(ExitCode::SUCCESS)
}

/// Files under `path` (itself if a file) whose extension a reader handles.
fn collect(path: &Path, explicit: bool, out: &mut Vec<PathBuf>) {
    if path.is_dir() {
        let mut entries: Vec<PathBuf> = match std::fs::read_dir(path) {
            Ok(rd) => rd.filter_map(|e| e.ok().map(|e| e.path())).collect(),
            Err(_) => {
                out.push(path.to_path_buf());
                return;
            }
        };
        entries.sort();
        for entry in entries {
            collect(&entry, false, out);
        }
    } else if explicit || is_motion_file(path) {
        out.push(path.to_path_buf());
    }
}

fn is_motion_file(path: &Path) -> bool {
    let known = |e: &str| Format::EXTENSIONS.iter().any(|x| e.eq_ignore_ascii_case(x));
    path.extension().and_then(|e| e.to_str()).is_some_and(known)
}

/// One line on what a valid file holds, or why it is not valid.
fn describe(file: &Path) -> Result<String, String> {
    let one = [file.to_path_buf()];
    Ok(match one_asset(read_set(&one)?, &one)? {
        Asset::Model(model) => {
            format!("MD2 model, {} vertices, {} frames", model.mesh.source_counts.vertices, model.mesh.frame_count())
        }
        Asset::Clip(clip) => {
            let warn =
                if clip.warnings.is_empty() { String::new() } else { format!(", {} warnings", clip.warnings.len()) };
            format!("{} joints, {} frames{warn}", clip.skeleton().len(), clip.frame_count())
        }
    })
}

/// `mocap validate`.
pub fn validate(paths: &[PathBuf]) -> Result<ExitCode, String> {
    let mut files = Vec::new();
    for p in paths {
        if !p.exists() {
            return Err(format!("{}: no such file or directory", p.display()));
        }
        collect(p, true, &mut files);
    }
    let mut failed = 0;
    for file in &files {
        match describe(file) {
            Ok(line) => println!("ok   {}: {line}", file.display()),
            Err(message) => {
                failed += 1;
                println!("FAIL {message}");
            }
        }
    }
    eprintln!("{} files, {} failed", files.len(), failed);
    Ok(if failed > 0 { ExitCode::FAILURE } else { ExitCode::SUCCESS })
}

/// What `mocap render` produces.
pub enum Shot {
    /// One frame (in the first clip's frame time).
    Frame(usize),
    /// One time in seconds.
    Time(f64),
    /// `a:b:step` frames into a directory.
    Sequence(String),
    /// A contact sheet with this many columns.
    Sheet(u32),
}

/// Parses `a:b[:step]` (end inclusive).
fn parse_range(text: &str) -> Result<(usize, usize, usize), String> {
    let parts: Vec<Option<usize>> = text.split(':').map(|p| p.trim().parse().ok()).collect();
    let (a, b, step) = match parts.as_slice() {
        [Some(a), Some(b)] => (*a, *b, 1),
        [Some(a), Some(b), Some(s)] => (*a, *b, *s),
        _ => return Err(format!("--frames: expected a:b or a:b:step, found `{text}`")),
    };
    if step == 0 || b < a {
        return Err(format!("--frames {text}: need a <= b and step >= 1"));
    }
    Ok((a, b, step))
}

/// What `mocap render` draws besides the files: how, from where, and which
/// model animation.
pub struct RenderOptions<'a> {
    /// Draw mode name (`capsules`, `sticks`).
    pub mode: &'a str,
    /// Camera `yaw,pitch[,distance]`.
    pub camera: Option<&'a str>,
    /// Animation the models play (`all` for every frame).
    pub animation: Option<&'a str>,
    /// The up axis of every clip (`y` or `z`; guessed per clip when absent).
    pub up: Option<&'a str>,
}

/// `mocap render`: `files` may hold models with their skins (`--skin` files are
/// added to the set).
pub fn render(
    files: &[PathBuf],
    shot: Shot,
    out: &Path,
    size: &str,
    options: &RenderOptions,
) -> Result<ExitCode, String> {
    let mode = options.mode;
    let mode = mocap_render::DrawMode::from_name(mode)
        .ok_or_else(|| format!("--mode {mode}: expected `capsules`, `sticks` or `body`"))?;
    let size = crate::render::parse_size(size)?;
    let orbit = options.camera.map(crate::render::parse_orbit).transpose()?.unwrap_or_default();
    let assets = read_set(files)?.into_iter().map(|l| (l.name, l.asset)).collect();
    let mut stage = crate::render::StageView::new(assets).with_mode(mode);
    if let Some(name) = options.up {
        let up = mocap::UpAxis::from_name(name).ok_or_else(|| format!("--up: expected y or z, found `{name}`"))?;
        stage.set_up_axis(up);
    }
    if let Some(name) = options.animation {
        if !stage.set_animation(name) {
            return Err(format!("--animation {name}: no model in {} has that animation", shown(files)));
        }
    }
    let gpu = crate::render::Gpu::new()?;
    let mut scene = mocap_render::Scene::default();
    let timeline = stage.timeline();
    match shot {
        Shot::Frame(_) | Shot::Time(_) => {
            let time = match shot {
                Shot::Time(t) if t.is_finite() => t.max(0.0),
                Shot::Time(_) => return Err("--time must be a number of seconds".into()),
                Shot::Frame(f) if f < timeline.frames().max(1) => timeline.time_of(f),
                Shot::Frame(f) => {
                    return Err(format!("frame {f} is out of range (the clip has {} frames)", timeline.frames()));
                }
                _ => 0.0,
            };
            let mut offscreen = crate::render::Offscreen::new(&gpu, size);
            stage.scene_at(time, &mut scene);
            let pixels = offscreen.draw(&gpu, &scene, &stage.camera(orbit, offscreen.size()))?;
            crate::render::write_png(out, offscreen.size(), &pixels)?;
        }
        Shot::Sequence(range) => {
            let (a, b, step) = parse_range(&range)?;
            let last = timeline.last();
            if a > last {
                return Err(format!("--frames {range}: the clip has {} frames", timeline.frames()));
            }
            std::fs::create_dir_all(out).map_err(|e| format!("{}: cannot create: {e}", out.display()))?;
            let mut offscreen = crate::render::Offscreen::new(&gpu, size);
            let camera = stage.camera(orbit, offscreen.size());
            for frame in (a..=b.min(last)).step_by(step) {
                stage.scene_at(timeline.time_of(frame), &mut scene);
                let pixels = offscreen.draw(&gpu, &scene, &camera)?;
                crate::render::write_png(&out.join(format!("frame_{frame:05}.png")), offscreen.size(), &pixels)?;
            }
        }
        Shot::Sheet(columns) => {
            let columns = columns.clamp(1, 16);
            let tile_w = (size[0] / columns).max(16);
            let rows = ((size[1] as f32 / (tile_w as f32 * 9.0 / 16.0)).floor() as u32).clamp(1, 16);
            let tile = [tile_w, (size[1] / rows).max(16)];
            let mut offscreen = crate::render::Offscreen::new(&gpu, tile);
            let tile = offscreen.size();
            let camera = stage.camera(orbit, tile);
            let count = (columns * rows) as usize;
            let sheet_size = [tile[0] * columns, tile[1] * rows];
            let mut sheet = vec![0u8; (sheet_size[0] * sheet_size[1] * 4) as usize];
            for n in 0..count {
                let time = if count > 1 { stage.duration() * n as f64 / (count - 1) as f64 } else { 0.0 };
                stage.scene_at(time, &mut scene);
                let pixels = offscreen.draw(&gpu, &scene, &camera)?;
                let (x, y) = ((n as u32 % columns) * tile[0], (n as u32 / columns) * tile[1]);
                crate::render::blit(&mut sheet, sheet_size[0], &pixels, tile, x, y);
            }
            crate::render::write_png(out, sheet_size, &sheet)?;
        }
    }
    Ok(ExitCode::SUCCESS)
}
