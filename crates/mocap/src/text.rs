//! Text helpers every reader and writer shares: error-message quoting, name
//! decoding and shortest round-trip float formatting.

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
