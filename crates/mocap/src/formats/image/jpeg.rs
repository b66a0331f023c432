//! JPEG (baseline and progressive) to RGBA8 through zune-jpeg, the decoder the
//! `image` crate itself uses. Called directly because `image`'s wrapper builds the
//! decoder for two reader types (one to read metadata, one to decode), which put
//! the whole decoder into the browser build twice.

use super::{MAX_SIDE, Rgba};
use crate::error::ParseError;
use zune_core::bytestream::ZCursor;
use zune_core::colorspace::ColorSpace;
use zune_core::options::DecoderOptions;
use zune_jpeg::JpegDecoder;
use zune_jpeg::errors::DecodeErrors;

/// Decodes a JPEG file to RGBA8. Grey images come out grey, images with an alpha
/// plane keep it, CMYK and YCCK are converted to RGB. A width or height past
/// [`MAX_SIDE`] is refused from the header, before the pixels are allocated;
/// broken data is an error, never a panic.
pub fn decode(bytes: &[u8]) -> Result<Rgba, ParseError> {
    let fail = |why: &str| ParseError::at_byte(0, format!("cannot decode this JPEG image: {why}"));
    let zune = |e: DecodeErrors| match e {
        DecodeErrors::IoErrors(_) | DecodeErrors::ExhaustedData => fail("the file ends before the image does"),
        e => fail(e.to_string().trim_matches('"')),
    };
    // The decoder's own size limits stay at what JPEG allows: [`MAX_SIDE`] is
    // checked below, with a message of our own, once the header is read.
    let jpeg_side = usize::from(u16::MAX);
    let options = DecoderOptions::default().set_strict_mode(false).set_max_width(jpeg_side).set_max_height(jpeg_side);
    let mut decoder = JpegDecoder::new_with_options(ZCursor::new(bytes), options);
    decoder.decode_headers().map_err(zune)?;
    let ((width, height), input) =
        decoder.dimensions().zip(decoder.input_colorspace()).ok_or_else(|| fail("no frame header"))?;
    let (width, height) = (u32::try_from(width).unwrap_or(u32::MAX), u32::try_from(height).unwrap_or(u32::MAX));
    if width > MAX_SIDE || height > MAX_SIDE {
        return Err(fail(&format!(
            "it is {width} × {height} pixels; images over {MAX_SIDE} pixels on a side are not read"
        )));
    }
    let output = output_colorspace(input);
    decoder.set_options(options.jpeg_set_out_colorspace(output));
    let pixels = decoder.decode().map_err(zune)?;
    let rgba =
        to_rgba(pixels, output.num_components()).ok_or_else(|| fail("the decoder gave an unexpected pixel layout"))?;
    if rgba.len() != width as usize * height as usize * 4 {
        return Err(fail("the decoded pixels do not fill the image"));
    }
    Ok(Rgba { width, height, pixels: rgba })
}

/// What to ask the decoder for, given the file's colour space: grey, RGB and RGBA
/// as they are (the decoder cannot turn RGB planes into RGBA itself), two planes
/// (which the decoder copies through as they are) as grey with alpha, everything
/// else (YCbCr, CMYK, YCCK) as RGB.
fn output_colorspace(input: ColorSpace) -> ColorSpace {
    match input {
        ColorSpace::Luma | ColorSpace::LumaA | ColorSpace::RGB | ColorSpace::RGBA => input,
        ColorSpace::MultiBand(n) if n.get() == 2 => ColorSpace::LumaA,
        _ => ColorSpace::RGB,
    }
}

/// `pixels` of `components` bytes each (1 grey, 2 grey + alpha, 3 RGB, 4 RGBA)
/// as RGBA8 (RGBA as it is); `None` for another count or a length that is not
/// whole pixels.
fn to_rgba(pixels: Vec<u8>, components: usize) -> Option<Vec<u8>> {
    if components == 0 || components > 4 || !pixels.len().is_multiple_of(components) {
        return None;
    }
    if components == 4 {
        return Some(pixels);
    }
    let mut out = Vec::with_capacity(pixels.len() / components * 4);
    for p in pixels.chunks_exact(components) {
        let rgba = match *p {
            [g] => [g, g, g, 255],
            [g, a] => [g, g, g, a],
            [r, g, b] => [r, g, b, 255],
            _ => return None,
        };
        out.extend_from_slice(&rgba);
    }
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_layout_becomes_rgba() {
        assert_eq!(to_rgba(vec![7, 9], 1), Some(vec![7, 7, 7, 255, 9, 9, 9, 255]));
        assert_eq!(to_rgba(vec![7, 9], 2), Some(vec![7, 7, 7, 9]));
        assert_eq!(to_rgba(vec![1, 2, 3], 3), Some(vec![1, 2, 3, 255]));
        assert_eq!(to_rgba(vec![1, 2, 3, 4], 4), Some(vec![1, 2, 3, 4]));
        assert_eq!(to_rgba(vec![1, 2, 3, 4], 3), None);
        assert_eq!(to_rgba(vec![1], 0), None);
        assert_eq!(to_rgba(vec![1; 5], 5), None);
    }

    #[test]
    fn colour_spaces_the_decoder_cannot_convert_are_asked_for_as_rgb() {
        assert_eq!(output_colorspace(ColorSpace::YCbCr), ColorSpace::RGB);
        assert_eq!(output_colorspace(ColorSpace::CMYK), ColorSpace::RGB);
        assert_eq!(output_colorspace(ColorSpace::YCCK), ColorSpace::RGB);
        assert_eq!(output_colorspace(ColorSpace::Luma), ColorSpace::Luma);
        assert_eq!(output_colorspace(ColorSpace::RGB), ColorSpace::RGB);
    }
}
