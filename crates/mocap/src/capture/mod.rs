//! Skeletal motion from a vertex-animated model (a Quake 2 MD2): the capture.
//!
//! Inputs: the model's vertex frames and a [`Rig`] (a skeleton posed inside its
//! set-up frame, bone spins, vertex binding; [`Rig::fit`] makes one for any
//! humanoid). Output: a [`Capture`]: a skeletal [`Clip`] (joint rotations
//! relative to the parent, the root's translation; one frame per model frame at
//! 10 fps) with the model's animations as frame ranges, every joint's position
//! and every bone's rotation per frame, and a [`Report`].
//!
//! Per joint, four tracked vertices ([`track::joint_sets`]) keep their set-up
//! distances to it. Their places in each frame are, by default, the best fit of
//! the rigid part they belong to, its shape averaged over all frames
//! ([`shape::RigidShape`]; MD2's 8-bit noise is divided among the part's
//! vertices), or their stored places ([`Options::average_shapes`] off). In each
//! frame the joint is where the four spheres meet, found
//! by successive approximation ([`spheres::successive`], started from the joint's
//! place in the previous frame) and checked by the closed form
//! ([`spheres::least_squares`]): the report gives where they disagree, and each
//! joint's residual (how far the solved joint is from its four spheres). A joint
//! with no valid vertex set, or a frame that does not converge, takes the
//! closed-form answer if it has one, else follows its parent rigidly; the report
//! says which. A bone's rotation comes from its direction and its spin (tracked
//! by a triangle, [`track::spin_triangle`]); a joint with two or more children
//! takes its rotation from two of its bones' directions.
//!
//! Work is split by frame ([`Capturer::step`]) so a caller can show progress.
//! Nothing recurses: joints are visited in parent-before-child order.

pub mod frames;
pub mod rig;
pub mod shape;
pub mod spheres;
pub mod track;

mod capturer;
mod report;
mod rotation;

pub use capturer::Capturer;
pub use report::{JointReport, Report};
pub use rig::{Rig, RigError, RigJoint};
pub use rotation::fit_rotation;

use crate::formats::md2::{Animation, Md2};
use crate::model::clip::Clip;
use glam::{Quat, Vec3};

/// The rig a capture uses: a given one, or one fitted into the model's first
/// frame ([`Rig::fit`]: a humanoid, or the given skeleton in the given pose), so
/// the frames are decoded once whichever it is.
#[derive(Clone, Copy, Debug)]
pub enum RigChoice<'a> {
    /// This rig.
    Given(&'a Rig),
    /// Fit one: `None` for the humanoid, else a skeleton and its model transforms.
    Fit(Option<(&'a crate::Skeleton, &'a [crate::Transform])>),
}

impl<'a> From<&'a Rig> for RigChoice<'a> {
    fn from(rig: &'a Rig) -> RigChoice<'a> {
        RigChoice::Given(rig)
    }
}

/// Settings of a capture.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Options {
    /// Largest accepted change of a distance between two tracked vertices over
    /// the frames, as a share of the model's height (MD2 positions are 8-bit:
    /// one step is about 0.4 % of a frame's size).
    pub rigid_tolerance: f32,
    /// Most rounds of successive approximation per joint and frame.
    pub max_rounds: usize,
    /// Vertices tracked per joint: four (the source's method), or more to average
    /// out noise (every one is another sphere in the same iteration).
    pub vertices_per_joint: usize,
    /// Whether the tracked vertices are placed, in each frame, by the best fit of
    /// their rigid part's shape averaged over all frames ([`shape::RigidShape`]),
    /// which divides MD2's 8-bit noise among the part's vertices; false uses each
    /// vertex's stored place as it is (the source's method, noisier).
    pub average_shapes: bool,
}

impl Default for Options {
    fn default() -> Options {
        Options { rigid_tolerance: 0.015, max_rounds: 2000, vertices_per_joint: 4, average_shapes: true }
    }
}

/// Why there is no capture.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("capture: {0}")]
pub struct CaptureError(pub String);

/// A finished capture.
#[derive(Clone, Debug)]
pub struct Capture {
    /// The skeletal clip (rig joints; rotations relative to the parent, root
    /// translation), one frame per model frame, in metres (an MD2's Quake units
    /// read as inches, as the viewer reads the model, so the two stand together).
    pub clip: Clip,
    /// The model's animations, as frame ranges of the clip.
    pub animations: Vec<Animation>,
    /// The model's frame names.
    pub frame_names: Vec<String>,
    /// Per frame, every joint's position (mesh units, Y-up).
    pub positions: Vec<Vec<Vec3>>,
    /// Per frame, every joint's rotation from the set-up pose (world).
    pub rotations: Vec<Vec<Quat>>,
    /// The report.
    pub report: Report,
    /// Metres per mesh unit (the clip is in metres, positions in mesh units).
    pub meters_per_unit: f32,
    /// The rig used (given or fitted).
    pub rig: Rig,
}

impl Capture {
    /// The clip of one animation (its frame range), or `None` without one of that name.
    pub fn animation_clip(&self, name: &str) -> Option<Clip> {
        let a = self.animations.iter().find(|a| a.name == name)?;
        crate::ops::edit::apply(&self.clip, &crate::ops::edit::Edit::Trim { first: a.first, last: a.last }).ok()
    }

    /// The capture in the source's per-frame layout ([`frames`]).
    pub fn frames(&self) -> frames::CaptureFrames {
        let bones = self.report.joints.iter().map(|j| j.name.clone()).collect();
        let records = self
            .positions
            .iter()
            .zip(&self.rotations)
            .enumerate()
            .map(|(f, (p, r))| {
                frames::FrameRecord::from_y_up(self.frame_names.get(f).cloned().unwrap_or_default(), p, r)
            })
            .collect();
        frames::CaptureFrames { bones, frames: records }
    }
}

/// Every frame's vertex positions (Y-up, mesh units).
pub fn model_frames(md2: &Md2) -> Vec<Vec<Vec3>> {
    let mut scratch = Vec::new();
    (0..md2.frames.len())
        .map(|f| {
            md2.frame_positions(f, &mut scratch);
            scratch.iter().map(|p| Vec3::from_array(*p)).collect()
        })
        .collect()
}

/// The mean of `points` (the origin for none).
fn centroid(points: &[Vec3]) -> Vec3 {
    if points.is_empty() {
        return Vec3::ZERO;
    }
    points.iter().copied().sum::<Vec3>() / points.len() as f32
}

/// Captures every frame of `md2` with `rig` (see the module documentation).
pub fn capture(md2: &Md2, rig: &Rig, options: &Options) -> Result<Capture, CaptureError> {
    Capturer::new(md2, rig, options)?.finish()
}
