//! The subcommands. Each returns an exit code or a message for stderr.

use mocap::Clip;
use serde_json::{json, Value};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// Reads and parses a file; errors read `FILE:LINE:COL: message`.
fn read_clip(path: &Path) -> Result<Clip, String> {
    let bytes = std::fs::read(path).map_err(|e| format!("{}: cannot read: {e}", path.display()))?;
    mocap::load(&path.display().to_string(), &bytes).map_err(|e| e.to_string())
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
    println!("{text}");
    Ok(ExitCode::SUCCESS)
}

/// `mocap info`.
pub fn info(path: &Path, as_json: bool) -> Result<ExitCode, String> {
    let clip = read_clip(path)?;
    let skeleton = &clip.skeleton();
    let roots: Vec<&str> = skeleton.roots().filter_map(|r| skeleton.joints.get(r)).map(|j| j.name.as_str()).collect();
    let joints = skeleton.joints.iter().filter(|j| !j.is_end_site()).count();
    let end_sites = skeleton.len() - joints;
    let bounds = clip.bounds();
    let units = clip.units();
    let warnings: Vec<String> = clip.warnings.iter().map(ToString::to_string).collect();
    if as_json {
        return print_json(&json!({
            "file": path.display().to_string(),
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
            "warnings": warnings,
        }));
    }
    let mut out = std::io::stdout().lock();
    let _ = writeln!(out, "file:       {}", path.display());
    let _ = writeln!(out, "skeletons:  {} ({})", roots.len(), roots.join(", "));
    let _ = writeln!(out, "joints:     {joints} (+{end_sites} End Sites)");
    let _ = writeln!(out, "channels:   {}", skeleton.channel_count());
    let _ = writeln!(out, "frames:     {}", clip.frame_count());
    let _ = writeln!(out, "frame time: {} s ({:.3} fps)", clip.frame_time(), clip.fps());
    let _ = writeln!(out, "duration:   {:.3} s", clip.duration());
    let _ = writeln!(out, "bounds:     min {:?} max {:?}", bounds.min.to_array(), bounds.max.to_array());
    let _ = writeln!(out, "units:      {} (guessed from a first-pose height of {:.3})", units.name(), clip.pose_height());
    for w in &warnings {
        let _ = writeln!(out, "warning:    {w}");
    }
    Ok(ExitCode::SUCCESS)
}

/// `mocap pose`.
pub fn pose(path: &Path, frame: usize) -> Result<ExitCode, String> {
    let clip = read_clip(path)?;
    if frame >= clip.frame_count().max(1) {
        return Err(format!("{}: frame {frame} is out of range (the clip has {} frames)", path.display(), clip.frame_count()));
    }
    let mut positions = Vec::new();
    clip.world_positions_into(frame, &mut positions);
    let joints: Vec<Value> = clip
        .skeleton
        .joints
        .iter()
        .zip(&positions)
        .map(|(j, p)| json!({ "name": j.name, "parent": j.parent, "end_site": j.is_end_site(), "position": vec3(*p) }))
        .collect();
    let time = mocap::sample::time_of_frame(frame, clip.frame_time());
    print_json(&json!({ "frame": frame, "time": time, "joints": joints }))
}

/// `mocap convert`.
pub fn convert(input: &Path, output: &Path) -> Result<ExitCode, String> {
    let ext = output.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    if ext.as_deref() != Some("bvh") {
        return Err(format!("{}: can only write .bvh files", output.display()));
    }
    let clip = read_clip(input)?;
    std::fs::write(output, mocap::bvh::write(&clip)).map_err(|e| format!("{}: cannot write: {e}", output.display()))?;
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
    path.extension().and_then(|e| e.to_str()).is_some_and(|e| e.eq_ignore_ascii_case("bvh"))
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
        match read_clip(file) {
            Ok(clip) => {
                let warn = if clip.warnings.is_empty() { String::new() } else { format!(", {} warnings", clip.warnings.len()) };
                println!("ok   {}: {} joints, {} frames{warn}", file.display(), clip.skeleton().len(), clip.frame_count());
            }
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

/// `mocap render`.
pub fn render(files: &[PathBuf], shot: Shot, out: &Path, size: &str, mode: &str, camera: Option<&str>) -> Result<ExitCode, String> {
    let mode = mocap_render::DrawMode::from_name(mode).ok_or_else(|| format!("--mode {mode}: expected `capsules` or `sticks`"))?;
    let size = crate::render::parse_size(size)?;
    let orbit = camera.map(crate::render::parse_orbit).transpose()?.unwrap_or_default();
    let clips = files.iter().map(|f| read_clip(f)).collect::<Result<Vec<_>, _>>()?;
    let stage = crate::render::Stage::new(clips.iter().collect()).with_mode(mode);
    let gpu = crate::render::Gpu::new()?;
    let mut scene = mocap_render::Scene::default();
    let dt = stage.frame_time();
    match shot {
        Shot::Frame(_) | Shot::Time(_) => {
            let time = match shot {
                Shot::Time(t) if t.is_finite() => t.max(0.0),
                Shot::Time(_) => return Err("--time must be a number of seconds".into()),
                Shot::Frame(f) if f < stage.frame_count() => mocap::sample::time_of_frame(f, dt),
                Shot::Frame(f) => return Err(format!("frame {f} is out of range (the clip has {} frames)", stage.frame_count())),
                _ => 0.0,
            };
            let mut offscreen = crate::render::Offscreen::new(&gpu, size);
            stage.scene_at(time, &mut scene);
            let pixels = offscreen.draw(&gpu, &scene, &stage.camera(orbit, offscreen.size()))?;
            crate::render::write_png(out, offscreen.size(), &pixels)?;
        }
        Shot::Sequence(range) => {
            let (a, b, step) = parse_range(&range)?;
            let last = stage.frame_count().saturating_sub(1);
            if a > last {
                return Err(format!("--frames {range}: the clip has {} frames", stage.frame_count()));
            }
            std::fs::create_dir_all(out).map_err(|e| format!("{}: cannot create: {e}", out.display()))?;
            let mut offscreen = crate::render::Offscreen::new(&gpu, size);
            let camera = stage.camera(orbit, offscreen.size());
            for frame in (a..=b.min(last)).step_by(step) {
                stage.scene_at(mocap::sample::time_of_frame(frame, dt), &mut scene);
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
