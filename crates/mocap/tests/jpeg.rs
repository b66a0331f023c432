//! The JPEG skin reader (`mocap::formats::image::jpeg`), on files made here with the
//! `image` crate's encoder: colour and grey pictures come back as RGBA8 close to
//! what was encoded, and damaged or oversized files are errors, never panics.

use image::ExtendedColorType;
use image::codecs::jpeg::JpegEncoder;
use mocap::formats::image::{MAX_SIDE, Rgba, decode_any};

/// A `width × height` picture with red across, green down and blue from both.
fn gradient(width: u32, height: u32) -> Vec<u8> {
    let mut rgb = Vec::new();
    for y in 0..height {
        for x in 0..width {
            let (r, g) = ((x * 255 / (width - 1)) as u8, (y * 255 / (height - 1)) as u8);
            rgb.extend_from_slice(&[r, g, ((u32::from(r) + u32::from(g)) / 2) as u8]);
        }
    }
    rgb
}

fn encode(pixels: &[u8], width: u32, height: u32, color: ExtendedColorType) -> Vec<u8> {
    let mut out = Vec::new();
    JpegEncoder::new_with_quality(&mut out, 100).encode(pixels, width, height, color).expect("encodes");
    out
}

/// The largest difference of any channel between `decoded` and `expected` (RGB).
fn worst_difference(decoded: &Rgba, expected: &[u8]) -> u8 {
    decoded
        .pixels
        .chunks_exact(4)
        .zip(expected.chunks_exact(3))
        .flat_map(|(d, e)| (0..3).map(move |c| d[c].abs_diff(e[c])))
        .max()
        .unwrap_or(u8::MAX)
}

#[test]
fn a_colour_jpeg_decodes_to_rgba_close_to_what_was_encoded() {
    let (width, height) = (37, 23);
    let rgb = gradient(width, height);
    let decoded = decode_any("skin.jpg", &encode(&rgb, width, height, ExtendedColorType::Rgb8)).expect("decodes");
    assert_eq!((decoded.width, decoded.height), (width, height));
    assert_eq!(decoded.pixels.len(), (width * height * 4) as usize);
    assert!(decoded.pixels.chunks_exact(4).all(|p| p[3] == 255), "opaque");
    let worst = worst_difference(&decoded, &rgb);
    assert!(worst <= 16, "a channel is {worst} off");
    // The picture is not flat: the corners keep their colours.
    assert!(decoded.pixel(0, 0).is_some_and(|p| p[0] < 20 && p[1] < 20));
    assert!(decoded.pixel(width - 1, height - 1).is_some_and(|p| p[0] > 235 && p[1] > 235));
}

#[test]
fn a_grey_jpeg_decodes_to_equal_channels() {
    let (width, height) = (16, 9);
    let grey: Vec<u8> = (0..width * height).map(|i| (i * 255 / (width * height - 1)) as u8).collect();
    let decoded = decode_any("skin.jpeg", &encode(&grey, width, height, ExtendedColorType::L8)).expect("decodes");
    assert_eq!((decoded.width, decoded.height), (width, height));
    for (p, g) in decoded.pixels.chunks_exact(4).zip(&grey) {
        assert!(p[0] == p[1] && p[1] == p[2] && p[3] == 255, "{p:?}");
        assert!(p[0].abs_diff(*g) <= 12, "{} for {g}", p[0]);
    }
}

#[test]
fn a_damaged_jpeg_is_an_error_or_a_picture_never_a_panic() {
    let (width, height) = (24, 24);
    let file = encode(&gradient(width, height), width, height, ExtendedColorType::Rgb8);
    for end in (0..file.len()).step_by(7) {
        match decode_any("skin.jpg", &file[..end]) {
            Ok(image) => assert_eq!(image.pixels.len(), (image.width * image.height * 4) as usize),
            Err(e) => assert!(e.to_string().contains("JPEG"), "{e}"),
        }
    }
    let cut = decode_any("skin.jpg", &file[..file.len() / 3]).map(|_| String::new()).unwrap_or_else(|e| e.to_string());
    let header_only = decode_any("skin.jpg", &file[..40]).expect_err("no frame header yet");
    assert_eq!(
        header_only.to_string(),
        "byte 0: cannot decode this JPEG image: the file ends before the image does",
        "(a third of it: {cut})"
    );
    // Flipped bytes throughout the entropy-coded data and the tables.
    for at in (2..file.len()).step_by(5) {
        let mut bad = file.clone();
        bad[at] ^= 0x5A;
        if let Ok(image) = decode_any("skin.jpg", &bad) {
            assert_eq!(image.pixels.len(), (image.width * image.height * 4) as usize);
        }
    }
}

#[test]
fn a_jpeg_claiming_a_huge_size_is_refused_from_its_header() {
    let file = encode(&gradient(8, 8), 8, 8, ExtendedColorType::Rgb8);
    // The frame header (SOF0: FF C0, length, precision, height, width).
    let sof = file.windows(2).position(|w| w == [0xFF, 0xC0]).expect("a baseline frame header");
    let mut huge = file.clone();
    let side = (MAX_SIDE + 1) as u16;
    huge[sof + 5..sof + 7].copy_from_slice(&side.to_be_bytes());
    huge[sof + 7..sof + 9].copy_from_slice(&side.to_be_bytes());
    let error = decode_any("huge.jpg", &huge).expect_err("past MAX_SIDE");
    assert_eq!(
        error.to_string(),
        format!(
            "byte 0: cannot decode this JPEG image: it is {side} × {side} pixels; images over {MAX_SIDE} pixels on a side are not read"
        )
    );
    // At the limit itself the header is accepted (the missing rows decode as
    // blank: the decoder is lenient, as for any truncated file).
    let mut at_limit = file;
    at_limit[sof + 5..sof + 7].copy_from_slice(&(MAX_SIDE as u16).to_be_bytes());
    let tall = decode_any("tall.jpg", &at_limit).expect("a picture 8 wide and MAX_SIDE tall");
    assert_eq!((tall.width, tall.height), (8, MAX_SIDE));
}
