//! `cargo xtask test` and `cargo xtask bench-web`: native tests, then headless
//! Chromium (Playwright) against a locally served `dist/`.

use crate::setup;
use crate::util::{output, root, run};
use std::net::TcpListener;
use std::path::{Path, PathBuf};
use std::process::Command;

/// Corpus files the browser tests drop, relative to the corpus root.
const CORPUS_FILES: &[&str] = &["bvh/assimp_cmu/01_01.bvh", "bvh/snu_mass/walk.bvh"];

/// The largest corpus file (drop-to-first-frame benchmark).
const BENCH_FILE: &str = "bvh/axis_neuron/test.bvh";

/// `../shared/corpus` next to the repository, when present.
fn corpus_dir() -> Option<PathBuf> {
    let dir = root().join("../shared/corpus");
    dir.is_dir().then(|| dir.canonicalize().unwrap_or(dir))
}

/// The corpus, required: missing, it is an error unless `MOCAP_SKIP_CORPUS=1` opts out.
fn required_corpus() -> Result<Option<PathBuf>, String> {
    match corpus_dir() {
        Some(dir) => Ok(Some(dir)),
        None if std::env::var("MOCAP_SKIP_CORPUS").is_ok_and(|v| v == "1") => {
            eprintln!("xtask: ../shared/corpus not found; corpus tests skipped (MOCAP_SKIP_CORPUS=1)");
            Ok(None)
        }
        None => Err("../shared/corpus not found: put the shared folder beside the repository, or opt out with MOCAP_SKIP_CORPUS=1".into()),
    }
}

/// The Acclaim pair the browser drops, relative to the corpus root.
const ACCLAIM_PAIR: (&str, &str) = ("asf_amc/cmu/02.asf", "asf_amc/cmu/02_01.amc");
/// The joint whose position the browser test checks.
const ACCLAIM_JOINT: &str = "ltibia";

/// Writes `acclaim.json` for formats.mjs: the pair's paths, frame count and one
/// joint's frame-0 position, from the core loader (what the page must agree with).
fn expected_acclaim(out: &Path, corpus: &Path) -> Result<PathBuf, String> {
    let (asf, amc) = (corpus.join(ACCLAIM_PAIR.0), corpus.join(ACCLAIM_PAIR.1));
    let read = |p: &Path| std::fs::read(p).map_err(|e| format!("{}: {e}", p.display()));
    let (asf_bytes, amc_bytes) = (read(&asf)?, read(&amc)?);
    let inputs =
        [mocap::Input { name: "02.asf", bytes: &asf_bytes }, mocap::Input { name: "02_01.amc", bytes: &amc_bytes }];
    let clip =
        mocap::load(&inputs).pop().ok_or("no clip")?.map_err(|e| e.to_string())?.into_clip().ok_or("not a clip")?;
    let joint = clip.skeleton().find(ACCLAIM_JOINT).ok_or("no ltibia")?;
    let p = clip.world_positions(0).get(joint).copied().ok_or("no position")?;
    let json = format!(
        "{{\"corpus\":{:?},\"asf\":{:?},\"amc\":{:?},\"frames\":{},\"joint\":{:?},\"position\":[{},{},{}]}}",
        corpus.display().to_string(),
        asf.display().to_string(),
        amc.display().to_string(),
        clip.frame_count(),
        ACCLAIM_JOINT,
        p.x,
        p.y,
        p.z
    );
    let path = out.join("acclaim.json");
    std::fs::write(&path, json).map_err(|e| e.to_string())?;
    Ok(path)
}

/// Runs every test: `cargo test --workspace`, then the browser suite in WebGL2 and WebGPU modes.
pub fn test_all(args: &[String]) -> Result<(), String> {
    let fast = args.iter().any(|a| a == "--fast");
    let corpus = required_corpus()?;
    if !args.iter().any(|a| a == "--browser-only") {
        setup::vulkan_driver();
        setup::ffmpeg()?;
        let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
        run(Command::new(&cargo).current_dir(root()).args(["test", "--workspace"]))?;
    }
    let dist = crate::dist::dist(fast)?;
    let chromium = setup::chromium()?;
    setup::ffmpeg()?;
    setup::playwright()?;
    let out = root().join("tests/browser/out");
    std::fs::create_dir_all(&out).map_err(|e| format!("{}: {e}", out.display()))?;
    let expected = expected_frames(&out)?;
    let acclaim = corpus.as_deref().map(|c| expected_acclaim(&out, c)).transpose()?;
    let url = spawn_server(dist.clone())?;
    let mut failures = Vec::new();
    for mode in ["webgl2", "webgpu"] {
        let result = run(node("run.mjs").args([url.as_str(), mode]).arg(&out).arg(&chromium).arg(&expected));
        if let Err(e) = result {
            failures.push(format!("{mode}: {e}"));
        }
        if let Err(e) = run(node("links.mjs").args([url.as_str(), mode]).arg(&out).arg(&chromium)) {
            failures.push(format!("{mode} links: {e}"));
        }
        if let Err(e) = run(node("render.mjs").args([url.as_str(), mode]).arg(&out).arg(&chromium)) {
            failures.push(format!("{mode} rendering: {e}"));
        }
        if let Err(e) = run(node("demo.mjs").args([url.as_str(), mode]).arg(&out).arg(&chromium)) {
            failures.push(format!("{mode} tentacle demo: {e}"));
        }
        if let Err(e) = run(node("gpu-loss.mjs").args([url.as_str(), mode]).arg(&out).arg(&chromium)) {
            failures.push(format!("{mode} lost graphics device: {e}"));
        }
        if let Err(e) = run(node("autosave.mjs").args([url.as_str(), mode]).arg(&out).arg(&chromium)) {
            failures.push(format!("{mode} autosave and restore: {e}"));
        }
        let walk = root().join("data/walk.bvh");
        if let Err(e) = run(node("video.mjs").args([url.as_str(), mode]).arg(&out).arg(&chromium).arg(&walk)) {
            failures.push(format!("{mode} video export: {e}"));
        }
        let mut multi = node("multi.mjs");
        multi.args([url.as_str(), mode]).arg(&out).arg(&chromium);
        if let Some(corpus) = corpus_dir() {
            multi.arg(corpus);
        }
        if let Err(e) = run(&mut multi) {
            failures.push(format!("{mode} several characters: {e}"));
        }
        if let Some(acclaim) = &acclaim {
            if let Err(e) = run(node("formats.mjs").args([url.as_str(), mode]).arg(&out).arg(&chromium).arg(acclaim)) {
                failures.push(format!("{mode} formats: {e}"));
            }
        }
    }
    if let Err(e) = run(node("api.mjs").arg(&url).arg(&dist).arg(&out).arg(&chromium)) {
        failures.push(format!("JavaScript API: {e}"));
    }
    if let Err(e) = run(node("editing.mjs").arg(&url).arg(&out).arg(&chromium)) {
        failures.push(format!("editing through the page's controls: {e}"));
    }
    if let Err(e) = run(node("nogpu.mjs").arg(&url).arg(&out).arg(&chromium)) {
        failures.push(format!("no-gpu message: {e}"));
    }
    match crate::gltf_files::write(&out.join("gltf"), corpus.as_deref()) {
        Ok(dir) => {
            if let Err(e) = run(node("gltf.mjs").arg(&dir).arg(&chromium)) {
                failures.push(format!("glTF written (validator, three.js): {e}"));
            }
            if let Err(e) = run(node("character.mjs").arg(&url).arg(&out).arg(&chromium).arg(&dir)) {
                failures.push(format!("glTF characters in the page: {e}"));
            }
        }
        Err(e) => failures.push(format!("glTF files: {e}")),
    }
    if !args.iter().any(|a| a == "--browser-only") {
        if let Err(e) = crate::python::test(corpus.as_deref()) {
            failures.push(format!("Python package: {e}"));
        }
    }
    if !fast {
        if let Err(e) = crate::dist::check_download_size(&dist) {
            failures.push(e);
        }
    }
    if failures.is_empty() {
        println!("xtask test: all tests passed (screenshots in {})", out.display());
        Ok(())
    } else {
        Err(format!("browser tests failed: {}", failures.join("; ")))
    }
}

/// Builds `dist/` and prints the web performance figures.
pub fn bench() -> Result<(), String> {
    let dist = crate::dist::dist(false)?;
    let chromium = setup::chromium()?;
    setup::playwright()?;
    let file = corpus_dir().map(|c| c.join(BENCH_FILE)).filter(|f| f.is_file());
    println!(
        "transfer size: {} bytes gzipped (wasm + js + html + css; aim <= {} = 2.0 MB)",
        crate::dist::download_size(&dist),
        crate::dist::DOWNLOAD_AIM
    );
    let url = spawn_server(dist.clone())?;
    let mut cmd = node("bench.mjs");
    cmd.args([url.as_str()]).arg(&chromium);
    if let Some(f) = file {
        cmd.arg(f);
        if let Some(corpus) = corpus_dir() {
            let dir = std::env::temp_dir().join("mocap-bench-glb");
            cmd.arg(crate::gltf_files::bench_glb(&corpus, &dir)?);
        }
    }
    run(&mut cmd)?;
    // The page's video export: a 10 s corpus clip where there is one, else the default walk.
    let clip = corpus_dir()
        .map(|c| c.join("bvh/animated_drawings/jesse_dance.bvh"))
        .filter(|f| f.is_file())
        .unwrap_or_else(|| root().join("data/walk.bvh"));
    run(node("bench-video.mjs").arg(&url).arg(&chromium).arg(clip))
}

fn node(script: &str) -> Command {
    let dir = root().join("tests/browser");
    let mut c = Command::new("node");
    c.current_dir(&dir).arg(dir.join(script));
    c
}

/// Serves `dist` on a free port in a background thread; returns the URL.
fn spawn_server(dist: PathBuf) -> Result<String, String> {
    let listener = TcpListener::bind("127.0.0.1:0").map_err(|e| e.to_string())?;
    let port = listener.local_addr().map_err(|e| e.to_string())?.port();
    std::thread::spawn(move || crate::serve::serve_forever(listener, dist));
    Ok(format!("http://127.0.0.1:{port}/"))
}

/// Writes `expected.json`: frame counts of the corpus files per `mocap info --json`.
fn expected_frames(out: &Path) -> Result<PathBuf, String> {
    let path = out.join("expected.json");
    let mut entries = Vec::new();
    if let Some(corpus) = corpus_dir() {
        let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
        for rel in CORPUS_FILES {
            let file = corpus.join(rel);
            if !file.is_file() {
                continue;
            }
            let info = output(
                Command::new(&cargo)
                    .current_dir(root())
                    .args(["run", "-q", "-p", "mocap-cli", "--", "info", "--json"])
                    .arg(&file),
            )
            .ok_or_else(|| format!("mocap info {} failed", file.display()))?;
            let frames = json_number(&info, "\"frames\"").ok_or("no frames in mocap info output")?;
            entries.push(format!("{{\"path\":{:?},\"frames\":{frames}}}", file.display().to_string()));
        }
    } else {
        eprintln!("xtask: ../shared/corpus not found; corpus drop tests will be skipped");
    }
    std::fs::write(&path, format!("[{}]", entries.join(","))).map_err(|e| e.to_string())?;
    Ok(path)
}

/// The integer after `key:` in a JSON text (enough for `mocap info`).
fn json_number(text: &str, key: &str) -> Option<u64> {
    let rest = &text[text.find(key)? + key.len()..];
    let rest = rest.trim_start().strip_prefix(':')?.trim_start();
    let digits: String = rest.chars().take_while(char::is_ascii_digit).collect();
    digits.parse().ok()
}
