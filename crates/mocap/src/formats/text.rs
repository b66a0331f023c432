//! Text helpers every reader and writer shares: tokens with their position,
//! error-message quoting, name decoding and shortest round-trip float formatting.

/// One whitespace-separated token of a text file.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Token<'a> {
    /// The token's bytes.
    pub text: &'a [u8],
    /// Byte offset of the token in the file.
    pub start: usize,
    /// 1-based line.
    pub line: u32,
    /// 1-based byte column.
    pub column: u32,
}

impl Token<'_> {
    /// Case-insensitive keyword comparison.
    pub fn is(&self, keyword: &str) -> bool {
        self.text.eq_ignore_ascii_case(keyword.as_bytes())
    }

    /// The token as text for messages, shortened and with odd bytes escaped.
    pub fn show(&self) -> String {
        show_bytes(self.text)
    }
}

/// True for the bytes that separate tokens on one line: space, tab, vertical tab,
/// form feed, and the NUL and Ctrl-Z (DOS end-of-file) padding some old files end with.
#[inline]
pub(crate) const fn is_blank(b: u8) -> bool {
    matches!(b, b' ' | b'\t' | 0x0b | 0x0c | 0x00 | 0x1a)
}

/// True for a byte that ends a line (LF or CR).
#[inline]
pub(crate) const fn is_eol(b: u8) -> bool {
    b == b'\n' || b == b'\r'
}

/// The length of a UTF-8 byte-order mark at the start of `bytes` (0 or 3).
pub(crate) fn bom_len(bytes: &[u8]) -> usize {
    if bytes.starts_with(&[0xEF, 0xBB, 0xBF]) { 3 } else { 0 }
}

/// The length of the line break at `at`: 1 for LF or a lone CR, 2 for CRLF, 0 when
/// there is none.
pub(crate) fn line_break_len(src: &[u8], at: usize) -> usize {
    match src.get(at) {
        Some(b'\n') => 1,
        Some(b'\r') if src.get(at + 1) == Some(&b'\n') => 2,
        Some(b'\r') => 1,
        _ => 0,
    }
}

/// Where the line holding `at` ends: the position of its line break, or the end.
pub(crate) fn line_end(src: &[u8], at: usize) -> usize {
    let rest = src.get(at..).unwrap_or(&[]);
    at + memchr::memchr2(b'\n', b'\r', rest).unwrap_or(rest.len())
}

/// Bytes as text for an error message: at most 40 bytes, control characters escaped.
pub(crate) fn show_bytes(bytes: &[u8]) -> String {
    let text = String::from_utf8_lossy(bytes.get(..40).unwrap_or(bytes));
    let mut out: String = text.chars().flat_map(|c| c.escape_debug()).collect();
    if bytes.len() > 40 {
        out.push('…');
    }
    out
}

/// Decodes a name: UTF-8 when valid, otherwise Latin-1 (every byte is a character).
pub(crate) fn decode_name(bytes: &[u8]) -> String {
    match std::str::from_utf8(bytes) {
        Ok(s) => s.to_owned(),
        Err(_) => bytes.iter().map(|&b| char::from(b)).collect(),
    }
}

/// Appends a float in its shortest form that reads back to the same bits
/// (`1.0` is written `1`; non-finite values as `nan`, `inf`, `-inf`).
pub(crate) fn push_f32(out: &mut String, buffer: &mut ryu::Buffer, v: f32) {
    if v.is_finite() {
        let s = buffer.format_finite(v);
        out.push_str(s.strip_suffix(".0").unwrap_or(s));
    } else if v.is_nan() {
        out.push_str("nan");
    } else if v > 0.0 {
        out.push_str("inf");
    } else {
        out.push_str("-inf");
    }
}
