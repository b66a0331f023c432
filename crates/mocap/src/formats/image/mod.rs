//! Images the formats refer to (model skins): decoded to RGBA8 in memory by
//! [`decode`]. [`pcx`] reads ZSoft PCX, the Quake 2 skin format, which no well-kept
//! image crate reads; [`jpeg`] calls zune-jpeg; BMP and PNG come from the `image`
//! crate. The format is
//! found from the content ([`ImageFormat::detect`]), never from the extension alone.

pub mod jpeg;
pub mod pcx;

use crate::error::ParseError;

/// The decoded image: the model's own type (a skin's pixels), which every decoder here makes.
pub use crate::model::mesh::Rgba;

/// Largest width or height of a decoded image; larger ones are refused before
/// anything is allocated (skins are at most a few thousand pixels wide).
pub const MAX_SIDE: u32 = 8192;

/// The image formats [`decode`] reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ImageFormat {
    /// ZSoft PCX (8-bit paletted or 24-bit, RLE).
    Pcx,
    /// Windows bitmap.
    Bmp,
    /// Portable Network Graphics.
    Png,
    /// JPEG (baseline and progressive).
    Jpeg,
    /// Truevision TGA (what Quake 2 engines load when a skin's `.pcx` is missing).
    Tga,
}

impl ImageFormat {
    /// File extensions of images (for file pickers), without the dot.
    pub const EXTENSIONS: [&'static str; 6] = ["pcx", "bmp", "png", "jpg", "jpeg", "tga"];

    /// The format of `bytes` from their first bytes (signatures), if an image.
    pub fn detect(bytes: &[u8]) -> Option<ImageFormat> {
        if bytes.starts_with(b"\x89PNG\r\n\x1a\n") {
            Some(ImageFormat::Png)
        } else if bytes.starts_with(&[0xFF, 0xD8, 0xFF]) {
            Some(ImageFormat::Jpeg)
        } else if bytes.starts_with(b"BM") && bytes.len() >= 26 {
            Some(ImageFormat::Bmp)
        } else if pcx::sniff(bytes) {
            Some(ImageFormat::Pcx)
        } else if sniff_tga(bytes) {
            Some(ImageFormat::Tga)
        } else {
            None
        }
    }

    /// The format a file name's extension names (case-insensitive), if an image's.
    pub fn from_extension(name: &str) -> Option<ImageFormat> {
        let ext = name.rsplit_once('.')?.1.to_ascii_lowercase();
        match ext.as_str() {
            "pcx" => Some(ImageFormat::Pcx),
            "bmp" => Some(ImageFormat::Bmp),
            "png" => Some(ImageFormat::Png),
            "jpg" | "jpeg" => Some(ImageFormat::Jpeg),
            "tga" => Some(ImageFormat::Tga),
            _ => None,
        }
    }

    /// The format's usual name.
    pub fn name(self) -> &'static str {
        match self {
            ImageFormat::Pcx => "PCX",
            ImageFormat::Bmp => "BMP",
            ImageFormat::Png => "PNG",
            ImageFormat::Jpeg => "JPEG",
            ImageFormat::Tga => "TGA",
        }
    }
}

/// Decodes an image in `format` to RGBA8. Sizes past [`MAX_SIDE`] and broken data
/// are errors (`byte N: …` where the decoder tells the offset), never a panic or a
/// huge allocation.
pub fn decode(format: ImageFormat, bytes: &[u8]) -> Result<Rgba, ParseError> {
    let kind = match format {
        ImageFormat::Pcx => return pcx::decode(bytes),
        ImageFormat::Bmp => ::image::ImageFormat::Bmp,
        ImageFormat::Png => ::image::ImageFormat::Png,
        ImageFormat::Jpeg => return jpeg::decode(bytes),
        ImageFormat::Tga => ::image::ImageFormat::Tga,
    };
    let mut reader = ::image::ImageReader::with_format(std::io::Cursor::new(bytes), kind);
    let mut limits = ::image::Limits::default();
    limits.max_image_width = Some(MAX_SIDE);
    limits.max_image_height = Some(MAX_SIDE);
    limits.max_alloc = Some(u64::from(MAX_SIDE) * u64::from(MAX_SIDE) * 4);
    reader.limits(limits);
    let image = reader
        .decode()
        .map_err(|e| ParseError::at_byte(0, format!("cannot decode this {} image: {e}", format.name())))?;
    let rgba = image.into_rgba8();
    Ok(Rgba { width: rgba.width(), height: rgba.height(), pixels: rgba.into_raw() })
}

/// Decodes `bytes` as whichever image format their content shows (the extension of
/// `name` is the fallback, so a damaged file still gets its decoder's error).
pub fn decode_any(name: &str, bytes: &[u8]) -> Result<Rgba, ParseError> {
    let format = ImageFormat::detect(bytes)
        .or_else(|| ImageFormat::from_extension(name))
        .ok_or_else(|| ParseError::at_byte(0, "not an image this viewer reads (PCX, BMP, PNG, JPEG or TGA)"))?;
    decode(format, bytes)
}

/// True when `bytes` start with a TGA header every field of which holds an allowed
/// value: colour-map type 0 or 1, image type 1–3 or 9–11 (colour-mapped, true-colour
/// or grey, raw or RLE), a colour map only with a colour-mapped type, 8/15/16/24/32
/// bits per pixel, a non-zero size, and the ID field and colour map inside the file.
/// TGA has no signature, so this is the last format tried.
fn sniff_tga(bytes: &[u8]) -> bool {
    let Some(h) = bytes.get(..18) else { return false };
    let word = |i: usize| usize::from(u16::from_le_bytes([h[i], h[i + 1]]));
    let (id_len, map_type, image_type) = (usize::from(h[0]), h[1], h[2]);
    let mapped = matches!(image_type, 1 | 9);
    let known_type = matches!(image_type, 1..=3 | 9..=11);
    let map_ok = match map_type {
        0 => !mapped,
        1 => mapped && matches!(h[7], 15 | 16 | 24 | 32),
        _ => false,
    };
    let map_bytes = if map_type == 1 { word(5) * usize::from(h[7]).div_ceil(8) } else { 0 };
    let depth_ok = matches!(h[16], 8 | 15 | 16 | 24 | 32);
    let size_ok = word(12) > 0 && word(14) > 0;
    known_type && map_ok && depth_ok && size_ok && h[17] & 0xC0 == 0 && 18 + id_len + map_bytes < bytes.len()
}
