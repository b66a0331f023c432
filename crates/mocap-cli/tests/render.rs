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
    let decoder = png::Decoder::new(std::io::BufReader::new(
        std::fs::File::open(path).unwrap_or_else(|e| panic!("{}: {e}", path.display())),
    ));
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut buf).unwrap();
    buf.truncate(info.buffer_size());
    assert_eq!(info.color_type, png::ColorType::Rgba, "{}", path.display());
    ([info.width, info.height], buf)
}

/// Share of pixels whose largest channel difference exceeds `tolerance`.
fn differing_share(a: &[u8], b: &[u8], tolerance: u8) -> f64 {
    let differing = a
        .chunks(4)
        .zip(b.chunks(4))
        .filter(|(p, q)| p.iter().zip(q.iter()).any(|(x, y)| x.abs_diff(*y) > tolerance))
        .count();
    differing as f64 / (a.len() / 4).max(1) as f64
}

/// Renders with `args` (plus the figure file and --out) and checks against `name`.
fn check_golden(name: &str, files: usize, args: &[&str]) {
    let dir = tempfile::tempdir().unwrap();
    let figure = dir.path().join("figure.bvh");
    std::fs::write(&figure, FIGURE).unwrap();
    check_golden_files(name, &vec![figure; files], args);
}

/// `../shared/corpus` beside the repository (or `$MOCAP_CORPUS`); missing, a
/// failure unless `MOCAP_SKIP_CORPUS=1` opts out (then `None`).
fn corpus_dir() -> Option<PathBuf> {
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
        "{}: corpus not found (put ../shared beside the repository, or opt out with MOCAP_SKIP_CORPUS=1)",
        dir.display()
    );
}

/// Renders `files` with `args` (plus --out) and checks against `name`.
fn check_golden_files(name: &str, files: &[PathBuf], args: &[&str]) {
    if std::env::var_os("MOCAP_SKIP_GPU_TESTS").is_some() {
        eprintln!("MOCAP_SKIP_GPU_TESTS set: skipping golden image {name}");
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join(name);
    let mut command = Command::new(env!("CARGO_BIN_EXE_mocap"));
    command.arg("render").args(files);
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
        panic!(
            "{name}: {:.3}% of pixels differ (limit 0.5%); the rendered image is at {}",
            share * 100.0,
            kept.display()
        );
    }
}

#[test]
fn golden_single_frame() {
    check_golden("figure_frame1.png", 1, &["--frame", "1", "--size", "320x180"]);
}

#[test]
fn golden_sticks_mode() {
    check_golden(
        "figure_sticks.png",
        1,
        &["--frame", "2", "--size", "320x180", "--mode", "sticks", "--camera", "-20,10"],
    );
}

#[test]
fn golden_two_characters_custom_camera() {
    check_golden("figure_pair_camera.png", 2, &["--time", "0.75", "--size", "320x180", "--camera", "60,25"]);
}

/// Body mode: the figure's generated body, skinned on the GPU, bent at frame 2.
#[test]
fn golden_body_mode() {
    check_golden("figure_body.png", 1, &["--frame", "2", "--size", "320x180", "--mode", "body", "--camera", "25,10"]);
}

#[test]
fn golden_contact_sheet() {
    check_golden("figure_sheet.png", 1, &["--sheet", "--columns", "3", "--size", "480x180"]);
}

/// A textured Quake 2 model mid-run, frames blended on the GPU, lit and shadowed;
/// its skin (`--skin`) is a PCX whose size is not a power of two.
#[test]
fn golden_textured_md2() {
    let Some(corpus) = corpus_dir() else { return };
    let model = corpus.join("md2/waste/tris.md2");
    let skin = corpus.join("md2/waste/waste.pcx");
    let skin = skin.to_str().unwrap();
    check_golden_files(
        "md2_waste_run.png",
        &[model],
        &["--skin", skin, "--animation", "run", "--time", "0.25", "--size", "320x240", "--camera", "35,12"],
    );
}

/// Without a skin the model gets the neutral material: the same frame, grey.
#[test]
fn md2_without_a_skin_is_drawn_neutral_and_differs_from_the_textured_one() {
    if std::env::var_os("MOCAP_SKIP_GPU_TESTS").is_some() {
        return;
    }
    let Some(corpus) = corpus_dir() else { return };
    let dir = tempfile::tempdir().unwrap();
    let render = |extra: &[&str], out: &Path| {
        let model = corpus.join("md2/waste/tris.md2");
        let status = Command::new(env!("CARGO_BIN_EXE_mocap"))
            .arg("render")
            .arg(&model)
            .args(extra)
            .args(["--animation", "run", "--time", "0.25", "--size", "160x120", "--camera", "35,12", "--out"])
            .arg(out)
            .output()
            .unwrap();
        assert!(status.status.success(), "{}", String::from_utf8_lossy(&status.stderr));
        decode(out).1
    };
    let skin = corpus.join("md2/waste/waste.pcx");
    let plain = render(&[], &dir.path().join("plain.png"));
    let textured = render(&["--skin", skin.to_str().unwrap()], &dir.path().join("textured.png"));
    let share = differing_share(&plain, &textured, 24);
    assert!(share > 0.01, "the skin changes the picture ({:.3}% of pixels)", share * 100.0);
    // The neutral material is grey: model pixels have nearly equal channels.
    let background = [plain[0], plain[1], plain[2]];
    let greyish = plain.chunks(4).filter(|p| p[..3] != background).all(|p| p[0].abs_diff(p[2]) < 40);
    assert!(greyish);
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
fn a_z_up_clip_is_stood_up_as_guessed_and_up_sets_it() {
    if std::env::var_os("MOCAP_SKIP_GPU_TESTS").is_some() {
        eprintln!("MOCAP_SKIP_GPU_TESTS set: skipping the up-axis render");
        return;
    }
    // A figure standing along +Z: hips at 1, spine up, arms along X, legs down to 0.
    let mut text = String::from(
        "HIERARCHY\nROOT Hips\n{\nOFFSET 0 0 1\nCHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation\n",
    );
    text.push_str("JOINT Chest\n{\nOFFSET 0 0 0.5\nCHANNELS 3 Zrotation Xrotation Yrotation\nJOINT L\n{\nOFFSET 0.6 0 0.3\nCHANNELS 3 Zrotation Xrotation Yrotation\nEnd Site\n{\nOFFSET 0 0 0.4\n}\n}\n}\n");
    text.push_str("JOINT Leg\n{\nOFFSET 0.1 0 0\nCHANNELS 3 Zrotation Xrotation Yrotation\nEnd Site\n{\nOFFSET 0 0 -1\n}\n}\n}\nMOTION\nFrames: 2\nFrame Time: 0.1\n");
    text.push_str(&format!("0 0 1{}\n0 0.1 1{}\n", " 0".repeat(12), " 0".repeat(12)));
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("z.bvh");
    std::fs::write(&file, text).unwrap();
    let render = |up: Option<&str>| {
        let out = dir.path().join(format!("{}.png", up.unwrap_or("guess")));
        let mut command = Command::new(env!("CARGO_BIN_EXE_mocap"));
        command.arg("render").arg(&file).args(["--size", "160x120", "--camera", "0,10,4"]).arg("--out").arg(&out);
        if let Some(up) = up {
            command.args(["--up", up]);
        }
        let output = command.output().unwrap();
        assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
        decode(&out).1
    };
    let (guess, z, y) = (render(None), render(Some("z")), render(Some("y")));
    assert_eq!(differing_share(&guess, &z, 24), 0.0, "the guess is Z");
    assert!(differing_share(&guess, &y, 24) > 0.02, "read Y-up it lies down: another picture");
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
        (vec![f, "--out", "x.png", "--mode", "boxes"], "expected `capsules`, `sticks` or `body`"),
        (vec![f, "--out", "d", "--frames", "5:1"], "a <= b"),
        (vec![f, "--out", "x.png", "--frame", "99"], "out of range"),
        (vec![f, "--out", "x.png", "--up", "x"], "--up: expected y or z"),
    ] {
        let out = run(&args);
        assert!(!out.status.success());
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(needle), "{args:?}: {err}");
    }
}

#[test]
fn a_lost_device_is_an_error_not_a_hang() {
    if std::env::var_os("MOCAP_SKIP_GPU_TESTS").is_some() {
        eprintln!("MOCAP_SKIP_GPU_TESTS set: skipping the lost-device render");
        return;
    }
    use mocap_cli::render::{Gpu, Offscreen, Orbit, StageView};
    let clip = mocap::formats::bvh::parse(include_bytes!("../../../data/walk.bvh")).unwrap();
    let view = StageView::new(vec![("walk.bvh".into(), mocap::Asset::Clip(clip))]);
    let gpu = Gpu::new().expect("a Vulkan adapter (apt-get install mesa-vulkan-drivers)");
    let size = [64, 48];
    let mut offscreen = Offscreen::new(&gpu, size);
    let mut scene = mocap_render::Scene::default();
    view.scene_at(0.5, &mut scene);
    let camera = view.camera(Orbit::default(), size);
    assert_eq!(offscreen.draw(&gpu, &scene, &camera).expect("a frame").len(), 64 * 48 * 4);
    // The device goes (what a driver reset or a GPU removed does): the next frames
    // are refused with the reason, at once, instead of waiting for ever.
    gpu.device().destroy();
    let started = std::time::Instant::now();
    let error = offscreen.draw(&gpu, &scene, &camera).expect_err("no frame from a lost device");
    println!("{error}");
    assert!(error.contains("lost"), "{error}");
    assert!(offscreen.render(&gpu, &scene, &camera).is_err());
    assert!(started.elapsed() < std::time::Duration::from_secs(30), "{:?}", started.elapsed());
}
