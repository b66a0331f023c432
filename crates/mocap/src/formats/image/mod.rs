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
}

impl ImageFormat {
    /// File extensions of images (for file pickers), without the dot.
    pub const EXTENSIONS: [&'static str; 5] = ["pcx", "bmp", "png", "jpg", "jpeg"];

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
        .ok_or_else(|| ParseError::at_byte(0, "not an image this viewer reads (PCX, BMP, PNG or JPEG)"))?;
    decode(format, bytes)
}
