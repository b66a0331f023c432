//! Biovision BVH: a pure [`parse`] from bytes to a [`Clip`], and [`write`] back.
//!
//! The reader accepts what real files contain: keywords in any case, any whitespace
//! and line endings (LF, CRLF, lone CR), braces glued to names, names with spaces or
//! non-ASCII bytes (UTF-8, else Latin-1), several ROOTs, End Sites with or without a
//! name, joints with no channels, and position channels on any joint. Problems that
//! leave the data usable become [`Warning`]s; the rest are [`ParseError`]s with line
//! and column.

mod cursor;
mod header;
mod rows;
mod stream;
mod write;
pub use stream::Stream;

pub use write::write;

use crate::error::{ParseError, Warning};
use crate::model::clip::Clip;
use crate::model::motion::Motion;

/// Frame time used when the file gives none or an unusable one (30 fps).
pub const DEFAULT_FRAME_TIME: f64 = 1.0 / 30.0;

/// True when `bytes` look like BVH (the first word is HIERARCHY, any case).
pub fn sniff(bytes: &[u8]) -> bool {
    let text = bytes.get(crate::formats::text::bom_len(bytes)..).unwrap_or(bytes);
    let start = text.iter().position(|b| !b.is_ascii_whitespace()).unwrap_or(text.len());
    text.get(start..start + 9).is_some_and(|w| w.eq_ignore_ascii_case(b"HIERARCHY"))
}

/// Parses a whole BVH file.
pub fn parse(bytes: &[u8]) -> Result<Clip, ParseError> {
    let header = header::parse_header(bytes)?;
    let width = header.skeleton.channel_count();
    let rows = match header.data {
        Some((start, line, column)) => rows::parse_rows(bytes.get(start..).unwrap_or(&[]), line, column, width)?,
        None => rows::Rows { data: Vec::new(), count: 0, notes: rows::RowNotes::default() },
    };
    assemble(header, rows)
}

/// The clip from a parsed header and its rows, with the warnings both call for.
fn assemble(header: header::Header, rows: rows::Rows) -> Result<Clip, ParseError> {
    let mut warnings = header.warnings;
    let width = header.skeleton.channel_count();
    let mut frame_count = rows.count;
    if width == 0 && header.has_motion {
        // No channels: rows are empty, so the declared count is all there is.
        frame_count = header.declared_frames.map_or(0, |(n, _)| n.min(1) as usize);
    }
    if let Some(line) = rows.notes.decimal_comma {
        warnings.push(Warning {
            line: Some(line),
            message: "numbers written with a decimal comma (0,5): read as decimals".into(),
        });
    }
    if let Some(line) = rows.notes.non_finite {
        warnings.push(Warning {
            line: Some(line),
            message: "motion holds NaN or infinite values; those joints are not drawn".into(),
        });
    }
    match header.declared_frames {
        Some((declared, line)) if declared != rows.count as u64 && width > 0 => warnings.push(Warning {
            line: Some(line),
            message: format!("Frames: says {declared} but the file has {} rows; using {}", rows.count, rows.count),
        }),
        None if header.has_motion => warnings
            .push(Warning { line: None, message: format!("no Frames: line; using the {} rows present", rows.count) }),
        _ => {}
    }
    let frame_time = match header.frame_time {
        Some((t, _)) if t > 0.0 && t.is_finite() => t,
        Some((t, line)) => {
            warnings.push(Warning {
                line: Some(line),
                message: format!("Frame Time {t} is not a positive duration; using 1/30 s"),
            });
            DEFAULT_FRAME_TIME
        }
        None => {
            if header.has_motion {
                warnings.push(Warning { line: None, message: "no Frame Time: line; using 1/30 s".into() });
            }
            DEFAULT_FRAME_TIME
        }
    };
    let motion = Motion::new(frame_time, width, frame_count, rows.data)
        .or_else(|| Motion::new(frame_time, width, 0, Vec::new()))
        .unwrap_or_default();
    let clip = Clip::new(header.skeleton, motion).map_err(|e| ParseError::new(1, 1, e.to_string()))?;
    Ok(clip.with_warnings(warnings))
}
