//! Images the formats refer to (model skins): decoded to RGBA8 in memory.
//! `pcx` reads ZSoft PCX, the Quake 2 skin format, which no well-kept image crate
//! reads; BMP, PNG and JPEG will come from an image crate when skins are drawn.

pub mod pcx;

/// An RGBA8 image, rows top to bottom.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Rgba {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// `width × height × 4` bytes: red, green, blue, alpha per pixel.
    pub pixels: Vec<u8>,
}

impl Rgba {
    /// The pixel at `(x, y)` as `[r, g, b, a]`; `None` outside the image.
    pub fn pixel(&self, x: u32, y: u32) -> Option<[u8; 4]> {
        if x >= self.width || y >= self.height {
            return None;
        }
        let i = (y as usize * self.width as usize + x as usize) * 4;
        let p = self.pixels.get(i..i + 4)?;
        Some([p[0], p[1], p[2], p[3]])
    }
}
