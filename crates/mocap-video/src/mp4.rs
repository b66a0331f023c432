//! MP4 with H.264: OpenH264 encodes each frame (every one kept, none skipped,
//! a key frame every two seconds); the `mp4` crate writes the container with
//! the stream's own parameter sets.

use crate::yuv::I420;
use crate::{Rate, VideoError};
use openh264::encoder::{
    BitRate, Complexity, Encoder, EncoderConfig, FrameRate, FrameType, IntraFramePeriod, QpRange, RateControlMode,
};
use openh264::formats::YUVSlices;
use openh264::OpenH264API;
use std::io::Cursor;

/// H.264 encoder and MP4 muxer state.
pub struct Mp4Encoder {
    encoder: Encoder,
    picture: I420,
    size: [u32; 2],
    rate: Rate,
    frame: u64,
    /// Samples waiting for the parameter sets (the first frame brings them).
    writer: Option<::mp4::Mp4Writer<Cursor<Vec<u8>>>>,
    nal: Vec<u8>,
}

fn error(e: impl std::fmt::Display) -> VideoError {
    VideoError::Encode(format!("MP4: {e}"))
}

/// A NAL unit without its Annex B start code.
fn payload(nal: &[u8]) -> &[u8] {
    if let Some(rest) = nal.strip_prefix(&[0, 0, 0, 1]) {
        rest
    } else {
        nal.strip_prefix(&[0, 0, 1]).unwrap_or(nal)
    }
}

/// The track's time scale: a multiple of the rate's numerator of at least 600
/// ticks a second, so every frame starts on a tick.
fn timescale(rate: Rate) -> u32 {
    rate.num.saturating_mul((600 / rate.num.max(1)).max(1))
}

impl Mp4Encoder {
    /// Starts the encoder (the caller checked the size and rate).
    pub fn new(size: [u32; 2], rate: Rate) -> Result<Mp4Encoder, VideoError> {
        let pixels_per_second = size[0] as f64 * size[1] as f64 * rate.fps();
        // About 0.12 bit a pixel: 3.3 Mbit/s at 720p30, plenty for flat-shaded scenes.
        let bps = (pixels_per_second * 0.12).clamp(200_000.0, 40_000_000.0) as u32;
        let key_every = (rate.fps() * 2.0).round().max(1.0) as u32;
        let config = EncoderConfig::new()
            .bitrate(BitRate::from_bps(bps))
            .max_frame_rate(FrameRate::from_hz(rate.fps() as f32))
            .skip_frames(false)
            .rate_control_mode(RateControlMode::Off)
            .qp(QpRange::new(18, 26))
            .complexity(Complexity::Low)
            .intra_frame_period(IntraFramePeriod::from_num_frames(key_every));
        let encoder = Encoder::with_api_config(OpenH264API::from_source(), config).map_err(error)?;
        let picture = I420::new(size[0] as usize, size[1] as usize);
        Ok(Mp4Encoder { encoder, picture, size, rate, frame: 0, writer: None, nal: Vec::new() })
    }

    /// Encodes one frame and adds it to the file.
    pub fn push(&mut self, rgba: &[u8]) -> Result<(), VideoError> {
        let (w, h) = (self.size[0] as usize, self.size[1] as usize);
        self.picture.fill(rgba, w, h);
        let yuv = YUVSlices::new((&self.picture.y, &self.picture.u, &self.picture.v), (w, h), (w, w / 2, w / 2));
        let stream = self.encoder.encode(&yuv).map_err(error)?;
        let key = matches!(stream.frame_type(), FrameType::IDR | FrameType::I);
        let (mut sps, mut pps) = (None, None);
        self.nal.clear();
        for l in 0..stream.num_layers() {
            let Some(layer) = stream.layer(l) else { continue };
            for n in 0..layer.nal_count() {
                let Some(nal) = layer.nal_unit(n).map(payload) else { continue };
                match nal.first().map(|b| b & 0x1f) {
                    Some(7) => sps = Some(nal.to_vec()),
                    Some(8) => pps = Some(nal.to_vec()),
                    Some(_) => {
                        self.nal.extend_from_slice(&(nal.len() as u32).to_be_bytes());
                        self.nal.extend_from_slice(nal);
                    }
                    None => {}
                }
            }
        }
        if self.writer.is_none() {
            let (Some(sps), Some(pps)) = (sps, pps) else {
                return Err(error("the encoder's first frame has no parameter sets"));
            };
            self.writer = Some(self.start(sps, pps)?);
        }
        if self.nal.is_empty() {
            return Err(error(format!("the encoder gave no picture for frame {}", self.frame)));
        }
        let scale = timescale(self.rate) as u64;
        let (start, end) = (self.rate.start(self.frame, scale), self.rate.start(self.frame + 1, scale));
        let sample = ::mp4::Mp4Sample {
            start_time: start,
            duration: (end - start) as u32,
            rendering_offset: 0,
            is_sync: key,
            bytes: ::mp4::Bytes::copy_from_slice(&self.nal),
        };
        if let Some(writer) = &mut self.writer {
            writer.write_sample(1, &sample).map_err(error)?;
        }
        self.frame += 1;
        Ok(())
    }

    /// The container, its one H.264 track in the rate's own time scale.
    fn start(&self, sps: Vec<u8>, pps: Vec<u8>) -> Result<::mp4::Mp4Writer<Cursor<Vec<u8>>>, VideoError> {
        let config = ::mp4::Mp4Config {
            major_brand: "isom".parse().map_err(error)?,
            minor_version: 512,
            compatible_brands: ["isom", "iso2", "avc1", "mp41"].iter().filter_map(|b| b.parse().ok()).collect(),
            // The movie's time scale is the track's: the crate adds each sample's
            // duration to the track header converted (and floored) into it.
            timescale: timescale(self.rate),
        };
        let mut writer = ::mp4::Mp4Writer::write_start(Cursor::new(Vec::new()), &config).map_err(error)?;
        let track = ::mp4::TrackConfig {
            track_type: ::mp4::TrackType::Video,
            timescale: timescale(self.rate),
            language: "und".into(),
            media_conf: ::mp4::MediaConfig::AvcConfig(::mp4::AvcConfig {
                width: self.size[0] as u16,
                height: self.size[1] as u16,
                seq_param_set: sps,
                pic_param_set: pps,
            }),
        };
        writer.add_track(&track).map_err(error)?;
        Ok(writer)
    }

    /// Ends the file.
    pub fn finish(self) -> Result<Vec<u8>, VideoError> {
        let mut writer = self.writer.ok_or(VideoError::Empty)?;
        writer.write_end().map_err(error)?;
        Ok(writer.into_writer().into_inner())
    }
}
