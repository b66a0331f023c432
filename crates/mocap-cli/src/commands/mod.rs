//! The subcommands. Each returns an exit code or a message for stderr.

use mocap::ops::edit::EditSpec;
use mocap::{Asset, Clip, Format, Loaded, Model};
use serde_json::{Value, json};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

mod batch;
mod capture;
mod compare;
mod convert;
mod edit;
mod info;
mod render;
mod retarget;
mod video;

pub use batch::batch;
pub use compare::compare;
pub use capture::{CaptureRequest, IkRequest, capture, ik};
pub use convert::{convert, validate};
pub use edit::{LayerRequest, edit, flag_spec, layer};
pub use info::{info, pose};
pub use render::{RenderOptions, Shot, render};
pub use retarget::{RetargetRequest, retarget};
pub use video::VideoRequest;

pub use mocap_files::{find_skeleton, read_set};

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
