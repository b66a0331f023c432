//! A clip: skeleton + motion + what the reader warned about, and the queries the
//! viewer and CLI need (poses, bounds, units).

use std::cell::RefCell;

use crate::error::Warning;
use crate::model::character::{Character, Take};
use crate::model::motion::Motion;
use crate::model::skeleton::Skeleton;
use crate::model::time::Timeline;
use crate::model::up::UpAxis;
use crate::runtime::fk::{Transform, local_to_model, model_from_row, rest_positions};
use crate::runtime::pose::{self, LocalPose};
use crate::runtime::sample::{Interpolation, SampleScratch, sample};
use glam::Vec3;

/// An axis-aligned bounding box.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    /// Smallest corner.
    pub min: Vec3,
    /// Largest corner.
    pub max: Vec3,
}

impl Aabb {
    /// An inverted box that any point enlarges.
    pub const EMPTY: Aabb = Aabb { min: Vec3::splat(f32::INFINITY), max: Vec3::splat(f32::NEG_INFINITY) };

    /// Grows the box to hold `p` (non-finite points are ignored).
    pub fn include(&mut self, p: Vec3) {
        if p.is_finite() {
            self.min = self.min.min(p);
            self.max = self.max.max(p);
        }
    }

    /// True when no point was added.
    pub fn is_empty(&self) -> bool {
        // NaN-safe: an untouched box has min = +inf > max = -inf.
        self.min.x.partial_cmp(&self.max.x).is_none_or(|o| o.is_gt())
    }

    /// Center, or the origin when empty.
    pub fn center(&self) -> Vec3 {
        if self.is_empty() { Vec3::ZERO } else { (self.min + self.max) * 0.5 }
    }

    /// Edge lengths, or zero when empty.
    pub fn size(&self) -> Vec3 {
        if self.is_empty() { Vec3::ZERO } else { self.max - self.min }
    }

    /// The box with both corners multiplied by a positive `scale` (empty stays empty).
    pub fn scaled(&self, scale: f32) -> Aabb {
        if self.is_empty() { *self } else { Aabb { min: self.min * scale, max: self.max * scale } }
    }

    /// The box moved by `offset` (empty stays empty).
    pub fn translated(&self, offset: Vec3) -> Aabb {
        if self.is_empty() { *self } else { Aabb { min: self.min + offset, max: self.max + offset } }
    }

    /// The smallest box holding both (an empty one adds nothing).
    pub fn union(&self, other: &Aabb) -> Aabb {
        let mut out = *self;
        if !other.is_empty() {
            out.include(other.min);
            out.include(other.max);
        }
        out
    }
}

/// A guess of the length unit a file uses, from its skeleton's rest height.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Units {
    /// Metres (a person is ~1.7 units tall).
    Meters,
    /// Centimetres (~170).
    Centimeters,
    /// Millimetres (~1700).
    Millimeters,
    /// Decimetres (~17; MakeHuman exports).
    Decimeters,
    /// Inches (~50–100).
    Inches,
    /// The CMU motion-capture scale, inches / 0.45 (the `length 0.45` of CMU's
    /// ASF files, kept by the common BVH conversions): a person is ~30 units.
    CmuInches,
    /// Nothing plausible; treated as metres.
    Unknown,
}

impl Units {
    /// Guesses the unit from the height of a humanoid in file units.
    pub fn guess(extent: f32) -> Units {
        match extent {
            e if !(e.is_finite()) => Units::Unknown,
            e if (0.25..4.0).contains(&e) => Units::Meters,
            e if (10.0..20.0).contains(&e) => Units::Decimeters,
            // A 20–45 unit humanoid is 0.5–1.1 m in inches, implausible, but 1.1–2.5 m
            // at the CMU scale.
            e if (20.0..45.0).contains(&e) => Units::CmuInches,
            e if (45.0..110.0).contains(&e) => Units::Inches,
            e if (110.0..400.0).contains(&e) => Units::Centimeters,
            e if (400.0..4000.0).contains(&e) => Units::Millimeters,
            _ => Units::Unknown,
        }
    }

    /// Metres per file unit.
    pub fn meters_per_unit(self) -> f32 {
        match self {
            Units::Meters | Units::Unknown => 1.0,
            Units::Decimeters => 0.1,
            Units::Centimeters => 0.01,
            Units::Millimeters => 0.001,
            Units::Inches => 0.0254,
            Units::CmuInches => 0.0254 / 0.45,
        }
    }

    /// Short name: "m", "dm", "cm", "mm", "in", "cmu" (inches / 0.45), "unknown".
    pub fn name(self) -> &'static str {
        match self {
            Units::Meters => "m",
            Units::Decimeters => "dm",
            Units::Centimeters => "cm",
            Units::Millimeters => "mm",
            Units::Inches => "in",
            Units::CmuInches => "cmu",
            Units::Unknown => "unknown",
        }
    }
}

thread_local! {
    /// Scratch for the convenience queries that return model transforms.
    static SCRATCH: RefCell<(LocalPose, SampleScratch, Vec<Transform>)> = RefCell::new(Default::default());
}

/// Why a skeleton and a motion do not make a clip.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("the motion has {motion} channels per frame but the skeleton has {skeleton}")]
pub struct ClipError {
    /// Channels per motion row.
    pub motion: usize,
    /// Channels the skeleton's joints have.
    pub skeleton: usize,
}

/// A skeleton with its motion, as read from one file (or a skeleton file and a
/// motion file).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Clip {
    skeleton: Skeleton,
    motion: Motion,
    /// Non-fatal problems the reader found.
    pub warnings: Vec<Warning>,
    /// What the file says about itself (name, version, units, documentation…), as
    /// `(key, value)` pairs in file order, for the inspector.
    pub metadata: Vec<(String, String)>,
    /// The look and other animations of a character file (glTF); `None` for
    /// motion-only formats.
    pub character: Option<std::sync::Arc<Character>>,
    /// Which of the character's takes the motion is.
    take: usize,
}

impl Clip {
    /// Pairs a skeleton with its motion; the motion's rows must be exactly as wide
    /// as the skeleton's channels.
    pub fn new(skeleton: Skeleton, motion: Motion) -> Result<Clip, ClipError> {
        if motion.channel_count() != skeleton.channel_count() {
            return Err(ClipError { motion: motion.channel_count(), skeleton: skeleton.channel_count() });
        }
        Ok(Clip { skeleton, motion, warnings: Vec::new(), metadata: Vec::new(), character: None, take: 0 })
    }

    /// The same clip carrying `character` (its look and takes, whose motions must
    /// fit this skeleton); the motion stays as it is.
    pub fn with_character(mut self, character: std::sync::Arc<Character>) -> Clip {
        self.character = Some(character);
        self
    }

    /// Keeps `other`'s character (look and takes) on this clip, an edit of it,
    /// when the two skeletons are the same joints and channels.
    pub fn keep_character_of(&mut self, other: &Clip) {
        if self.skeleton == other.skeleton {
            self.character = other.character.clone();
            self.take = other.take;
        }
    }

    /// The character's animations (empty for motion-only formats).
    pub fn takes(&self) -> &[Take] {
        self.character.as_deref().map_or(&[], |c| c.takes.as_slice())
    }

    /// Which of the character's takes the motion is (0 when there are none).
    pub(crate) fn take_index(&self) -> usize {
        self.take
    }

    /// Says that the motion is take `index` of the character; false (and no
    /// change) unless it is 0 or one of the character's takes.
    pub(crate) fn set_take_index(&mut self, index: usize) -> bool {
        if index != 0 && index >= self.takes().len() {
            return false;
        }
        self.take = index;
        true
    }

    /// The look's morph-target weights at `time` seconds into `out`, one per
    /// target ([`crate::model::character::Morph`]): the take's where it sets
    /// them and the motion still has its frames (not trimmed or resampled),
    /// else the rest weights. False when the look has no morph targets.
    pub fn morph_weights_at(&self, time: f64, out: &mut Vec<f32>) -> bool {
        let Some(character) = self.character.as_deref() else { return false };
        let Some(morph) = character.look.as_ref().and_then(|l| l.morph.as_ref()) else { return false };
        let targets = morph.targets.len();
        let take = character.takes.get(self.take).filter(|t| {
            t.motion.frame_count() == self.motion.frame_count() && t.motion.frame_time() == self.motion.frame_time()
        });
        if !take.is_some_and(|t| t.weights_at(time, targets, out)) {
            out.clear();
            out.extend_from_slice(&morph.rest);
        }
        true
    }

    /// The name of the take the motion is, when the clip has takes.
    pub fn take_name(&self) -> Option<&str> {
        self.takes().get(self.take).map(|t| t.name.as_str())
    }

    /// Makes the take named `name` the clip's motion; false (and no change) when
    /// there is none of that name or its motion does not fit the skeleton.
    pub fn set_take(&mut self, name: &str) -> bool {
        let Some((index, take)) = self.takes().iter().enumerate().find(|(_, t)| t.name == name) else {
            return false;
        };
        if take.motion.channel_count() != self.skeleton.channel_count() {
            return false;
        }
        self.motion = take.motion.clone();
        self.take = index;
        true
    }

    /// The same clip with these warnings.
    pub fn with_warnings(mut self, warnings: Vec<Warning>) -> Clip {
        self.warnings = warnings;
        self
    }

    /// The joints.
    pub fn skeleton(&self) -> &Skeleton {
        &self.skeleton
    }

    /// Frame time, angle unit and channel values.
    pub fn motion(&self) -> &Motion {
        &self.motion
    }

    /// Number of frames.
    pub fn frame_count(&self) -> usize {
        self.motion().frame_count()
    }

    /// Seconds per frame.
    pub fn frame_time(&self) -> f64 {
        self.motion.frame_time()
    }

    /// Frames per second.
    pub fn fps(&self) -> f64 {
        1.0 / self.motion.frame_time()
    }

    /// The clip's frames in time (the one time↔frame rule).
    pub fn timeline(&self) -> Timeline {
        self.motion.timeline()
    }

    /// Time of the last frame: `(frames - 1) × frame_time`, 0 for 0 or 1 frame.
    pub fn duration(&self) -> f64 {
        self.timeline().duration()
    }

    /// One frame's channel values (empty when out of range).
    pub fn channel_values(&self, frame: usize) -> &[f32] {
        self.motion().row(frame)
    }

    /// The local pose of a frame, into `out`. A frame past the end gives the rest pose.
    pub fn local_pose_into(&self, frame: usize, out: &mut LocalPose) {
        pose::from_row(&self.skeleton, self.motion().row(frame), self.motion.angle_unit(), out);
    }

    /// The local pose at a time in seconds, interpolated or nearest, into `out`.
    pub fn sample_local_into(
        &self,
        time: f64,
        interpolation: Interpolation,
        scratch: &mut SampleScratch,
        out: &mut LocalPose,
    ) {
        sample(&self.skeleton, &self.motion, time, interpolation, scratch, out);
    }

    /// Model transforms of every joint (End Sites included) at a frame, into `out`:
    /// the frame's local pose through the local-to-model pass ([`model_from_row`]).
    pub fn world_transforms_into(&self, frame: usize, out: &mut Vec<Transform>) {
        SCRATCH.with_borrow_mut(|(local, _, _)| {
            model_from_row(&self.skeleton, self.motion.row(frame), self.motion.angle_unit(), local, out);
        });
    }

    /// Model positions of every joint at a frame, into `out` (no allocation once sized).
    pub fn world_positions_into(&self, frame: usize, out: &mut Vec<Vec3>) {
        SCRATCH.with_borrow_mut(|(local, _, model)| {
            model_from_row(&self.skeleton, self.motion.row(frame), self.motion.angle_unit(), local, model);
            out.clear();
            out.extend(model.iter().map(|t| t.translation));
        });
    }

    /// Model positions of every joint at a frame.
    pub fn world_positions(&self, frame: usize) -> Vec<Vec3> {
        let mut out = Vec::new();
        self.world_positions_into(frame, &mut out);
        out
    }

    /// Model transforms at a time in seconds, interpolated or nearest, into `out`.
    pub fn sample_world_transforms_into(&self, time: f64, interpolation: Interpolation, out: &mut Vec<Transform>) {
        SCRATCH.with_borrow_mut(|(local, scratch, _)| {
            self.sample_local_into(time, interpolation, scratch, local);
            local_to_model(&self.skeleton, local, out);
        });
    }

    /// Model positions at a time in seconds, into `out`.
    pub fn sample_world_positions_into(&self, time: f64, interpolation: Interpolation, out: &mut Vec<Vec3>) {
        SCRATCH.with_borrow_mut(|(local, scratch, model)| {
            self.sample_local_into(time, interpolation, scratch, local);
            local_to_model(&self.skeleton, local, model);
            out.clear();
            out.extend(model.iter().map(|t| t.translation));
        });
    }

    /// Calls `visit(frame, positions)` for every frame with the model positions of
    /// all joints, computing several frames at once (much faster than a loop over
    /// [`Clip::world_positions_into`]).
    pub fn for_each_frame_positions(&self, visit: impl FnMut(usize, &[Vec3])) {
        crate::runtime::batch::for_each_frame_positions(&self.skeleton, &self.motion, visit);
    }

    /// The pose a skin is bound in (a generated body is built around it): the model
    /// transforms of frame 0, or of the rest pose when there are no frames (file
    /// units; a rest pose with zero offsets and positions in the channels would
    /// have no bones).
    pub fn bind_pose(&self) -> Vec<Transform> {
        let mut bind = Vec::new();
        if self.frame_count() > 0 {
            self.world_transforms_into(0, &mut bind);
        } else {
            crate::runtime::fk::local_to_model(&self.skeleton, &LocalPose::rest(&self.skeleton), &mut bind);
        }
        bind
    }

    /// Bounding box of all joints over all frames (the rest pose when there are no
    /// frames). Non-finite positions are skipped.
    pub fn bounds(&self) -> Aabb {
        let mut bounds = Aabb::EMPTY;
        if self.frame_count() == 0 {
            rest_positions(&self.skeleton).into_iter().for_each(|p| bounds.include(p));
            return bounds;
        }
        let runs = crate::runtime::batch::fold_frame_positions(
            &self.skeleton,
            &self.motion,
            || Aabb::EMPTY,
            |b, _, positions| positions.iter().for_each(|&p| b.include(p)),
        );
        runs.iter().fold(bounds, |a, b| a.union(b))
    }

    /// Bounding box of the first frame's pose (the rest pose when there are no
    /// frames), without the root joints when there are others: a root is inside the
    /// body for most skeletons, but some (Bandai-Namco's `joint_Root`) sit on the
    /// floor far from it and would inflate every size.
    pub fn first_pose_bounds(&self) -> Aabb {
        let positions = if self.frame_count() == 0 { rest_positions(&self.skeleton) } else { self.world_positions(0) };
        let skip_roots = self.skeleton().joints().iter().any(|j| j.parent.is_some());
        let mut b = Aabb::EMPTY;
        for (joint, p) in self.skeleton().joints().iter().zip(positions) {
            if !(skip_roots && joint.parent.is_none()) {
                b.include(p);
            }
        }
        b
    }

    /// Largest edge of the first pose's bounding box: a humanoid's height or arm span.
    pub fn pose_extent(&self) -> f32 {
        self.first_pose_bounds().size().max_element()
    }

    /// The first pose's height along the guessed up axis ([`Clip::up_axis`]).
    pub fn pose_height(&self) -> f32 {
        self.pose_height_along(self.up_axis())
    }

    /// The first pose's height along `up`; its largest edge when it is lying down
    /// (height under a quarter of the largest edge).
    pub fn pose_height_along(&self, up: UpAxis) -> f32 {
        let size = self.first_pose_bounds().size();
        let height = up.height(size);
        if height >= 0.25 * size.max_element() { height } else { size.max_element() }
    }

    /// Which file axis points up, guessed from the motion ([`UpAxis::guess`]).
    pub fn up_axis(&self) -> UpAxis {
        if self.character.is_some() {
            return UpAxis::Y;
        }
        UpAxis::guess(self)
    }

    /// Guess of the file's length unit from the height of the first pose.
    pub fn units(&self) -> Units {
        if self.character.is_some() {
            return Units::Meters;
        }
        Units::guess(self.pose_height())
    }

    /// Guess of the file's length unit from the first pose's height along `up`.
    pub fn units_along(&self, up: UpAxis) -> Units {
        Units::guess(self.pose_height_along(up))
    }
}

#[cfg(test)]
mod tests {
    use super::{Aabb, Units};
    use glam::Vec3;

    #[test]
    fn boxes_scale_move_and_join_and_empty_ones_stay_empty() {
        let a = Aabb { min: Vec3::new(-1.0, 0.0, -1.0), max: Vec3::new(1.0, 2.0, 1.0) };
        assert_eq!(
            a.scaled(0.5).translated(Vec3::X),
            Aabb { min: Vec3::new(0.5, 0.0, -0.5), max: Vec3::new(1.5, 1.0, 0.5) }
        );
        let b = Aabb { min: Vec3::splat(3.0), max: Vec3::splat(4.0) };
        assert_eq!(a.union(&b), Aabb { min: a.min, max: Vec3::splat(4.0) });
        assert_eq!(a.union(&Aabb::EMPTY), a);
        assert!(Aabb::EMPTY.scaled(2.0).translated(Vec3::ONE).is_empty());
        assert_eq!(Aabb::EMPTY.union(&b), b);
    }

    #[test]
    fn unit_guesses_put_a_person_near_human_height() {
        for (height, units) in [
            (1.7, Units::Meters),
            (17.0, Units::Decimeters),
            (30.0, Units::CmuInches),
            (67.0, Units::Inches),
            (170.0, Units::Centimeters),
            (1700.0, Units::Millimeters),
        ] {
            assert_eq!(Units::guess(height), units, "{height}");
            let metres = height * units.meters_per_unit();
            assert!((1.5..1.95).contains(&metres), "{height} {units:?}: {metres} m");
        }
        assert_eq!(Units::guess(f32::NAN), Units::Unknown);
        assert_eq!(Units::guess(1e9), Units::Unknown);
    }
}
