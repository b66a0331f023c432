//! The Python package's tests under `cargo xtask test`: a virtual environment in
//! `target/pyenv` with pinned maturin, NumPy, pytest and Dask from PyPI, the
//! wheel built once by maturin (`crates/mocap-python/target`) and installed,
//! then pytest over `crates/mocap-python/tests` against the corpus and the
//! `mocap` binary `cargo test` built. Without Python this fails unless
//! `MOCAP_SKIP_PYTHON=1` opts out.

use crate::setup;
use crate::util::{have, root, run};
use std::path::{Path, PathBuf};
use std::process::Command;

/// What the venv holds, pinned.
const PACKAGES: &[&str] = &["maturin==1.16.0", "numpy==2.4.6", "pytest==9.2.0", "dask[distributed]==2026.8.0"];

/// The venv's `bin/` (made and filled on first use).
pub fn venv() -> Result<PathBuf, String> {
    let dir = root().join("target/pyenv");
    let bin = dir.join("bin");
    if !bin.join("python").is_file() {
        if !have("python3") {
            setup::apt_install(&["python3", "python3-venv"])?;
        }
        if run(Command::new("python3").args(["-m", "venv"]).arg(&dir)).is_err() {
            setup::apt_install(&["python3-venv"])?;
            run(Command::new("python3").args(["-m", "venv"]).arg(&dir))?;
        }
    }
    let stamp = dir.join("packages.txt");
    let wanted = PACKAGES.join("\n");
    if std::fs::read_to_string(&stamp).ok().as_deref() != Some(wanted.as_str()) {
        run(Command::new(bin.join("pip")).args(["install", "-q", "--disable-pip-version-check"]).args(PACKAGES))?;
        std::fs::write(&stamp, wanted).map_err(|e| format!("{}: {e}", stamp.display()))?;
    }
    Ok(bin)
}

/// Builds and installs the wheel into the venv; returns the venv's `bin/`.
pub fn install() -> Result<PathBuf, String> {
    let bin = venv()?;
    let crate_dir = root().join("crates/mocap-python");
    let wheels = root().join("target/wheels");
    let _ = std::fs::remove_dir_all(&wheels);
    run(Command::new(bin.join("maturin"))
        .args(["build", "--release", "--quiet", "-o"])
        .arg(&wheels)
        .current_dir(&crate_dir))?;
    let wheel = std::fs::read_dir(&wheels)
        .map_err(|e| format!("{}: {e}", wheels.display()))?
        .flatten()
        .map(|e| e.path())
        .find(|p| p.extension().is_some_and(|x| x == "whl"))
        .ok_or("maturin built no wheel")?;
    run(Command::new(bin.join("pip"))
        .args(["install", "-q", "--disable-pip-version-check", "--force-reinstall", "--no-deps"])
        .arg(&wheel))?;
    Ok(bin)
}

/// Runs the package's pytest suite (`corpus`: `../shared/corpus` when present).
pub fn test(corpus: Option<&Path>) -> Result<(), String> {
    if std::env::var("MOCAP_SKIP_PYTHON").is_ok_and(|v| v == "1") {
        eprintln!("xtask: the Python package's tests skipped (MOCAP_SKIP_PYTHON=1)");
        return Ok(());
    }
    let bin = install()?;
    let mut pytest = Command::new(bin.join("python"));
    pytest.args(["-m", "pytest", "-q", "-p", "no:cacheprovider"]).arg(root().join("crates/mocap-python/tests"));
    pytest.env("MOCAP_BIN", root().join("target/debug/mocap"));
    if let Some(c) = corpus {
        pytest.env("MOCAP_CORPUS", c);
    }
    run(&mut pytest)
}
