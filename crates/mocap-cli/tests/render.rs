//! Golden images for `mocap render` on the native Vulkan path (Mesa lavapipe on a
//! machine without a GPU): fixed scenes compared with reference PNGs in
//! `tests/golden/` within a tolerance; the report gives the share of differing pixels.
//!
//! Regenerate the references (after an intended change in looks) with
//! `MOCAP_UPDATE_GOLDEN=1 cargo test -p mocap-cli --test render`.
//! Needs a Vulkan driver (`apt-get install mesa-vulkan-drivers`, which
//! `cargo xtask test` installs); `MOCAP_SKIP_GPU_TESTS=1` skips them elsewhere.

use std::path::{Path, PathBuf};
use std::process::Command;

/// A small figure (hips, spine, head, two legs, two arms) with three frames of motion.
const FIGURE: &str = "HIERARCHY
ROOT Hips
{
  OFFSET 0 0 0
  CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation
  JOINT Spine
  {
    OFFSET 0 20 0
    CHANNELS 3 Zrotation Xrotation Yrotation
    JOINT Head
    {
      OFFSET 0 30 0
      CHANNELS 3 Zrotation Xrotation Yrotation
      End Site
      {
        OFFSET 0 15 0
      }
    }
    JOINT LeftArm
    {
      OFFSET 15 25 0
      CHANNELS 3 Zrotation Xrotation Yrotation
      End Site
      {
        OFFSET 45 0 0
      }
    }
    JOINT RightArm
    {
      OFFSET -15 25 0
      CHANNELS 3 Zrotation Xrotation Yrotation
      End Site
      {
        OFFSET -45 0 0
      }
    }
  }
  JOINT LeftLeg
  {
    OFFSET 10 0 0
    CHANNELS 3 Zrotation Xrotation Yrotation
    End Site
    {
      OFFSET 0 -90 0
    }
  }
  JOINT RightLeg
  {
    OFFSET -10 0 0
    CHANNELS 3 Zrotation Xrotation Yrotation
    End Site
    {
      OFFSET 0 -90 0
    }
  }
}
MOTION
Frames: 3
Frame Time: 0.5
0 90 0 0 0 0 0 0 0 0 0 0 -60 0 0 60 0 0 0 25 0 0 -25 0
0 92 10 0 0 30 10 0 0 -10 0 0 -20 0 0 20 0 0 0 -25 0 0 25 0
0 90 20 0 0 60 0 0 0 0 0 0 60 0 0 -60 0 0 0 25 0 0 -25 0
";

fn golden_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/golden")
}

fn decode(path: &Path) -> ([u32; 2], Vec<u8>) {
    let decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))));
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut buf).unwrap();
    buf.truncate(info.buffer_size());
    assert_eq!(info.color_type, png::ColorType::Rgba, "{}", path.display());
    ([info.width, info.height], buf)
}

/// Share of pixels whose largest channel difference exceeds `tolerance`.
fn differing_share(a: &[u8], b: &[u8], tolerance: u8) -> f64 {
    let differing = a.chunks(4).zip(b.chunks(4)).filter(|(p, q)| p.iter().zip(q.iter()).any(|(x, y)| x.abs_diff(*y) > tolerance)).count();
    differing as f64 / (a.len() / 4).max(1) as f64
}

/// Renders with `args` (plus the figure file and --out) and checks against `name`.
fn check_golden(name: &str, files: usize, args: &[&str]) {
    if std::env::var_os("MOCAP_SKIP_GPU_TESTS").is_some() {
        eprintln!("MOCAP_SKIP_GPU_TESTS set: skipping golden image {name}");
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let figure = dir.path().join("figure.bvh");
    std::fs::write(&figure, FIGURE).unwrap();
    let out = dir.path().join(name);
    let mut command = Command::new(env!("CARGO_BIN_EXE_mocap"));
    command.arg("render");
    for _ in 0..files {
        command.arg(&figure);
    }
    let output = command.args(args).arg("--out").arg(&out).output().unwrap();
    assert!(
        output.status.success(),
        "mocap render failed (is a Vulkan driver installed? apt-get install mesa-vulkan-drivers): {}",
        String::from_utf8_lossy(&output.stderr)
    );
    let golden = golden_dir().join(name);
    if std::env::var_os("MOCAP_UPDATE_GOLDEN").is_some() {
        std::fs::copy(&out, &golden).unwrap();
        eprintln!("updated {}", golden.display());
        return;
    }
    let (size_a, a) = decode(&out);
    let (size_b, b) = decode(&golden);
    assert_eq!(size_a, size_b, "{name}: size differs from the golden image");
    let share = differing_share(&a, &b, 24);
    eprintln!("{name}: {:.3}% of pixels differ from the golden image", share * 100.0);
    if share > 0.005 {
        let kept = std::env::temp_dir().join(format!("mocap-golden-actual-{name}"));
        let _ = std::fs::copy(&out, &kept);
        panic!("{name}: {:.3}% of pixels differ (limit 0.5%); the rendered image is at {}", share * 100.0, kept.display());
    }
}

#[test]
fn golden_single_frame() {
    check_golden("figure_frame1.png", 1, &["--frame", "1", "--size", "320x180"]);
}

#[test]
fn golden_sticks_mode() {
    check_golden("figure_sticks.png", 1, &["--frame", "2", "--size", "320x180", "--mode", "sticks", "--camera", "-20,10"]);
}

#[test]
fn golden_two_characters_custom_camera() {
    check_golden("figure_pair_camera.png", 2, &["--time", "0.75", "--size", "320x180", "--camera", "60,25"]);
}

#[test]
fn golden_contact_sheet() {
    check_golden("figure_sheet.png", 1, &["--sheet", "--columns", "3", "--size", "480x180"]);
}

#[test]
fn comparison_detects_a_changed_image() {
    let a = vec![10u8; 400];
    let mut b = a.clone();
    b[0] = 200;
    b[41] = 20;
    assert_eq!(differing_share(&a, &b, 24), 0.01);
}

#[test]
fn render_rejects_bad_arguments_clearly() {
    let run = |args: &[&str]| Command::new(env!("CARGO_BIN_EXE_mocap")).arg("render").args(args).output().unwrap();
    let dir = tempfile::tempdir().unwrap();
    let figure = dir.path().join("f.bvh");
    std::fs::write(&figure, FIGURE).unwrap();
    let f = figure.to_str().unwrap();
    for (args, needle) in [
        (vec![f, "--out", "x.png", "--size", "10x10"], "16 to 8192"),
        (vec![f, "--out", "x.png", "--camera", "a,b"], "not a number"),
        (vec![f, "--out", "x.png", "--mode", "boxes"], "expected `capsules` or `sticks`"),
        (vec![f, "--out", "d", "--frames", "5:1"], "a <= b"),
        (vec![f, "--out", "x.png", "--frame", "99"], "out of range"),
    ] {
        let out = run(&args);
        assert!(!out.status.success());
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(needle), "{args:?}: {err}");
    }
}
