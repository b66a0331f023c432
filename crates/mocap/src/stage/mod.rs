//! Several characters on one stage: each asset (a clip or a model) scaled to metres by its guessed
//! unit, placed by a layout (side by side or overlaid) plus a hand-set offset, and
//! one timeline over all of them. Shared by the viewer and `mocap render`; each
//! keeps what only it needs in an actor's `extra`.

pub mod arrange;

use crate::model::asset::Asset;
use crate::model::clip::{Aabb, Clip, Units};
use crate::model::mesh::{Model, MorphSample};
use crate::model::time::Timeline;
use crate::model::up::UpAxis;
use crate::runtime::fk::{Transform, local_to_model};
use crate::runtime::pose::LocalPose;
use crate::runtime::sample::{Interpolation, SampleScratch};
use crate::stage::arrange::spread;
use glam::Vec3;

/// Gap between spread lanes, as a share of the largest character's size.
pub const GAP_PER_EXTENT: f32 = 0.5;

/// How characters are placed.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Layout {
    /// Side by side along X, wrapping into rows past eight (see [`crate::stage::arrange::spread`]).
    #[default]
    Spread,
    /// Every layout offset zero, to compare motions in place.
    Overlay,
}

impl Layout {
    /// The name used in the fragment, on command lines and from JavaScript.
    pub fn name(self) -> &'static str {
        match self {
            Layout::Spread => "spread",
            Layout::Overlay => "overlay",
        }
    }

    /// Reads `spread` or `overlay`.
    pub fn parse(name: &str) -> Option<Layout> {
        match name {
            "spread" => Some(Layout::Spread),
            "overlay" => Some(Layout::Overlay),
            _ => None,
        }
    }
}

/// Reusable buffers for posing actors.
#[derive(Clone, Debug, Default)]
pub struct PoseScratch {
    /// The last local pose sampled ([`Actor::sample_local`]).
    pub local: LocalPose,
    sample: SampleScratch,
}

/// An asset placed in the shared world (metres, Y up), with what is derived from it
/// once, and `extra` for the caller.
#[derive(Clone, Debug)]
pub struct Actor<E> {
    /// File name as given when loading.
    pub name: String,
    /// The clip or model.
    pub asset: Asset,
    /// Guessed length unit (from the height along [`Actor::up`]).
    pub units: Units,
    /// Which file axis points up (guessed for a clip, Y for a model; see
    /// [`Actor::set_up`]).
    pub up: UpAxis,
    /// Bounds of all joints over all frames, file units.
    pub bounds: Aabb,
    /// Size of the first pose in file units (a humanoid's height; 1 when unknown).
    pub extent: f32,
    /// Whether it is drawn (hidden actors keep their lane and their time).
    pub visible: bool,
    /// Offset set by hand in metres, added to the layout's.
    pub offset: Vec3,
    /// Offset the layout gave it in metres (see [`Stage::arrange`]).
    pub layout_offset: Vec3,
    /// What the caller keeps per actor.
    pub extra: E,
}

impl<E> Actor<E> {
    /// A visible actor at the origin.
    pub fn new(name: &str, asset: impl Into<Asset>, extra: E) -> Actor<E> {
        let asset = asset.into();
        let extent = asset.extent();
        let extent = if extent.is_finite() && extent > 0.0 { extent } else { 1.0 };
        let (up, units) = match asset.clip() {
            Some(clip) => {
                let up = clip.up_axis();
                (up, clip.units_along(up))
            }
            None => (UpAxis::Y, asset.units()),
        };
        Actor {
            name: name.to_owned(),
            units,
            up,
            bounds: asset.bounds(),
            asset,
            extent,
            visible: true,
            offset: Vec3::ZERO,
            layout_offset: Vec3::ZERO,
            extra,
        }
    }

    /// Metres per file unit (from the guessed unit).
    pub fn scale(&self) -> f32 {
        self.units.meters_per_unit()
    }

    /// Where the clip's origin stands: layout offset plus the hand-set one (metres).
    pub fn placement(&self) -> Vec3 {
        self.layout_offset + self.offset
    }

    /// File units to the world: the up axis turned to Y, the unit's scale, then
    /// the placement.
    pub fn world_matrix(&self) -> glam::Mat4 {
        glam::Mat4::from_scale_rotation_translation(Vec3::splat(self.scale()), self.up.rotation(), self.placement())
    }

    /// A point in the world (metres) in the file's units and axes
    /// ([`Actor::world_matrix`] undone).
    pub fn to_file(&self, world: Vec3) -> Vec3 {
        self.up.from_y_up((world - self.placement()) / self.scale())
    }

    /// Sets which file axis points up, and guesses the unit again from the height
    /// along it (a model stays Y-up). The caller arranges the stage again.
    pub fn set_up(&mut self, up: UpAxis) {
        if let Some(clip) = self.asset.clip() {
            self.units = clip.units_along(up);
            self.up = up;
        }
    }

    /// Bounds of the whole motion in metres, Y up, before placement.
    pub fn local_bounds(&self) -> Aabb {
        self.up.box_to_y_up(self.bounds).scaled(self.scale())
    }

    /// Bounds of the whole motion in metres, where it stands.
    pub fn world_bounds(&self) -> Aabb {
        self.local_bounds().translated(self.placement())
    }

    /// Height of what the actor stands on, in file units along the world's up
    /// (after [`Actor::up`]): a clip's lowest point
    /// over its motion; a model's lowest point in its first key frame (its
    /// standing pose: MD2 models are centred on their origin, and frames such
    /// as deaths sink below their feet). 0 when unknown.
    pub fn ground(&self) -> f32 {
        let y = match self.asset.model() {
            Some(m) => m.mesh.first_bounds().min.y,
            None => self.up.box_to_y_up(self.bounds).min.y,
        };
        if y.is_finite() { y } else { 0.0 }
    }

    /// [`Actor::ground`] in metres, where the actor stands.
    pub fn world_ground(&self) -> f32 {
        self.ground() * self.scale() + self.placement().y
    }

    /// Size of the first pose in metres.
    pub fn world_extent(&self) -> f32 {
        self.extent * self.scale()
    }

    /// The clip, when the actor is a skeleton.
    pub fn clip(&self) -> Option<&Clip> {
        self.asset.clip()
    }

    /// The model, when the actor is a mesh.
    pub fn model(&self) -> Option<&Model> {
        self.asset.model()
    }

    /// The frame of this asset shown at `time` (its own frame time; past its end the
    /// last); for a model, counted from the first frame of its animation.
    pub fn frame_at(&self, time: f64) -> usize {
        self.asset.timeline().frame_at(time)
    }

    /// The model's key frames at `time` (`None` for a clip): the same rule and
    /// interpolation choice as [`Actor::pose_at`].
    pub fn morph_at(&self, time: f64, interpolation: Interpolation) -> Option<MorphSample> {
        self.model().map(|m| m.frames_at(time, interpolation))
    }

    /// Model transforms at `time` in metres, placed: interpolated, or the frame
    /// shown ([`Interpolation::Step`]). Past its end a clip holds its last pose. A
    /// model has no joints: `out` is left empty.
    pub fn pose_at(
        &self,
        time: f64,
        interpolation: Interpolation,
        scratch: &mut PoseScratch,
        out: &mut Vec<Transform>,
    ) {
        if !self.sample_local(time, interpolation, scratch) {
            out.clear();
            return;
        }
        let local = std::mem::take(&mut scratch.local);
        self.place(&local, out);
        scratch.local = local;
    }

    /// Samples the clip at `time` into `scratch`'s local pose ([`PoseScratch::local`]),
    /// the seam where IK and edits change it before [`Actor::place`]; false for a model.
    pub fn sample_local(&self, time: f64, interpolation: Interpolation, scratch: &mut PoseScratch) -> bool {
        let Some(clip) = self.clip() else { return false };
        clip.sample_local_into(time, interpolation, &mut scratch.sample, &mut scratch.local);
        true
    }

    /// Model transforms of a local pose of this clip, in metres and placed (empty
    /// for a model).
    pub fn place(&self, local: &LocalPose, out: &mut Vec<Transform>) {
        let Some(clip) = self.clip() else {
            out.clear();
            return;
        };
        local_to_model(clip.skeleton(), local, out);
        let (scale, at, up) = (self.scale(), self.placement(), self.up);
        let turn = up.rotation();
        for t in out.iter_mut() {
            t.translation = up.to_y_up(t.translation) * scale + at;
            if up != UpAxis::Y {
                t.rotation = turn * t.rotation;
            }
            t.scale *= scale;
        }
    }
}

/// Every open actor, in order, and how they are placed.
#[derive(Clone, Debug)]
pub struct Stage<E> {
    /// The actors (index 0 is "character 1" in the fragment).
    pub actors: Vec<Actor<E>>,
    /// Spread or overlay.
    pub layout: Layout,
}

impl<E> Default for Stage<E> {
    fn default() -> Stage<E> {
        Stage { actors: Vec::new(), layout: Layout::default() }
    }
}

impl<E> Stage<E> {
    /// A stage holding `actors` in `layout`, arranged.
    pub fn new(actors: Vec<Actor<E>>, layout: Layout) -> Stage<E> {
        let mut stage = Stage { actors, layout };
        stage.arrange();
        stage
    }

    /// Closes everything and opens `actors`.
    pub fn replace(&mut self, actors: Vec<Actor<E>>) {
        self.actors = actors;
        self.arrange();
    }

    /// Adds an actor after the open ones.
    pub fn add(&mut self, actor: Actor<E>) {
        self.actors.push(actor);
        self.arrange();
    }

    /// Closes actor `index`; returns whether it existed.
    pub fn remove(&mut self, index: usize) -> bool {
        if index >= self.actors.len() {
            return false;
        }
        self.actors.remove(index);
        self.arrange();
        true
    }

    /// Plays animation `name` on actor `index` — a model's named frames (`all`:
    /// every frame), or one of a character clip's takes ([`crate::Clip::set_take`])
    /// — with its bounds (so the floor and lanes follow it); false (no change)
    /// when there is no such actor or animation.
    pub fn set_animation(&mut self, index: usize, name: &str) -> bool {
        let Some(actor) = self.actors.get_mut(index) else { return false };
        let done = match &mut actor.asset {
            crate::Asset::Model(model) => model.set_animation_by_name(name),
            crate::Asset::Clip(clip) => clip.set_take(name),
        };
        if !done {
            return false;
        }
        actor.bounds = actor.asset.bounds();
        self.arrange();
        true
    }

    /// Sets which file axis points up in clip `index` ([`Actor::set_up`]) and
    /// arranges again; false (no change) when there is no such clip.
    pub fn set_up_axis(&mut self, index: usize, up: UpAxis) -> bool {
        let Some(actor) = self.actors.get_mut(index).filter(|a| a.clip().is_some()) else { return false };
        actor.set_up(up);
        self.arrange();
        true
    }

    /// Shows or hides actor `index`; returns whether it exists.
    pub fn set_visible(&mut self, index: usize, visible: bool) -> bool {
        self.actors.get_mut(index).map(|c| c.visible = visible).is_some()
    }

    /// Switches the layout and places the actors again.
    pub fn set_layout(&mut self, layout: Layout) {
        self.layout = layout;
        self.arrange();
    }

    /// Recomputes every actor's layout offset. Spread lanes count hidden actors too,
    /// so hiding one moves no other.
    ///
    /// Heights: in Spread every actor stands on the floor (its [`Actor::ground`]
    /// at height 0), so clips whose files put the floor at different heights, and
    /// models (whose origin is their centre), stand side by side. In Overlay every
    /// actor stays where its file puts it, to compare in place (a skeleton
    /// captured from a model stays inside it), over a floor under the lowest
    /// ground ([`Stage::floor_height`]).
    pub fn arrange(&mut self) {
        let offsets = match self.layout {
            Layout::Overlay => vec![Vec3::ZERO; self.actors.len()],
            Layout::Spread => {
                let bounds: Vec<Aabb> = self.actors.iter().map(Actor::local_bounds).collect();
                let extent = self.actors.iter().map(Actor::world_extent).fold(0.0f32, f32::max);
                let extent = if extent.is_finite() && extent > 0.0 { extent } else { 1.0 };
                spread(&bounds, extent * GAP_PER_EXTENT)
            }
        };
        let spread_out = self.layout == Layout::Spread;
        for (c, o) in self.actors.iter_mut().zip(offsets) {
            let lift = if spread_out { -c.ground() * c.scale() } else { 0.0 };
            c.layout_offset = Vec3::new(o.x, if lift.is_finite() { lift } else { 0.0 }, o.z);
        }
    }

    /// Height of the floor in metres: the lowest ground a visible actor stands on
    /// ([`Actor::world_ground`]); 0 when none is visible.
    pub fn floor_height(&self) -> f32 {
        let y = self.visible().map(|(_, c)| c.world_ground()).fold(f32::INFINITY, f32::min);
        if y.is_finite() { y } else { 0.0 }
    }

    /// What a floor is laid under: [`Stage::bounds`] with its bottom at
    /// [`Stage::floor_height`] (empty when nothing is visible).
    pub fn floor_bounds(&self) -> Aabb {
        let b = self.bounds();
        if b.is_empty() {
            return b;
        }
        let floor = self.floor_height();
        Aabb { min: b.min.with_y(floor), max: b.max.with_y(b.max.y.max(floor)) }
    }

    /// The visible actors with their indices.
    pub fn visible(&self) -> impl Iterator<Item = (usize, &Actor<E>)> {
        self.actors.iter().enumerate().filter(|(_, c)| c.visible)
    }

    /// Union of the visible actors' motion bounds, in metres where they stand.
    pub fn bounds(&self) -> Aabb {
        self.visible().fold(Aabb::EMPTY, |union, (_, c)| union.union(&c.world_bounds()))
    }

    /// Largest first-pose size among the visible actors in metres (1 when none).
    pub fn extent(&self) -> f32 {
        let e = self.visible().map(|(_, c)| c.world_extent()).fold(0.0f32, f32::max);
        if e.is_finite() && e > 0.0 { e } else { 1.0 }
    }

    /// The longest asset's duration in seconds (hidden actors included).
    pub fn duration(&self) -> f64 {
        self.actors.iter().map(|c| c.asset.duration()).filter(|d| d.is_finite()).fold(0.0, f64::max)
    }

    /// The shared timeline: frames in the frame time of actor `reference` (the first
    /// when out of range), as many as it takes to reach the end of the longest clip
    /// ([`Timeline::frames_to_reach`]). With one actor it is that clip's timeline.
    pub fn timeline(&self, reference: usize) -> Option<Timeline> {
        let r = self.actors.get(reference).or(self.actors.first())?.asset.timeline();
        let duration = self.duration();
        let frames = if duration > 0.0 {
            r.frames_to_reach(duration)
        } else {
            self.actors.iter().map(|c| c.asset.frame_count()).max().unwrap_or(0).min(1)
        };
        Some(Timeline::new(r.frame_time(), frames.max(r.frames())))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn clip(frames: usize, frame_time: f64, height: f32) -> Clip {
        let mut text = format!(
            "HIERARCHY\nROOT a\n{{\nOFFSET 0 0 0\nCHANNELS 1 Xposition\nJOINT b\n{{\nOFFSET 0 0 0\nEnd Site\n{{\nOFFSET 0 {height} 0\n}}\n}}\n}}\nMOTION\nFrames: {frames}\nFrame Time: {frame_time}\n"
        );
        for f in 0..frames {
            text.push_str(&format!("{f}\n"));
        }
        crate::formats::bvh::parse(text.as_bytes()).unwrap()
    }

    #[test]
    fn actors_stand_on_one_floor() {
        // A model centred on its origin (Y-up, Quake units): standing from -24 to
        // 32, its death frame reaching down to -32.
        let stand = vec![Vec3::new(0.0, -24.0, 0.0), Vec3::new(10.0, 32.0, 0.0), Vec3::new(-10.0, 0.0, 5.0)];
        let death = vec![Vec3::new(0.0, -32.0, 0.0), Vec3::new(30.0, -28.0, 0.0), Vec3::new(-10.0, -30.0, 5.0)];
        let md2 =
            crate::formats::md2::build(&[("stand01".into(), stand), ("death01".into(), death)], &[[0, 1, 2]]).unwrap();
        let model = Model::new(crate::model::mesh::MorphMesh::from_md2(&md2), None);
        // A clip whose feet hang 1.7 below its root.
        let hanging = clip(2, 0.1, -1.7);
        let mut stage = Stage::new(vec![Actor::new("m", model, ()), Actor::new("c", hanging, ())], Layout::Spread);
        // Spread: each stands on the floor, at 0.
        for a in &stage.actors {
            assert!(a.world_ground().abs() < 1e-4, "{}: ground at {}", a.name, a.world_ground());
        }
        assert!(stage.floor_height().abs() < 1e-4);
        assert!(stage.actors[0].world_bounds().min.y < -0.1, "its death frame sinks below the floor");
        assert_eq!(stage.floor_bounds().min.y, stage.floor_height());
        assert!(stage.floor_bounds().max.y >= stage.bounds().max.y);
        // Another animation does not move the model up or down.
        let lift = stage.actors[0].placement().y;
        assert!(stage.set_animation(0, "death"));
        assert_eq!(stage.actors[0].placement().y, lift);
        // Overlay: both stay where their files put them, over a floor under the
        // lower ground (the clip's feet, 1.7 below its root).
        stage.set_layout(Layout::Overlay);
        assert!(stage.actors.iter().all(|a| a.placement() == Vec3::ZERO));
        assert!((stage.floor_height() + 1.7).abs() < 1e-4, "the floor under the clip's feet: {}", stage.floor_height());
        // Nothing visible: the floor at 0.
        assert_eq!(Stage::<()>::default().floor_height(), 0.0);
    }

    #[test]
    fn one_timeline_spans_the_longest_clip_in_the_reference_frame_time() {
        let stage = Stage::new(
            vec![Actor::new("a", clip(11, 0.1, 1.7), ()), Actor::new("b", clip(121, 1.0 / 120.0, 1.7), ())],
            Layout::Spread,
        );
        assert_eq!(stage.timeline(0).unwrap().frames(), 11);
        assert_eq!(stage.timeline(1).unwrap().frames(), 121);
        let long = Stage::new(
            vec![Actor::new("a", clip(3, 0.1, 1.7), ()), Actor::new("b", clip(31, 0.0333333, 1.7), ())],
            Layout::Spread,
        );
        assert_eq!(long.timeline(0).unwrap().frames(), 11, "1 s in 0.1 s frames, within the snap of 0.999999 s");
        assert!(Stage::<()>::default().timeline(0).is_none());
    }

    #[test]
    fn spread_places_actors_apart_and_overlay_together() {
        let mut stage = Stage::new(
            vec![Actor::new("a", clip(2, 0.1, 1.7), ()), Actor::new("b", clip(2, 0.1, 170.0), ())],
            Layout::Spread,
        );
        assert_eq!(stage.actors[1].units, Units::Centimeters);
        assert!((stage.actors[1].world_extent() - 1.7).abs() < 1e-4);
        assert!(stage.actors[0].placement().x < stage.actors[1].placement().x);
        stage.set_layout(Layout::Overlay);
        assert!(stage.actors.iter().all(|a| a.placement() == Vec3::ZERO));
        let mut out = Vec::new();
        stage.actors[1].pose_at(0.05, Interpolation::Linear, &mut PoseScratch::default(), &mut out);
        assert!((out[2].translation.y - 1.7).abs() < 1e-4, "{:?}", out[2]);
    }
}
