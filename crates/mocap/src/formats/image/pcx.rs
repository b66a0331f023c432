//! ZSoft PCX: a pure [`decode`] of the 8-bit paletted, run-length encoded images
//! Quake 2 uses for skins (and 24-bit three-plane images) to RGBA8.
//!
//! Layout: a 128-byte header (manufacturer 10, version, encoding 1 = RLE, bits per
//! pixel, window `xmin ymin xmax ymax`, …, planes at byte 65, bytes per line at 66),
//! then the scanlines, RLE-coded (a byte `0xC0 | n` repeats the next byte `n`
//! times), and for 8-bit images a 256-colour palette in the last 769 bytes
//! (`0x0C` then 768 bytes of RGB). Every size is checked against the bytes present
//! before anything is allocated; errors say `byte N: what`.

use super::Rgba;
use crate::error::ParseError;

/// Header length.
const HEADER: usize = 128;
/// Largest width or height accepted (the window is 16-bit anyway).
const MAX_SIDE: u32 = 1 << 15;

fn u16_at(bytes: &[u8], offset: usize) -> u16 {
    bytes.get(offset..offset + 2).map_or(0, |b| u16::from_le_bytes([b[0], b[1]]))
}

/// True when `bytes` look like PCX (manufacturer byte 10, RLE or raw encoding).
pub fn sniff(bytes: &[u8]) -> bool {
    bytes.len() >= HEADER && bytes.first() == Some(&10) && matches!(bytes.get(2), Some(0 | 1))
}

/// Decodes a PCX image to RGBA8 (alpha 255).
pub fn decode(bytes: &[u8]) -> Result<Rgba, ParseError> {
    if bytes.len() < HEADER {
        return Err(ParseError::at_byte(
            bytes.len(),
            format!("the file ends inside the 128-byte PCX header ({} bytes)", bytes.len()),
        ));
    }
    if bytes.first() != Some(&10) {
        return Err(ParseError::at_byte(0, "not a PCX image: the first byte is not 10 (ZSoft)"));
    }
    let encoding = bytes.get(2).copied().unwrap_or(0);
    if encoding > 1 {
        return Err(ParseError::at_byte(2, format!("unknown encoding {encoding} (expected 0 = raw or 1 = RLE)")));
    }
    let bits = bytes.get(3).copied().unwrap_or(0);
    let planes = bytes.get(65).copied().unwrap_or(0);
    if !(bits == 8 && (planes == 1 || planes == 3)) {
        return Err(ParseError::at_byte(
            3,
            format!(
                "{bits} bits per pixel in {planes} planes: only 8-bit paletted (1 plane) and 24-bit (3 planes) images are read"
            ),
        ));
    }
    let (xmin, ymin, xmax, ymax) = (u16_at(bytes, 4), u16_at(bytes, 6), u16_at(bytes, 8), u16_at(bytes, 10));
    if xmax < xmin || ymax < ymin {
        return Err(ParseError::at_byte(4, format!("the window {xmin},{ymin}–{xmax},{ymax} is empty")));
    }
    let width = u32::from(xmax - xmin) + 1;
    let height = u32::from(ymax - ymin) + 1;
    if width > MAX_SIDE || height > MAX_SIDE {
        return Err(ParseError::at_byte(8, format!("{width}×{height} pixels is larger than {MAX_SIDE} on a side")));
    }
    let line = usize::from(u16_at(bytes, 66));
    if line < width as usize {
        return Err(ParseError::at_byte(66, format!("{line} bytes per line cannot hold {width} pixels")));
    }
    let palette = if planes == 1 { Some(palette(bytes)?) } else { None };
    let data_end = if palette.is_some() { bytes.len() - 769 } else { bytes.len() };
    let stride = line * usize::from(planes);
    let needed =
        stride.checked_mul(height as usize).ok_or_else(|| ParseError::at_byte(66, "the image size overflows"))?;
    // RLE packs at most 63 bytes into 2, so the data bounds what can be claimed.
    let data = bytes.get(HEADER..data_end).unwrap_or(&[]);
    if needed > data.len().saturating_mul(32) {
        return Err(ParseError::at_byte(
            HEADER,
            format!("{width}×{height} pixels cannot come from {} bytes of image data", data.len()),
        ));
    }
    let scan = unpack(data, needed, encoding == 1)?;
    let mut pixels = Vec::with_capacity(width as usize * height as usize * 4);
    for y in 0..height as usize {
        let row = scan.get(y * stride..(y + 1) * stride).unwrap_or(&[]);
        for x in 0..width as usize {
            let rgb = match &palette {
                Some(p) => {
                    let i = usize::from(row.get(x).copied().unwrap_or(0)) * 3;
                    [p[i], p[i + 1], p[i + 2]]
                }
                None => [0, 1, 2].map(|c| row.get(c * line + x).copied().unwrap_or(0)),
            };
            pixels.extend([rgb[0], rgb[1], rgb[2], 255]);
        }
    }
    Ok(Rgba { width, height, pixels })
}

/// The 256-colour palette at the end of an 8-bit image.
fn palette(bytes: &[u8]) -> Result<[u8; 768], ParseError> {
    let start = bytes.len().checked_sub(769).filter(|&s| s >= HEADER);
    let Some(start) = start else {
        return Err(ParseError::at_byte(
            bytes.len(),
            "an 8-bit PCX image ends with a 769-byte palette, and this file is too short for one",
        ));
    };
    if bytes.get(start) != Some(&0x0C) {
        return Err(ParseError::at_byte(start, "no palette: an 8-bit PCX image ends with 0x0C and 768 bytes of RGB"));
    }
    let mut p = [0u8; 768];
    p.copy_from_slice(bytes.get(start + 1..).unwrap_or(&[0; 768]).get(..768).unwrap_or(&[0; 768]));
    Ok(p)
}

/// Unpacks `needed` bytes of scanlines from `data` (RLE or raw). Data that ends
/// early is an error at the byte where it ended.
fn unpack(data: &[u8], needed: usize, rle: bool) -> Result<Vec<u8>, ParseError> {
    if !rle {
        return data.get(..needed).map(<[u8]>::to_vec).ok_or_else(|| {
            ParseError::at_byte(
                HEADER + data.len(),
                format!("raw image data ends after {} of {needed} bytes", data.len()),
            )
        });
    }
    let mut out = Vec::with_capacity(needed);
    let mut i = 0;
    while out.len() < needed {
        let Some(&b) = data.get(i) else {
            return Err(ParseError::at_byte(
                HEADER + i,
                format!("the image data ends after {} of {needed} bytes", out.len()),
            ));
        };
        i += 1;
        if b & 0xC0 == 0xC0 {
            let Some(&value) = data.get(i) else {
                return Err(ParseError::at_byte(HEADER + i, "the image data ends inside a run"));
            };
            i += 1;
            let count = usize::from(b & 0x3F).min(needed - out.len());
            out.extend(std::iter::repeat_n(value, count));
        } else {
            out.push(b);
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A `w`×`h` 8-bit image from `data` (already RLE-coded) and a grey palette.
    fn pcx(w: u16, h: u16, line: u16, data: &[u8]) -> Vec<u8> {
        let mut b = vec![0u8; HEADER];
        b[0] = 10;
        b[1] = 5;
        b[2] = 1;
        b[3] = 8;
        b[8..10].copy_from_slice(&(w - 1).to_le_bytes());
        b[10..12].copy_from_slice(&(h - 1).to_le_bytes());
        b[65] = 1;
        b[66..68].copy_from_slice(&line.to_le_bytes());
        b.extend_from_slice(data);
        b.push(0x0C);
        b.extend((0..=255u8).flat_map(|i| [i, i, 255 - i]));
        b
    }

    #[test]
    fn runs_literals_and_the_palette() {
        // 3×2, 4 bytes per line: row 0 = run of 4 × 7; row 1 = literals 1 2 3 and a pad 0.
        let img = decode(&pcx(3, 2, 4, &[0xC4, 7, 1, 2, 3, 0])).unwrap();
        assert_eq!((img.width, img.height), (3, 2));
        assert_eq!(img.pixel(2, 0), Some([7, 7, 248, 255]));
        assert_eq!(img.pixel(1, 1), Some([2, 2, 253, 255]));
        assert_eq!(img.pixel(3, 0), None);
        // A literal byte of 0xC0 or more must be coded as a run of one.
        let img = decode(&pcx(1, 1, 1, &[0xC1, 0xF0])).unwrap();
        assert_eq!(img.pixel(0, 0), Some([0xF0, 0xF0, 0x0F, 255]));
    }

    #[test]
    fn malformed_images_say_where() {
        let e = decode(b"short").unwrap_err();
        assert!(e.to_string().starts_with("byte 5: the file ends inside"), "{e}");
        let mut wrong = pcx(3, 2, 4, &[0xC4, 7, 1, 2, 3, 0]);
        wrong[0] = 11;
        assert!(decode(&wrong).unwrap_err().to_string().starts_with("byte 0: not a PCX image"));
        let e = decode(&pcx(3, 2, 4, &[0xC4, 7, 1])).unwrap_err();
        assert!(e.message.contains("ends after 5 of 8 bytes"), "{e}");
        let e = decode(&pcx(3, 2, 2, &[0xC4, 7])).unwrap_err();
        assert!(e.message.contains("2 bytes per line cannot hold 3 pixels"), "{e}");
        let mut no_palette = pcx(3, 2, 4, &[0xC4, 7, 1, 2, 3, 0]);
        let at = no_palette.len() - 769;
        no_palette[at] = 0;
        assert!(decode(&no_palette).unwrap_err().message.contains("no palette"));
        // A huge window over a few bytes allocates nothing and says so.
        let e = decode(&pcx(30000, 30000, 30000, &[0xC1, 0])).unwrap_err();
        assert!(e.message.contains("cannot come from"), "{e}");
    }

    #[test]
    fn no_truncation_or_byte_change_panics() {
        let good = pcx(3, 2, 4, &[0xC4, 7, 1, 2, 3, 0]);
        for cut in 0..good.len() {
            let _ = decode(&good[..cut]);
        }
        for i in 0..HEADER + 8 {
            for v in [0u8, 1, 3, 8, 0x0C, 0xC0, 0xFF] {
                let mut b = good.clone();
                b[i] = v;
                let _ = decode(&b);
            }
        }
    }
}
