//! `cargo xtask dist`: builds the wasm crate, runs wasm-bindgen (and wasm-opt when
//! available) and copies the page into `dist/`.

use crate::setup::{self, WASM_LD, WasmToolchain};
use crate::util::{root, run};
use std::path::{Path, PathBuf};
use std::process::Command;

const TARGET: &str = "wasm32-unknown-unknown";

/// Builds `dist/`; `fast` skips LTO and wasm-opt for quicker iteration. Returns the dist path.
pub fn dist(fast: bool) -> Result<PathBuf, String> {
    let root = root();
    let profile = if fast { "web-fast" } else { "web-release" };
    let target_dir = root.join("target/wasm");
    let mut cargo = match setup::wasm_toolchain()? {
        WasmToolchain::Rustup => Command::new(std::env::var("CARGO").unwrap_or_else(|_| "cargo".into())),
        WasmToolchain::Debian => {
            let mut c = Command::new("/usr/bin/cargo");
            c.env("RUSTC", "/usr/bin/rustc")
                .env("RUSTDOC", "/usr/bin/rustdoc")
                .env("RUSTC_BOOTSTRAP", "1")
                .env("CARGO_TARGET_WASM32_UNKNOWN_UNKNOWN_LINKER", WASM_LD)
                .env_remove("RUSTUP_TOOLCHAIN")
                .env_remove("CARGO")
                .args(["-Zbuild-std=std,panic_abort"]);
            c
        }
    };
    cargo
        .current_dir(&root)
        .args(["build", "-p", "mocap-web", "--lib", "--target", TARGET, "--profile", profile, "--target-dir"])
        .arg(&target_dir);
    run(&mut cargo)?;
    let wasm = target_dir.join(TARGET).join(profile).join("mocap_web.wasm");
    if !fast {
        optimize(&wasm);
    }

    let dist = root.join("dist");
    let _ = std::fs::remove_dir_all(&dist);
    let pkg = dist.join("pkg");
    std::fs::create_dir_all(&pkg).map_err(|e| format!("{}: {e}", pkg.display()))?;
    let bindgen = setup::wasm_bindgen_cli()?;
    run(Command::new(bindgen)
        .args(["--target", "web", "--remove-name-section", "--remove-producers-section", "--out-dir"])
        .arg(&pkg)
        .arg(&wasm))?;
    copy(&root.join("index.html"), &dist.join("index.html"))?;
    copy_dir(&root.join("web"), &dist.join("web"))?;
    println!("dist: {}", dist.display());
    Ok(dist)
}

/// Oldest wasm-opt trusted with current Rust output: 108 (Debian 12) breaks the
/// externref table when run after wasm-bindgen and grows the gzipped size before it.
const MIN_WASM_OPT: u32 = 116;

/// Shrinks the cargo output with `wasm-opt -Os` (before wasm-bindgen) when a recent
/// enough binaryen is available; keeps the input on any failure.
fn optimize(wasm: &Path) {
    let Some(wasm_opt) = setup::wasm_opt() else {
        eprintln!("xtask: wasm-opt not found; skipping size optimisation");
        return;
    };
    let version = crate::util::output(Command::new(wasm_opt).arg("--version"))
        .and_then(|v| v.split_whitespace().nth(2).and_then(|n| n.parse::<u32>().ok()))
        .unwrap_or(0);
    if version < MIN_WASM_OPT {
        eprintln!("xtask: wasm-opt version {version} is older than {MIN_WASM_OPT}; skipping it");
        return;
    }
    let out = wasm.with_extension("opt.wasm");
    let features = [
        "--enable-bulk-memory",
        "--enable-nontrapping-float-to-int",
        "--enable-sign-ext",
        "--enable-mutable-globals",
        "--enable-reference-types",
        "--enable-multivalue",
    ];
    let ok = run(Command::new(wasm_opt).arg("-Os").args(features).arg(wasm).arg("-o").arg(&out)).is_ok();
    if ok && std::fs::rename(&out, wasm).is_ok() {
        return;
    }
    let _ = std::fs::remove_file(&out);
    eprintln!("xtask: wasm-opt failed; keeping the unoptimised wasm");
}

fn copy(from: &Path, to: &Path) -> Result<(), String> {
    std::fs::copy(from, to).map(|_| ()).map_err(|e| format!("copy {} -> {}: {e}", from.display(), to.display()))
}

fn copy_dir(from: &Path, to: &Path) -> Result<(), String> {
    std::fs::create_dir_all(to).map_err(|e| format!("{}: {e}", to.display()))?;
    let entries = std::fs::read_dir(from).map_err(|e| format!("{}: {e}", from.display()))?;
    for entry in entries.flatten() {
        let path = entry.path();
        let dest = to.join(entry.file_name());
        if path.is_dir() { copy_dir(&path, &dest)? } else { copy(&path, &dest)? }
    }
    Ok(())
}
