//! Animated GIF: one NeuQuant palette per frame, delays that add up to the
//! frames' true times (rounded to hundredths where each frame ends), looping.

use crate::{Quality, Rate, VideoError};

/// GIF writer state.
pub struct GifEncoder {
    encoder: gif::Encoder<Vec<u8>>,
    size: [u16; 2],
    rate: Rate,
    speed: i32,
    frame: u64,
    pixels: Vec<u8>,
}

fn error(e: gif::EncodingError) -> VideoError {
    VideoError::Encode(format!("GIF: {e}"))
}

impl GifEncoder {
    /// Starts a looping GIF (the caller checked size and rate).
    pub fn new(size: [u32; 2], rate: Rate, quality: Quality) -> Result<GifEncoder, VideoError> {
        let size = [size[0] as u16, size[1] as u16];
        let mut encoder = gif::Encoder::new(Vec::new(), size[0], size[1], &[]).map_err(error)?;
        encoder.set_repeat(gif::Repeat::Infinite).map_err(error)?;
        let speed = match quality {
            Quality::High => 3,
            Quality::Normal => 10,
        };
        Ok(GifEncoder { encoder, size, rate, speed, frame: 0, pixels: Vec::new() })
    }

    /// Quantises and writes one frame.
    pub fn push(&mut self, rgba: &[u8]) -> Result<(), VideoError> {
        self.pixels.clear();
        self.pixels.extend(rgba.chunks_exact(4).flat_map(|p| [p[0], p[1], p[2], 255]));
        let mut frame = gif::Frame::from_rgba_speed(self.size[0], self.size[1], &mut self.pixels, self.speed);
        let (start, end) = (self.rate.start(self.frame, 100), self.rate.start(self.frame + 1, 100));
        frame.delay = (end - start).clamp(2, u16::MAX as u64) as u16;
        self.encoder.write_frame(&frame).map_err(error)?;
        self.frame += 1;
        Ok(())
    }

    /// Ends the file.
    pub fn finish(self) -> Result<Vec<u8>, VideoError> {
        self.encoder.into_inner().map_err(|e| VideoError::Encode(format!("GIF: {e}")))
    }
}
