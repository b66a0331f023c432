//! `mocap convert` and `mocap validate`.

use super::*;

/// `mocap convert`: to BVH (general clips baked, every position kept), BVA (each
/// joint's world transform a segment) or glTF (`.glb`, `.gltf`: skeleton, skin,
/// generated body and animation, metres and Y up; an MD2 model as a textured
/// mesh with morph targets and an animation per named animation). What the
/// target cannot keep is said on stderr.
pub fn convert(inputs: &[PathBuf], output: &Path, animation: Option<&str>) -> Result<ExitCode, String> {
    let ext = output.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    let glb = matches!(ext.as_deref(), Some("glb" | "gltf"));
    // An MD2 model goes to glTF whole: its frames as morph targets, every animation.
    if glb && let Asset::Model(model) = one_asset(read_set(inputs)?, inputs)? {
        let name = inputs
            .first()
            .and_then(|p| p.file_stem())
            .map_or_else(|| "model".into(), |s| s.to_string_lossy().into_owned());
        let bytes = match ext.as_deref() {
            Some("glb") => mocap::formats::gltf::model_to_glb(&model, &name),
            _ => mocap::formats::gltf::model_to_gltf(&model, &name).map(String::into_bytes),
        }
        .map_err(|e| format!("{}: {e}", output.display()))?;
        if model.skin.is_none() {
            eprintln!("{}: warning: no skin image given; the mesh is written untextured", output.display());
        }
        std::fs::write(output, bytes).map_err(|e| format!("{}: cannot write: {e}", output.display()))?;
        return Ok(ExitCode::SUCCESS);
    }
    let clip = read_take(inputs, animation)?;
    if let Some(kind @ ("glb" | "gltf")) = ext.as_deref() {
        let name = clip.take_name().map(str::to_owned).unwrap_or_else(|| {
            inputs
                .last()
                .and_then(|p| p.file_stem())
                .map_or_else(|| "motion".to_owned(), |s| s.to_string_lossy().into_owned())
        });
        let options = mocap::formats::gltf::Options { name, body: true };
        let bytes = match kind {
            "glb" => mocap::formats::gltf::to_glb(&clip, &options),
            _ => mocap::formats::gltf::to_gltf(&clip, &options).map(String::into_bytes),
        }
        .map_err(|e| format!("{}: {e}", output.display()))?;
        std::fs::write(output, bytes).map_err(|e| format!("{}: cannot write: {e}", output.display()))?;
        return Ok(ExitCode::SUCCESS);
    }
    let (text, warnings) = match ext.as_deref() {
        Some("bvh") => {
            let (baked, warnings) = mocap::ops::bake::to_bvh(&clip);
            (mocap::formats::bvh::write(&baked), warnings)
        }
        Some("bva") => {
            let (bva, warnings) = mocap::formats::bva::from_clip(&clip);
            (mocap::formats::bva::write(&bva), warnings)
        }
        _ => return Err(format!("{}: can write .bvh, .bva, .glb or .gltf files", output.display())),
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

/// One line on what a valid file holds and the reader's warnings, or why it is not valid.
fn describe(file: &Path) -> Result<(String, Vec<mocap::Warning>), String> {
    let one = [file.to_path_buf()];
    Ok(match one_asset(read_set(&one)?, &one)? {
        Asset::Model(model) => (
            format!("MD2 model, {} vertices, {} frames", model.mesh.source_counts.vertices, model.mesh.frame_count()),
            Vec::new(),
        ),
        Asset::Clip(clip) => {
            let warn =
                if clip.warnings.is_empty() { String::new() } else { format!(", {} warnings", clip.warnings.len()) };
            (format!("{} joints, {} frames{warn}", clip.skeleton().len(), clip.frame_count()), clip.warnings.clone())
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
            Ok((line, warnings)) => {
                println!("ok   {}: {line}", file.display());
                for w in warnings {
                    match w.line {
                        Some(n) => println!("     warning: {}:{n}: {}", file.display(), w.message),
                        None => println!("     warning: {}: {}", file.display(), w.message),
                    }
                }
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
