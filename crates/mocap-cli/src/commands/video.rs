//! `mocap render --video`: a clip (or a model's animation) as MP4, WebM or GIF.
//!
//! Frame `k` of the video is the picture `mocap render --time` gives at
//! `from + k / fps`: the same stage, camera and offscreen renderer, at full
//! quality. The GPU draws frame `k + 1` while another thread encodes frame `k`.

use crate::render::{Gpu, Orbit, StageView};
use mocap_video::{Format, Quality, Rate, VideoWriter};
use std::io::IsTerminal;
use std::path::Path;
use std::time::Instant;

/// What `--video` was asked for beyond the files and the view.
pub struct VideoRequest {
    /// Frames per second (default: the first clip's rate; GIF: at most 50).
    pub fps: Option<f64>,
    /// First time shown, in seconds (default 0).
    pub from: Option<f64>,
    /// Last time shown, in seconds (default: the end of the longest clip).
    pub to: Option<f64>,
    /// No progress bar and no summary.
    pub quiet: bool,
}

/// The frames a video shows: `count` frames at `rate` from `from` seconds.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Span {
    /// Time of frame 0.
    pub from: f64,
    /// Frame rate.
    pub rate: Rate,
    /// Frames.
    pub count: u64,
}

impl Span {
    /// The time frame `k` shows.
    pub fn time(&self, k: u64) -> f64 {
        self.from + k as f64 * self.rate.den as f64 / self.rate.num as f64
    }
}

/// The frames of a video of a stage `duration` s long whose clips run at
/// `clip_fps`, as `request` and `format` allow.
pub fn span(request: &VideoRequest, format: Format, duration: f64, clip_fps: f64) -> Result<Span, String> {
    let fps = match request.fps {
        Some(fps) if !(fps.is_finite() && fps > 0.0) => return Err(format!("--fps {fps}: expected frames per second")),
        Some(fps) if fps > format.max_fps() => {
            return Err(format!("--fps {fps}: {} shows at most {} frames per second", format.name(), format.max_fps()));
        }
        Some(fps) => fps,
        // A GIF of a faster clip shows every second (third…) frame.
        None => clip_fps / (clip_fps / format.max_fps()).ceil().max(1.0),
    };
    let rate = Rate::from_fps(fps).map_err(|e| format!("--fps: {e}"))?;
    let from = request.from.unwrap_or(0.0);
    let to = request.to.unwrap_or(duration);
    if !(from.is_finite() && to.is_finite() && from >= 0.0) {
        return Err("--from and --to are times in seconds, 0 or more".into());
    }
    if to < from {
        return Err(format!("--from {from} is after --to {to}"));
    }
    let count = ((to - from) * rate.fps() + 1e-6).floor() as u64 + 1;
    const MAX_FRAMES: u64 = 1_000_000;
    if count > MAX_FRAMES {
        return Err(format!("{count} frames: a video is at most {MAX_FRAMES} frames; use --from/--to or --fps"));
    }
    Ok(Span { from, rate, count })
}

/// `mocap render FILES --video OUT`: `stage` drawn from `orbit` into frames of
/// `size` (sides rounded down to even for MP4 and WebM), encoded as `out`'s
/// extension says.
pub fn video(
    gpu: &Gpu,
    stage: &StageView,
    orbit: Orbit,
    size: [u32; 2],
    out: &Path,
    request: &VideoRequest,
) -> Result<(), String> {
    let format =
        Format::from_path(out).ok_or_else(|| format!("{}: --video writes .mp4, .webm or .gif", out.display()))?;
    let size = if format.needs_even_size() { [size[0] & !1, size[1] & !1].map(|s| s.max(2)) } else { size };
    let span = span(request, format, stage.duration(), 1.0 / stage.timeline().frame_time())?;
    let mut offscreen = crate::render::Offscreen::new(gpu, size);
    let size = offscreen.size();
    let camera = stage.camera(orbit, size);
    let writer = VideoWriter::new(format, size, span.rate, Quality::Normal).map_err(|e| format!("{}: {e}", out.display()))?;
    let mut progress = Progress::new(out, span.count, !request.quiet && std::io::stderr().is_terminal());
    let started = Instant::now();
    let (frames, encoded) = std::sync::mpsc::sync_channel::<Vec<u8>>(2);
    let encoder = std::thread::spawn(move || -> Result<Vec<u8>, String> {
        let mut writer = writer;
        for rgba in encoded {
            writer.push(&rgba).map_err(|e| e.to_string())?;
        }
        writer.finish().map_err(|e| e.to_string())
    });
    let mut scene = mocap_render::Scene::default();
    let mut drawn = Ok(());
    for k in 0..span.count {
        stage.scene_at(span.time(k), &mut scene);
        match offscreen.draw(gpu, &scene, &camera) {
            Ok(pixels) => {
                if frames.send(pixels).is_err() {
                    break; // The encoder stopped; its error is below.
                }
            }
            Err(e) => {
                drawn = Err(e);
                break;
            }
        }
        progress.show(k + 1);
    }
    drop(frames);
    let bytes = encoder.join().map_err(|_| "the video encoder failed".to_string())?;
    drawn?;
    let bytes = bytes.map_err(|e| format!("{}: {e}", out.display()))?;
    std::fs::write(out, &bytes).map_err(|e| format!("{}: cannot write: {e}", out.display()))?;
    progress.clear();
    if !request.quiet {
        let seconds = span.count as f64 / span.rate.fps();
        let took = started.elapsed().as_secs_f64();
        eprintln!(
            "{}: {} frames at {} fps ({seconds:.2} s), {}x{}, {:.1} MB, written in {took:.1} s ({:.1}x real time)",
            out.display(),
            span.count,
            trim(span.rate.fps()),
            size[0],
            size[1],
            bytes.len() as f64 / 1e6,
            seconds / took.max(1e-9)
        );
    }
    Ok(())
}

fn trim(fps: f64) -> String {
    let s = format!("{fps:.3}");
    s.trim_end_matches('0').trim_end_matches('.').to_string()
}

/// A one-line progress bar on a terminal's stderr.
struct Progress {
    name: String,
    total: u64,
    shown: bool,
    started: Instant,
    last: Option<Instant>,
}

impl Progress {
    fn new(out: &Path, total: u64, shown: bool) -> Progress {
        let name = out.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
        Progress { name, total, shown, started: Instant::now(), last: None }
    }

    fn show(&mut self, done: u64) {
        let now = Instant::now();
        if !self.shown || (self.last.is_some_and(|t| now - t < std::time::Duration::from_millis(100)) && done < self.total) {
            return;
        }
        self.last = Some(now);
        const WIDTH: u64 = 30;
        let filled = (done * WIDTH / self.total.max(1)) as usize;
        let rate = done as f64 / (now - self.started).as_secs_f64().max(1e-9);
        eprint!(
            "\r{} [{}{}] {done}/{} frames, {rate:.0}/s ",
            self.name,
            "#".repeat(filled),
            " ".repeat(WIDTH as usize - filled),
            self.total
        );
    }

    fn clear(&self) {
        if self.shown {
            eprint!("\r{}\r", " ".repeat(self.name.len() + 70));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn request(fps: Option<f64>, from: Option<f64>, to: Option<f64>) -> VideoRequest {
        VideoRequest { fps, from, to, quiet: true }
    }

    #[test]
    fn the_whole_clip_at_its_rate() {
        // 100 frames at 1/30 s: 3.3 s, every frame once.
        let s = span(&request(None, None, None), Format::Mp4, 99.0 / 30.0, 30.0).unwrap();
        assert_eq!((s.count, s.rate), (100, Rate { num: 30, den: 1 }));
        assert!((s.time(99) - 3.3).abs() < 1e-9);
    }

    #[test]
    fn a_gif_of_a_fast_clip_takes_every_other_frame() {
        let s = span(&request(None, None, None), Format::Gif, 1.0, 120.0).unwrap();
        assert_eq!((s.count, s.rate), (41, Rate { num: 40, den: 1 }));
        assert!(span(&request(Some(60.0), None, None), Format::Gif, 1.0, 120.0).is_err());
    }

    #[test]
    fn a_range_and_a_rate() {
        let s = span(&request(Some(10.0), Some(1.0), Some(2.0)), Format::WebM, 5.0, 30.0).unwrap();
        assert_eq!(s.count, 11);
        assert_eq!(s.time(0), 1.0);
        assert!((s.time(10) - 2.0).abs() < 1e-9);
        assert!(span(&request(None, Some(3.0), Some(2.0)), Format::WebM, 5.0, 30.0).is_err());
        assert!(span(&request(Some(f64::NAN), None, None), Format::WebM, 5.0, 30.0).is_err());
        assert!(span(&request(Some(240.0), None, Some(1e9)), Format::WebM, 5.0, 30.0).is_err());
    }
}
