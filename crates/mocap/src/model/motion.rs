//! Motion data: a frame time, an angle unit and one contiguous `frames × channels`
//! f32 matrix.

use crate::model::channel::AngleUnit;

/// Sampled channel values for every frame.
#[derive(Clone, Debug, PartialEq)]
pub struct Motion {
    frame_time: f64,
    angle_unit: AngleUnit,
    channel_count: usize,
    frame_count: usize,
    data: Vec<f32>,
}

impl Motion {
    /// Builds motion from a row-major matrix, rotations in degrees. `None` unless
    /// `frame_time` is positive and finite and `data.len()` equals
    /// `frame_count * channel_count` (when `channel_count` is 0, `data` is empty and
    /// `frame_count` is kept as given).
    pub fn new(frame_time: f64, channel_count: usize, frame_count: usize, data: Vec<f32>) -> Option<Motion> {
        if data.len() != frame_count.checked_mul(channel_count)? || !(frame_time.is_finite() && frame_time > 0.0) {
            return None;
        }
        Some(Motion { frame_time, angle_unit: AngleUnit::Degrees, channel_count, frame_count, data })
    }

    /// The same motion with rotation values in `unit`.
    pub fn with_angle_unit(mut self, unit: AngleUnit) -> Motion {
        self.angle_unit = unit;
        self
    }

    /// The unit of the rotation values.
    pub fn angle_unit(&self) -> AngleUnit {
        self.angle_unit
    }

    /// Frame timing: the one time↔frame rule for this motion.
    pub fn timeline(&self) -> crate::model::time::Timeline {
        crate::model::time::Timeline::new(self.frame_time, self.frame_count)
    }

    /// Seconds between frames (always positive and finite).
    pub fn frame_time(&self) -> f64 {
        self.frame_time
    }

    /// Number of frames.
    pub fn frame_count(&self) -> usize {
        self.frame_count
    }

    /// Number of channels, the width of a row.
    pub fn channel_count(&self) -> usize {
        self.channel_count
    }

    /// The whole matrix, row-major.
    pub fn data(&self) -> &[f32] {
        &self.data
    }

    /// One frame's row; empty when `frame` is out of range.
    pub fn row(&self, frame: usize) -> &[f32] {
        let start = frame.saturating_mul(self.channel_count);
        self.data.get(start..start.saturating_add(self.channel_count)).unwrap_or(&[])
    }

    /// One value; 0 when out of range.
    pub fn value(&self, frame: usize, channel: usize) -> f32 {
        if channel >= self.channel_count {
            return 0.0;
        }
        self.row(frame).get(channel).copied().unwrap_or(0.0)
    }

    /// Iterates one channel's values over all frames.
    pub fn column(&self, channel: usize) -> impl Iterator<Item = f32> + '_ {
        let width = self.channel_count.max(1);
        let ok = channel < self.channel_count;
        self.data.iter().skip(channel).step_by(width).copied().filter(move |_| ok)
    }
}

impl Default for Motion {
    /// No frames, no channels, 30 fps.
    fn default() -> Motion {
        Motion {
            frame_time: 1.0 / 30.0,
            angle_unit: AngleUnit::Degrees,
            channel_count: 0,
            frame_count: 0,
            data: Vec::new(),
        }
    }
}
