//! Biovision BVA: a pure [`parse`] from bytes to a [`Bva`], and [`write`] back.
//!
//! A BVA file is a list of segments with no hierarchy; each segment holds, for
//! every frame, its world-space translation, rotation and scale:
//!
//! ```text
//! Segment: Hips
//! Frames: 2
//! Frame Time: 0.033333
//! XTRAN   YTRAN   ZTRAN   XROT    YROT    ZROT    XSCALE  YSCALE  ZSCALE
//! INCHES  INCHES  INCHES  DEGREES DEGREES DEGREES INCHES  INCHES  INCHES
//! 8.03 35.01 88.36 14.78 -164.35 -3.41 5.21 5.21 5.21
//! 7.81 35.10 86.47 12.94 -166.97 -2.35 5.21 5.21 5.21
//! ```
//!
//! The reader accepts keywords in any case, `Segment:`, `Frames:` and `Frame Time:`
//! with the colon glued or separated, names with spaces, LF, CRLF or lone CR line
//! endings, a byte-order mark, blank lines and tabs. Problems that leave the data
//! usable become [`Warning`]s; the rest are [`ParseError`]s with line and column.
//! Nothing is allocated from a number written in the file.
//!
//! The units line may be left out: when the line after the channel line is a row of
//! numbers, the next `Segment:` line, or the end of the file, the units default to
//! `INCHES` for translation and scale and `DEGREES` for rotation (by channel kind,
//! so a permuted channel line gets matching units), with one warning per file.
//!
//! ```
//! let text = b"Segment: Hips\nFrames: 1\nFrame Time: 0.5\n\
//!     XTRAN YTRAN ZTRAN XROT YROT ZROT XSCALE YSCALE ZSCALE\n\
//!     INCHES INCHES INCHES DEGREES DEGREES DEGREES INCHES INCHES INCHES\n\
//!     1 2 3 4 5 6 7 8 9\n";
//! let bva = mocap::formats::bva::parse(text).unwrap();
//! assert_eq!(bva.segments[0].row(0), &[1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0]);
//! assert_eq!(mocap::formats::bva::parse(mocap::formats::bva::write(&bva).as_bytes()).unwrap(), bva);
//! ```

mod lines;
mod model;
mod read;
#[cfg(test)]
mod tests;
mod write;

pub use model::{from_clip, to_clip};
pub use write::write;

use crate::error::{ParseError, Warning};

/// Frame time used when a segment gives none or an unusable one (30 fps).
pub const DEFAULT_FRAME_TIME: f64 = 1.0 / 30.0;

/// Number of channels (columns) of every BVA segment.
pub const CHANNEL_COUNT: usize = 9;

/// One of the nine BVA channel kinds.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum BvaChannel {
    /// Translation along X (`XTRAN`).
    XTran,
    /// Translation along Y (`YTRAN`).
    YTran,
    /// Translation along Z (`ZTRAN`).
    ZTran,
    /// Rotation about X (`XROT`).
    XRot,
    /// Rotation about Y (`YROT`).
    YRot,
    /// Rotation about Z (`ZROT`).
    ZRot,
    /// Scale along X (`XSCALE`).
    XScale,
    /// Scale along Y (`YSCALE`).
    YScale,
    /// Scale along Z (`ZSCALE`).
    ZScale,
}

impl BvaChannel {
    /// All nine channels in the standard column order.
    pub const ALL: [BvaChannel; CHANNEL_COUNT] = [
        BvaChannel::XTran,
        BvaChannel::YTran,
        BvaChannel::ZTran,
        BvaChannel::XRot,
        BvaChannel::YRot,
        BvaChannel::ZRot,
        BvaChannel::XScale,
        BvaChannel::YScale,
        BvaChannel::ZScale,
    ];

    /// The channel's name as written in files (`XTRAN`, `YROT`, `ZSCALE`, ...).
    pub fn name(self) -> &'static str {
        match self {
            BvaChannel::XTran => "XTRAN",
            BvaChannel::YTran => "YTRAN",
            BvaChannel::ZTran => "ZTRAN",
            BvaChannel::XRot => "XROT",
            BvaChannel::YRot => "YROT",
            BvaChannel::ZRot => "ZROT",
            BvaChannel::XScale => "XSCALE",
            BvaChannel::YScale => "YSCALE",
            BvaChannel::ZScale => "ZSCALE",
        }
    }

    /// The channel with this name, in any case (`"xrot"` → [`BvaChannel::XRot`]).
    pub fn from_name(name: &str) -> Option<BvaChannel> {
        BvaChannel::from_bytes(name.as_bytes())
    }

    /// [`BvaChannel::from_name`] on raw bytes.
    pub(crate) fn from_bytes(name: &[u8]) -> Option<BvaChannel> {
        BvaChannel::ALL.into_iter().find(|c| c.name().as_bytes().eq_ignore_ascii_case(name))
    }

    /// The unit a file without a units line is assumed to use for this channel:
    /// `INCHES` for translation and scale, `DEGREES` for rotation.
    pub fn default_unit(self) -> &'static str {
        if self.is_rotation() { "DEGREES" } else { "INCHES" }
    }

    /// True for `XROT`, `YROT` and `ZROT`.
    pub fn is_rotation(self) -> bool {
        matches!(self, BvaChannel::XRot | BvaChannel::YRot | BvaChannel::ZRot)
    }
}

/// One BVA segment: a named body part with nine world-space channels per frame.
#[derive(Clone, Debug, PartialEq)]
pub struct Segment {
    /// The segment's name (the rest of the `Segment:` line, trimmed; may hold spaces).
    pub name: String,
    /// Seconds per frame (1/30 s when the file gave none or an unusable one).
    pub frame_time: f64,
    /// The column order of [`Segment::data`], as in the file's channel line: always
    /// a permutation of all nine channels.
    pub channels: [BvaChannel; CHANNEL_COUNT],
    /// The units line, one word per column as written (e.g. `INCHES`, `DEGREES`).
    pub units: [String; CHANNEL_COUNT],
    /// Number of rows actually present in the file.
    pub frame_count: usize,
    /// `frame_count × 9` values, row-major, columns in [`Segment::channels`] order.
    pub data: Vec<f32>,
    /// 1-based line of the `Segment:` keyword.
    pub line: u32,
}

impl Segment {
    /// The nine values of one frame, in [`Segment::channels`] order; empty when
    /// `frame` is out of range.
    pub fn row(&self, frame: usize) -> &[f32] {
        if frame >= self.frame_count {
            return &[];
        }
        frame
            .checked_mul(CHANNEL_COUNT)
            .and_then(|start| self.data.get(start..start.checked_add(CHANNEL_COUNT)?))
            .unwrap_or(&[])
    }

    /// The column of `channel` in [`Segment::data`] rows.
    pub fn column(&self, channel: BvaChannel) -> Option<usize> {
        self.channels.iter().position(|&c| c == channel)
    }

    /// True when the rotation units say radians (any rotation column whose unit
    /// starts with `RAD`, in any case); BVA rotations are degrees otherwise.
    pub fn angle_in_radians(&self) -> bool {
        self.channels
            .iter()
            .zip(&self.units)
            .any(|(c, u)| c.is_rotation() && u.as_bytes().get(..3).is_some_and(|p| p.eq_ignore_ascii_case(b"RAD")))
    }
}

/// A whole BVA file: its segments in file order, and what the reader found odd.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Bva {
    /// The segments in file order (at least one after a successful [`parse`]).
    pub segments: Vec<Segment>,
    /// Non-fatal problems found while reading.
    pub warnings: Vec<Warning>,
}

/// True when `bytes` look like BVA: the first word (after a byte-order mark and
/// whitespace) is `Segment:` or `Segment`, in any case.
pub fn sniff(bytes: &[u8]) -> bool {
    let text = bytes.strip_prefix(&[0xEF, 0xBB, 0xBF]).unwrap_or(bytes);
    let start = text.iter().position(|b| !b.is_ascii_whitespace()).unwrap_or(text.len());
    let Some(word) = text.get(start..start + 7) else { return false };
    word.eq_ignore_ascii_case(b"Segment") && text.get(start + 7).is_none_or(|&b| b == b':' || b.is_ascii_whitespace())
}

/// Parses a whole BVA file.
pub fn parse(bytes: &[u8]) -> Result<Bva, ParseError> {
    read::parse(bytes)
}
