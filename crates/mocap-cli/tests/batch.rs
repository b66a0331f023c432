//! `mocap batch` over the corpus: every file gets a manifest line, the bad ones
//! their located error without stopping the rest, a second run does nothing
//! again, and conversions land under --out with the same relative paths.

use std::path::{Path, PathBuf};
use std::process::Command;

fn corpus() -> Option<PathBuf> {
    let dir = std::env::var_os("MOCAP_CORPUS")
        .map(PathBuf::from)
        .unwrap_or_else(|| Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/corpus"));
    if dir.is_dir() {
        return Some(dir);
    }
    assert!(
        std::env::var("MOCAP_SKIP_CORPUS").is_ok_and(|v| v == "1"),
        "{} not found (opt out with MOCAP_SKIP_CORPUS=1)",
        dir.display()
    );
    None
}

fn lines(path: &Path) -> Vec<serde_json::Value> {
    std::fs::read_to_string(path).unwrap().lines().map(|l| serde_json::from_str(l).unwrap()).collect()
}

#[test]
fn a_dataset_is_validated_with_a_resumable_manifest() {
    let Some(corpus) = corpus() else { return };
    let dir = tempfile::tempdir().unwrap();
    let manifest = dir.path().join("m.jsonl");
    let run = || {
        Command::new(env!("CARGO_BIN_EXE_mocap"))
            .args(["batch", "--jobs", "2", "--quiet", "--manifest"])
            .arg(&manifest)
            .arg(&corpus)
            .output()
            .unwrap()
    };
    let out = run();
    assert!(!out.status.success(), "two corpus files are malformed");
    let first = lines(&manifest);
    assert!(first.len() >= 25, "{} lines", first.len());
    let bad: Vec<_> = first.iter().filter(|l| l["status"] == "error").collect();
    assert_eq!(bad.len(), 2, "{bad:?}");
    for line in &bad {
        let error = line["error"].as_str().unwrap();
        assert!(error.starts_with(line["file"].as_str().unwrap()) && error.matches(':').count() >= 3, "{error}");
    }
    assert!(first.iter().all(|l| l["sha256"].as_str().is_some_and(|h| h.len() == 64)));
    run();
    assert_eq!(lines(&manifest).len(), first.len(), "nothing done twice");
}

#[test]
fn summaries_and_conversions() {
    let Some(corpus) = corpus() else { return };
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let status = Command::new(env!("CARGO_BIN_EXE_mocap"))
        .arg("batch")
        .arg(corpus.join("bvh/bandai_namco"))
        .args(["--to", "bvh", "--quiet", "--out"])
        .arg(&out)
        .status()
        .unwrap();
    assert!(status.success());
    let converted = lines(&out.join("manifest.jsonl"));
    assert!(!converted.is_empty());
    for line in &converted {
        assert!(Path::new(line["output"].as_str().unwrap()).is_file(), "{line}");
    }
    let json = dir.path().join("json");
    let status = Command::new(env!("CARGO_BIN_EXE_mocap"))
        .arg("batch")
        .arg(corpus.join("bvh/bandai_namco"))
        .args(["--to", "json", "--quiet", "--out"])
        .arg(&json)
        .status()
        .unwrap();
    assert!(status.success());
    let summary = lines(&json.join("manifest.jsonl"));
    let first = &summary[0];
    assert_eq!(first["frames"], 128);
    assert_eq!(first["joints"], 27);
    assert_eq!(first["units"], "cm");
    assert_eq!(first["up_axis"], "y");
    assert!(first["bounds"][1][1].as_f64().unwrap() > 100.0);
}

#[test]
fn thumbnails_are_contact_sheets() {
    let Some(corpus) = corpus() else { return };
    if std::env::var_os("MOCAP_SKIP_GPU_TESTS").is_some() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("png");
    let status = Command::new(env!("CARGO_BIN_EXE_mocap"))
        .arg("batch")
        .arg(corpus.join("bvh/bandai_namco"))
        .args(["--to", "png", "--quiet", "--out"])
        .arg(&out)
        .status()
        .unwrap();
    assert!(status.success(), "is a Vulkan driver installed?");
    for line in lines(&out.join("manifest.jsonl")) {
        let png = std::fs::read(line["output"].as_str().unwrap()).unwrap();
        assert_eq!(&png[1..4], b"PNG");
        // 1280 wide: four 320-pixel tiles.
        assert_eq!(u32::from_be_bytes([png[16], png[17], png[18], png[19]]), 1280);
    }
}
