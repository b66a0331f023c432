//! The subcommands. Each returns an exit code or a message for stderr.

use mocap::ops::edit::EditSpec;
use mocap::{Asset, Clip, Format, Input, Loaded, Model};
use serde_json::{Value, json};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

mod capture;
mod convert;
mod edit;
mod info;
mod render;
mod retarget;
mod video;

pub use capture::{CaptureRequest, IkRequest, capture, ik};
pub use convert::{convert, validate};
pub use edit::{LayerRequest, edit, flag_spec, layer};
pub use info::{info, pose};
pub use render::{RenderOptions, Shot, render};
pub use retarget::{RetargetRequest, retarget};
pub use video::VideoRequest;

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
    add_gltf_companions(&mut files);
    let names: Vec<String> = files.iter().map(|(p, _)| p.display().to_string()).collect();
    let inputs: Vec<Input> = files.iter().zip(&names).map(|((_, bytes), name)| Input { name, bytes }).collect();
    mocap::load(&inputs).into_iter().map(|r| r.map_err(|e| e.to_string())).collect()
}

/// [`read_clip`], on the glTF animation named `animation` when one is given.
fn read_take(paths: &[PathBuf], animation: Option<&str>) -> Result<Clip, String> {
    let mut clip = read_clip(paths)?;
    if let Some(name) = animation
        && !clip.set_take(name)
    {
        let names: Vec<&str> = clip.takes().iter().map(|t| t.name.as_str()).collect();
        return Err(if names.is_empty() {
            format!("{}: --animation {name}: only glTF files have named animations", shown(paths))
        } else {
            format!("{}: no animation named `{name}`; the file has: {}", shown(paths), names.join(", "))
        });
    }
    Ok(clip)
}

/// The `.bin` buffers and images a `.gltf` names, read from beside it when they
/// are there and not given already (as an AMC finds its ASF).
fn add_gltf_companions(files: &mut Vec<(PathBuf, Vec<u8>)>) {
    let mut extra: Vec<(PathBuf, Vec<u8>)> = Vec::new();
    for (path, bytes) in files.iter() {
        for name in mocap::formats::gltf::document::external_files(bytes) {
            let beside = path.parent().unwrap_or(Path::new("")).join(&name);
            let given = |p: &Path| p.file_name() == beside.file_name();
            if files.iter().chain(&extra).any(|(p, _)| given(p)) {
                continue;
            }
            if let Ok(data) = std::fs::read(&beside) {
                extra.push((beside, data));
            }
        }
    }
    files.extend(extra);
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
