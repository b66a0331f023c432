//! The BVA reader: one pass over the lines, one segment after another.

use super::lines::{Line, Lines, decode, keyword, parse_f32, parse_f64, show_bytes};
use super::{Bva, BvaChannel, CHANNEL_COUNT, DEFAULT_FRAME_TIME, Segment};
use crate::error::{ParseError, Warning};

/// What a header line is.
enum Kind {
    /// `Segment: name`; the name starts at this byte.
    Segment(usize),
    /// `Frames: n`; the value starts at this byte.
    Frames(usize),
    /// `Frame Time: t`; the value starts at this byte.
    FrameTime(usize),
    /// Anything else.
    Other,
}

fn classify(line: &Line) -> Kind {
    if let Some(i) = keyword(line.text, &["segment"]) {
        Kind::Segment(i)
    } else if let Some(i) = keyword(line.text, &["frames"]) {
        Kind::Frames(i)
    } else if let Some(i) = keyword(line.text, &["frame", "time"]) {
        Kind::FrameTime(i)
    } else {
        Kind::Other
    }
}

/// The standard channel line, for messages.
const CHANNEL_LIST: &str = "XTRAN YTRAN ZTRAN XROT YROT ZROT XSCALE YSCALE ZSCALE";

/// File-wide oddities, reported once each.
#[derive(Default)]
struct Notes {
    /// First segment without a units line, and how many there were.
    no_units: Option<(u32, usize)>,
    /// Line of the first NaN or infinite value.
    non_finite: Option<u32>,
}

struct Reader<'a> {
    lines: Lines<'a>,
    /// The last line taken, for end-of-file positions.
    last: Option<Line<'a>>,
    warnings: Vec<Warning>,
    notes: Notes,
}

impl<'a> Reader<'a> {
    /// Skips blank lines; the next line with content, not consumed.
    fn peek(&mut self) -> Option<Line<'a>> {
        while let Some(line) = self.lines.peek() {
            if !line.is_blank() {
                return Some(line);
            }
            self.take();
        }
        None
    }

    /// Consumes the next line (after [`Reader::peek`] has shown it).
    fn take(&mut self) -> Option<Line<'a>> {
        let line = self.lines.next()?;
        self.last = Some(line);
        Some(line)
    }

    /// Where the file ends: just after the last line's content.
    fn end_of_file(&self) -> (u32, u32) {
        self.last.map_or((1, 1), |l| (l.number, l.end_column()))
    }

    fn segment(&mut self, head: Line<'a>, name_at: usize) -> Result<Segment, ParseError> {
        let (name_bytes, name_column) = head.rest(name_at);
        if name_bytes.is_empty() {
            return Err(ParseError::new(head.number, name_column, "expected a segment name after Segment:"));
        }
        let name = decode(name_bytes);
        let err = |line: u32, column: u32, message: String| {
            ParseError::new(line, column, format!("segment `{name}`: {message}"))
        };

        // Frames: and Frame Time:, in either order.
        let mut declared_frames: Option<(u64, u32)> = None;
        let mut frame_time: Option<(f64, u32)> = None;
        while let Some(line) = self.peek() {
            match classify(&line) {
                Kind::Frames(at) => {
                    self.take();
                    let Some(word) = line.words_from(at).next() else {
                        return Err(err(line.number, line.end_column(), "expected a frame count after Frames:".into()));
                    };
                    let digits = word.text.strip_prefix(b"+").unwrap_or(word.text);
                    if digits.is_empty() || !digits.iter().all(u8::is_ascii_digit) {
                        return Err(err(
                            line.number,
                            word.column,
                            format!("expected a frame count after Frames:, found `{}`", show_bytes(word.text)),
                        ));
                    }
                    let count =
                        digits.iter().fold(0u64, |n, &d| n.saturating_mul(10).saturating_add(u64::from(d - b'0')));
                    declared_frames = Some((count, line.number));
                }
                Kind::FrameTime(at) => {
                    self.take();
                    match line.words_from(at).next() {
                        None => frame_time = Some((f64::NAN, line.number)),
                        Some(word) => match parse_f64(word.text) {
                            Some(t) => frame_time = Some((t, line.number)),
                            None => {
                                return Err(err(
                                    line.number,
                                    word.column,
                                    format!("expected a number after Frame Time:, found `{}`", show_bytes(word.text)),
                                ));
                            }
                        },
                    }
                }
                Kind::Segment(_) | Kind::Other => break,
            }
        }

        let channels = self.channel_line(&name)?;

        // The units line, unless the next line already holds numbers.
        let units = match self.peek() {
            Some(line) if !matches!(classify(&line), Kind::Segment(_)) && !starts_with_number(&line) => {
                self.take();
                units_line(&line, &name)?
            }
            _ => {
                let first = self.notes.no_units.map_or(head.number, |(l, _)| l);
                let count = self.notes.no_units.map_or(0, |(_, n)| n);
                self.notes.no_units = Some((first, count + 1));
                channels.map(|c| c.default_unit().to_owned())
            }
        };

        // Rows until the next segment or the end of the file.
        let mut data = Vec::new();
        let mut frame_count = 0usize;
        while let Some(line) = self.peek() {
            if matches!(classify(&line), Kind::Segment(_)) {
                break;
            }
            self.take();
            let row = self.row(&line, &name, &channels)?;
            data.extend_from_slice(&row);
            frame_count += 1;
        }

        match declared_frames {
            Some((declared, line)) if declared != frame_count as u64 => self.warnings.push(Warning {
                line: Some(line),
                message: format!("segment `{name}`: Frames: says {declared} but the segment has {frame_count} rows; using {frame_count}"),
            }),
            Some(_) => {}
            None => self.warnings.push(Warning {
                line: Some(head.number),
                message: format!("segment `{name}`: no Frames: line; using the {frame_count} rows present"),
            }),
        }
        let frame_time = match frame_time {
            Some((t, _)) if t > 0.0 && t.is_finite() => t,
            Some((t, line)) => {
                let shown =
                    if t.is_nan() { "is missing".to_owned() } else { format!("{t} is not a positive duration") };
                self.warnings.push(Warning {
                    line: Some(line),
                    message: format!("segment `{name}`: Frame Time {shown}; using 1/30 s"),
                });
                DEFAULT_FRAME_TIME
            }
            None => {
                self.warnings.push(Warning {
                    line: Some(head.number),
                    message: format!("segment `{name}`: no Frame Time: line; using 1/30 s"),
                });
                DEFAULT_FRAME_TIME
            }
        };
        Ok(Segment { name, frame_time, channels, units, frame_count, data, line: head.number })
    }

    /// The channel line: all nine channel names, each once, in any order.
    fn channel_line(&mut self, name: &str) -> Result<[BvaChannel; CHANNEL_COUNT], ParseError> {
        let err = |line: u32, column: u32, message: String| {
            ParseError::new(line, column, format!("segment `{name}`: {message}"))
        };
        let Some(line) = self.peek() else {
            let (l, c) = self.end_of_file();
            return Err(err(l, c, format!("unexpected end of file: expected the channel line ({CHANNEL_LIST})")));
        };
        self.take();
        let mut channels = [BvaChannel::XTran; CHANNEL_COUNT];
        let mut count = 0usize;
        for word in line.words() {
            let Some(channel) = BvaChannel::from_bytes(word.text) else {
                let message = if count == 0 {
                    format!("expected the channel line ({CHANNEL_LIST}), found `{}`", show_bytes(word.text))
                } else {
                    format!("unknown channel `{}` (expected one of {CHANNEL_LIST})", show_bytes(word.text))
                };
                return Err(err(line.number, word.column, message));
            };
            if channels.get(..count).is_some_and(|seen| seen.contains(&channel)) {
                return Err(err(line.number, word.column, format!("channel {} listed twice", channel.name())));
            }
            let Some(slot) = channels.get_mut(count) else {
                return Err(err(
                    line.number,
                    word.column,
                    format!("more than {CHANNEL_COUNT} channels ({CHANNEL_LIST})"),
                ));
            };
            *slot = channel;
            count += 1;
        }
        if count < CHANNEL_COUNT {
            return Err(err(
                line.number,
                line.end_column(),
                format!("channel line has {count} names, expected all {CHANNEL_COUNT} ({CHANNEL_LIST})"),
            ));
        }
        Ok(channels)
    }

    /// One row of nine numbers.
    fn row(
        &mut self,
        line: &Line,
        name: &str,
        channels: &[BvaChannel; CHANNEL_COUNT],
    ) -> Result<[f32; CHANNEL_COUNT], ParseError> {
        let mut row = [0.0f32; CHANNEL_COUNT];
        let mut count = 0usize;
        let mut extra_column = None;
        for word in line.words() {
            let Some(value) = parse_f32(word.text) else {
                return Err(ParseError::new(
                    line.number,
                    word.column,
                    format!("segment `{name}`: expected a number, found `{}`", show_bytes(word.text)),
                ));
            };
            if !value.is_finite() && self.notes.non_finite.is_none() {
                self.notes.non_finite = Some(line.number);
            }
            match row.get_mut(count) {
                Some(slot) => *slot = value,
                None => extra_column = extra_column.or(Some(word.column)),
            }
            count += 1;
        }
        if count != CHANNEL_COUNT {
            let first = channels.first().map_or("", |c| c.name());
            let last = channels.last().map_or("", |c| c.name());
            return Err(ParseError::new(
                line.number,
                extra_column.unwrap_or_else(|| line.end_column()),
                format!("segment `{name}`: expected {CHANNEL_COUNT} values ({first} … {last}), found {count}"),
            ));
        }
        Ok(row)
    }
}

/// True when the line's first word is a number (so it is a row, not units).
fn starts_with_number(line: &Line) -> bool {
    line.words().next().is_some_and(|w| parse_f32(w.text).is_some())
}

/// The units line: exactly nine words.
fn units_line(line: &Line, name: &str) -> Result<[String; CHANNEL_COUNT], ParseError> {
    let mut units: [String; CHANNEL_COUNT] = Default::default();
    let mut count = 0usize;
    for word in line.words() {
        let Some(slot) = units.get_mut(count) else {
            return Err(ParseError::new(
                line.number,
                word.column,
                format!(
                    "segment `{name}`: units line has more than {CHANNEL_COUNT} words, expected one per channel (e.g. INCHES or DEGREES)"
                ),
            ));
        };
        *slot = decode(word.text);
        count += 1;
    }
    if count < CHANNEL_COUNT {
        return Err(ParseError::new(
            line.number,
            line.end_column(),
            format!(
                "segment `{name}`: units line has {count} words, expected {CHANNEL_COUNT}, one per channel (e.g. INCHES or DEGREES)"
            ),
        ));
    }
    Ok(units)
}

/// Parses a whole BVA file.
pub(super) fn parse(bytes: &[u8]) -> Result<Bva, ParseError> {
    let mut reader = Reader { lines: Lines::new(bytes), last: None, warnings: Vec::new(), notes: Notes::default() };
    let mut segments: Vec<Segment> = Vec::new();
    while let Some(line) = reader.peek() {
        let Kind::Segment(at) = classify(&line) else {
            let word = line.words().next();
            let column = word.map_or(1, |w| w.column);
            let found = show_bytes(word.map_or(&[][..], |w| w.text));
            let message = if segments.is_empty() {
                format!("expected Segment: at the start of a BVA file, found `{found}`")
            } else {
                format!("expected Segment:, found `{found}`")
            };
            return Err(ParseError::new(line.number, column, message));
        };
        reader.take();
        segments.push(reader.segment(line, at)?);
    }
    let Some(first) = segments.first() else {
        return Err(ParseError::new(1, 1, "empty file: expected Segment:"));
    };
    let mut warnings = reader.warnings;
    if let Some((line, count)) = reader.notes.no_units {
        let message = if count == 1 {
            "a segment has no units line; assuming INCHES for translation and scale, DEGREES for rotation".to_owned()
        } else {
            format!(
                "{count} segments have no units line; assuming INCHES for translation and scale, DEGREES for rotation"
            )
        };
        warnings.push(Warning { line: Some(line), message });
    }
    if let Some(line) = reader.notes.non_finite {
        warnings.push(Warning { line: Some(line), message: "data holds NaN or infinite values".into() });
    }
    if let Some(other) = segments.iter().find(|s| s.frame_count != first.frame_count) {
        warnings.push(Warning {
            line: Some(other.line),
            message: format!(
                "segments have different frame counts (`{}`: {}, `{}`: {})",
                first.name, first.frame_count, other.name, other.frame_count
            ),
        });
    }
    if let Some(other) = segments.iter().find(|s| s.frame_time.to_bits() != first.frame_time.to_bits()) {
        warnings.push(Warning {
            line: Some(other.line),
            message: format!(
                "segments have different frame times (`{}`: {} s, `{}`: {} s)",
                first.name, first.frame_time, other.name, other.frame_time
            ),
        });
    }
    Ok(Bva { segments, warnings })
}
