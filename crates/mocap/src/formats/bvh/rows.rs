//! The hot path: motion rows to one contiguous f32 matrix.
//!
//! Rows are lines; each must hold exactly one value per channel. Big inputs are cut
//! into chunks at line breaks (a few per thread) and parsed on several threads
//! straight into their part of one buffer, sized by counting non-blank lines first. Nothing is allocated from
//! a count written in the file: the buffer is at most the number of lines present
//! times the row width, and that product is checked against the byte length.

use super::cursor::{is_blank, show_bytes};
use crate::error::ParseError;

/// The parsed rows.
pub(crate) struct Rows {
    /// Row-major values.
    pub data: Vec<f32>,
    /// Number of rows.
    pub count: usize,
    /// Oddities worth a warning.
    pub notes: RowNotes,
}

/// Lines of the first oddity of each kind in the rows.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct RowNotes {
    /// First NaN or infinite value (including MSVC's `1.#QNAN`, `-1.#IND`, `1.#INF`).
    pub non_finite: Option<u32>,
    /// First number written with a decimal comma (`0,5`).
    pub decimal_comma: Option<u32>,
}

impl RowNotes {
    fn or(self, other: RowNotes) -> RowNotes {
        RowNotes {
            non_finite: self.non_finite.or(other.non_finite),
            decimal_comma: self.decimal_comma.or(other.decimal_comma),
        }
    }
}

/// Where a chunk starts in the file, for messages.
#[derive(Clone, Copy)]
struct Origin {
    /// Line number of the chunk's first line.
    line: u32,
    /// Columns before the chunk's first byte on its first line.
    column_offset: u32,
}

/// Parses `data` (everything after the MOTION header) into rows of `width` values.
pub(crate) fn parse_rows(data: &[u8], first_line: u32, first_column: u32, width: usize) -> Result<Rows, ParseError> {
    let origin = Origin { line: first_line, column_offset: first_column.saturating_sub(1) };
    let chunks = split_at_lines(data, crate::runtime::parallel::piece_count(data.len(), 4));
    let counts: Vec<LineCount> = crate::runtime::parallel::map(chunks.clone(), |c| count_lines(c))
        .into_iter()
        .collect::<Option<_>>()
        .ok_or_else(thread_failed)?;
    let total_rows: usize = counts.iter().map(|c| c.content).sum();
    // A valid row of `width` values takes at least 2·width bytes (value + separator).
    let fits = total_rows.checked_mul(width).is_some_and(|n| n <= data.len());
    if width == 0 || !fits {
        // Some line is malformed; find it without allocating a matrix.
        let mut row = vec![0.0; width.max(1)];
        parse_chunk(data, origin, width, &mut row, true)?;
        if total_rows > 0 {
            return Err(ParseError::new(
                first_line,
                first_column,
                format!("{total_rows} motion rows but the skeleton has no channels"),
            ));
        }
        return Ok(Rows { data: Vec::new(), count: 0, notes: RowNotes::default() });
    }
    let mut matrix = vec![0.0f32; total_rows * width];
    let mut jobs = Vec::with_capacity(chunks.len());
    let mut rest = matrix.as_mut_slice();
    let mut line = first_line;
    for (i, (chunk, count)) in chunks.iter().zip(&counts).enumerate() {
        let (mine, tail) = rest.split_at_mut(count.content * width);
        rest = tail;
        let origin = Origin { line, column_offset: if i == 0 { origin.column_offset } else { 0 } };
        jobs.push((*chunk, origin, mine));
        line = line.saturating_add(count.breaks);
    }
    let results = run_jobs(jobs, width);
    let mut count = 0;
    let mut notes = RowNotes::default();
    for result in results {
        let (rows, chunk_notes) = result?;
        count += rows;
        notes = notes.or(chunk_notes);
    }
    matrix.truncate(count * width);
    Ok(Rows { data: matrix, count, notes })
}

/// Rows parsed piece by piece, in file order (for [`super::Stream`]): each piece
/// ends at a line break, except the last.
pub(crate) struct RowBuilder {
    width: usize,
    origin: Origin,
    rows: Rows,
}

impl RowBuilder {
    /// Rows of `width` values (at least one) starting at `first_line`,
    /// `first_column` (as [`parse_rows`] takes them).
    pub(crate) fn new(first_line: u32, first_column: u32, width: usize) -> RowBuilder {
        let origin = Origin { line: first_line, column_offset: first_column.saturating_sub(1) };
        RowBuilder {
            width: width.max(1),
            origin,
            rows: Rows { data: Vec::new(), count: 0, notes: RowNotes::default() },
        }
    }

    /// Parses the rows of `piece` (the bytes right after the last piece) and
    /// appends them; `None` on any problem (a malformed row, more values than
    /// the bytes can hold), which [`parse_rows`] over the whole data then reports.
    pub(crate) fn push(&mut self, piece: &[u8]) -> Option<()> {
        let count = count_lines(piece);
        let values = count.content.checked_mul(self.width).filter(|&n| n <= piece.len())?;
        let start = self.rows.data.len();
        self.rows.data.try_reserve(values).ok()?;
        self.rows.data.resize(start + values, 0.0);
        let (rows, notes) = parse_chunk(piece, self.origin, self.width, &mut self.rows.data[start..], false).ok()?;
        self.rows.data.truncate(start + rows * self.width);
        self.rows.count += rows;
        self.rows.notes = self.rows.notes.or(notes);
        self.origin = Origin { line: self.origin.line.saturating_add(count.breaks), column_offset: 0 };
        Some(())
    }

    /// Reserves room for the rows `bytes` more bytes would hold, at the rate
    /// of values per byte seen so far (at most one value per two bytes, as a
    /// row takes; nothing when the room cannot be had or no row is in yet).
    /// Called once the first rows are in, with what is left of the file's
    /// announced size, it saves growing the matrix push by push: each growth
    /// copies it into fresh memory, which a browser fills page by page.
    pub(crate) fn reserve_for(&mut self, bytes: usize, bytes_so_far: usize) {
        let values = self.rows.data.len();
        if values == 0 || bytes_so_far == 0 {
            return;
        }
        let estimate = (bytes as f64 * values as f64 / bytes_so_far as f64) as usize;
        let _ = self.rows.data.try_reserve_exact(estimate.min(bytes / 2));
    }

    /// Whether no row is in yet.
    pub(crate) fn is_empty(&self) -> bool {
        self.rows.data.is_empty()
    }

    /// The rows so far.
    pub(crate) fn finish(mut self) -> Rows {
        self.rows.data.shrink_to_fit();
        self.rows
    }
}

type Job<'a, 'b> = (&'a [u8], Origin, &'b mut [f32]);
type JobResult = Result<(usize, RowNotes), ParseError>;

fn run_jobs(jobs: Vec<Job<'_, '_>>, width: usize) -> Vec<JobResult> {
    crate::runtime::parallel::map(jobs, |(c, o, out)| parse_chunk(c, o, width, out, false))
        .into_iter()
        .map(|r| r.unwrap_or_else(|| Err(thread_failed())))
        .collect()
}

fn thread_failed() -> ParseError {
    ParseError::new(0, 0, "internal error: a parser thread failed")
}

/// Cuts `data` into about `parts` pieces, each ending just after a line break.
fn split_at_lines(data: &[u8], parts: usize) -> Vec<&[u8]> {
    let mut chunks = Vec::with_capacity(parts);
    let mut start = 0;
    for k in 1..parts {
        let target = (data.len() * k / parts).max(start);
        let Some(rest) = data.get(target..) else { break };
        let cut = match memchr::memchr(b'\n', rest) {
            Some(i) => target + i + 1,
            None => match memchr::memchr(b'\r', rest) {
                Some(i) => target + i + 1,
                None => break,
            },
        };
        if cut > start && cut < data.len() {
            chunks.push(&data[start..cut]);
            start = cut;
        }
    }
    chunks.push(&data[start..]);
    chunks
}

/// Lines in a chunk: how many hold something, and how many line breaks there are.
struct LineCount {
    content: usize,
    breaks: u32,
}

fn count_lines(chunk: &[u8]) -> LineCount {
    let mut count = LineCount { content: 0, breaks: 0 };
    let mut start = 0;
    let mut ends = memchr::memchr2_iter(b'\n', b'\r', chunk).peekable();
    while let Some(end) = ends.next() {
        if chunk.get(start..end).is_some_and(has_content) {
            count.content += 1;
        }
        // CRLF is one break.
        if chunk.get(end) == Some(&b'\r') && chunk.get(end + 1) == Some(&b'\n') {
            ends.next();
            start = end + 2;
        } else {
            start = end + 1;
        }
        count.breaks = count.breaks.saturating_add(1);
    }
    if chunk.get(start..).is_some_and(has_content) {
        count.content += 1;
    }
    count
}

#[inline]
fn has_content(line: &[u8]) -> bool {
    line.iter().any(|&b| !is_blank(b))
}

/// Byte classes for the row scanner.
const OTHER: u8 = 0;
const BLANK: u8 = 1;
const LF: u8 = 2;
const CR: u8 = 3;

const CLASS: [u8; 256] = {
    let mut t = [OTHER; 256];
    let mut b = 0;
    while b < 256 {
        if crate::formats::text::is_blank(b as u8) {
            t[b] = BLANK;
        }
        b += 1;
    }
    t[b'\n' as usize] = LF;
    t[b'\r' as usize] = CR;
    t
};

/// How a number that the standard parsers refuse was read.
enum Quirk {
    /// `0,25`: a decimal comma (a locale bug in some exporters).
    DecimalComma,
    /// `1.#QNAN`, `-1.#IND00`, `1.#INF`: MSVC's printf of NaN and infinity.
    MsvcSpecial,
}

/// Reads the number forms real exporters write by mistake; `None` for anything else.
fn parse_quirky_number(token: &[u8]) -> Option<(f32, Quirk)> {
    let negative = token.first() == Some(&b'-');
    let body = token.strip_prefix(b"-").or_else(|| token.strip_prefix(b"+")).unwrap_or(token);
    if let Some(at) = body.windows(2).position(|w| w == b".#") {
        let (digits, kind) = (body.get(..at)?, body.get(at + 2..)?.to_ascii_uppercase());
        if digits.is_empty() || !digits.iter().all(u8::is_ascii_digit) {
            return None;
        }
        if kind.starts_with(b"INF") {
            return Some((if negative { f32::NEG_INFINITY } else { f32::INFINITY }, Quirk::MsvcSpecial));
        }
        if kind.starts_with(b"IND") || kind.starts_with(b"QNAN") || kind.starts_with(b"SNAN") {
            return Some((f32::NAN, Quirk::MsvcSpecial));
        }
        return None;
    }
    if token.iter().filter(|&&b| b == b',').count() == 1 && !token.contains(&b'.') {
        let fixed: Vec<u8> = token.iter().map(|&b| if b == b',' { b'.' } else { b }).collect();
        let value = fast_float2::parse::<f32, _>(&fixed).ok()?;
        return Some((value, Quirk::DecimalComma));
    }
    None
}

/// A number at the start of `rest` that is not a short decimal (see
/// [`crate::formats::decimal::Decimals`]): long, with an exponent, `inf` or `nan`, or one of
/// the quirky forms. Returns the value and the bytes it takes; notes the first
/// non-finite value or decimal comma on `line`; an error at `line`, `column`
/// when `rest` does not start with a number ending at a separator.
#[cold]
fn read_other_number(rest: &[u8], line: u32, column: u32, notes: &mut RowNotes) -> Result<(f32, usize), ParseError> {
    let (value, used) = match fast_float2::parse_partial::<f32, _>(rest) {
        Ok((v, used)) if used > 0 && rest.get(used).is_none_or(|&c| CLASS[c as usize] != OTHER) => (v, used),
        _ => {
            let end = rest.iter().position(|&c| CLASS[c as usize] != OTHER).unwrap_or(rest.len());
            let token = rest.get(..end).unwrap_or(rest);
            match parse_quirky_number(token) {
                Some((v, Quirk::DecimalComma)) => {
                    notes.decimal_comma = notes.decimal_comma.or(Some(line));
                    (v, end)
                }
                Some((v, Quirk::MsvcSpecial)) => (v, end),
                None => {
                    return Err(ParseError::new(
                        line,
                        column,
                        format!("expected a number in motion row, found `{}`", show_bytes(token)),
                    ));
                }
            }
        }
    };
    if !value.is_finite() && notes.non_finite.is_none() {
        notes.non_finite = Some(line);
    }
    Ok((value, used))
}

/// Parses the rows of one chunk into `out` (row after row). With `ring`, every row
/// is written to the start of `out` instead: used to find an error without storing.
/// Returns the number of rows and the line of the first non-finite value.
fn parse_chunk(chunk: &[u8], origin: Origin, width: usize, out: &mut [f32], ring: bool) -> JobResult {
    let mut i = 0;
    let mut line = origin.line;
    // Column of byte i is i - line_start + 1 (+ offset on the first line).
    let mut line_start: isize = -(origin.column_offset as isize);
    let mut rows = 0usize;
    let mut k = 0usize;
    let mut base = 0usize;
    let mut notes = RowNotes::default();
    let decimals = crate::formats::decimal::Decimals::for_text(chunk);
    let column = |i: usize, line_start: isize| u32::try_from(i as isize - line_start + 1).unwrap_or(u32::MAX);
    let row_error = |line: u32, column: u32, k: usize| {
        ParseError::new(line, column, format!("motion row has {k} values, expected {width} (one per channel)"))
    };
    while let Some(&b) = chunk.get(i) {
        match CLASS[b as usize] {
            BLANK => i += 1,
            LF | CR => {
                if k != 0 {
                    if k != width {
                        return Err(row_error(line, column(i, line_start), k));
                    }
                    rows += 1;
                    k = 0;
                    base = if ring { 0 } else { base + width };
                }
                i += if b == b'\r' && chunk.get(i + 1) == Some(&b'\n') { 2 } else { 1 };
                line = line.saturating_add(1);
                line_start = i as isize;
            }
            _ => {
                if k == width {
                    return Err(ParseError::new(
                        line,
                        column(i, line_start),
                        format!("motion row has more than {width} values (one per channel)"),
                    ));
                }
                let rest = chunk.get(i..).unwrap_or(&[]);
                // Short decimals are finite and end at a separator; anything else
                // goes through the general reader.
                let (value, used) = match decimals.read(rest) {
                    Some(parsed) => parsed,
                    None => read_other_number(rest, line, column(i, line_start), &mut notes)?,
                };
                match out.get_mut(base + k) {
                    Some(slot) => *slot = value,
                    None => {
                        return Err(ParseError::new(
                            line,
                            column(i, line_start),
                            "internal error: row buffer too small",
                        ));
                    }
                }
                k += 1;
                i += used;
                // The usual single space to the next number, without a turn of the loop.
                if chunk.get(i) == Some(&b' ') {
                    i += 1;
                }
            }
        }
    }
    if k != 0 {
        if k != width {
            return Err(row_error(line, column(i, line_start), k));
        }
        rows += 1;
    }
    Ok((rows, notes))
}
