//! Whole-dataset jobs (`mocap batch`, Python's `mocap.batch`): every motion
//! file under a folder validated, summarised or converted, one JSON line each
//! in a manifest (file, sha256, status, the error with its location or the
//! figures), in parallel, never stopped by a bad file, resumable (a file the
//! manifest already lists with the same hash is not done again).

use serde_json::{Map, Value, json};
use sha2::{Digest, Sha256};
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};

/// The extensions a dataset's motion files have (an `.asf` is read with its `.amc`).
pub const MOTION_EXTENSIONS: [&str; 5] = ["bvh", "bva", "amc", "glb", "gltf"];

/// Writes a clip to a file: what [`Task::Write`] does (the CLI's contact sheets).
pub type WriteClip = std::sync::Arc<dyn Fn(&mocap::Clip, &Path) -> Result<(), String> + Send + Sync>;

/// What is done to each file.
#[derive(Clone)]
pub enum Task {
    /// Read it: `ok` or `error` with the location.
    Validate,
    /// Read it and record its figures (frames, fps, joints, units, up axis,
    /// duration, bounds, warnings).
    Summary,
    /// Write it as BVH into `out` (the same relative path, `.bvh`).
    Bvh(PathBuf),
    /// Write it as binary glTF into `out`.
    Glb(PathBuf),
    /// Write it with `write` into `out` (the same relative path, `extension`).
    Write {
        /// The output folder.
        out: PathBuf,
        /// The written files' extension.
        extension: &'static str,
        /// What writes one.
        write: WriteClip,
    },
}

/// Every motion file under `root` (recursively, sorted; no recursion on the
/// folder depth), or `root` itself when it is a file.
pub fn motion_files(root: &Path) -> Vec<PathBuf> {
    if root.is_file() {
        return vec![root.to_path_buf()];
    }
    let mut files = Vec::new();
    let mut dirs = vec![root.to_path_buf()];
    while let Some(dir) = dirs.pop() {
        for entry in std::fs::read_dir(&dir).into_iter().flatten().flatten() {
            let path = entry.path();
            if path.is_dir() {
                dirs.push(path);
            } else if path
                .extension()
                .and_then(|e| e.to_str())
                .is_some_and(|e| MOTION_EXTENSIONS.iter().any(|m| e.eq_ignore_ascii_case(m)))
            {
                files.push(path);
            }
        }
    }
    files.sort();
    files
}

fn sha256(bytes: &[u8]) -> String {
    Sha256::digest(bytes).iter().map(|b| format!("{b:02x}")).collect()
}

/// Does `task` to one file (`root`: the folder its output path is relative
/// to); the manifest line. Never fails: a bad file is a line with its error.
pub fn run_one(path: &Path, root: &Path, task: &Task) -> Value {
    let mut line = Map::new();
    line.insert("file".into(), json!(path.display().to_string()));
    let bytes = match std::fs::read(path) {
        Ok(b) => b,
        Err(e) => {
            line.insert("status".into(), json!("error"));
            line.insert("error".into(), json!(format!("{}: cannot read: {e}", path.display())));
            return Value::Object(line);
        }
    };
    run_bytes(path, bytes, root, task, line)
}

/// [`run_one`] on bytes already read (hashed here once).
fn run_bytes(path: &Path, bytes: Vec<u8>, root: &Path, task: &Task, mut line: Map<String, Value>) -> Value {
    line.insert("sha256".into(), json!(sha256(&bytes)));
    match do_task(path, bytes, root, task, &mut line) {
        Ok(()) => {
            line.insert("status".into(), json!("ok"));
        }
        Err(e) => {
            line.insert("status".into(), json!("error"));
            line.insert("error".into(), json!(e));
        }
    }
    Value::Object(line)
}

fn do_task(path: &Path, bytes: Vec<u8>, root: &Path, task: &Task, line: &mut Map<String, Value>) -> Result<(), String> {
    let loaded = crate::load_files(vec![(path.to_path_buf(), bytes)])?;
    let Some(clip) = loaded.into_iter().find_map(|l| l.into_clip()) else {
        return Err(format!("{}: a model, not a motion", path.display()));
    };
    match task {
        Task::Validate => {}
        Task::Summary => summary(&clip, line),
        Task::Bvh(out) | Task::Glb(out) => {
            let glb = matches!(task, Task::Glb(_));
            let relative = path.strip_prefix(root).unwrap_or(path);
            let target = out.join(relative).with_extension(if glb { "glb" } else { "bvh" });
            if let Some(dir) = target.parent() {
                std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
            }
            let data = if glb {
                mocap::formats::gltf::write::to_glb(&clip, &Default::default()).map_err(|e| format!("{}: {e}", path.display()))?
            } else {
                mocap::formats::bvh::write(&clip).into_bytes()
            };
            std::fs::write(&target, data).map_err(|e| format!("{}: {e}", target.display()))?;
            line.insert("output".into(), json!(target.display().to_string()));
        }
        Task::Write { out, extension, write } => {
            let relative = path.strip_prefix(root).unwrap_or(path);
            let target = out.join(relative).with_extension(extension);
            if let Some(dir) = target.parent() {
                std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
            }
            write(&clip, &target).map_err(|e| format!("{}: {e}", path.display()))?;
            line.insert("output".into(), json!(target.display().to_string()));
        }
    }
    Ok(())
}

/// The figures of a clip, in the file's units.
fn summary(clip: &mocap::Clip, line: &mut Map<String, Value>) {
    let bounds = clip.bounds();
    line.insert("frames".into(), json!(clip.frame_count()));
    line.insert("fps".into(), json!(clip.fps()));
    line.insert("joints".into(), json!(clip.skeleton().len()));
    line.insert("units".into(), json!(clip.units().name()));
    line.insert("up_axis".into(), json!(clip.up_axis().name()));
    line.insert("duration".into(), json!(clip.duration()));
    line.insert("bounds".into(), json!([bounds.min.to_array(), bounds.max.to_array()]));
    let warnings: Vec<String> = clip.warnings.iter().map(|w| w.to_string()).collect();
    line.insert("warnings".into(), json!(warnings));
}

/// Does `task` to every file with `jobs` threads, skipping those `manifest`
/// already lists with the same SHA-256 and appending the new lines to it;
/// `progress(done, total)` after each file. The lines come back in file order.
pub fn run(
    files: &[PathBuf],
    root: &Path,
    task: &Task,
    manifest: Option<&Path>,
    jobs: usize,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<Vec<Value>, String> {
    let done: std::collections::HashMap<String, Value> = match manifest {
        Some(m) if m.is_file() => std::fs::read_to_string(m)
            .map_err(|e| format!("{}: {e}", m.display()))?
            .lines()
            .filter_map(|l| serde_json::from_str::<Value>(l).ok())
            .filter_map(|v| Some((v.get("file")?.as_str()?.to_string(), v)))
            .collect(),
        _ => Default::default(),
    };
    let next = AtomicUsize::new(0);
    let finished = AtomicUsize::new(0);
    let slots: Vec<Mutex<Option<(Value, bool)>>> = files.iter().map(|_| Mutex::new(None)).collect();
    std::thread::scope(|s| {
        for _ in 0..jobs.clamp(1, files.len().max(1)) {
            s.spawn(|| {
                loop {
                    let i = next.fetch_add(1, Ordering::Relaxed);
                    let Some(path) = files.get(i) else { break };
                    // Each file is read once: hashed for the resume check, then worked on.
                    let result = match (done.get(&path.display().to_string()), std::fs::read(path)) {
                        (Some(old), Ok(bytes))
                            if old.get("sha256").and_then(Value::as_str) == Some(sha256(&bytes).as_str()) =>
                        {
                            (old.clone(), false)
                        }
                        (_, Ok(bytes)) => {
                            let mut line = Map::new();
                            line.insert("file".into(), json!(path.display().to_string()));
                            (run_bytes(path, bytes, root, task, line), true)
                        }
                        (_, Err(_)) => (run_one(path, root, task), true),
                    };
                    if let Some(Ok(mut slot)) = slots.get(i).map(|m| m.lock()) {
                        *slot = Some(result);
                    }
                    progress(finished.fetch_add(1, Ordering::Relaxed) + 1, files.len());
                }
            });
        }
    });
    let results: Vec<(Value, bool)> = slots.into_iter().filter_map(|m| m.into_inner().ok().flatten()).collect();
    if let Some(m) = manifest {
        use std::io::Write;
        let mut out = std::fs::OpenOptions::new()
            .create(true)
            .append(true)
            .open(m)
            .map_err(|e| format!("{}: {e}", m.display()))?;
        for (line, new) in &results {
            if *new {
                writeln!(out, "{line}").map_err(|e| format!("{}: {e}", m.display()))?;
            }
        }
    }
    Ok(results.into_iter().map(|(line, _)| line).collect())
}
