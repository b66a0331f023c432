//! Shared text helpers for the Acclaim readers: a token cursor with line and column,
//! number parsing, name decoding and binary-data detection.

pub(crate) use crate::formats::text::{
    Token, bom_len, decode_name, is_blank, is_eol, line_break_len, line_end, show_bytes,
};

/// The 16-byte header GUID of a Windows Media (ASF container) file.
const WINDOWS_MEDIA: [u8; 16] =
    [0x30, 0x26, 0xB2, 0x75, 0x8E, 0x66, 0xCF, 0x11, 0xA6, 0xD9, 0x00, 0xAA, 0x00, 0x62, 0xCE, 0x6C];

/// What kind of binary file `bytes` is, when they are not text: looks at the first
/// KiB only. Text may hold a few bytes that are not UTF-8 (Latin-1 names); NUL
/// bytes, or more than 1/8 control or invalid bytes, make it binary.
pub(crate) fn binary_kind(bytes: &[u8]) -> Option<&'static str> {
    if bytes.starts_with(&WINDOWS_MEDIA) {
        return Some("this looks like a Windows Media (.asf) video file");
    }
    let head = bytes.get(..1024).unwrap_or(bytes);
    if head.contains(&0) {
        return Some("binary data");
    }
    let control = head
        .iter()
        .filter(|&&b| (b < 0x20 && !matches!(b, b'\t' | b'\n' | b'\r' | 0x0b | 0x0c | 0x1a)) || b == 0x7f)
        .count();
    let mut invalid = 0usize;
    let mut rest = head;
    while let Err(e) = std::str::from_utf8(rest) {
        let Some(len) = e.error_len() else { break }; // cut in the middle of a character at the 1 KiB mark
        invalid += len;
        rest = rest.get(e.valid_up_to() + len..).unwrap_or(&[]);
    }
    if (control + invalid) * 8 > head.len() {
        return Some("binary data");
    }
    None
}

/// Parses a whole token as an `f32` (exponents, leading `+`, `inf` and `nan` accepted:
/// callers decide which values they allow).
pub(crate) fn parse_f32(text: &[u8]) -> Option<f32> {
    match fast_float2::parse_partial::<f32, _>(text) {
        Ok((v, used)) if used == text.len() => Some(v),
        _ => None,
    }
}

/// Parses a whole token as an integer with an optional sign.
pub(crate) fn parse_i64(text: &[u8]) -> Option<i64> {
    std::str::from_utf8(text).ok()?.parse().ok()
}

/// Walks a text file token by token, keeping line and column. Line breaks are LF,
/// CRLF or a lone CR; a token starting with `#` starts a comment that runs to the end
/// of its line; `(` and `)` are tokens of their own.
#[derive(Clone)]
pub(crate) struct Cursor<'a> {
    src: &'a [u8],
    pos: usize,
    line: u32,
    line_start: usize,
}

impl<'a> Cursor<'a> {
    /// Starts at the beginning, skipping a UTF-8 byte-order mark.
    pub fn new(src: &'a [u8]) -> Cursor<'a> {
        let pos = bom_len(src);
        Cursor { src, pos, line: 1, line_start: pos }
    }

    /// Current line and column (1-based).
    pub fn position(&self) -> (u32, u32) {
        (self.line, self.column_at(self.pos))
    }

    fn column_at(&self, pos: usize) -> u32 {
        u32::try_from(pos.saturating_sub(self.line_start) + 1).unwrap_or(u32::MAX)
    }

    /// Consumes one line break at the current position, if there is one.
    fn line_break(&mut self) -> bool {
        match line_break_len(self.src, self.pos) {
            0 => return false,
            n => self.pos += n,
        }
        self.line = self.line.saturating_add(1);
        self.line_start = self.pos;
        true
    }

    /// Moves to the end of the current line (not past its line break).
    fn skip_to_eol(&mut self) {
        self.pos = line_end(self.src, self.pos);
    }

    /// Skips blanks, line breaks and comments.
    fn skip_space(&mut self) {
        while let Some(&b) = self.src.get(self.pos) {
            if is_eol(b) {
                self.line_break();
            } else if is_blank(b) {
                self.pos += 1;
            } else if b == b'#' {
                self.skip_to_eol();
            } else {
                break;
            }
        }
    }

    /// The next token, or `None` at the end of the input.
    pub fn next_token(&mut self) -> Option<Token<'a>> {
        self.skip_space();
        let start = self.pos;
        let first = *self.src.get(start)?;
        let mut end = start + 1;
        if first != b'(' && first != b')' {
            while let Some(&b) = self.src.get(end) {
                if is_blank(b) || is_eol(b) || b == b'(' || b == b')' {
                    break;
                }
                end += 1;
            }
        }
        self.pos = end;
        Some(Token {
            text: self.src.get(start..end).unwrap_or(&[]),
            start,
            line: self.line,
            column: self.column_at(start),
        })
    }

    /// The next token without consuming it.
    pub fn peek_token(&self) -> Option<Token<'a>> {
        self.clone().next_token()
    }

    /// The next token when it is on line `line`; otherwise nothing is consumed.
    pub fn next_on_line(&mut self, line: u32) -> Option<Token<'a>> {
        let mut probe = self.clone();
        let token = probe.next_token()?;
        if token.line != line {
            return None;
        }
        *self = probe;
        Some(token)
    }

    /// The raw rest of the current line (without its line break), consuming the break.
    pub fn take_line(&mut self) -> &'a [u8] {
        let start = self.pos;
        self.skip_to_eol();
        let text = self.src.get(start..self.pos).unwrap_or(&[]);
        self.line_break();
        text
    }

    /// The first byte of the current line that is not blank, without consuming
    /// anything; `None` at the end of the input or on an empty line.
    pub fn first_on_line(&self) -> Option<u8> {
        self.src.get(self.pos..)?.iter().copied().find(|&b| !is_blank(b)).filter(|&b| !is_eol(b))
    }

    /// True at the end of the input.
    pub fn at_end(&self) -> bool {
        self.pos >= self.src.len()
    }
}

/// Trims blanks from both ends of a line.
pub(crate) fn trim_blanks(mut s: &[u8]) -> &[u8] {
    while let [first, rest @ ..] = s {
        if !is_blank(*first) {
            break;
        }
        s = rest;
    }
    while let [rest @ .., last] = s {
        if !is_blank(*last) {
            break;
        }
        s = rest;
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cursor_tracks_lines_and_columns_with_any_line_ending() {
        let mut c = Cursor::new(b"\xEF\xBB\xBFa b\r\n c # x y\r(d)\n\te");
        let mut got = Vec::new();
        while let Some(t) = c.next_token() {
            got.push((String::from_utf8_lossy(t.text).into_owned(), t.line, t.column));
        }
        let want: Vec<(String, u32, u32)> =
            [("a", 1, 1), ("b", 1, 3), ("c", 2, 2), ("(", 3, 1), ("d", 3, 2), (")", 3, 3), ("e", 4, 2)]
                .iter()
                .map(|&(s, l, c)| (s.to_owned(), l, c))
                .collect();
        assert_eq!(got, want);
    }

    #[test]
    fn binary_detection() {
        let mut wmv = WINDOWS_MEDIA.to_vec();
        wmv.extend_from_slice(&[1, 2, 3]);
        assert!(binary_kind(&wmv).is_some_and(|k| k.contains("Windows Media")));
        assert_eq!(binary_kind(b"abc\0def"), Some("binary data"));
        assert_eq!(binary_kind(&[0xff; 100]), Some("binary data"));
        assert_eq!(binary_kind(b":name caf\xe9\nmore text here that is plain"), None);
        assert_eq!(binary_kind(b""), None);
    }

    #[test]
    fn numbers() {
        assert_eq!(parse_f32(b"3.64024e-015"), Some(3.64024e-15));
        assert_eq!(parse_f32(b"-inf"), Some(f32::NEG_INFINITY));
        assert_eq!(parse_f32(b"1.5x"), None);
        assert_eq!(parse_i64(b"-12"), Some(-12));
        assert_eq!(trim_blanks(b" \ta b\t "), b"a b");
    }
}
