//! Playback state: playhead time, play/pause, speed, looping and the loop range.

/// Slowest and fastest playback speed.
pub const SPEED_RANGE: std::ops::RangeInclusive<f32> = 0.1..=4.0;

/// Plain playback state; all fields are user settings except `time`.
#[derive(Clone, Debug, PartialEq)]
pub struct Playback {
    /// Playhead in seconds from frame 0.
    pub time: f64,
    /// Whether time advances.
    pub playing: bool,
    /// Speed factor (see [`SPEED_RANGE`]).
    pub speed: f32,
    /// Wrap around at the end of the range instead of stopping.
    pub looping: bool,
    /// Inclusive loop sub-range in frames; `None` means the whole clip.
    pub range: Option<(usize, usize)>,
}

impl Default for Playback {
    fn default() -> Playback {
        Playback { time: 0.0, playing: true, speed: 1.0, looping: true, range: None }
    }
}

/// The timeline playback runs on: the core's one time↔frame rule.
pub use mocap::Timeline as Timing;

impl Playback {
    /// The loop range clamped to the clip, in frames (inclusive, start ≤ end).
    pub fn frame_range(&self, timing: Timing) -> (usize, usize) {
        let last = timing.last();
        match self.range {
            Some((a, b)) => {
                let (a, b) = (a.min(last), b.min(last));
                (a.min(b), a.max(b))
            }
            None => (0, last),
        }
    }

    /// Current frame: the frame shown at the playhead ([`Timing::frame_at`]).
    pub fn frame(&self, timing: Timing) -> usize {
        timing.frame_at(self.time)
    }

    /// Advances the playhead by `dt` wall-clock seconds when playing.
    pub fn advance(&mut self, dt: f64, timing: Timing) {
        if !self.playing || timing.frames() == 0 {
            return;
        }
        let (a, b) = self.frame_range(timing);
        let (start, end) = (timing.time_of(a), timing.time_of(b));
        self.time =
            self.time.max(start) + dt.max(0.0) * f64::from(self.speed.clamp(*SPEED_RANGE.start(), *SPEED_RANGE.end()));
        if self.time > end {
            let span = end - start;
            if self.looping && span > 0.0 {
                self.time = start + (self.time - start) % (span + timing.frame_time());
                if self.time > end {
                    self.time = start;
                }
            } else {
                self.time = end;
                self.playing = self.looping && span > 0.0;
            }
        }
    }

    /// Moves to a frame exactly (clamped).
    pub fn seek(&mut self, frame: usize, timing: Timing) {
        self.time = timing.time_of(frame.min(timing.last()));
    }

    /// Pauses and moves `delta` frames (clamped to the clip).
    pub fn step(&mut self, delta: isize, timing: Timing) {
        self.playing = false;
        let frame = self.frame(timing).saturating_add_signed(delta);
        self.seek(frame, timing);
    }

    /// Pauses or resumes; pausing snaps to the current frame so paused views are frame-exact.
    pub fn set_playing(&mut self, playing: bool, timing: Timing) {
        self.playing = playing;
        if !playing {
            self.seek(self.frame(timing), timing);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const T: Timing = Timing::new(0.1, 11);

    #[test]
    fn advances_in_real_time_and_loops() {
        let mut p = Playback::default();
        p.advance(0.35, T);
        assert_eq!(p.frame(T), 3);
        p.advance(0.8, T);
        assert!(p.playing);
        assert!(p.frame(T) <= 10);
        assert!((p.time - 0.05).abs() < 1e-9, "{}", p.time);
    }

    #[test]
    fn stops_at_end_without_loop() {
        let mut p = Playback { looping: false, ..Playback::default() };
        p.advance(5.0, T);
        assert_eq!(p.frame(T), 10);
        assert!(!p.playing);
    }

    #[test]
    fn speed_scales_time() {
        let mut p = Playback { speed: 2.0, ..Playback::default() };
        p.advance(0.2, T);
        assert_eq!(p.frame(T), 4);
    }

    #[test]
    fn step_and_seek_clamp() {
        let mut p = Playback::default();
        p.step(-1, T);
        assert_eq!(p.frame(T), 0);
        assert!(!p.playing);
        p.step(100, T);
        assert_eq!(p.frame(T), 10);
        p.seek(3, T);
        assert!((p.time - 0.3).abs() < 1e-9);
        assert_eq!(p.frame(T), 3);
    }

    #[test]
    fn loop_range_is_respected() {
        let mut p = Playback { range: Some((7, 4)), ..Playback::default() };
        assert_eq!(p.frame_range(T), (4, 7));
        p.advance(0.0, T);
        assert_eq!(p.frame(T), 4);
        p.advance(0.35, T);
        assert!((4..=7).contains(&p.frame(T)));
    }

    #[test]
    fn empty_clip_is_harmless() {
        let mut p = Playback::default();
        let t = Timing::new(0.0, 0);
        p.advance(1.0, t);
        p.step(1, t);
        assert_eq!(p.frame(t), 0);
    }
}
