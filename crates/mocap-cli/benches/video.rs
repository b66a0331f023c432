//! `cargo bench -p mocap-cli --bench video`: `mocap render --video` of a 30 s
//! clip at 1280×720 and 30 fps, side by side with real time (30 s), on
//! whatever Vulkan adapter is present (lavapipe without a GPU). The clip is
//! `../shared/corpus/bvh/assimp_cmu/01_01.bvh` (120 fps) played on past its
//! end by repeating its frames. The whole process is timed: reading, drawing
//! every frame at full quality, reading the pixels back, encoding, writing.
//! AV1 (WebM) is timed over the first 5 s: rav1e without assembly is the slow one.

use std::path::Path;
use std::process::Command;
use std::time::Instant;

fn main() {
    let corpus = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/corpus");
    let Ok(text) = std::fs::read_to_string(corpus.join("bvh/assimp_cmu/01_01.bvh")) else {
        println!("skipping: the corpus is not beside the repository");
        return;
    };
    let dir = tempfile::tempdir().expect("temp dir");
    let clip = dir.path().join("long.bvh");
    std::fs::write(&clip, repeated(&text, 30.5)).expect("write clip");
    println!("mocap render --video, 1280x720, 30 fps, shadows and 4x MSAA as for stills:");
    for (ext, seconds) in [("mp4", 30.0), ("gif", 30.0), ("webm", 5.0)] {
        let out = dir.path().join(format!("walk.{ext}"));
        let started = Instant::now();
        let status = Command::new(env!("CARGO_BIN_EXE_mocap"))
            .arg("render")
            .arg(&clip)
            .args(["--size", "1280x720", "--fps", if ext == "gif" { "25" } else { "30" }, "--quiet", "--to"])
            .arg(seconds.to_string())
            .arg("--video")
            .arg(&out)
            .status()
            .expect("run mocap");
        let took = started.elapsed().as_secs_f64();
        if !status.success() {
            println!("{ext}: mocap render failed");
            continue;
        }
        let size = std::fs::metadata(&out).map_or(0, |m| m.len());
        println!(
            "  {ext:>4} {seconds:>4.0} s of motion: {took:6.1} s   real time {seconds:4.0} s   {:4.2}x real time   {:.1} MB",
            seconds / took,
            size as f64 / 1e6
        );
    }
}

/// The BVH `text` with its motion repeated until it lasts `seconds`.
fn repeated(text: &str, seconds: f64) -> String {
    let (head, motion) = text.split_once("MOTION").expect("a MOTION section");
    let mut lines = motion.lines().filter(|l| !l.trim().is_empty());
    let frames_line = lines.next().unwrap_or_default();
    let time_line = lines.next().unwrap_or_default();
    let frame_time: f64 = time_line.split(':').nth(1).and_then(|t| t.trim().parse().ok()).expect("Frame Time");
    let rows: Vec<&str> = lines.collect();
    let _ = frames_line;
    let wanted = (seconds / frame_time).ceil() as usize;
    let mut out = format!("{head}MOTION\nFrames: {wanted}\n{time_line}\n");
    for k in 0..wanted {
        out.push_str(rows[k % rows.len()]);
        out.push('\n');
    }
    out
}
