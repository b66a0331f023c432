//! `mocap info` and `mocap pose`: what a file holds, as text or JSON.

use super::*;

/// `mocap info` for a vertex-animated model (MD2, or glTF morph targets): frames, vertices, triangles, texture
/// coordinates, skins, animations (`frames` is the same key as for motion files).
fn info_model(path: &str, model: &Model, as_json: bool) -> Result<ExitCode, String> {
    let mesh = &model.mesh;
    let units = mesh.units();
    let counts = mesh.source_counts;
    let animations: Vec<Value> =
        mesh.animations().iter().map(|a| json!({ "name": a.name, "first": a.first, "last": a.last })).collect();
    let skin = model.skin.as_ref().map(|s| s.name.clone());
    // A model read from glTF (a mesh moved by morph targets) or from MD2.
    let gltf = [".glb", ".gltf"].iter().any(|e| path.to_ascii_lowercase().ends_with(e));
    if as_json {
        return print_json(&json!({
            "file": path,
            "format": if gltf { "gltf-morph" } else { "md2" },
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
    let format = if gltf { "glTF 2.0, a mesh moved by morph targets" } else { "Quake 2 MD2 model" };
    let _ = writeln!(out, "format:     {format}");
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
        let mut value = json!({
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
        });
        if let Some(character) = &clip.character {
            value["gltf"] = gltf_info(character);
            value["format"] = json!("gltf");
        }
        return print_json(&value);
    }
    let mut out = std::io::stdout().lock();
    let _ = writeln!(out, "file:       {path}");
    if let Some(character) = &clip.character {
        gltf_lines(character, &mut out);
    }
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

/// `mocap pose`: every joint's world position at a frame, or at a time (sampled
/// between frames), of the glTF animation named when one is.
pub fn pose(
    paths: &[PathBuf],
    frame: usize,
    time: Option<f64>,
    animation: Option<&str>,
    interpolation: Option<&str>,
) -> Result<ExitCode, String> {
    let between = interpolation.map(super::render::interpolation).transpose()?.unwrap_or(mocap::Interpolation::Linear);
    let clip = read_take(paths, animation)?;
    let mut positions = Vec::new();
    let (frame, time) = match time {
        Some(t) if !(t.is_finite() && t >= 0.0) => return Err(format!("--time {t}: a time in seconds, 0 or more")),
        Some(t) => {
            clip.sample_world_positions_into(t, between, &mut positions);
            (clip.timeline().frame_at(t), t)
        }
        None => {
            if frame >= clip.frame_count().max(1) {
                return Err(format!(
                    "{}: frame {frame} is out of range (the clip has {} frames)",
                    shown(paths),
                    clip.frame_count()
                ));
            }
            clip.world_positions_into(frame, &mut positions);
            (frame, clip.timeline().time_of(frame))
        }
    };
    let joints: Vec<Value> = clip
        .skeleton()
        .joints()
        .iter()
        .zip(&positions)
        .map(|(j, p)| json!({ "name": j.name, "parent": j.parent, "end_site": j.is_end_site(), "position": vec3(*p) }))
        .collect();
    let mut out = json!({ "frame": frame, "time": time, "joints": joints });
    if let Some(name) = clip.take_name() {
        out["animation"] = json!(name);
    }
    print_json(&out)
}

/// What `mocap info` adds for a glTF file: meshes, skins, animations, extensions.
fn gltf_info(character: &mocap::model::character::Character) -> Value {
    let s = &character.summary;
    json!({
        "nodes": s.nodes,
        "scenes": s.scenes,
        "meshes": s.meshes.iter().map(|(n, p, v)| json!({ "name": n, "primitives": p, "vertices": v })).collect::<Vec<_>>(),
        "vertices": s.meshes.iter().map(|m| m.2).sum::<usize>(),
        "skins": s.skins.iter().map(|(n, j)| json!({ "name": n, "joints": j })).collect::<Vec<_>>(),
        "animations": s.animations.iter().map(|(n, d, c)| json!({ "name": n, "duration": d, "channels": c })).collect::<Vec<_>>(),
        "extensions_used": s.extensions_used,
        "extensions_required": s.extensions_required,
        "drawn_vertices": character.look.as_ref().map_or(0, |l| l.skin.positions().len()),
    })
}

/// The glTF lines of `mocap info`'s text.
fn gltf_lines(character: &mocap::model::character::Character, out: &mut impl Write) {
    let s = &character.summary;
    let _ = writeln!(out, "format:     glTF 2.0 ({} nodes, {} scenes)", s.nodes, s.scenes);
    for (name, primitives, vertices) in &s.meshes {
        let _ = writeln!(out, "mesh:       {name} ({primitives} primitives, {vertices} vertices)");
    }
    for (name, joints) in &s.skins {
        let _ = writeln!(out, "skin:       {name} ({joints} joints)");
    }
    for (name, duration, channels) in &s.animations {
        let _ = writeln!(out, "animation:  {name} ({duration:.3} s, {channels} channels)");
    }
    if !s.extensions_required.is_empty() {
        let _ = writeln!(out, "requires:   {}", s.extensions_required.join(", "));
    }
    if !s.extensions_used.is_empty() {
        let _ = writeln!(out, "uses:       {}", s.extensions_used.join(", "));
    }
}
