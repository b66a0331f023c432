//! How the 3D view trades looks for speed: full quality (multisampled edges),
//! a fast look (one sample per pixel and the renderer's
//! `SceneRenderer::fast_look`: a smaller shadow map read once per pixel,
//! capsules spanning under two pixels left out), or the automatic rule between
//! them. Every look is drawn at the display's resolution, and the panels, tree,
//! inspector and timeline around the view are never touched by it: their text
//! stays sharp while the view moves.
//!
//! The automatic rule ([`Adaptive::decide`]): a view at rest (nothing playing,
//! nothing dragged) is always drawn at full quality. While it moves, frames are
//! drawn at full quality until three in a row take longer than [`SLOW_FRAME`]
//! seconds; from then on, until the view comes to rest, they are drawn fast. On
//! a software rasteriser multisampling is a large share of the frame's cost.

/// A frame slower than this (seconds; under 24 frames per second) counts as slow.
pub const SLOW_FRAME: f32 = 1.0 / 24.0;

/// Slow frames in a row that switch a moving view to the fast look.
const SLOW_IN_A_ROW: u32 = 3;

/// The 3D view's quality setting (URL fragment `quality=auto|full|fast`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Quality {
    /// Full quality at rest; fast while moving when frames are slow.
    #[default]
    Auto,
    /// Always full quality.
    Full,
    /// Fast while moving; full quality at rest.
    Fast,
}

impl Quality {
    /// Its name in the URL fragment and the JS API.
    pub fn name(self) -> &'static str {
        match self {
            Quality::Auto => "auto",
            Quality::Full => "full",
            Quality::Fast => "fast",
        }
    }

    /// The setting called `name` (see [`Quality::name`]).
    pub fn from_name(name: &str) -> Option<Quality> {
        [Quality::Auto, Quality::Full, Quality::Fast].into_iter().find(|q| q.name() == name)
    }
}

/// The automatic rule's memory between frames.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Adaptive {
    slow_in_a_row: u32,
    fast: bool,
}

impl Adaptive {
    /// Whether this frame is drawn fast, given the setting, whether the view is
    /// moving, and `dt`, the seconds since the last frame.
    pub fn decide(&mut self, quality: Quality, moving: bool, dt: f32) -> bool {
        if !moving {
            *self = Adaptive::default();
            return false;
        }
        match quality {
            Quality::Full => false,
            Quality::Fast => true,
            Quality::Auto => {
                if !self.fast {
                    self.slow_in_a_row = if dt > SLOW_FRAME { self.slow_in_a_row + 1 } else { 0 };
                    self.fast = self.slow_in_a_row >= SLOW_IN_A_ROW;
                }
                self.fast
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn slow_moving_frames_switch_to_fast_until_rest() {
        let mut a = Adaptive::default();
        assert!(!a.decide(Quality::Auto, true, 0.1));
        assert!(!a.decide(Quality::Auto, true, 0.1));
        assert!(a.decide(Quality::Auto, true, 0.1), "third slow frame in a row");
        assert!(a.decide(Quality::Auto, true, 0.01), "stays fast while moving");
        assert!(!a.decide(Quality::Auto, false, 0.01), "a still frame is full quality");
        assert!(!a.decide(Quality::Auto, true, 0.1), "the count starts again");
    }

    #[test]
    fn fast_frames_and_broken_runs_stay_full() {
        let mut a = Adaptive::default();
        for dt in [0.1, 0.1, 0.01, 0.1, 0.1, 0.01, 0.016, 0.016] {
            assert!(!a.decide(Quality::Auto, true, dt));
        }
    }

    #[test]
    fn settings_override_the_rule_but_rest_is_full() {
        let mut a = Adaptive::default();
        assert!(a.decide(Quality::Fast, true, 0.0));
        assert!(!a.decide(Quality::Fast, false, 0.0));
        for _ in 0..5 {
            assert!(!a.decide(Quality::Full, true, 1.0));
        }
        assert_eq!(Quality::from_name("fast"), Some(Quality::Fast));
        assert_eq!(Quality::from_name("auto").map(Quality::name), Some("auto"));
        assert_eq!(Quality::from_name("best"), None);
    }
}
