//! `mocap render --video`: MP4, WebM and GIF decoded with FFmpeg have the
//! clip's frames (count and duration), frames that move, and frame k is the
//! picture `mocap render --time` draws at k / fps (PSNR at least 26 dB).
//!
//! Needs a Vulkan driver and FFmpeg (`cargo xtask test` installs both);
//! `MOCAP_SKIP_GPU_TESTS=1` / `MOCAP_SKIP_FFMPEG=1` opt out elsewhere.

use std::path::{Path, PathBuf};
use std::process::Command;

const W: u32 = 320;
const H: u32 = 180;

fn walk() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/walk.bvh")
}

fn ready() -> bool {
    if std::env::var_os("MOCAP_SKIP_GPU_TESTS").is_some() {
        eprintln!("MOCAP_SKIP_GPU_TESTS set: skipping the video tests");
        return false;
    }
    let ok = |p: &str| Command::new(p).arg("-version").output().is_ok_and(|o| o.status.success());
    if ok("ffmpeg") && ok("ffprobe") {
        return true;
    }
    assert!(
        std::env::var("MOCAP_SKIP_FFMPEG").is_ok_and(|v| v == "1"),
        "ffmpeg/ffprobe not found: `cargo xtask setup` installs them (or opt out with MOCAP_SKIP_FFMPEG=1)"
    );
    false
}

fn mocap(args: &[&std::ffi::OsStr]) {
    let output = Command::new(env!("CARGO_BIN_EXE_mocap")).args(args).output().unwrap();
    assert!(output.status.success(), "mocap {args:?}: {}", String::from_utf8_lossy(&output.stderr));
}

/// Frames `ffprobe` decodes and the stream's duration in seconds.
fn probe(path: &Path) -> (usize, f64) {
    let out = Command::new("ffprobe")
        .args(["-v", "error", "-count_frames", "-select_streams", "v:0"])
        .args(["-show_entries", "stream=nb_read_frames:format=duration", "-of", "default=nw=1"])
        .arg(path)
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&out.stdout).to_string();
    let field = |name: &str| text.lines().find_map(|l| l.strip_prefix(name)).unwrap_or_else(|| panic!("{text}")).to_string();
    (field("nb_read_frames=").parse().unwrap(), field("duration=").parse().unwrap())
}

fn decode(path: &Path) -> Vec<Vec<u8>> {
    let out = Command::new("ffmpeg")
        .args(["-v", "error", "-i"])
        .arg(path)
        .args(["-f", "rawvideo", "-pix_fmt", "rgba", "-fps_mode", "passthrough", "-"])
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    out.stdout.chunks_exact((W * H * 4) as usize).map(<[u8]>::to_vec).collect()
}

fn still(dir: &Path, time: f64) -> Vec<u8> {
    let out = dir.join(format!("still-{time}.png"));
    let size = format!("{W}x{H}");
    let time = time.to_string();
    mocap(&["render".as_ref(), walk().as_os_str(), "--time".as_ref(), time.as_ref(), "--size".as_ref(), size.as_ref(), "--out".as_ref(), out.as_os_str()]);
    let decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(&out).unwrap()));
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut buf).unwrap();
    buf.truncate(info.buffer_size());
    buf
}

fn psnr(a: &[u8], b: &[u8]) -> f64 {
    let (mut sum, mut n) = (0.0, 0.0);
    for (p, q) in a.chunks_exact(4).zip(b.chunks_exact(4)) {
        for c in 0..3 {
            let d = p[c] as f64 - q[c] as f64;
            sum += d * d;
            n += 1.0;
        }
    }
    10.0 * (255.0f64 * 255.0 / (sum / n).max(1e-9)).log10()
}

/// walk.bvh has 66 frames at 30 fps: the video has them all, 2.2 s.
fn check(ext: &str, extra: &[&str], fps: f64, frames: usize) {
    if !ready() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let video = dir.path().join(format!("walk.{ext}"));
    let size = format!("{W}x{H}");
    let mut args: Vec<&std::ffi::OsStr> = vec!["render".as_ref(), walk().as_os_str().to_owned().leak(), "--video".as_ref(), video.as_os_str(), "--size".as_ref(), size.as_ref(), "--quiet".as_ref()];
    args.extend(extra.iter().map(|a| std::ffi::OsStr::new(*a)));
    mocap(&args);
    let (count, duration) = probe(&video);
    assert_eq!(count, frames, "{ext}: frames");
    let expected = frames as f64 / fps;
    assert!((duration - expected).abs() < 0.011, "{ext}: {duration} s, expected {expected}");
    let decoded = decode(&video);
    assert_eq!(decoded.len(), frames);
    assert!(psnr(&decoded[0], &decoded[frames / 2]) < 30.0, "{ext}: the figure does not move");
    for k in [0, frames / 3, frames - 1] {
        let reference = still(dir.path(), k as f64 / fps);
        let p = psnr(&decoded[k], &reference);
        assert!(p >= 26.0, "{ext}: frame {k} is {p:.1} dB from mocap render --time {}", k as f64 / fps);
    }
}

#[test]
fn mp4_has_every_frame_as_render_draws_it() {
    check("mp4", &[], 30.0, 66);
}

#[test]
fn webm_has_every_frame_as_render_draws_it() {
    check("webm", &[], 30.0, 66);
}

#[test]
fn gif_at_a_chosen_rate_and_range() {
    // 0.5 s to 1.5 s at 10 fps: 11 frames, shown 0.1 s each.
    check("gif", &["--fps", "10", "--from", "0", "--to", "1"], 10.0, 11);
}

#[test]
fn bad_video_requests_are_refused_clearly() {
    let run = |args: &[&str]| Command::new(env!("CARGO_BIN_EXE_mocap")).arg("render").arg(walk()).args(args).output().unwrap();
    let out = run(&["--video", "walk.avi"]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains(".mp4, .webm or .gif"), "{}", String::from_utf8_lossy(&out.stderr));
    let out = run(&["--video", "walk.gif", "--fps", "60"]);
    assert!(String::from_utf8_lossy(&out.stderr).contains("at most 50"), "{}", String::from_utf8_lossy(&out.stderr));
    let out = run(&["--video", "walk.mp4", "--from", "2", "--to", "1"]);
    assert!(String::from_utf8_lossy(&out.stderr).contains("after --to"), "{}", String::from_utf8_lossy(&out.stderr));
    let out = run(&["--fps", "10", "--out", "x.png"]);
    assert!(!out.status.success(), "--fps without --video");
}
