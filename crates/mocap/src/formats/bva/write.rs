//! Writes BVA in the standard layout: LF line endings, tab-separated columns, and
//! shortest round-trip float formatting (so write → parse gives bit-identical f32
//! values and frame times).

use crate::formats::text::push_f32;

use super::{Bva, CHANNEL_COUNT, Segment};
use std::fmt::Write as _;

/// A name that reads back as itself where possible: line breaks become spaces,
/// surrounding blanks go, and an empty name becomes `unnamed`.
fn clean_name(name: &str) -> String {
    let one_line = name.replace(['\n', '\r'], " ");
    let trimmed = one_line.trim_matches(|c: char| c.is_ascii() && super::lines::is_blank(c as u8));
    if trimmed.is_empty() { "unnamed".to_owned() } else { trimmed.to_owned() }
}

/// A unit as one word: blanks and line breaks become `_`; empty becomes `-`.
fn clean_unit(unit: &str) -> String {
    let word: String = unit
        .chars()
        .map(|c| if c == '\n' || c == '\r' || (c.is_ascii() && super::lines::is_blank(c as u8)) { '_' } else { c })
        .collect();
    if word.is_empty() { "-".to_owned() } else { word }
}

fn write_segment(out: &mut String, buffer: &mut ryu::Buffer, segment: &Segment) {
    // Only whole rows that exist are written, and Frames: says how many.
    let frames = segment.frame_count.min(segment.data.len() / CHANNEL_COUNT);
    let _ = write!(
        out,
        "Segment: {}\nFrames: {}\nFrame Time: {}\n",
        clean_name(&segment.name),
        frames,
        ryu::Buffer::new().format(segment.frame_time)
    );
    for (i, channel) in segment.channels.iter().enumerate() {
        if i > 0 {
            out.push('\t');
        }
        out.push_str(channel.name());
    }
    out.push('\n');
    for (i, unit) in segment.units.iter().enumerate() {
        if i > 0 {
            out.push('\t');
        }
        out.push_str(&clean_unit(unit));
    }
    out.push('\n');
    for row in segment.data.chunks_exact(CHANNEL_COUNT).take(frames) {
        for (i, &v) in row.iter().enumerate() {
            if i > 0 {
                out.push('\t');
            }
            push_f32(out, buffer, v);
        }
        out.push('\n');
    }
}

/// Serialises a BVA file: for each segment `Segment:`, `Frames:`, `Frame Time:`,
/// the channel line, the units line and one tab-separated row per frame, LF line
/// endings. Warnings are not written. `parse(write(x))` gives bit-identical data
/// and frame times. Values the format cannot hold are adjusted so the output still
/// reads: a name is put on one line and trimmed (`unnamed` when empty), a unit
/// becomes one word (blanks → `_`, empty → `-`), and only whole rows present in
/// `data` (at most `frame_count`) are written. A units line whose first word reads
/// as a number (`inf`, `nan`) or as `Segment` cannot be told from a row or the next
/// segment, and does not read back.
pub fn write(bva: &Bva) -> String {
    let values: usize = bva.segments.iter().map(|s| s.data.len()).sum();
    let mut out = String::with_capacity(160 * bva.segments.len() + values.saturating_mul(10));
    let mut buffer = ryu::Buffer::new();
    for segment in &bva.segments {
        write_segment(&mut out, &mut buffer, segment);
    }
    out
}
