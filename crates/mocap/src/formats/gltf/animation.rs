//! glTF animations: each channel's keys read and checked, and sampled exactly as
//! the specification defines: `STEP` holds, `LINEAR` interpolates translations
//! and scales linearly and rotations by slerp, `CUBICSPLINE` is the Hermite form
//! with tangents scaled by the key interval (rotations normalised). Before the
//! first key the first value holds, after the last the last one.
//!
//! Inputs: an animation and the buffers. Output: [`Track`]s, one per channel on
//! a node's translation, rotation or scale; [`Track::sample`] evaluates one; and
//! [`WeightTrack`]s, one per channel on a mesh node's morph-target `weights`
//! (each weight interpolated on its own: `STEP`, `LINEAR` or the Hermite form).

use super::accessor;
use crate::error::ParseError;
use gltf::animation::{Interpolation, Property};

/// What a track animates.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Path {
    /// The node's translation (3 values).
    Translation,
    /// The node's rotation (4 values, x y z w).
    Rotation,
    /// The node's scale (3 values).
    Scale,
}

/// One channel's keys.
#[derive(Clone, Debug)]
pub struct Track {
    /// The node it moves.
    pub node: usize,
    /// What of the node.
    pub path: Path,
    /// How keys are joined.
    pub interpolation: Interpolation,
    /// Key times in seconds, strictly increasing.
    pub times: Vec<f32>,
    /// Values, `width` per key (three per key for cubic: in-tangent, value, out-tangent).
    pub values: Vec<f32>,
}

impl Track {
    /// Components per value.
    pub fn width(&self) -> usize {
        if self.path == Path::Rotation { 4 } else { 3 }
    }

    /// The value at time `t` into `out` (4 slots; 3 used for translation and
    /// scale). `cursor` remembers the key interval found last (start it at 0), so
    /// a pass over increasing times walks the keys once instead of searching them
    /// for every frame; any time is still answered exactly.
    pub fn sample(&self, t: f32, cursor: &mut usize, out: &mut [f32; 4]) {
        let w = self.width();
        let n = self.times.len();
        let cubic = self.interpolation == Interpolation::CubicSpline;
        let value = |k: usize, c: usize| -> f32 {
            let at = if cubic { (3 * k + 1) * w + c } else { k * w + c };
            self.values.get(at).copied().unwrap_or(0.0)
        };
        if n == 0 {
            return;
        }
        let first = self.times[0];
        let last = self.times[n - 1];
        let held = if t <= first || n == 1 {
            Some(0)
        } else if t >= last {
            Some(n - 1)
        } else {
            None
        };
        if let Some(k) = held {
            (0..w).for_each(|c| out[c] = value(k, c));
            return self.finish(out);
        }
        // The key interval holding t: times[k] <= t < times[k + 1].
        let mut k = (*cursor).min(n - 2);
        if self.times[k] > t {
            k = self.times.partition_point(|&x| x <= t).saturating_sub(1).min(n - 2);
        }
        while k + 2 < n && self.times[k + 1] <= t {
            k += 1;
        }
        *cursor = k;
        let (t0, t1) = (self.times[k], self.times[k + 1]);
        let dt = t1 - t0;
        let s = if dt > 0.0 { ((t - t0) / dt).clamp(0.0, 1.0) } else { 0.0 };
        match self.interpolation {
            Interpolation::Step => (0..w).for_each(|c| out[c] = value(k, c)),
            Interpolation::Linear if self.path == Path::Rotation => {
                let a = glam::Quat::from_array([value(k, 0), value(k, 1), value(k, 2), value(k, 3)]);
                let b = glam::Quat::from_array([value(k + 1, 0), value(k + 1, 1), value(k + 1, 2), value(k + 1, 3)]);
                *out = slerp(a, b, s).to_array();
            }
            Interpolation::Linear => (0..w).for_each(|c| out[c] = value(k, c) + (value(k + 1, c) - value(k, c)) * s),
            Interpolation::CubicSpline => {
                let tangent = |key: usize, which: usize, c: usize| -> f32 {
                    self.values.get((3 * key + which) * w + c).copied().unwrap_or(0.0)
                };
                let (s2, s3) = (s * s, s * s * s);
                for (c, slot) in out.iter_mut().enumerate().take(w) {
                    let p0 = value(k, c);
                    let m0 = tangent(k, 2, c) * dt; // out-tangent of key k
                    let p1 = value(k + 1, c);
                    let m1 = tangent(k + 1, 0, c) * dt; // in-tangent of key k + 1
                    *slot = (2.0 * s3 - 3.0 * s2 + 1.0) * p0
                        + (s3 - 2.0 * s2 + s) * m0
                        + (-2.0 * s3 + 3.0 * s2) * p1
                        + (s3 - s2) * m1;
                }
            }
        }
        self.finish(out);
    }

    /// Whether key `f` lies at `(f as f64 * frame_time) as f32` for every one of
    /// `frames` frames (within a ten-thousandth of a frame plus the rounding of
    /// an `f32` time that large), so that sampling frame `f` is reading key `f`
    /// ([`Track::key`]): a take baked a key per frame, as this project's exports
    /// and most tools' are. Only for `LINEAR` tracks, where a time a rounding
    /// error off a key moves the value by that fraction of the key interval's
    /// change, under what an `f32` angle shows; `STEP` and cubic tracks are
    /// always sampled.
    pub fn on_grid(&self, frame_time: f64, frames: usize) -> bool {
        let slack = |grid: f32| (frame_time * 1e-4) as f32 + grid.abs() * 4.0 * f32::EPSILON;
        self.interpolation == Interpolation::Linear
            && self.times.len() == frames
            && self.values.len() == frames * self.width()
            && self.times.iter().enumerate().all(|(f, &t)| {
                let grid = (f as f64 * frame_time) as f32;
                (t - grid).abs() <= slack(grid)
            })
    }

    /// Key `k`'s value into `out` (rotations normalised, as [`Track::sample`]
    /// gives them); nothing when there is no key `k`.
    pub fn key(&self, k: usize, out: &mut [f32; 4]) {
        let w = self.width();
        let at = k.checked_mul(w).and_then(|start| Some(start..start.checked_add(w)?));
        if let Some(v) = at.and_then(|at| self.values.get(at)) {
            // By pattern: a copy of a run-time length is a call to `memcpy`.
            match *v {
                [x, y, z, w] => *out = [x, y, z, w],
                [x, y, z] => (out[0], out[1], out[2]) = (x, y, z),
                _ => {}
            }
            self.finish(out);
        }
    }

    /// Normalises a rotation.
    fn finish(&self, out: &mut [f32; 4]) {
        if self.path == Path::Rotation {
            let q = glam::Quat::from_array(*out);
            let len = q.length();
            *out = if len > 0.0 && len.is_finite() { (q / len).to_array() } else { [0.0, 0.0, 0.0, 1.0] };
        }
    }

    /// The last key's time.
    pub fn end(&self) -> f32 {
        self.times.last().copied().unwrap_or(0.0)
    }
}

/// One channel on a node's morph-target `weights`: `targets` weights per key.
#[derive(Clone, Debug)]
pub struct WeightTrack {
    /// The mesh node whose weights it sets.
    pub node: usize,
    /// Weights per key (the mesh's morph targets).
    pub targets: usize,
    /// How keys are joined.
    pub interpolation: Interpolation,
    /// Key times in seconds, strictly increasing, at least one.
    pub times: Vec<f32>,
    /// `targets` values per key (three sets per key for cubic: in-tangents,
    /// values, out-tangents).
    pub values: Vec<f32>,
}

impl WeightTrack {
    /// The weights at time `t` into `out` (its first `targets` slots; held before
    /// the first key and after the last). `cursor` remembers the key interval
    /// found last, as in [`Track::sample`].
    pub fn sample(&self, t: f32, cursor: &mut usize, out: &mut [f32]) {
        let n = self.times.len();
        if n == 0 {
            return;
        }
        let cubic = self.interpolation == Interpolation::CubicSpline;
        let per_key = self.targets * if cubic { 3 } else { 1 };
        let part = usize::from(cubic);
        let value = |key: usize, set: usize, i: usize| {
            self.values.get(key * per_key + set * self.targets + i).copied().unwrap_or(0.0)
        };
        let mut k = (*cursor).min(n - 1);
        if self.times[k] > t {
            k = self.times.partition_point(|&x| x <= t).saturating_sub(1);
        }
        while k + 1 < n && self.times[k + 1] <= t {
            k += 1;
        }
        *cursor = k;
        let next = (k + 1).min(n - 1);
        let span = self.times[next] - self.times[k];
        let u = if span > 0.0 && t > self.times[k] { ((t - self.times[k]) / span).clamp(0.0, 1.0) } else { 0.0 };
        for (i, slot) in out.iter_mut().enumerate().take(self.targets) {
            *slot = match self.interpolation {
                _ if u == 0.0 => value(k, part, i),
                Interpolation::Step => value(k, 0, i),
                Interpolation::Linear => value(k, 0, i) * (1.0 - u) + value(next, 0, i) * u,
                Interpolation::CubicSpline => {
                    let (u2, u3) = (u * u, u * u * u);
                    let (p0, p1) = (value(k, 1, i), value(next, 1, i));
                    let (m0, m1) = (value(k, 2, i) * span, value(next, 0, i) * span);
                    (2.0 * u3 - 3.0 * u2 + 1.0) * p0
                        + (u3 - 2.0 * u2 + u) * m0
                        + (-2.0 * u3 + 3.0 * u2) * p1
                        + (u3 - u2) * m1
                }
            };
        }
    }

    /// The last key's time.
    pub fn end(&self) -> f32 {
        self.times.last().copied().unwrap_or(0.0)
    }
}

/// The specification's slerp: the shorter arc, linear when the two are nearly equal.
fn slerp(a: glam::Quat, b: glam::Quat, s: f32) -> glam::Quat {
    let mut d = a.dot(b);
    let b = if d < 0.0 {
        d = -d;
        -b
    } else {
        b
    };
    if d > 0.9995 {
        return (a + (b - a) * s).normalize();
    }
    let angle = d.clamp(-1.0, 1.0).acos();
    let sin = angle.sin();
    a * (((1.0 - s) * angle).sin() / sin) + b * ((s * angle).sin() / sin)
}

/// The tracks of an animation on nodes' transforms, and how many morph-weight
/// channels it has (played only on meshes with targets).
pub fn tracks(
    animation: &gltf::Animation<'_>,
    buffers: &[super::document::Buffer<'_>],
) -> Result<(Vec<Track>, Vec<WeightTrack>), ParseError> {
    let mut out = Vec::new();
    let mut weights = Vec::new();
    for (c, channel) in animation.channels().enumerate() {
        let pointer = format!("animations[{}].channels[{c}]", animation.index());
        let path = match channel.target().property() {
            Property::Translation => Path::Translation,
            Property::Rotation => Path::Rotation,
            Property::Scale => Path::Scale,
            Property::MorphTargetWeights => {
                weights.push(weight_track(&channel, buffers, &pointer)?);
                continue;
            }
        };
        let sampler = channel.sampler();
        let fail = |m: String| ParseError::new(0, 0, format!("{pointer}: {m}"));
        let times = accessor::floats(&sampler.input(), buffers, 1)?;
        if let Some(k) = times.windows(2).position(|w| !(w[1] > w[0])) {
            return Err(fail(format!(
                "key times must increase, but key {} is at {} after {}",
                k + 1,
                times[k + 1],
                times[k]
            )));
        }
        let width = if path == Path::Rotation { 4 } else { 3 };
        let values = accessor::floats(&sampler.output(), buffers, width)?;
        let interpolation = sampler.interpolation();
        let per_key = if interpolation == Interpolation::CubicSpline { 3 * width } else { width };
        if values.len() != times.len() * per_key {
            return Err(fail(format!(
                "{} keys but {} values ({} per key expected for {interpolation:?})",
                times.len(),
                values.len() / width,
                per_key / width
            )));
        }
        out.push(Track { node: channel.target().node().index(), path, interpolation, times, values });
    }
    Ok((out, weights))
}

/// Reads a `weights` channel: increasing key times, and a whole number of
/// weights per key (the mesh's target count, checked where the mesh is known).
pub(super) fn weight_track(
    channel: &gltf::animation::Channel<'_>,
    buffers: &[super::document::Buffer<'_>],
    pointer: &str,
) -> Result<WeightTrack, ParseError> {
    let sampler = channel.sampler();
    let fail = |m: String| ParseError::new(0, 0, format!("{pointer}: {m}"));
    let times = accessor::floats(&sampler.input(), buffers, 1)?;
    if let Some(k) = times.windows(2).position(|w| !(w[1] > w[0])) {
        return Err(fail(format!("key times must increase, but key {} is at {} after {}", k + 1, times[k + 1], times[k])));
    }
    let values = accessor::floats(&sampler.output(), buffers, 1)?;
    let interpolation = sampler.interpolation();
    let sets = if interpolation == Interpolation::CubicSpline { 3 } else { 1 };
    let per_key = sets * times.len();
    if times.is_empty() || values.is_empty() || values.len() % per_key != 0 {
        return Err(fail(format!("{} weights for {} keys ({interpolation:?})", values.len(), times.len())));
    }
    let targets = values.len() / per_key;
    Ok(WeightTrack { node: channel.target().node().index(), targets, interpolation, times, values })
}
