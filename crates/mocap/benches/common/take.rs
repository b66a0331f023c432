//! The long take the benches read: a BVH's header with its motion rows repeated
//! to a frame count (the 27 MB, 36,000-frame input from CMU's 01_01).

/// `src`'s header with its rows repeated to `frames` rows.
pub fn long_take(src: &[u8], frames: usize) -> Vec<u8> {
    let text = std::str::from_utf8(src).expect("utf-8");
    let start = text.find("Frame Time").expect("Frame Time line");
    let rows_at = start + text[start..].find('\n').expect("newline") + 1;
    let rows: Vec<&str> = text[rows_at..].lines().filter(|l| !l.trim().is_empty()).collect();
    let header = text[..rows_at].replace(&format!("Frames: {}", rows.len()), &format!("Frames: {frames}"));
    let mut out = header.into_bytes();
    for i in 0..frames {
        out.extend_from_slice(rows[i % rows.len()].as_bytes());
        out.push(b'\n');
    }
    out
}
