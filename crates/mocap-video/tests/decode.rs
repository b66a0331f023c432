//! Every format decodes with FFmpeg to the frames that went in: their number,
//! their times, and their pictures (PSNR).
//!
//! Needs `ffmpeg` and `ffprobe` (`cargo xtask test` installs them); without
//! them this fails unless `MOCAP_SKIP_FFMPEG=1` opts out.

use mocap_video::{Format, Quality, Rate, VideoWriter};
use std::path::Path;
use std::process::Command;

const W: u32 = 96;
const H: u32 = 64;

/// Frame `k`: a grey floor, a gradient, and a red square that moves 3 px a frame.
fn picture(k: u32) -> Vec<u8> {
    let mut rgba = Vec::with_capacity((W * H * 4) as usize);
    for y in 0..H {
        for x in 0..W {
            let inside = x >= 3 * k % (W - 16) && x < 3 * k % (W - 16) + 16 && (20..40).contains(&y);
            let px = if inside { [220, 30, 30, 255] } else { [(x * 2) as u8, 120, (y * 3) as u8, 255] };
            rgba.extend_from_slice(&px);
        }
    }
    rgba
}

fn have_ffmpeg() -> bool {
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

/// `ffprobe`'s count of decoded frames and the stream's duration in seconds.
fn probe(path: &Path) -> (usize, f64) {
    let out = Command::new("ffprobe")
        .args(["-v", "error", "-count_frames", "-select_streams", "v:0"])
        .args(["-show_entries", "stream=nb_read_frames:format=duration", "-of", "default=nw=1"])
        .arg(path)
        .output()
        .expect("ffprobe");
    let text = String::from_utf8_lossy(&out.stdout).to_string();
    let field = |name: &str| {
        text.lines().find_map(|l| l.strip_prefix(name)).unwrap_or_else(|| panic!("{name} in {text}")).to_string()
    };
    (field("nb_read_frames=").parse().unwrap(), field("duration=").parse().unwrap())
}

/// Every decoded frame as RGBA.
fn decode(path: &Path) -> Vec<Vec<u8>> {
    let out = Command::new("ffmpeg")
        .args(["-v", "error", "-i"])
        .arg(path)
        .args(["-f", "rawvideo", "-pix_fmt", "rgba", "-fps_mode", "passthrough", "-"])
        .output()
        .expect("ffmpeg");
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    out.stdout.chunks_exact((W * H * 4) as usize).map(|c| c.to_vec()).collect()
}

/// Peak signal-to-noise ratio over RGB, in dB.
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

fn round_trip(format: Format, fps: f64, frames: u32, min_psnr: f64) {
    if !have_ffmpeg() {
        return;
    }
    let rate = Rate::from_fps(fps).unwrap();
    let mut writer = VideoWriter::new(format, [W, H], rate, Quality::Normal).unwrap();
    for k in 0..frames {
        writer.push(&picture(k)).unwrap();
    }
    let bytes = writer.finish().unwrap();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join(format!("v.{}", format.name()));
    std::fs::write(&path, &bytes).unwrap();
    let (count, duration) = probe(&path);
    assert_eq!(count, frames as usize, "{format:?}: frames");
    let expected = frames as f64 / fps;
    assert!((duration - expected).abs() <= 0.011, "{format:?}: duration {duration} s, expected {expected}");
    let decoded = decode(&path);
    assert_eq!(decoded.len(), frames as usize);
    for (k, got) in decoded.iter().enumerate() {
        let p = psnr(got, &picture(k as u32));
        assert!(p >= min_psnr, "{format:?}: frame {k} PSNR {p:.1} dB");
        if k > 0 {
            assert!(psnr(got, &decoded[k - 1]) < 60.0, "{format:?}: frame {k} equals frame {}", k - 1);
        }
    }
}

#[test]
fn mp4_decodes_frame_for_frame() {
    round_trip(Format::Mp4, 30.0, 45, 28.0);
}

#[test]
fn webm_decodes_frame_for_frame() {
    round_trip(Format::WebM, 24.0, 30, 28.0);
}

#[test]
fn gif_decodes_frame_for_frame() {
    round_trip(Format::Gif, 25.0, 20, 26.0);
}

#[test]
fn a_rate_that_is_not_whole_keeps_its_frames() {
    round_trip(Format::Mp4, 30000.0 / 1001.0, 20, 28.0);
}
