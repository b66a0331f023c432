//! How the 3D view trades looks for speed: full quality (multisampled edges),
//! a fast look (the 3D view drawn at half the display's resolution per axis
//! and stretched over its rect, one sample per pixel, and the renderer's
//! `SceneRenderer::fast_look`: the floor's shadow drawn from the casters'
//! footprints where capsules are all that cast, else a smaller shadow map read
//! once per pixel; capsules spanning under two pixels left out), or the
//! automatic rule between
//! them. The panels, tree, inspector and timeline around the view are never
//! touched by it: they are drawn at the display's resolution in every look,
//! and their text stays sharp while the view moves.
//!
//! The automatic rule ([`Adaptive::decide`]): a view at rest (nothing playing,
//! nothing dragged) is always drawn at full quality. While it moves, frames are
//! drawn at full quality until they fall behind the display: over the last
//! [`WINDOW`] moving frames (after the first [`WARM_UP`], which include the
//! pause before and the first use of shaders), with the slowest one left out
//! (a single stall is not a slow device), the mean frame time is longer than
//! [`SLOW_FRAME`]. From then on, until the view comes to rest, they are drawn
//! fast. On a software rasteriser the 3D view's pixels are most of the frame's
//! cost.

/// A mean moving frame time longer than this (seconds; under 55 frames per
/// second: a 60 Hz display's frames being missed) counts as slow.
pub const SLOW_FRAME: f32 = 1.0 / 55.0;

/// Moving frames whose times the automatic rule averages.
pub const WINDOW: usize = 10;

/// Moving frames the automatic rule does not time after the view starts to
/// move.
pub const WARM_UP: u32 = 3;

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
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Adaptive {
    /// Moving frames seen since the view started to move.
    moving_frames: u32,
    /// The last [`WINDOW`] timed frames' times, in a ring.
    recent: [f32; WINDOW],
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
                    self.moving_frames = self.moving_frames.saturating_add(1);
                    if let Some(timed) = self.moving_frames.checked_sub(WARM_UP + 1) {
                        self.recent[timed as usize % WINDOW] = if dt.is_finite() { dt.max(0.0) } else { 0.0 };
                        self.fast = timed as usize + 1 >= WINDOW && trimmed_mean(&self.recent) > SLOW_FRAME;
                    }
                }
                self.fast
            }
        }
    }
}

/// The mean of `times` without the largest.
fn trimmed_mean(times: &[f32; WINDOW]) -> f32 {
    let largest = times.iter().copied().fold(0.0, f32::max);
    (times.iter().sum::<f32>() - largest) / (WINDOW - 1) as f32
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Feeds `dts` as moving frames; whether each was drawn fast.
    fn run(a: &mut Adaptive, dts: &[f32]) -> Vec<bool> {
        dts.iter().map(|&dt| a.decide(Quality::Auto, true, dt)).collect()
    }

    #[test]
    fn frames_behind_the_display_switch_to_fast_until_rest() {
        let mut a = Adaptive::default();
        // 40 frames a second: the warm-up, then a window's worth of them.
        let looks = run(&mut a, &[0.025; WARM_UP as usize + WINDOW]);
        assert!(looks[..looks.len() - 1].iter().all(|f| !f), "full quality until a window is timed: {looks:?}");
        assert!(looks[looks.len() - 1], "the window's mean is slow");
        assert!(a.decide(Quality::Auto, true, 0.001), "stays fast while moving");
        assert!(!a.decide(Quality::Auto, false, 0.001), "a still frame is full quality");
        assert!(!a.decide(Quality::Auto, true, 0.025), "the count starts again");
    }

    #[test]
    fn frames_at_the_display_rate_and_single_stalls_stay_full() {
        let mut a = Adaptive::default();
        // 60 Hz with the first frames slow (shaders), a stall of half a second
        // and a long gap before the first (the pause before playing).
        let mut dts = vec![5.0, 0.2, 0.1];
        dts.extend([1.0 / 60.0; 30]);
        dts[20] = 0.5;
        assert!(run(&mut a, &dts).iter().all(|f| !f));
        // Two vsync intervals now and then (55-60 frames a second) stay full.
        let mut a = Adaptive::default();
        let dts: Vec<f32> = (0..40).map(|i| if i % 12 == 5 { 2.0 / 60.0 } else { 1.0 / 60.0 }).collect();
        assert!(run(&mut a, &dts).iter().all(|f| !f));
        // Every other frame missed (40 a second): fast.
        let mut a = Adaptive::default();
        let dts: Vec<f32> = (0..40).map(|i| if i % 2 == 0 { 2.0 / 60.0 } else { 1.0 / 60.0 }).collect();
        assert!(run(&mut a, &dts).iter().any(|&f| f));
    }

    #[test]
    fn times_that_are_not_numbers_count_as_none() {
        let mut a = Adaptive::default();
        assert!(run(&mut a, &[f32::NAN; 20]).iter().all(|f| !f));
        assert!(run(&mut a, &[f32::INFINITY; 20]).iter().all(|f| !f));
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
