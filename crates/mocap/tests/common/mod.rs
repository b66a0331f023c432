//! Shared by the integration tests: where the corpus of real files is.

use std::path::{Path, PathBuf};

/// `../shared/corpus` beside the repository (or `$MOCAP_CORPUS`). Missing, it is a
/// test failure unless `MOCAP_SKIP_CORPUS=1` opts out (then `None`).
pub fn corpus_dir() -> Option<PathBuf> {
    let dir = std::env::var_os("MOCAP_CORPUS")
        .map(PathBuf::from)
        .unwrap_or_else(|| Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/corpus"));
    if dir.join("MANIFEST.tsv").is_file() {
        return Some(dir);
    }
    if std::env::var("MOCAP_SKIP_CORPUS").is_ok_and(|v| v == "1") {
        eprintln!("{}: corpus not found, skipped (MOCAP_SKIP_CORPUS=1)", dir.display());
        return None;
    }
    panic!(
        "{}: corpus not found (put ../shared beside the repository, set MOCAP_CORPUS, or opt out with MOCAP_SKIP_CORPUS=1)",
        dir.display()
    );
}
