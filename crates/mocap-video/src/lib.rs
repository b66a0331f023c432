//! RGBA frames in, a video file's bytes out: MP4 (H.264), WebM (AV1) and GIF.
//!
//! The one entry point is [`VideoWriter`]: made for a [`Format`], a frame size
//! and a [`Rate`], it takes frames in display order (frame `k` is shown from
//! `k / rate` seconds on) and gives the whole file when finished. Colours are
//! converted as BT.601 limited range, what players assume of a stream that does
//! not say otherwise (and what the streams here say).
//!
//! No file system, GPU or terminal: `mocap render --video` and the Python
//! package feed it pixels and write its bytes where they want them.

mod gif;
mod mp4;
mod webm;
mod yuv;

use std::path::Path;

/// What can go wrong while writing a video.
#[derive(Debug, thiserror::Error)]
pub enum VideoError {
    /// The frame size cannot be encoded (zero, odd for a 4:2:0 format, too large).
    #[error("{0}")]
    Size(String),
    /// The frame rate cannot be encoded.
    #[error("{0}")]
    Rate(String),
    /// A frame with the wrong number of bytes.
    #[error("frame {frame}: expected {expected} bytes of RGBA, got {got}")]
    Frame {
        /// The frame's index.
        frame: usize,
        /// `width * height * 4`.
        expected: usize,
        /// What was given.
        got: usize,
    },
    /// The encoder or muxer failed.
    #[error("{0}")]
    Encode(String),
    /// `finish` with no frame pushed.
    #[error("a video needs at least one frame")]
    Empty,
}

/// A video container and its codec.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// MPEG-4 with H.264 (Constrained Baseline, OpenH264).
    Mp4,
    /// WebM with AV1 (rav1e).
    WebM,
    /// An animated GIF, one palette per frame, looping.
    Gif,
}

impl Format {
    /// The format a file name asks for, from its extension (`.mp4`, `.m4v`,
    /// `.webm`, `.gif`, any case).
    pub fn from_path(path: &Path) -> Option<Format> {
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        match ext.as_str() {
            "mp4" | "m4v" => Some(Format::Mp4),
            "webm" => Some(Format::WebM),
            "gif" => Some(Format::Gif),
            _ => None,
        }
    }

    /// Lower-case name (`mp4`, `webm`, `gif`).
    pub fn name(self) -> &'static str {
        match self {
            Format::Mp4 => "mp4",
            Format::WebM => "webm",
            Format::Gif => "gif",
        }
    }

    /// Whether frame sides must be even (4:2:0 chroma).
    pub fn needs_even_size(self) -> bool {
        !matches!(self, Format::Gif)
    }

    /// The highest frame rate the format shows faithfully: GIF delays are
    /// whole hundredths of a second and browsers slow anything under 2 to 10.
    pub fn max_fps(self) -> f64 {
        match self {
            Format::Gif => 50.0,
            Format::Mp4 | Format::WebM => 240.0,
        }
    }
}

/// A frame rate as a fraction `num / den` frames per second.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Rate {
    /// Frames…
    pub num: u32,
    /// …per this many seconds.
    pub den: u32,
}

impl Rate {
    /// The fraction nearest `fps` with a denominator of at most 1001 (so 30,
    /// 29.97 = 30000/1001 and 1/0.0083333 = 120 come out exact).
    pub fn from_fps(fps: f64) -> Result<Rate, VideoError> {
        if !(fps.is_finite() && (0.1..=1000.0).contains(&fps)) {
            return Err(VideoError::Rate(format!("a frame rate of {fps} per second cannot be encoded (0.1 to 1000)")));
        }
        let mut best = Rate { num: fps.round().max(1.0) as u32, den: 1 };
        let mut best_err = (best.fps() - fps).abs();
        for den in [1001u32, 1000, 100, 10, 1] {
            let num = (fps * den as f64).round() as u32;
            let r = Rate { num, den }.reduced();
            let err = (r.fps() - fps).abs();
            if err + 1e-12 < best_err {
                (best, best_err) = (r, err);
            }
        }
        if best_err > 1e-6 * fps.max(1.0) && best.den == 1 {
            best = Rate { num: (fps * 1000.0).round() as u32, den: 1000 }.reduced();
        }
        Ok(best)
    }

    /// Frames per second.
    pub fn fps(self) -> f64 {
        self.num as f64 / self.den as f64
    }

    /// The time frame `k` starts, in units of `1 / timescale` s, rounded.
    pub fn start(self, k: u64, timescale: u64) -> u64 {
        let n = k as u128 * self.den as u128 * timescale as u128;
        ((n + self.num as u128 / 2) / self.num as u128) as u64
    }

    fn reduced(self) -> Rate {
        let g = gcd(self.num, self.den).max(1);
        Rate { num: self.num / g, den: self.den / g }
    }
}

fn gcd(a: u32, b: u32) -> u32 {
    if b == 0 { a } else { gcd(b, a % b) }
}

/// How hard to try: the encoders' speed and quality presets.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Quality {
    /// Smaller files, slower (GIF: finer palettes; AV1: a slower preset).
    High,
    /// The default: faster than real time for 720p on a laptop.
    #[default]
    Normal,
}

/// Writes one video from RGBA frames (see the crate's documentation).
pub struct VideoWriter {
    inner: Inner,
    size: [u32; 2],
    frames: usize,
}

enum Inner {
    Mp4(Box<mp4::Mp4Encoder>),
    WebM(Box<webm::WebmEncoder>),
    Gif(gif::GifEncoder),
}

impl VideoWriter {
    /// A writer for `size` = `[width, height]` pixels at `rate`; the size is
    /// checked against the format (even sides for MP4 and WebM, at most 65,535
    /// for GIF, at most 8,192 for the others) and the rate against
    /// [`Format::max_fps`].
    pub fn new(format: Format, size: [u32; 2], rate: Rate, quality: Quality) -> Result<VideoWriter, VideoError> {
        let [w, h] = size;
        let max = if format == Format::Gif { 65_535 } else { 8_192 };
        if w == 0 || h == 0 || w > max || h > max {
            return Err(VideoError::Size(format!("{w}x{h}: a {} frame is 1 to {max} pixels a side", format.name())));
        }
        if format.needs_even_size() && (w % 2 == 1 || h % 2 == 1) {
            return Err(VideoError::Size(format!("{w}x{h}: {} needs even sides", format.name())));
        }
        if rate.num == 0 || rate.den == 0 || rate.fps() > format.max_fps() + 1e-9 {
            return Err(VideoError::Rate(format!(
                "{:.3} frames per second: {} shows at most {}",
                rate.fps(),
                format.name(),
                format.max_fps()
            )));
        }
        let inner = match format {
            Format::Mp4 => Inner::Mp4(Box::new(mp4::Mp4Encoder::new(size, rate)?)),
            Format::WebM => Inner::WebM(Box::new(webm::WebmEncoder::new(size, rate, quality)?)),
            Format::Gif => Inner::Gif(gif::GifEncoder::new(size, rate, quality)?),
        };
        Ok(VideoWriter { inner, size, frames: 0 })
    }

    /// The frame size.
    pub fn size(&self) -> [u32; 2] {
        self.size
    }

    /// Frames pushed so far.
    pub fn frames(&self) -> usize {
        self.frames
    }

    /// Adds the next frame: `width * height` RGBA pixels, rows top to bottom
    /// (alpha is ignored).
    pub fn push(&mut self, rgba: &[u8]) -> Result<(), VideoError> {
        let expected = self.size[0] as usize * self.size[1] as usize * 4;
        if rgba.len() != expected {
            return Err(VideoError::Frame { frame: self.frames, expected, got: rgba.len() });
        }
        match &mut self.inner {
            Inner::Mp4(e) => e.push(rgba)?,
            Inner::WebM(e) => e.push(rgba)?,
            Inner::Gif(e) => e.push(rgba)?,
        }
        self.frames += 1;
        Ok(())
    }

    /// Ends the stream and gives the file's bytes.
    pub fn finish(self) -> Result<Vec<u8>, VideoError> {
        if self.frames == 0 {
            return Err(VideoError::Empty);
        }
        match self.inner {
            Inner::Mp4(e) => e.finish(),
            Inner::WebM(e) => e.finish(),
            Inner::Gif(e) => e.finish(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rates_come_out_exact() {
        assert_eq!(Rate::from_fps(30.0).unwrap(), Rate { num: 30, den: 1 });
        assert_eq!(Rate::from_fps(1.0 / 0.0083333).unwrap(), Rate { num: 120, den: 1 });
        assert_eq!(Rate::from_fps(30000.0 / 1001.0).unwrap(), Rate { num: 30000, den: 1001 });
        assert_eq!(Rate::from_fps(12.5).unwrap(), Rate { num: 25, den: 2 });
        assert!(Rate::from_fps(f64::NAN).is_err());
        assert!(Rate::from_fps(0.0).is_err());
    }

    #[test]
    fn frame_starts_round_to_the_timescale() {
        let r = Rate { num: 30, den: 1 };
        assert_eq!(r.start(3, 100), 10);
        assert_eq!(r.start(1, 100), 3);
        assert_eq!(r.start(2, 100), 7);
        assert_eq!(Rate { num: 30000, den: 1001 }.start(1, 30000), 1001);
    }

    #[test]
    fn formats_from_names() {
        assert_eq!(Format::from_path(Path::new("a/walk.MP4")), Some(Format::Mp4));
        assert_eq!(Format::from_path(Path::new("walk.webm")), Some(Format::WebM));
        assert_eq!(Format::from_path(Path::new("walk.gif")), Some(Format::Gif));
        assert_eq!(Format::from_path(Path::new("walk.avi")), None);
    }

    #[test]
    fn sizes_and_rates_are_checked() {
        let r = Rate { num: 30, den: 1 };
        assert!(matches!(VideoWriter::new(Format::Mp4, [33, 20], r, Quality::Normal), Err(VideoError::Size(_))));
        assert!(matches!(VideoWriter::new(Format::Gif, [0, 20], r, Quality::Normal), Err(VideoError::Size(_))));
        let fast = Rate { num: 60, den: 1 };
        assert!(matches!(VideoWriter::new(Format::Gif, [32, 20], fast, Quality::Normal), Err(VideoError::Rate(_))));
        let mut w = VideoWriter::new(Format::Gif, [4, 2], r, Quality::Normal).unwrap();
        assert!(matches!(w.push(&[0; 7]), Err(VideoError::Frame { frame: 0, expected: 32, got: 7 })));
        assert!(matches!(w.finish(), Err(VideoError::Empty)));
    }
}
