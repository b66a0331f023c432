//! Installs missing tools: Debian Rust-for-wasm packages, wasm-bindgen-cli,
//! chromium, mesa Vulkan (lavapipe) and npm playwright-core.

use crate::util::{have, output, root, run};
use std::path::PathBuf;
use std::process::Command;

/// How the wasm build is done on this machine.
#[derive(Clone, Copy, PartialEq, Eq)]
pub enum WasmToolchain {
    /// rustup with the wasm32 target installed: plain `cargo build --target`.
    Rustup,
    /// Debian's `rustc-web` + std sources: `-Zbuild-std` with the system rustc.
    Debian,
}

/// Chooses (and if needed installs) the wasm toolchain.
pub fn wasm_toolchain() -> Result<WasmToolchain, String> {
    let installed = output(Command::new("rustup").args(["target", "list", "--installed"])).unwrap_or_default();
    if installed.lines().any(|l| l.trim() == "wasm32-unknown-unknown") {
        return Ok(WasmToolchain::Rustup);
    }
    if !debian_ready() {
        apt_install(&["rustc-web", "cargo-web", "rust-web-src", "lld-22"])?;
    }
    if debian_ready() {
        Ok(WasmToolchain::Debian)
    } else {
        Err("no wasm32 toolchain: run `rustup target add wasm32-unknown-unknown`, or install Debian's rustc-web cargo-web rust-web-src lld-22".into())
    }
}

fn debian_ready() -> bool {
    have("/usr/bin/rustc") && have("/usr/bin/cargo") && have(WASM_LD) && std_sources().is_some()
}

/// The wasm linker from the Debian `lld-22` package.
pub const WASM_LD: &str = "/usr/lib/llvm-22/bin/wasm-ld";

fn std_sources() -> Option<PathBuf> {
    let sysroot = output(Command::new("/usr/bin/rustc").args(["--print", "sysroot"]))?;
    let p = PathBuf::from(sysroot.trim()).join("lib/rustlib/src/rust/library");
    p.is_dir().then_some(p)
}

/// `apt-get install -y` (after `apt-get update`), with sudo when not root.
pub fn apt_install(packages: &[&str]) -> Result<(), String> {
    if !have("apt-get") {
        return Err(format!("please install {packages:?} (no apt-get here)"));
    }
    let root_user = output(Command::new("id").arg("-u")).is_some_and(|u| u.trim() == "0");
    let apt = |args: &[&str]| {
        let mut c = if root_user { Command::new("apt-get") } else { Command::new("sudo") };
        if !root_user {
            c.arg("apt-get");
        }
        c.args(args).env("DEBIAN_FRONTEND", "noninteractive");
        c
    };
    run(&mut apt(&["update"]))?;
    let mut install = apt(&["install", "-y", "--no-install-recommends"]);
    install.args(packages);
    run(&mut install)
}

/// The wasm-bindgen version pinned in Cargo.lock.
pub fn locked_wasm_bindgen_version() -> Result<String, String> {
    let lock = std::fs::read_to_string(root().join("Cargo.lock")).map_err(|e| format!("Cargo.lock: {e}"))?;
    let mut lines = lock.lines();
    while let Some(line) = lines.next() {
        if line.trim() == "name = \"wasm-bindgen\""
            && let Some(v) = lines.next().and_then(|l| l.trim().strip_prefix("version = \""))
        {
            return Ok(v.trim_end_matches('"').to_owned());
        }
    }
    Err("wasm-bindgen not found in Cargo.lock".into())
}

/// Path of a wasm-bindgen CLI matching the crate version, installing it if needed.
pub fn wasm_bindgen_cli() -> Result<String, String> {
    let version = locked_wasm_bindgen_version()?;
    let cargo_bin =
        std::env::var("CARGO_HOME").map(PathBuf::from).unwrap_or_else(|_| home().join(".cargo")).join("bin");
    let candidates = ["wasm-bindgen".to_owned(), cargo_bin.join("wasm-bindgen").display().to_string()];
    for c in &candidates {
        if output(Command::new(c).arg("--version"))
            .is_some_and(|v| v.split_whitespace().nth(1) == Some(version.as_str()))
        {
            return Ok(c.clone());
        }
    }
    run(Command::new("cargo").args(["install", "wasm-bindgen-cli", "--version", &version]))?;
    Ok(candidates[1].clone())
}

fn home() -> PathBuf {
    std::env::var_os("HOME").map(PathBuf::from).unwrap_or_else(|| PathBuf::from("/root"))
}

/// The Chromium binary, installing Debian's package if missing.
pub fn chromium() -> Result<String, String> {
    for c in ["/usr/bin/chromium", "/usr/bin/chromium-browser"] {
        if have(c) {
            return Ok(c.to_owned());
        }
    }
    apt_install(&["chromium"])?;
    Ok("/usr/bin/chromium".to_owned())
}

/// Node.js, playwright-core, three (the benchmark's comparison page and the
/// glTF check's loader), gltf-validator (Khronos) and esbuild (minifies the
/// page's JavaScript in `cargo xtask dist`) under
/// `tests/browser/node_modules` (never downloads browsers).
pub fn playwright() -> Result<(), String> {
    if !have("node") || !have("npm") {
        apt_install(&["nodejs", "npm"])?;
    }
    let dir = root().join("tests/browser");
    if ["playwright-core", "three", "esbuild", "gltf-validator", "mediabunny", "gifenc"]
        .iter()
        .any(|p| !dir.join("node_modules").join(p).is_dir())
    {
        run(Command::new("npm")
            .args(["install", "--no-audit", "--no-fund"])
            .current_dir(&dir)
            .env("PLAYWRIGHT_SKIP_BROWSER_DOWNLOAD", "1"))?;
    }
    Ok(())
}

/// esbuild from `tests/browser`'s npm packages (installed on first use; `None`
/// where npm cannot install it).
pub fn esbuild() -> Option<PathBuf> {
    let bin = root().join("tests/browser/node_modules/.bin/esbuild");
    if !bin.is_file() {
        let _ = playwright();
    }
    bin.is_file().then_some(bin)
}

/// npm's binaryen (its JavaScript build of wasm-opt), installed into
/// `tests/browser/node_modules` on first use without touching package.json.
pub fn npm_wasm_opt() -> Option<PathBuf> {
    let dir = root().join("tests/browser");
    let bin = dir.join("node_modules/.bin/wasm-opt");
    if !bin.is_file() {
        let _ = run(Command::new("npm")
            .args(["install", "--no-save", "--no-audit", "--no-fund", "binaryen@132.0.0"])
            .current_dir(&dir));
    }
    bin.is_file().then_some(bin)
}

/// `wasm-opt` if present; tries to install binaryen once when missing.
pub fn wasm_opt() -> Option<&'static str> {
    if !have("wasm-opt") {
        let _ = apt_install(&["binaryen"]);
    }
    have("wasm-opt").then_some("wasm-opt")
}

/// Mesa's lavapipe (software Vulkan) for the native render tests, when no Vulkan
/// driver is installed. Failure is not fatal here: the tests then say what is missing.
pub fn vulkan_driver() {
    let icd = std::path::Path::new("/usr/share/vulkan/icd.d");
    let any_driver = std::fs::read_dir(icd).is_ok_and(|mut entries| entries.next().is_some());
    if !any_driver {
        if let Err(e) = apt_install(&["mesa-vulkan-drivers"]) {
            eprintln!("xtask: could not install mesa-vulkan-drivers: {e}");
        }
    }
}

/// `ffmpeg` and `ffprobe` (Debian's), which the video tests decode with.
pub fn ffmpeg() -> Result<(), String> {
    if have("ffmpeg") && have("ffprobe") {
        return Ok(());
    }
    apt_install(&["ffmpeg"])
}

/// Everything at once.
pub fn setup_all() -> Result<(), String> {
    wasm_toolchain()?;
    wasm_bindgen_cli()?;
    chromium()?;
    playwright()?;
    vulkan_driver();
    ffmpeg()?;
    println!("setup: done");
    Ok(())
}
