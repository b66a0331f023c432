//! Lines and whitespace-separated words of a BVA file, with line numbers and byte
//! columns, plus the keyword matcher for the segment header lines.

pub(crate) use crate::formats::text::{decode_name as decode, is_blank, show_bytes};

/// One line of the file, without its line break.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Line<'a> {
    /// 1-based line number.
    pub number: u32,
    /// The line's bytes (no line break; on line 1, no byte-order mark).
    pub text: &'a [u8],
    /// Bytes on this line before `text` (the byte-order mark on line 1, else 0).
    pub column_offset: u32,
}

/// One word of a line.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Word<'a> {
    /// The word's bytes.
    pub text: &'a [u8],
    /// 1-based byte column.
    pub column: u32,
}

impl<'a> Line<'a> {
    /// The 1-based column of byte `index` of `text`.
    pub fn column(&self, index: usize) -> u32 {
        u32::try_from(index.saturating_add(1)).unwrap_or(u32::MAX).saturating_add(self.column_offset)
    }

    /// Column just after the last non-blank byte (where a missing word was expected).
    pub fn end_column(&self) -> u32 {
        let end = self.text.iter().rposition(|&b| !is_blank(b)).map_or(0, |i| i + 1);
        self.column(end)
    }

    /// True when the line holds nothing but blanks.
    pub fn is_blank(&self) -> bool {
        self.text.iter().all(|&b| is_blank(b))
    }

    /// The words of the line from byte `from` on.
    pub fn words_from(&self, from: usize) -> Words<'a> {
        Words { line: *self, pos: from }
    }

    /// The words of the whole line.
    pub fn words(&self) -> Words<'a> {
        self.words_from(0)
    }

    /// The rest of the line from byte `from`, with blanks trimmed on both sides, and
    /// the column where it starts.
    pub fn rest(&self, from: usize) -> (&'a [u8], u32) {
        let tail = self.text.get(from..).unwrap_or(&[]);
        let start = tail.iter().position(|&b| !is_blank(b)).unwrap_or(tail.len());
        let end = tail.iter().rposition(|&b| !is_blank(b)).map_or(start, |i| i + 1);
        (tail.get(start..end).unwrap_or(&[]), self.column(from.saturating_add(start)))
    }
}

/// Iterator over the words of a line.
pub(crate) struct Words<'a> {
    line: Line<'a>,
    pos: usize,
}

impl<'a> Iterator for Words<'a> {
    type Item = Word<'a>;

    fn next(&mut self) -> Option<Word<'a>> {
        let text = self.line.text;
        while text.get(self.pos).is_some_and(|&b| is_blank(b)) {
            self.pos += 1;
        }
        let start = self.pos;
        text.get(start)?;
        while text.get(self.pos).is_some_and(|&b| !is_blank(b)) {
            self.pos += 1;
        }
        Some(Word { text: text.get(start..self.pos).unwrap_or(&[]), column: self.line.column(start) })
    }
}

/// Splits a file into lines: LF, CRLF and lone CR all end a line; a UTF-8
/// byte-order mark at the start is skipped (but counted in line 1's columns).
#[derive(Clone)]
pub(crate) struct Lines<'a> {
    src: &'a [u8],
    pos: usize,
    number: u32,
    column_offset: u32,
}

impl<'a> Lines<'a> {
    /// Starts at the beginning of `src`.
    pub fn new(src: &'a [u8]) -> Lines<'a> {
        let bom = crate::formats::text::bom_len(src);
        Lines { src, pos: bom, number: 1, column_offset: bom as u32 }
    }

    /// The next line without consuming it.
    pub fn peek(&self) -> Option<Line<'a>> {
        self.clone().next()
    }
}

impl<'a> Iterator for Lines<'a> {
    type Item = Line<'a>;

    fn next(&mut self) -> Option<Line<'a>> {
        let rest = self.src.get(self.pos..)?;
        if rest.is_empty() {
            return None;
        }
        let (text, used) = match memchr::memchr2(b'\n', b'\r', rest) {
            Some(end) => {
                let crlf = rest.get(end) == Some(&b'\r') && rest.get(end + 1) == Some(&b'\n');
                (rest.get(..end).unwrap_or(&[]), end + if crlf { 2 } else { 1 })
            }
            None => (rest, rest.len()),
        };
        let line = Line { number: self.number, text, column_offset: self.column_offset };
        self.pos += used;
        self.number = self.number.saturating_add(1);
        self.column_offset = 0;
        Some(line)
    }
}

/// Matches a header keyword at the start of a line: `words` in any case, with
/// optional blanks between them, then an optional `:` (glued or separated by
/// blanks). The keyword must end at a blank, a colon or the line end. Returns the
/// byte index just after the keyword (and colon) when it matches.
pub(crate) fn keyword(text: &[u8], words: &[&str]) -> Option<usize> {
    let skip_blanks = |mut i: usize| {
        while text.get(i).is_some_and(|&b| is_blank(b)) {
            i += 1;
        }
        i
    };
    let mut i = skip_blanks(0);
    for (n, word) in words.iter().enumerate() {
        if n > 0 {
            i = skip_blanks(i);
        }
        let end = i.checked_add(word.len())?;
        if !text.get(i..end)?.eq_ignore_ascii_case(word.as_bytes()) {
            return None;
        }
        i = end;
    }
    match text.get(i) {
        None => return Some(i),
        Some(&b) if b == b':' || is_blank(b) => {}
        Some(_) => return None,
    }
    let after = skip_blanks(i);
    Some(if text.get(after) == Some(&b':') { after + 1 } else { i })
}

/// Parses a whole word as an f32 (exponents, `+`, `-0`, `nan`, `inf` accepted).
pub(crate) fn parse_f32(text: &[u8]) -> Option<f32> {
    match fast_float2::parse_partial::<f32, _>(text) {
        Ok((v, used)) if used == text.len() && used > 0 => Some(v),
        _ => None,
    }
}

/// Parses a whole word as an f64.
pub(crate) fn parse_f64(text: &[u8]) -> Option<f64> {
    match fast_float2::parse_partial::<f64, _>(text) {
        Ok((v, used)) if used == text.len() && used > 0 => Some(v),
        _ => None,
    }
}
