//! Compare ▸ with another character: the core's [`mocap::ops::compare`] of the
//! other take against the current one, kept up to date with their edits; the
//! other drawn as a ghost in the current one's place, each bone coloured by
//! its joint's mean error ([`color`]), with a legend and the per-frame error
//! curve under the timeline.

use mocap::ops::compare::Report;

/// Two characters being compared and what the comparison found.
#[derive(Clone, Debug, PartialEq)]
pub struct Comparison {
    /// The reference (its frames, units and place).
    pub a: usize,
    /// The take measured against it (drawn as the ghost).
    pub b: usize,
    /// The errors.
    pub report: Report,
    /// `a`'s unit name (what the numbers are in).
    pub units: &'static str,
    /// The history's state the report was made at (it is made again when it changes).
    pub mark: (Option<String>, Option<String>),
}

impl Comparison {
    /// The largest per-joint mean error: the top of the colour scale.
    pub fn scale(&self) -> f32 {
        self.report.joints.iter().map(|j| j.mean).fold(0.0, f32::max).max(f32::MIN_POSITIVE)
    }

    /// The mean error of `a`'s joint `name` (0 when not compared).
    pub fn error_of(&self, name: &str) -> f32 {
        self.report.joints.iter().find(|j| j.name == name).map_or(0.0, |j| j.mean)
    }
}

/// The colour of an error `e` on a scale to `max`: green, yellow, red.
pub fn color(e: f32, max: f32) -> [u8; 4] {
    let t = (e / max.max(f32::MIN_POSITIVE)).clamp(0.0, 1.0);
    let (r, g) = if t < 0.5 { (2.0 * t, 1.0) } else { (1.0, 2.0 * (1.0 - t)) };
    [(60.0 + 195.0 * r) as u8, (60.0 + 180.0 * g) as u8, 60, 230]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_scale_runs_green_to_red() {
        assert!(color(0.0, 1.0)[1] > color(0.0, 1.0)[0]);
        assert!(color(1.0, 1.0)[0] > color(1.0, 1.0)[1]);
        assert_eq!(color(5.0, 1.0), color(1.0, 1.0));
    }
}
