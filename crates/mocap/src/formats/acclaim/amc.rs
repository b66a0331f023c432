//! The AMC motion reader: a byte scanner over lines that writes each value straight
//! into one row-major `f32` matrix.

use super::AngleUnit;
use super::text::{binary_kind, bom_len, is_blank, is_eol, line_break_len, line_end, parse_i64, show_bytes};
use crate::error::{ParseError, Warning};
use std::collections::HashMap;

/// A parsed AMC motion.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Amc {
    /// `:DEGREES` or `:RADIANS`; degrees when the file says neither.
    pub angle: AngleUnit,
    /// Whether the file has a `:FULLY-SPECIFIED` line.
    pub fully_specified: bool,
    /// Number of frames.
    pub frame_count: usize,
    /// Values per frame: the sum of the layout's counts.
    pub width: usize,
    /// `frame_count × width` values, row-major, columns in layout order.
    pub data: Vec<f32>,
    /// The number written before the first frame, when there is a frame.
    pub first_frame_number: Option<i64>,
    /// Non-fatal problems.
    pub warnings: Vec<Warning>,
}

impl Amc {
    /// The values of frame `frame`, or `None` past the end.
    pub fn frame(&self, frame: usize) -> Option<&[f32]> {
        let start = frame.checked_mul(self.width)?;
        self.data.get(start..start.checked_add(self.width)?)
    }
}

/// True when `bytes` look like an AMC motion: the first line that is not blank or a
/// `#` comment starts with `:FULLY-SPECIFIED`, `:DEGREES` or `:RADIANS` (any case), or
/// holds only an integer and is followed by a line starting with a letter.
pub fn sniff_amc(bytes: &[u8]) -> bool {
    let head = bytes.get(..4096).unwrap_or(bytes);
    let head = head.get(bom_len(head)..).unwrap_or(&[]);
    let mut lines =
        head.split(|&b| is_eol(b)).map(super::text::trim_blanks).filter(|l| !l.is_empty() && !l.starts_with(b"#"));
    let Some(first) = lines.next() else { return false };
    if first.starts_with(b":") {
        let word = first.split(|&b| is_blank(b)).next().unwrap_or(&[]);
        return [&b":FULLY-SPECIFIED"[..], b":DEGREES", b":RADIANS"].iter().any(|k| word.eq_ignore_ascii_case(k));
    }
    is_frame_number(first)
        && lines.next().and_then(|l| l.first()).is_some_and(|b| b.is_ascii_alphabetic() || *b == b'_')
}

/// An optional sign and one or more ASCII digits.
fn is_frame_number(token: &[u8]) -> bool {
    let digits = match token {
        [b'-' | b'+', rest @ ..] => rest,
        _ => token,
    };
    !digits.is_empty() && digits.iter().all(u8::is_ascii_digit)
}

/// Parses the number at the start of `s`: the value and the bytes used (0 when there
/// is no number). Short decimals on the shared fast path ([`crate::formats::decimal::Decimals`]);
/// everything else through [`parse_other_value`]. (The scanner takes the two
/// steps itself, the first as its [`crate::formats::decimal::Decimals`] chose.)
#[cfg(test)]
fn parse_value(s: &[u8]) -> (f32, usize) {
    crate::formats::decimal::Decimals::default().read(s).unwrap_or_else(|| parse_other_value(s))
}

/// A number that is not a short decimal (exponents, long mantissas, `inf`),
/// through `fast_float2`: the value and the bytes used (0 when there is none).
fn parse_other_value(s: &[u8]) -> (f32, usize) {
    fast_float2::parse_partial::<f32, _>(s).unwrap_or((0.0, 0))
}

const NONE: usize = usize::MAX;

/// `a == b` for short slices (bone names) without a call to `memcmp`.
#[inline]
fn same_bytes(a: &[u8], b: &[u8]) -> bool {
    a.len() == b.len() && a.iter().zip(b).fold(0u8, |diff, (x, y)| diff | (x ^ y)) == 0
}

/// The row layout of the skeleton, as the scanners look it up.
struct Columns<'l> {
    layout: &'l [(&'l str, usize)],
    /// First column of each bone.
    offsets: Vec<usize>,
    /// Values per frame.
    width: usize,
    names: HashMap<&'l [u8], usize>,
    /// Non-zero-dof bones, in layout order.
    nonzero: Vec<usize>,
}

impl<'l> Columns<'l> {
    fn new(layout: &'l [(&'l str, usize)]) -> Columns<'l> {
        let mut offsets = Vec::with_capacity(layout.len());
        let mut width = 0usize;
        let mut names = HashMap::with_capacity(layout.len());
        let mut nonzero = Vec::new();
        for (i, &(name, count)) in layout.iter().enumerate() {
            offsets.push(width);
            width = width.saturating_add(count);
            names.entry(name.as_bytes()).or_insert(i);
            if count > 0 {
                nonzero.push(i);
            }
        }
        Columns { layout, offsets, width, names, nonzero }
    }
}

/// The scanner's state: one for the file, or one for each piece of a large file
/// (see [`cut_at_frames`]).
struct Scanner<'a, 'c> {
    src: &'a [u8],
    pos: usize,
    line: u32,
    line_start: usize,
    columns: &'c Columns<'c>,
    /// The bone that followed each bone the last time it appeared (prediction).
    next_after: Vec<usize>,
    /// First bone of the previous frame, and of the current one.
    first_bone: usize,
    current_first: usize,
    last_bone: usize,
    /// For each bone, the frame (1-based count) it last appeared in, and the line.
    seen: Vec<usize>,
    seen_line: Vec<u32>,
    /// Non-zero-dof bones seen in the current frame.
    seen_count: usize,
    row: usize,
    frame_line: u32,
    frame_number: i64,
    /// The values' short decimals (see [`crate::formats::decimal::Decimals`]).
    decimals: crate::formats::decimal::Decimals,
    part: Part,
}

/// What a scanner found in its bytes: the frames and what the warnings are made
/// of. Lines count from the first line of those bytes.
#[derive(Default)]
struct Part {
    /// Headers, first frame number, header warnings, and the values.
    amc: Amc,
    frame_count: usize,
    /// Line breaks scanned.
    breaks: u32,
    /// The line and number of the first frame, and the last frame's number.
    first_frame_line: u32,
    last_number: Option<i64>,
    /// For each bone, the first frame (1-based) that gives it; 0: none does.
    first_given: Vec<usize>,
    /// First missing bone: (frame line, bone, frame number); frames affected; bones affected.
    missing: Option<(u32, usize, i64)>,
    missing_frames: usize,
    missing_bones: Vec<bool>,
    /// First non-consecutive frame number: (line, expected, found), and how many.
    gap: Option<(u32, i64, i64)>,
    gap_count: usize,
    non_finite: Option<u32>,
}

/// Parses an AMC motion. `layout` is the row layout of the skeleton: (bone name,
/// number of values) in column order, the root named `"root"` (see
/// [`super::Asf::amc_layout`]). Bones may come in any order within a frame; a bone
/// missing from a frame keeps its value from the previous frame (zeros in the first),
/// with one warning for the whole file.
///
/// A large file is cut at frame lines into pieces read on several threads; the
/// pieces are then joined as if read in one go (values carried into a piece's
/// first frames, frame numbers checked across the cut, lines counted from the
/// file's start).
pub fn parse_amc(bytes: &[u8], layout: &[(&str, usize)]) -> Result<Amc, ParseError> {
    parse_in_pieces(bytes, layout, crate::runtime::parallel::piece_count(bytes.len(), 2))
}

/// [`parse_amc`] with the bytes cut into (at most) `pieces` pieces.
fn parse_in_pieces(bytes: &[u8], layout: &[(&str, usize)], pieces: usize) -> Result<Amc, ParseError> {
    if let Some(kind) = binary_kind(bytes) {
        return Err(ParseError::new(1, 1, format!("not an Acclaim motion file: {kind}")));
    }
    let columns = Columns::new(layout);
    let pieces = cut_at_frames(bytes, pieces);
    let parts = crate::runtime::parallel::map(pieces, |(piece, start)| {
        let mut scanner = Scanner::new(piece, start, &columns);
        scanner.run().map(|()| scanner.finish())
    });
    let mut joined: Vec<Part> = Vec::with_capacity(parts.len());
    for (i, part) in parts.into_iter().enumerate() {
        match part.ok_or_else(|| ParseError::new(0, 0, "internal error: an AMC reader thread failed"))? {
            Ok(part) => joined.push(part),
            // The first piece counts lines from the file's start.
            Err(e) if i == 0 => return Err(e),
            // A later piece's error may name lines of that piece (`first at line
            // …`): read the file again in one go, which words it from the start.
            Err(_) => return parse_in_pieces(bytes, layout, 1),
        }
    }
    Ok(join(joined, &columns).into_amc(&columns))
}

/// Cuts `bytes` into about `parts` pieces, each after the first starting at a
/// frame line (a line holding only a frame number); with where the first piece's
/// text starts (after a byte-order mark).
fn cut_at_frames(bytes: &[u8], parts: usize) -> Vec<(&[u8], usize)> {
    let mut cuts = vec![0];
    for k in 1..parts {
        let target = (bytes.len() * k / parts).max(cuts.last().copied().unwrap_or(0) + 1);
        match next_frame_line(bytes, target) {
            Some(cut) if cut < bytes.len() => cuts.push(cut),
            _ => break,
        }
    }
    cuts.push(bytes.len());
    cuts.windows(2)
        .enumerate()
        .filter_map(|(i, w)| {
            let piece = bytes.get(w[0]..w[1])?;
            Some((piece, if i == 0 { bom_len(bytes) } else { 0 }))
        })
        .collect()
}

/// The start of the first frame line that starts after `from` (past the line
/// break after `from`), or `None`.
fn next_frame_line(bytes: &[u8], from: usize) -> Option<usize> {
    let mut at = from;
    loop {
        let rest = bytes.get(at..)?;
        let brk = at + memchr::memchr2(b'\n', b'\r', rest)?;
        let start = brk + line_break_len(bytes, brk);
        if is_frame_line(bytes, start) {
            return Some(start);
        }
        at = start;
    }
}

/// Whether the line starting at `start` is a frame line (see [`is_frame_word`]).
fn is_frame_line(bytes: &[u8], start: usize) -> bool {
    let p = skip_blanks(bytes, start);
    let e = word_end(bytes, p);
    is_frame_word(bytes, p, e, skip_blanks(bytes, e))
}

/// Whether the word `p..e` of a line, the next byte that is not blank at
/// `after`, makes the line a frame line: a frame number alone on its line (a
/// comment may follow). One rule for the scanner and for cutting a file.
fn is_frame_word(src: &[u8], p: usize, e: usize, after: usize) -> bool {
    src.get(after).is_none_or(|&b| is_eol(b) || b == b'#') && is_frame_number(src.get(p..e).unwrap_or(&[]))
}

/// The first byte from `at` that is not blank.
#[inline]
fn skip_blanks(src: &[u8], mut at: usize) -> usize {
    while src.get(at).is_some_and(|&b| is_blank(b)) {
        at += 1;
    }
    at
}

/// The end of the word starting at `at` (a blank, a line break, or the end).
#[inline]
fn word_end(src: &[u8], mut at: usize) -> usize {
    while src.get(at).is_some_and(|&b| !is_blank(b) && !is_eol(b)) {
        at += 1;
    }
    at
}

/// The parts, in file order, as one: values carried into each part's first
/// frames from the part before, frame numbers checked across each cut, lines
/// counted from the file's start.
fn join(parts: Vec<Part>, columns: &Columns<'_>) -> Part {
    let mut parts = parts.into_iter();
    let mut all = parts.next().unwrap_or_default();
    let mut line = all.breaks;
    for mut part in parts {
        let shift = |l: u32| l.saturating_add(line);
        if part.frame_count > 0 {
            carry_into(&mut part, &all, columns);
            if all.frame_count == 0 {
                all.amc.first_frame_number = part.amc.first_frame_number;
                all.first_frame_line = shift(part.first_frame_line);
            }
            if let (Some(last), Some(first)) = (all.last_number, part.amc.first_frame_number) {
                if last.checked_add(1) != Some(first) {
                    all.gap_count += 1;
                    all.gap = all.gap.or(Some((shift(part.first_frame_line), last.saturating_add(1), first)));
                }
            }
            all.last_number = part.last_number;
        }
        all.amc.warnings.extend(part.amc.warnings.into_iter().map(|w| Warning { line: w.line.map(shift), ..w }));
        all.amc.data.extend_from_slice(&part.amc.data);
        all.frame_count += part.frame_count;
        all.missing = all.missing.or(part.missing.map(|(l, b, n)| (shift(l), b, n)));
        all.missing_frames += part.missing_frames;
        for (flag, more) in all.missing_bones.iter_mut().zip(&part.missing_bones) {
            *flag |= *more;
        }
        all.gap_count += part.gap_count;
        all.gap = all.gap.or(part.gap.map(|(l, e, f)| (shift(l), e, f)));
        all.non_finite = all.non_finite.or(part.non_finite.map(shift));
        line = line.saturating_add(part.breaks);
        all.breaks = line;
    }
    all
}

/// Gives the bones that `part`'s first frames lack (read as zeros) the values of
/// `before`'s last frame, as reading in one go would have.
fn carry_into(part: &mut Part, before: &Part, columns: &Columns<'_>) {
    let width = columns.width;
    if width == 0 {
        return;
    }
    let Some(last) = before.frame_count.checked_sub(1).and_then(|f| before.amc.data.get(f * width..(f + 1) * width))
    else {
        return;
    };
    for &bone in &columns.nonzero {
        let given = part.first_given.get(bone).copied().unwrap_or(0);
        let frames = if given == 0 { part.frame_count } else { given - 1 };
        let (Some(&offset), Some(&(_, count))) = (columns.offsets.get(bone), columns.layout.get(bone)) else {
            continue;
        };
        let Some(values) = last.get(offset..offset + count) else { continue };
        for row in part.amc.data.chunks_mut(width).take(frames) {
            if let Some(slot) = row.get_mut(offset..offset + count) {
                slot.copy_from_slice(values);
            }
        }
    }
}

fn plural(n: usize, one: &str, many: &str) -> String {
    if n == 1 { format!("1 {one}") } else { format!("{n} {many}") }
}

impl<'a, 'c> Scanner<'a, 'c> {
    /// A scanner over `src` from byte `start` (after a byte-order mark).
    fn new(src: &'a [u8], start: usize, columns: &'c Columns<'c>) -> Scanner<'a, 'c> {
        let bones = columns.layout.len();
        Scanner {
            src,
            pos: start,
            line: 1,
            line_start: start,
            columns,
            next_after: vec![NONE; bones],
            first_bone: NONE,
            current_first: NONE,
            last_bone: NONE,
            seen: vec![0; bones],
            seen_line: vec![0; bones],
            seen_count: 0,
            row: 0,
            frame_line: 0,
            frame_number: 0,
            decimals: crate::formats::decimal::Decimals::for_text(src),
            part: Part {
                // An estimate from the bytes present, never from the file's numbers.
                amc: Amc { width: columns.width, data: Vec::with_capacity(src.len() / 10), ..Amc::default() },
                first_given: vec![0; bones],
                missing_bones: vec![false; bones],
                ..Part::default()
            },
        }
    }

    fn column(&self, at: usize) -> u32 {
        u32::try_from(at.saturating_sub(self.line_start) + 1).unwrap_or(u32::MAX)
    }

    fn error(&self, at: usize, message: impl Into<String>) -> ParseError {
        ParseError::new(self.line, self.column(at), message)
    }

    /// The end of the line holding `at` (the position of its line break, or the end).
    fn eol_from(&self, at: usize) -> usize {
        // Most callers are at the line's end already.
        if self.src.get(at).is_none_or(|&b| is_eol(b)) {
            return at;
        }
        line_end(self.src, at)
    }

    /// Consumes the line break at `self.pos`, if any, and starts the next line.
    fn line_break(&mut self) {
        self.pos += line_break_len(self.src, self.pos);
        self.line = self.line.saturating_add(1);
    }

    /// Skips blanks from `at`.
    #[inline]
    fn skip_blanks(&self, at: usize) -> usize {
        skip_blanks(self.src, at)
    }

    /// The end of the token starting at `at`.
    #[inline]
    fn token_end(&self, at: usize) -> usize {
        word_end(self.src, at)
    }

    fn run(&mut self) -> Result<(), ParseError> {
        while self.pos < self.src.len() {
            self.line_start = self.pos;
            let p = self.skip_blanks(self.pos);
            match self.src.get(p) {
                None => break,
                Some(&b) if is_eol(b) => self.pos = p,
                Some(b'#') => self.pos = self.eol_from(p),
                Some(b':') => {
                    self.header(p);
                    self.pos = self.eol_from(p);
                }
                Some(_) => {
                    let e = self.token_end(p);
                    let after = self.skip_blanks(e);
                    if is_frame_word(self.src, p, e, after) {
                        self.new_frame(self.src.get(p..e).unwrap_or(&[]), p)?;
                        self.pos = self.eol_from(after);
                    } else {
                        self.bone_line(p, e)?;
                    }
                }
            }
            self.line_break();
        }
        Ok(())
    }

    fn header(&mut self, p: usize) {
        let e = self.token_end(p);
        let word = self.src.get(p..e).unwrap_or(&[]);
        let known = [&b":FULLY-SPECIFIED"[..], b":DEGREES", b":RADIANS"].iter().any(|k| word.eq_ignore_ascii_case(k));
        if self.part.frame_count > 0 {
            self.part.amc.warnings.push(Warning {
                line: Some(self.line),
                message: format!("header line `{}` after the first frame ignored", show_bytes(word)),
            });
        } else if word.eq_ignore_ascii_case(b":FULLY-SPECIFIED") {
            self.part.amc.fully_specified = true;
        } else if word.eq_ignore_ascii_case(b":DEGREES") {
            self.part.amc.angle = AngleUnit::Degrees;
        } else if word.eq_ignore_ascii_case(b":RADIANS") {
            self.part.amc.angle = AngleUnit::Radians;
        } else if !known {
            self.part.amc.warnings.push(Warning {
                line: Some(self.line),
                message: format!("unknown header line `{}` ignored", show_bytes(word)),
            });
        }
    }

    fn new_frame(&mut self, token: &[u8], p: usize) -> Result<(), ParseError> {
        let number = parse_i64(token)
            .ok_or_else(|| self.error(p, format!("frame number `{}` is out of range", show_bytes(token))))?;
        if self.part.frame_count > 0 {
            self.finish_frame();
        }
        self.part.frame_count += 1;
        if self.part.frame_count == 1 {
            self.part.amc.data.resize(self.columns.width, 0.0);
            self.row = 0;
            self.part.amc.first_frame_number = Some(number);
            self.part.first_frame_line = self.line;
        } else {
            let previous = self.row;
            self.row = self.part.amc.data.len();
            self.part.amc.data.extend_from_within(previous..self.row);
        }
        if let Some(last) = self.part.last_number {
            if last.checked_add(1) != Some(number) {
                self.part.gap_count += 1;
                if self.part.gap.is_none() {
                    self.part.gap = Some((self.line, last.saturating_add(1), number));
                }
            }
        }
        self.part.last_number = Some(number);
        self.frame_line = self.line;
        self.frame_number = number;
        self.seen_count = 0;
        if self.current_first != NONE {
            self.first_bone = self.current_first;
        }
        self.current_first = NONE;
        self.last_bone = NONE;
        Ok(())
    }

    /// Notes the bones the frame that just ended did not give.
    fn finish_frame(&mut self) {
        if self.seen_count >= self.columns.nonzero.len() {
            return;
        }
        self.part.missing_frames += 1;
        for &b in &self.columns.nonzero {
            if self.seen.get(b) != Some(&self.part.frame_count) {
                if let Some(flag) = self.part.missing_bones.get_mut(b) {
                    *flag = true;
                }
                if self.part.missing.is_none() {
                    self.part.missing = Some((self.frame_line, b, self.frame_number));
                }
            }
        }
    }

    fn bone_name(&self, bone: usize) -> &'c str {
        self.columns.layout.get(bone).map_or("", |&(name, _)| name)
    }

    /// A `bonename v1 v2 …` line; the name spans `p..e`. Leaves `pos` at the line end.
    fn bone_line(&mut self, p: usize, e: usize) -> Result<(), ParseError> {
        let name = self.src.get(p..e).unwrap_or(&[]);
        if self.part.frame_count == 0 {
            return Err(self.error(p, format!("values for `{}` before the first frame number: expected a line holding only the frame number (e.g. `1`)", show_bytes(name))));
        }
        let predicted = if self.last_bone == NONE {
            self.first_bone
        } else {
            self.next_after.get(self.last_bone).copied().unwrap_or(NONE)
        };
        let bone = if self.columns.layout.get(predicted).is_some_and(|&(n, _)| same_bytes(n.as_bytes(), name)) {
            predicted
        } else {
            match self.columns.names.get(name) {
                Some(&b) => b,
                None => return Err(self.error(p, format!("bone `{}` is not in the skeleton", show_bytes(name)))),
            }
        };
        let count = self.columns.layout.get(bone).map_or(0, |&(_, c)| c);
        if self.seen.get(bone) == Some(&self.part.frame_count) {
            let first = self.seen_line.get(bone).copied().unwrap_or(0);
            return Err(self.error(
                p,
                format!(
                    "bone `{}` appears twice in frame {} (first at line {first})",
                    self.bone_name(bone),
                    self.frame_number
                ),
            ));
        }
        if let (Some(s), Some(l)) = (self.seen.get_mut(bone), self.seen_line.get_mut(bone)) {
            *s = self.part.frame_count;
            *l = self.line;
        }
        if let Some(first) = self.part.first_given.get_mut(bone).filter(|f| **f == 0) {
            *first = self.part.frame_count;
        }
        if count > 0 {
            self.seen_count += 1;
        }
        if self.last_bone == NONE {
            self.current_first = bone;
        } else if let Some(next) = self.next_after.get_mut(self.last_bone) {
            *next = bone;
        }
        self.last_bone = bone;

        let base = self.row + self.columns.offsets.get(bone).copied().unwrap_or(0);
        let mut q = e;
        for k in 0..count {
            q = self.skip_blanks(q);
            if self.src.get(q).is_none_or(|&b| is_eol(b) || b == b'#') {
                return Err(self.count_error(q, bone, count, k));
            }
            let rest = self.src.get(q..).unwrap_or(&[]);
            // Short decimals are finite and end at a separator; the rest is checked.
            let (v, used) = match self.decimals.read(rest) {
                Some(parsed) => parsed,
                None => self.other_value(q, bone, k)?,
            };
            let end = q + used;
            if let Some(slot) = self.part.amc.data.get_mut(base + k) {
                *slot = v;
            }
            q = end;
        }
        q = self.skip_blanks(q);
        if self.src.get(q).is_some_and(|&b| !is_eol(b) && b != b'#') {
            // Count what is left for the message.
            let mut extra = 0;
            let mut r = q;
            while self.src.get(r).is_some_and(|&b| !is_eol(b) && b != b'#') {
                r = self.skip_blanks(self.token_end(r));
                extra += 1;
            }
            return Err(self.count_error(q, bone, count, count + extra));
        }
        self.pos = self.eol_from(q);
        Ok(())
    }

    /// Value `k` of `bone` at `q` when it is not a short decimal: the value and
    /// its length, the line noted when it is not finite, or an error when no
    /// number ending at a separator is there.
    #[cold]
    fn other_value(&mut self, q: usize, bone: usize, k: usize) -> Result<(f32, usize), ParseError> {
        let (v, used) = parse_other_value(self.src.get(q..).unwrap_or(&[]));
        if used == 0 || self.src.get(q + used).is_some_and(|&b| !is_blank(b) && !is_eol(b)) {
            let bad = self.src.get(q..self.token_end(q)).unwrap_or(&[]);
            return Err(self.error(
                q,
                format!(
                    "expected value {} of bone `{}` (a number), found `{}`",
                    k + 1,
                    self.bone_name(bone),
                    show_bytes(bad)
                ),
            ));
        }
        if !v.is_finite() && self.part.non_finite.is_none() {
            self.part.non_finite = Some(self.line);
        }
        Ok((v, used))
    }

    fn count_error(&self, at: usize, bone: usize, count: usize, given: usize) -> ParseError {
        self.error(
            at,
            format!(
                "bone `{}` has {}; this line gives {}",
                self.bone_name(bone),
                plural(count, "degree of freedom", "degrees of freedom"),
                plural(given, "value", "values")
            ),
        )
    }

    /// What the scanner found, once it has run.
    fn finish(mut self) -> Part {
        if self.part.frame_count > 0 {
            self.finish_frame();
        }
        self.part.breaks = self.line.saturating_sub(1);
        self.part
    }
}

impl Part {
    /// The motion, with the warnings made from what was found.
    fn into_amc(mut self, columns: &Columns<'_>) -> Amc {
        let bone_name = |bone: usize| columns.layout.get(bone).map_or("", |&(name, _)| name);
        if self.frame_count == 0 {
            self.amc.warnings.push(Warning { line: None, message: "the motion has no frames".into() });
        }
        if let Some((line, bone, number)) = self.missing {
            let bones = self.missing_bones.iter().filter(|&&m| m).count();
            let more = if self.missing_frames > 1 || bones > 1 {
                format!(
                    "; {} lack some bone ({} in all)",
                    plural(self.missing_frames, "frame", "frames"),
                    plural(bones, "bone", "bones")
                )
            } else {
                String::new()
            };
            self.amc.warnings.push(Warning {
                line: Some(line),
                message: format!("bone `{}` is missing from frame {number}: it keeps its previous value (zeros in the first frame){more}", bone_name(bone)),
            });
        }
        if let Some((line, expected, found)) = self.gap {
            self.amc.warnings.push(Warning {
                line: Some(line),
                message: format!("frame numbers are not consecutive: expected {expected}, found {found} ({} in all); frames are read in file order", plural(self.gap_count, "jump", "jumps")),
            });
        }
        if let Some(line) = self.non_finite {
            self.amc
                .warnings
                .push(Warning { line: Some(line), message: "the motion holds NaN or infinite values".into() });
        }
        self.amc.frame_count = self.frame_count;
        self.amc
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const LAYOUT: [(&str, usize); 4] = [("root", 6), ("hip", 3), ("toe", 0), ("knee", 2)];

    fn parse(src: &str) -> Amc {
        parse_amc(src.as_bytes(), &LAYOUT).unwrap_or_else(|e| panic!("{e}"))
    }

    fn fail(src: &str) -> ParseError {
        match parse_amc(src.as_bytes(), &LAYOUT) {
            Ok(amc) => panic!("expected an error, parsed {amc:?}"),
            Err(e) => e,
        }
    }

    fn at(e: &ParseError, line: u32, column: u32, words: &str) {
        assert_eq!((e.line, e.column), (line, column), "{e}");
        assert!(e.message.contains(words), "`{}` does not say `{words}`", e.message);
    }

    const TWO_FRAMES: &str = "#!OML:ASF test.asf
:FULLY-SPECIFIED
:DEGREES
1
root 1 2 3 4 5 6
hip 7 8 9
knee 10 11
2
knee -1e0 3.64024e-015
root 0.5 -0.25 +2 1.5E+002 -6.75868e-015 0
toe
hip\t-7\t-8.5\t-9
";

    #[test]
    fn frames_with_bones_in_any_order() {
        let amc = parse(TWO_FRAMES);
        assert!(amc.fully_specified);
        assert_eq!(amc.angle, AngleUnit::Degrees);
        assert_eq!((amc.frame_count, amc.width, amc.first_frame_number), (2, 11, Some(1)));
        assert_eq!(amc.frame(0), Some(&[1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0, 10.0, 11.0][..]));
        assert_eq!(
            amc.frame(1),
            Some(&[0.5, -0.25, 2.0, 150.0, -6.75868e-15, 0.0, -7.0, -8.5, -9.0, -1.0, 3.64024e-15][..])
        );
        assert_eq!(amc.frame(2), None);
        assert!(amc.warnings.is_empty(), "{:?}", amc.warnings);
        assert!(sniff_amc(TWO_FRAMES.as_bytes()));
        // The same with CRLF, lone CR and a byte-order mark.
        for text in [TWO_FRAMES.replace('\n', "\r\n"), TWO_FRAMES.replace('\n', "\r"), format!("\u{feff}{TWO_FRAMES}")]
        {
            assert_eq!(parse(&text), amc);
            assert!(sniff_amc(text.as_bytes()));
        }
    }

    #[test]
    fn missing_bone_keeps_previous_value_with_one_warning() {
        let amc = parse(
            "1\nroot 1 2 3 4 5 6\nhip 7 8 9\n2\nroot 0 0 0 0 0 0\n3\nroot 1 1 1 1 1 1\nknee 5 6\n4\nroot 1 1 1 1 1 1\nhip 1 2 3\nknee 7 8\n",
        );
        assert_eq!(amc.frame_count, 4);
        assert_eq!(amc.frame(0).map(|f| &f[6..]), Some(&[7.0, 8.0, 9.0, 0.0, 0.0][..]));
        assert_eq!(amc.frame(1).map(|f| &f[6..]), Some(&[7.0, 8.0, 9.0, 0.0, 0.0][..]));
        assert_eq!(amc.frame(2).map(|f| &f[6..]), Some(&[7.0, 8.0, 9.0, 5.0, 6.0][..]));
        assert_eq!(amc.frame(3).map(|f| &f[6..]), Some(&[1.0, 2.0, 3.0, 7.0, 8.0][..]));
        assert_eq!(amc.warnings.len(), 1, "{:?}", amc.warnings);
        assert_eq!(amc.warnings[0].line, Some(1));
        let message = &amc.warnings[0].message;
        assert!(
            message.contains("bone `knee` is missing from frame 1")
                && message.contains("3 frames lack some bone (2 bones in all)"),
            "{message}"
        );
    }

    #[test]
    fn unknown_bone() {
        let e = fail("1\nroot 1 2 3 4 5 6\n  lfemur 1 2 3\n");
        assert_eq!(e, ParseError::new(3, 3, "bone `lfemur` is not in the skeleton"));
    }

    #[test]
    fn wrong_number_of_values() {
        let e = fail("1\nroot 1 2 3 4 5 6\nhip 1 2\n");
        at(&e, 3, 8, "bone `hip` has 3 degrees of freedom; this line gives 2 values");
        let e = fail("1\nroot 1 2 3 4 5 6\nhip 1 2 3 4 5\n");
        at(&e, 3, 11, "bone `hip` has 3 degrees of freedom; this line gives 5 values");
        let e = fail("1\ntoe 1\n");
        at(&e, 2, 5, "bone `toe` has 0 degrees of freedom; this line gives 1 value");
        let e = fail("1\nknee 1 # two values\n");
        at(&e, 2, 8, "has 2 degrees of freedom; this line gives 1 value");
    }

    #[test]
    fn not_a_number() {
        let e = fail("1\nroot 1 2 3 4 5 6\nhip 1 x2 3\n");
        at(&e, 3, 7, "expected value 2 of bone `hip` (a number), found `x2`");
        let e = fail("1\nknee 1 2.5.5\n");
        at(&e, 2, 8, "found `2.5.5`");
        let e = fail("1\nknee 1,5 2\n");
        at(&e, 2, 6, "found `1,5`");
    }

    #[test]
    fn other_errors() {
        let e = fail(":DEGREES\nroot 1 2 3 4 5 6\n1\n");
        at(&e, 2, 1, "before the first frame number");
        let e = fail("1\nknee 1 2\nhip 1 2 3\nknee 3 4\n");
        at(&e, 4, 1, "bone `knee` appears twice in frame 1 (first at line 2)");
        let e = fail("99999999999999999999\nroot 1 2 3 4 5 6\n");
        at(&e, 1, 1, "out of range");
        let e = parse_amc(b"\x30\x26\xB2\x75\x8E\x66\xCF\x11\xA6\xD9\x00\xAA\x00\x62\xCE\x6C", &LAYOUT).unwrap_err();
        at(&e, 1, 1, "not an Acclaim motion file");
    }

    #[test]
    fn radians_no_header_and_zero_dof_bones() {
        let amc = parse(":RADIANS\n1\nroot 1 2 3 4 5 6\nhip 1 2 3\nknee 1 2\n");
        assert_eq!(amc.angle, AngleUnit::Radians);
        assert!(!amc.fully_specified);
        // No header at all; `toe` (no dofs) absent; blank lines and tabs.
        let amc =
            parse("\n\t\n7\nroot 1 2 3 4 5 6\n\nhip 1 2 3\nknee 1 2\n8\nroot 1 2 3 4 5 6\nhip 1 2 3\nknee 1 2\ntoe\n");
        assert_eq!((amc.frame_count, amc.first_frame_number, amc.angle), (2, Some(7), AngleUnit::Degrees));
        assert!(amc.warnings.is_empty(), "{:?}", amc.warnings);
        assert!(sniff_amc(b"# c\n\n1\nroot 0 0 0\n"));
        assert!(sniff_amc(b":radians\n"));
        assert!(!sniff_amc(b":root\n order TX\n"));
        assert!(!sniff_amc(b"HIERARCHY\n"));
        assert!(!sniff_amc(b"1\n2\n"));
        assert!(!sniff_amc(b""));
    }

    #[test]
    fn header_warnings_and_frame_number_gaps() {
        let amc =
            parse(":FULLY-SPECIFIED\n:SOMETHING else\n1\nroot 1 2 3 4 5 6\nhip 1 2 3\nknee 1 2\n3\n:DEGREES\n4\n9\n");
        assert_eq!(amc.frame_count, 4);
        let got: Vec<(Option<u32>, bool)> = amc
            .warnings
            .iter()
            .map(|w| (w.line, w.message.contains("not consecutive: expected 2, found 3 (2 jumps in all)")))
            .collect();
        assert_eq!(
            got,
            vec![(Some(2), false), (Some(8), false), (Some(7), false), (Some(7), true)],
            "{:?}",
            amc.warnings
        );
        assert!(amc.warnings[2].message.contains("bone `root` is missing from frame 3"));
        assert!(amc.warnings[0].message.contains("unknown header line `:SOMETHING`"));
        assert!(amc.warnings[1].message.contains("after the first frame"));
        let amc = parse(":FULLY-SPECIFIED\n");
        assert_eq!((amc.frame_count, amc.data.len(), amc.first_frame_number), (0, 0, None));
        assert_eq!(amc.warnings.len(), 1);
    }

    #[test]
    fn empty_layout_and_non_finite_values() {
        let amc = parse_amc(b"1\n2\n", &[]).unwrap();
        assert_eq!((amc.frame_count, amc.width, amc.data.len()), (2, 0, 0));
        let amc = parse("1\nroot nan inf -inf 0 0 0\nhip 1 2 3\nknee 1 2\n");
        assert!(amc.data[0].is_nan() && amc.data[1] == f32::INFINITY && amc.data[2] == f32::NEG_INFINITY);
        assert_eq!(amc.warnings.len(), 1);
        assert_eq!(amc.warnings[0].line, Some(2));
    }

    #[test]
    fn fast_number_path_matches_the_standard_parser() {
        let mut cases: Vec<String> = vec![
            "0",
            "-0",
            "+1",
            "1.",
            ".5",
            "-.5",
            "16777216",
            "16777217",
            "0.1",
            "0.2",
            "0.3",
            "9.37216",
            "-17.3198",
            "3.64024e-015",
            "-7.62852e-016",
            "1e3",
            "123456789.123456789",
            "0.0000001",
            "00000000000000000001.5",
            "1e-50",
            "3.4e38",
        ]
        .into_iter()
        .map(String::from)
        .collect();
        // A spread of values written with 0 to 9 decimals.
        let mut x: u64 = 0x9E37_79B9_7F4A_7C15;
        for _ in 0..20_000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            let v = (x % 2_000_000_000) as f64 / 10f64.powi((x >> 40) as i32 % 10) - 1000.0;
            cases.push(format!("{v:.*}", ((x >> 50) % 10) as usize));
        }
        for case in &cases {
            let want: f32 = case.parse().unwrap_or_else(|_| panic!("{case}"));
            let (got, used) = parse_value(case.as_bytes());
            assert_eq!(used, case.len(), "{case}");
            assert_eq!(got.to_bits(), want.to_bits(), "{case}: {got} vs {want}");
            // Followed by a separator, as in a file.
            assert_eq!(parse_value(format!("{case} 1").as_bytes()), (got, case.len()), "{case}");
        }
        assert_eq!(parse_value(b"x").1, 0);
        assert_eq!(parse_value(b"-").1, 0);
    }

    #[test]
    fn large_generated_file() {
        // 2,000 frames with the bones in changing order: checks every value.
        let mut src = String::from(":FULLY-SPECIFIED\n:DEGREES\n");
        for f in 0..2000u32 {
            src.push_str(&format!("{}\r\n", f + 1));
            let lines = [
                format!("root {f} 1.5 -2.25 3.64024e-015 {}.5 6", f % 7),
                format!("hip {}.25 -{f} 9", f % 3),
                format!("knee {f}.125 -0.5"),
            ];
            let order: &[usize] = if f % 5 == 0 { &[2, 0, 1] } else { &[0, 1, 2] };
            for &i in order {
                src.push_str(&lines[i]);
                src.push_str("\r\n");
            }
        }
        let amc = parse(&src);
        assert_eq!(amc.frame_count, 2000);
        for f in 0..2000u32 {
            let x = f as f32;
            let want = [
                x,
                1.5,
                -2.25,
                3.64024e-15,
                (f % 7) as f32 + 0.5,
                6.0,
                (f % 3) as f32 + 0.25,
                -x,
                9.0,
                x + 0.125,
                -0.5,
            ];
            assert_eq!(amc.frame(f as usize), Some(&want[..]), "frame {f}");
        }
    }

    /// A file with what the joining must get right: bones missing from some
    /// frames (the first among them), frame-number jumps, a header line and
    /// comments after the first frame, NaN, a zero-dof bone; `newline` between lines.
    fn awkward_file(frames: u32, newline: &str) -> String {
        let mut src = format!("# made by a test{newline}:FULLY-SPECIFIED{newline}:RADIANS{newline}");
        let mut x: u32 = 12345;
        for f in 0..frames {
            x = x.wrapping_mul(1_103_515_245).wrapping_add(12345);
            let number = if x % 29 == 0 { f + 3 } else { f + 1 };
            src.push_str(&format!("{number}{newline}"));
            if f == 40 {
                src.push_str(&format!(":DEGREES{newline}# a comment{newline}"));
            }
            if f == 0 || x % 7 != 1 {
                src.push_str(&format!("root {f} 1.5 -2.25 {} 0.5 6{newline}", if f == 77 { "nan" } else { "3" }));
            }
            if x % 5 != 2 {
                src.push_str(&format!("hip {}.25 -{f} 9{newline}", f % 3));
            }
            src.push_str(&format!("toe{newline}"));
            if f > 0 && x % 3 != 0 {
                src.push_str(&format!("knee {f}.125 -0.5{newline}"));
            }
        }
        src
    }

    #[test]
    fn pieces_read_like_one_go() {
        for newline in ["\n", "\r\n", "\r"] {
            let src = awkward_file(400, newline);
            assert!(cut_at_frames(src.as_bytes(), 8).len() >= 6, "the file is cut");
            let whole = parse_in_pieces(src.as_bytes(), &LAYOUT, 1).unwrap();
            assert_eq!(whole.frame_count, 400);
            assert_eq!(whole.warnings.len(), 4, "{:?}", whole.warnings);
            for pieces in 2..=9 {
                let joined = parse_in_pieces(src.as_bytes(), &LAYOUT, pieces).unwrap();
                let same_bits = joined.data.iter().zip(&whole.data).all(|(a, b)| a.to_bits() == b.to_bits());
                assert!(same_bits && joined.data.len() == whole.data.len(), "{pieces} pieces, {newline:?}");
                assert_eq!(joined.warnings, whole.warnings, "{pieces} pieces, {newline:?}");
                assert_eq!(
                    (joined.frame_count, joined.first_frame_number, joined.angle, joined.fully_specified),
                    (whole.frame_count, whole.first_frame_number, whole.angle, whole.fully_specified)
                );
            }
        }
    }

    #[test]
    fn pieces_report_the_first_error_at_its_line() {
        let good = awkward_file(300, "\n");
        let lines: Vec<&str> = good.lines().collect();
        for (at, bad) in [(5, "elbow 1 2 3"), (700, "hip 1 2"), (1001, "knee 1 x"), (lines.len() - 1, "root 1")] {
            let mut broken = lines.clone();
            broken[at] = bad;
            let src = broken.join("\n");
            let whole = parse_in_pieces(src.as_bytes(), &LAYOUT, 1).unwrap_err();
            for pieces in 2..=9 {
                let joined = parse_in_pieces(src.as_bytes(), &LAYOUT, pieces).unwrap_err();
                assert_eq!(
                    (joined.line, joined.column, &joined.message),
                    (whole.line, whole.column, &whole.message),
                    "{pieces} pieces"
                );
            }
            assert_eq!(whole.line as usize, at + 1);
        }
    }

    /// A random AMC-like file from `seed`: bones in any order, some missing,
    /// numbers of every form, frame-number jumps, comments and header lines,
    /// and now and then a line that is wrong.
    fn random_file(seed: u64) -> String {
        let mut x = seed | 1;
        let mut next = move |n: u64| {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            x % n.max(1)
        };
        let newline = ["\n", "\r\n", "\r"][next(3) as usize];
        let mut src = String::from(":FULLY-SPECIFIED");
        src.push_str(newline);
        let frames = 20 + next(150);
        let mut number = 1 + next(3);
        for _ in 0..frames {
            src.push_str(&format!("{number}{newline}"));
            number += if next(20) == 0 { 2 + next(5) } else { 1 };
            let mut bones: Vec<(&str, usize)> = LAYOUT.to_vec();
            for i in (1..bones.len()).rev() {
                bones.swap(i, next(i as u64 + 1) as usize);
            }
            for (name, count) in bones {
                if next(8) == 0 {
                    continue;
                }
                src.push_str(name);
                let values = if next(3000) == 0 { count + 1 } else { count };
                for _ in 0..values {
                    let v = match next(6) {
                        0 => format!("{}", next(200) as i64 - 100),
                        1 => format!("{:.4}", next(100_000) as f64 / 997.0 - 50.0),
                        2 => format!("{:.6}", next(1_000_000) as f64 / 7.0),
                        3 => format!("{:e}", next(1_000_000) as f64 / 3.0),
                        4 if next(50) == 0 => "nan".to_owned(),
                        _ => format!("-{}.{}", next(30), next(100_000)),
                    };
                    src.push_str(if next(4) == 0 { "\t" } else { " " });
                    src.push_str(&v);
                }
                src.push_str(newline);
            }
            match next(40) {
                0 => src.push_str(&format!("# a comment{newline}")),
                1 => src.push_str(&format!(":DEGREES{newline}")),
                2 if next(10) == 0 => src.push_str(&format!("elbow 1 2 3{newline}")),
                _ => {}
            }
        }
        src
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(48))]
        #[test]
        fn random_files_read_in_pieces_like_one_go(seed in proptest::prelude::any::<u64>()) {
            let src = random_file(seed);
            let whole = parse_in_pieces(src.as_bytes(), &LAYOUT, 1);
            for pieces in [2, 3, 5, 8] {
                let joined = parse_in_pieces(src.as_bytes(), &LAYOUT, pieces);
                match (&whole, &joined) {
                    (Ok(w), Ok(j)) => {
                        let bits = |a: &Amc| a.data.iter().map(|v| v.to_bits()).collect::<Vec<u32>>();
                        proptest::prop_assert_eq!(bits(w), bits(j));
                        proptest::prop_assert_eq!(&w.warnings, &j.warnings);
                        proptest::prop_assert_eq!((w.frame_count, w.first_frame_number), (j.frame_count, j.first_frame_number));
                    }
                    (Err(w), Err(j)) => proptest::prop_assert_eq!(w, j),
                    _ => proptest::prop_assert!(false, "one go {:?}, {} pieces {:?}", whole.as_ref().err(), pieces, joined.as_ref().err()),
                }
            }
        }
    }
}
