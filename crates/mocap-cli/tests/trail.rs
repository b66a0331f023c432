//! `mocap render --trail JOINT`: the path is drawn (pixels change where it
//! runs), an unknown joint is refused. Needs a Vulkan driver
//! (`MOCAP_SKIP_GPU_TESTS=1` opts out).

use std::path::Path;
use std::process::Command;

fn render(extra: &[&str], out: &Path) -> std::process::Output {
    let walk = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/walk.bvh");
    Command::new(env!("CARGO_BIN_EXE_mocap"))
        .arg("render")
        .arg(walk)
        .args(["--time", "1", "--size", "320x180", "--out"])
        .arg(out)
        .args(extra)
        .output()
        .unwrap()
}

fn pixels(path: &Path) -> Vec<u8> {
    let decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(path).unwrap()));
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut buf).unwrap();
    buf.truncate(info.buffer_size());
    buf
}

#[test]
fn a_trail_is_drawn_and_a_missing_joint_refused() {
    if std::env::var_os("MOCAP_SKIP_GPU_TESTS").is_some() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let (plain, trail) = (dir.path().join("plain.png"), dir.path().join("trail.png"));
    assert!(render(&[], &plain).status.success());
    let out = render(&["--trail", "Hips"], &trail);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let (a, b) = (pixels(&plain), pixels(&trail));
    let changed = a.chunks(4).zip(b.chunks(4)).filter(|(p, q)| p.iter().zip(q.iter()).any(|(x, y)| x.abs_diff(*y) > 40)).count();
    assert!(changed > 100, "the path shows ({changed} pixels)");
    let bad = render(&["--trail", "Nope"], &dir.path().join("x.png"));
    assert!(!bad.status.success() && String::from_utf8_lossy(&bad.stderr).contains("--trail Nope"));
}
