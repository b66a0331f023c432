//! `mocap batch`: a whole dataset through `mocap_files::batch`, with a
//! progress bar on a terminal and a count at the end.

use mocap_files::batch::{Task, motion_files, run};
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// `mocap batch SOURCE [--to json|bvh|glb] [--out DIR] [--manifest FILE] [--jobs N]`.
/// Succeeds when every file did; a bad file is a manifest line, not a stop.
pub fn batch(
    source: &Path,
    to: Option<&str>,
    out: Option<&Path>,
    manifest: Option<&Path>,
    jobs: Option<usize>,
    quiet: bool,
) -> Result<ExitCode, String> {
    let need_out = || out.map(Path::to_path_buf).ok_or_else(|| format!("--to {}: give --out DIR", to.unwrap_or("")));
    let task = match to {
        None => Task::Validate,
        Some("json") => Task::Summary,
        Some("bvh") => Task::Bvh(need_out()?),
        Some("glb") => Task::Glb(need_out()?),
        Some("png") => thumbnails(need_out()?)?,
        Some(other) => return Err(format!("--to {other}: expected json, bvh, glb or png")),
    };
    let (files, root) = listed(source)?;
    if let Some(dir) = out {
        std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    }
    let manifest = manifest.map(Path::to_path_buf).unwrap_or_else(|| out.unwrap_or(Path::new(".")).join("manifest.jsonl"));
    let jobs = jobs.unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()));
    let shown = !quiet && std::io::stderr().is_terminal();
    let progress = |done: usize, total: usize| {
        if shown {
            let filled = done * 30 / total.max(1);
            eprint!("\r[{}{}] {done}/{total} files ", "#".repeat(filled), " ".repeat(30 - filled));
        }
    };
    let lines = run(&files, &root, &task, Some(&manifest), jobs.max(1), &progress)?;
    if shown {
        eprint!("\r{}\r", " ".repeat(60));
    }
    let failed: Vec<&serde_json::Value> = lines.iter().filter(|l| l["status"] != "ok").collect();
    for line in &failed {
        eprintln!("FAIL {}", line["error"].as_str().unwrap_or("?"));
    }
    if !quiet {
        eprintln!("{} files: {} ok, {} failed; manifest {}", lines.len(), lines.len() - failed.len(), failed.len(), manifest.display());
    }
    Ok(if failed.is_empty() { ExitCode::SUCCESS } else { ExitCode::FAILURE })
}

/// Contact sheets (1280x720, four columns, the default camera) drawn on one GPU
/// shared by the batch's threads, one sheet at a time.
fn thumbnails(out: PathBuf) -> Result<Task, String> {
    let gpu = crate::render::Gpu::new()?;
    let sheet = super::render::Sheet::new(&gpu, [1280, 720], 4);
    let shared = std::sync::Mutex::new((gpu, sheet));
    let write = move |clip: &mocap::Clip, path: &Path| -> Result<(), String> {
        let stage = crate::render::StageView::new(vec![(String::new(), mocap::Asset::Clip(clip.clone()))]);
        let mut guard = shared.lock().map_err(|_| "the renderer failed on an earlier file".to_string())?;
        let (gpu, sheet) = &mut *guard;
        sheet.write(gpu, &stage, crate::render::Orbit::default(), path)
    };
    Ok(Task::Write { out, extension: "png", write: std::sync::Arc::new(write) })
}

/// The files of a folder (recursively), or those a list file names (one a
/// line, relative to the list's folder); and the folder outputs are relative to.
fn listed(source: &Path) -> Result<(Vec<PathBuf>, PathBuf), String> {
    if source.is_dir() {
        return Ok((motion_files(source), source.to_path_buf()));
    }
    let text = std::fs::read_to_string(source).map_err(|e| format!("{}: cannot read: {e}", source.display()))?;
    let base = source.parent().unwrap_or(Path::new("")).to_path_buf();
    let files = text.lines().map(str::trim).filter(|l| !l.is_empty() && !l.starts_with('#')).map(|l| base.join(l)).collect();
    Ok((files, base))
}
