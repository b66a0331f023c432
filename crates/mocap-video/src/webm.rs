//! WebM with AV1: rav1e encodes (low latency, so packets come in display
//! order; a key frame at least every two seconds), libwebm writes the
//! container with the stream's `av1C` record as its codec private data.

use crate::yuv::I420;
use crate::{Quality, Rate, VideoError};
use rav1e::prelude::*;
use std::io::Cursor;

/// AV1 encoder and WebM muxer state.
pub struct WebmEncoder {
    context: Context<u8>,
    picture: I420,
    size: [u32; 2],
    rate: Rate,
    /// Encoded frames in order: (bytes, key).
    packets: Vec<(Vec<u8>, bool)>,
}

fn error(e: impl std::fmt::Display) -> VideoError {
    VideoError::Encode(format!("WebM: {e}"))
}

impl WebmEncoder {
    /// Starts the encoder (the caller checked size and rate).
    pub fn new(size: [u32; 2], rate: Rate, quality: Quality) -> Result<WebmEncoder, VideoError> {
        let key_every = (rate.fps() * 2.0).round().max(1.0) as u64;
        let speed = match quality {
            Quality::High => 6,
            Quality::Normal => 10,
        };
        let encoder = EncoderConfig {
            width: size[0] as usize,
            height: size[1] as usize,
            time_base: Rational::new(rate.den as u64, rate.num as u64),
            bit_depth: 8,
            chroma_sampling: ChromaSampling::Cs420,
            pixel_range: PixelRange::Limited,
            color_description: Some(ColorDescription {
                color_primaries: ColorPrimaries::BT601,
                transfer_characteristics: TransferCharacteristics::BT601,
                matrix_coefficients: MatrixCoefficients::BT601,
            }),
            low_latency: true,
            min_key_frame_interval: 0,
            max_key_frame_interval: key_every,
            quantizer: 100,
            speed_settings: SpeedSettings::from_preset(speed),
            ..Default::default()
        };
        let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
        let config = Config::new().with_encoder_config(encoder).with_threads(threads);
        let context = config.new_context().map_err(error)?;
        let picture = I420::new(size[0] as usize, size[1] as usize);
        Ok(WebmEncoder { context, picture, size, rate, packets: Vec::new() })
    }

    /// Encodes one frame.
    pub fn push(&mut self, rgba: &[u8]) -> Result<(), VideoError> {
        let (w, h) = (self.size[0] as usize, self.size[1] as usize);
        self.picture.fill(rgba, w, h);
        let mut frame = self.context.new_frame();
        frame.planes[0].copy_from_raw_u8(&self.picture.y, w, 1);
        frame.planes[1].copy_from_raw_u8(&self.picture.u, w / 2, 1);
        frame.planes[2].copy_from_raw_u8(&self.picture.v, w / 2, 1);
        self.context.send_frame(frame).map_err(error)?;
        self.drain()
    }

    /// Collects what the encoder has finished.
    fn drain(&mut self) -> Result<(), VideoError> {
        loop {
            match self.context.receive_packet() {
                Ok(packet) => self.packets.push((packet.data, packet.frame_type == FrameType::KEY)),
                Err(EncoderStatus::Encoded) => continue,
                Err(EncoderStatus::NeedMoreData | EncoderStatus::LimitReached) => return Ok(()),
                Err(e) => return Err(error(e)),
            }
        }
    }

    /// Flushes the encoder and writes the container.
    pub fn finish(mut self) -> Result<Vec<u8>, VideoError> {
        self.context.flush();
        self.drain()?;
        let header = self.context.container_sequence_header();
        let writer = webm::mux::Writer::new(Cursor::new(Vec::new()));
        let builder = webm::mux::SegmentBuilder::new(writer).map_err(error)?;
        let builder = builder.set_writing_app("mocap").map_err(error)?;
        let (builder, track) =
            builder.add_video_track(self.size[0], self.size[1], webm::mux::VideoCodecId::AV1, None).map_err(error)?;
        let builder = builder.set_codec_private(track, &header).map_err(error)?;
        let mut segment = builder.build();
        for (k, (data, key)) in self.packets.iter().enumerate() {
            let ns = self.rate.start(k as u64, 1_000_000_000);
            segment.add_frame(track, data, ns, *key).map_err(error)?;
        }
        let end = self.rate.start(self.packets.len() as u64, 1_000_000_000);
        // libwebm's Duration is in the segment's time code scale (1 ms by default).
        let writer = segment.finalize(Some(end / 1_000_000)).map_err(|_| error("the container could not be finished"))?;
        Ok(writer.into_inner().into_inner())
    }
}
