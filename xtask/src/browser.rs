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

/// Runs every test: `cargo test --workspace`, then the browser suite in WebGL2 and WebGPU modes.
pub fn test_all(args: &[String]) -> Result<(), String> {
    let fast = args.iter().any(|a| a == "--fast");
    if !args.iter().any(|a| a == "--browser-only") {
        setup::vulkan_driver();
        let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
        run(Command::new(&cargo).current_dir(root()).args(["test", "--workspace"]))?;
    }
    let dist = crate::dist::dist(fast)?;
    let chromium = setup::chromium()?;
    setup::playwright()?;
    let out = root().join("tests/browser/out");
    std::fs::create_dir_all(&out).map_err(|e| format!("{}: {e}", out.display()))?;
    let expected = expected_frames(&out)?;
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
        let mut multi = node("multi.mjs");
        multi.args([url.as_str(), mode]).arg(&out).arg(&chromium);
        if let Some(corpus) = corpus_dir() {
            multi.arg(corpus);
        }
        if let Err(e) = run(&mut multi) {
            failures.push(format!("{mode} several characters: {e}"));
        }
    }
    if let Err(e) = run(node("api.mjs").arg(&url).arg(&dist).arg(&out).arg(&chromium)) {
        failures.push(format!("JavaScript API: {e}"));
    }
    if let Err(e) = run(node("nogpu.mjs").arg(&url).arg(&out).arg(&chromium)) {
        failures.push(format!("no-gpu message: {e}"));
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
    let url = spawn_server(dist.clone())?;
    let mut cmd = node("bench.mjs");
    cmd.args([url.as_str()]).arg(&dist).arg(&chromium);
    if let Some(f) = file {
        cmd.arg(f);
    }
    run(&mut cmd)
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
            let info = output(Command::new(&cargo).current_dir(root()).args(["run", "-q", "-p", "mocap-cli", "--", "info", "--json"]).arg(&file))
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
