//! `mocap info` and `mocap pose`: what a file holds, as text or JSON.

use super::*;

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
