//! The one rule that maps time to frames, used by sampling, the viewer's timeline
//! and playback, `mocap render` and the JS API.
//!
//! Frame `i` is sampled at `i × frame_time`. The frame shown at a time is the last
//! one not after it, except that a time less than [`SNAP`] of a frame before a
//! frame counts as on it: files write frame times with 6–7 digits (0.0333333), so
//! clips with different frame times, and times summed by playback, drift by a
//! little from exact frames.

/// Share of a frame within which a time before a frame counts as on it.
pub const SNAP: f64 = 0.01;

/// Frame time used when none usable is known (30 fps).
pub const DEFAULT_FRAME_TIME: f64 = 1.0 / 30.0;

/// Most frames a timeline spans (times beyond are clamped), so absurd frame times
/// and durations give bounded counts.
pub const MAX_FRAMES: usize = 1 << 30;

/// Where a time falls between two frames.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FramePosition {
    /// The frame shown at the time ([`Timeline::frame_at`]).
    pub frame0: usize,
    /// The frame after (equal to `frame0` at the end or on a frame).
    pub frame1: usize,
    /// Blend weight of `frame1`, in `[0, 1)`.
    pub alpha: f32,
}

/// Frame count and frame time of a clip (or of a shared timeline).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Timeline {
    frame_time: f64,
    frames: usize,
}

impl Timeline {
    /// `frames` frames `frame_time` seconds apart; an unusable frame time (zero,
    /// negative, not finite) counts as [`DEFAULT_FRAME_TIME`].
    pub const fn new(frame_time: f64, frames: usize) -> Timeline {
        let frame_time = if frame_time.is_finite() && frame_time > 0.0 { frame_time } else { DEFAULT_FRAME_TIME };
        Timeline { frame_time, frames: if frames < MAX_FRAMES { frames } else { MAX_FRAMES } }
    }

    /// Seconds between frames (positive, finite).
    pub fn frame_time(self) -> f64 {
        self.frame_time
    }

    /// Number of frames.
    pub fn frames(self) -> usize {
        self.frames
    }

    /// Index of the last frame (0 when there are none).
    pub fn last(self) -> usize {
        self.frames.saturating_sub(1)
    }

    /// Time of a frame's sample in seconds.
    pub fn time_of(self, frame: usize) -> f64 {
        frame as f64 * self.frame_time
    }

    /// Time of the last frame: 0 for 0 or 1 frame.
    pub fn duration(self) -> f64 {
        self.time_of(self.last())
    }

    /// The frame shown at `time`: the last frame not after it (see [`SNAP`]),
    /// clamped to the clip; 0 for NaN.
    pub fn frame_at(self, time: f64) -> usize {
        self.position(time).frame0
    }

    /// Where `time` falls: the frame shown, the next one and the blend weight.
    pub fn position(self, time: f64) -> FramePosition {
        let last = self.last();
        let f = time / self.frame_time;
        if !(f > 0.0) {
            return FramePosition { frame0: 0, frame1: 0, alpha: 0.0 };
        }
        if f >= last as f64 {
            return FramePosition { frame0: last, frame1: last, alpha: 0.0 };
        }
        let frame0 = ((f + SNAP).floor() as usize).min(last);
        let alpha = (f - frame0 as f64).max(0.0);
        if alpha == 0.0 || frame0 == last {
            return FramePosition { frame0, frame1: frame0, alpha: 0.0 };
        }
        FramePosition { frame0, frame1: frame0 + 1, alpha: alpha as f32 }
    }

    /// The frame nearest to `time` (rounding the position), clamped.
    pub fn nearest(self, time: f64) -> usize {
        let p = self.position(time);
        if p.alpha >= 0.5 { p.frame1 } else { p.frame0 }
    }

    /// How many frames of this frame time it takes to reach `duration` seconds:
    /// the last one at or just past it (within [`SNAP`]). At least one frame; bounded
    /// by [`MAX_FRAMES`] whatever the numbers.
    pub fn frames_to_reach(self, duration: f64) -> usize {
        let spans = (duration / self.frame_time - SNAP).ceil();
        if !(spans > 0.0) {
            return 1;
        }
        if spans >= MAX_FRAMES as f64 { MAX_FRAMES } else { spans as usize + 1 }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frames_round_trip_through_their_times() {
        for (n, dt) in [(1usize, 0.1), (11, 0.1), (2752, 0.0083333), (125, 0.03333), (7, 1.0 / 3.0)] {
            let t = Timeline::new(dt, n);
            for f in 0..n {
                assert_eq!(t.frame_at(t.time_of(f)), f, "n={n} f={f}");
                assert_eq!(t.nearest(t.time_of(f)), f);
            }
            assert_eq!(t.frame_at(1e9), t.last());
            assert_eq!(t.frame_at(-5.0), 0);
            assert_eq!(t.frame_at(f64::NAN), 0);
        }
    }

    #[test]
    fn a_time_just_before_a_frame_counts_as_on_it() {
        let t = Timeline::new(0.1, 11);
        assert_eq!(t.frame_at(0.2999), 3);
        assert_eq!(t.frame_at(0.295), 2);
        let p = t.position(0.25);
        assert_eq!((p.frame0, p.frame1), (2, 3));
        assert!((p.alpha - 0.5).abs() < 1e-6);
        assert_eq!(t.nearest(0.25), 3);
        assert_eq!(t.nearest(0.24), 2);
    }

    #[test]
    fn counts_stay_bounded_for_absurd_numbers() {
        for dt in [1e-300, 0.0, -1.0, f64::NAN, f64::INFINITY, 1e300] {
            let t = Timeline::new(dt, 10);
            assert!(t.frame_time() > 0.0 && t.frame_time().is_finite());
            for d in [0.0, 1.0, 1e300, f64::INFINITY, f64::NAN, -1.0] {
                let n = t.frames_to_reach(d);
                assert!((1..=MAX_FRAMES).contains(&n), "dt={dt} d={d}: {n}");
            }
        }
        assert_eq!(Timeline::new(1e-300, 10).frames_to_reach(1.0), MAX_FRAMES);
    }

    #[test]
    fn frames_to_reach_covers_a_longer_clip() {
        let t = Timeline::new(0.1, 11);
        assert_eq!(t.frames_to_reach(1.0), 11);
        assert_eq!(t.frames_to_reach(1.05), 12);
        assert_eq!(t.frames_to_reach(1.0009), 11, "within a hundredth of a frame");
        assert_eq!(t.frames_to_reach(0.0), 1);
        assert_eq!(Timeline::new(0.1, 0).frames(), 0);
    }
}
