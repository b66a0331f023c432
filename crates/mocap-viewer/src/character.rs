//! One character on the stage: a clip or a model placed in the shared world by the
//! core's [`mocap::stage`], with what only the viewer keeps ([`Look`]): its colour,
//! the figure or mesh the renderer draws, children lists for the joint tree, and
//! its current pose (joint transforms, or the model's two key frames).

use mocap::model::mesh::MorphSample;
use mocap::stage::{Actor, PoseScratch};
use mocap::{Asset, Interpolation, Transform};
use mocap_scene::Drawable;

/// Bone colours given to characters in turn (the renderer's palette).
pub use mocap_render::PALETTE;

/// What the viewer keeps per character.
#[derive(Clone, Debug, Default)]
pub struct Look {
    /// Bone colour (sRGB, 0-255).
    pub color: [u8; 4],
    /// What it is drawn with: a clip's figure and body, or a model's mesh.
    pub drawable: Drawable,
    /// Children of each joint, in joint order (for the joint tree).
    pub children: Vec<Vec<usize>>,
    /// World transforms of the last [`pose_at`] (metres, placed), in joint order
    /// (empty for a model).
    pub pose: Vec<Transform>,
    /// A model's key frames at the last [`pose_at`].
    pub morph: Option<MorphSample>,
    /// A pose corrected by dragging a joint (Edit mode), shown at its frame.
    pub correction: Option<Correction>,
    /// The clip's own pose (world, metres) while a correction is shown, drawn as a ghost.
    pub ghost: Vec<Transform>,
    /// Foot contacts and locks of a clip, found on first use (foot locking).
    pub foot_lock: Option<mocap::ops::contact::FootLock>,
    /// A glTF look's blend shapes at the last [`pose_at`] (`None`: the mesh as it is).
    pub shape: Option<std::sync::Arc<[mocap::glam::Vec3]>>,
    /// The last shape made, kept while the weights stay.
    pub shapes: mocap_scene::MorphShape,
}

/// Local rotations (and a root position) set by IK at one frame of a clip.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Correction {
    /// The clip frame it applies to.
    pub frame: usize,
    /// Joints and their corrected local rotations.
    pub rotations: Vec<(usize, mocap::glam::Quat)>,
    /// Roots moved by hand, and their local translations.
    pub translations: Vec<(usize, mocap::glam::Vec3)>,
    /// Draw the clip's own pose as a ghost under it.
    pub ghost: bool,
}

impl Correction {
    /// Writes the corrected values into `local`.
    pub fn apply(&self, local: &mut mocap::LocalPose) {
        for &(j, q) in &self.rotations {
            if let Some(slot) = local.rotation.get_mut(j) {
                *slot = q;
            }
        }
        for &(j, t) in &self.translations {
            if let Some(slot) = local.translation.get_mut(j) {
                *slot = t;
            }
        }
    }

    /// Keeps `local`'s values for `joints` (replacing earlier ones for them).
    fn record(&mut self, local: &mocap::LocalPose, joints: &[usize], moved_root: Option<usize>) {
        for &j in joints {
            let Some(&q) = local.rotation.get(j) else { continue };
            match self.rotations.iter_mut().find(|(k, _)| *k == j) {
                Some(slot) => slot.1 = q,
                None => self.rotations.push((j, q)),
            }
        }
        if let Some(j) = moved_root {
            let Some(&t) = local.translation.get(j) else { return };
            match self.translations.iter_mut().find(|(k, _)| *k == j) {
                Some(slot) => slot.1 = t,
                None => self.translations.push((j, t)),
            }
        }
    }
}

/// The local pose at the frame shown at `time` with that frame's corrections so
/// far applied, and the correction to add to (a new one when the frame has none).
/// The pose is taken out of `scratch`; put it back when done.
fn corrected_pose(c: &Character, time: f64, scratch: &mut PoseScratch) -> (mocap::LocalPose, Correction) {
    let frame = c.frame_at(time);
    c.sample_local(time, Interpolation::Step, scratch);
    let mut local = std::mem::take(&mut scratch.local);
    let correction = c.extra.correction.clone().filter(|k| k.frame == frame).unwrap_or(Correction {
        frame,
        ghost: true,
        ..Correction::default()
    });
    correction.apply(&mut local);
    (local, correction)
}

/// Sets joint `joint`'s local rotation at the frame shown at `time` (a correction,
/// like a drag: ghosted, keyed by Set key). `None` for a model or an unknown joint.
pub fn rotate_joint(
    c: &mut Character,
    joint: usize,
    rotation: mocap::glam::Quat,
    time: f64,
    scratch: &mut PoseScratch,
) -> Option<()> {
    let clip = c.clip()?;
    if joint >= clip.skeleton().len() || clip.skeleton().is_end_site(joint) || !rotation.is_finite() {
        return None;
    }
    let (mut local, mut correction) = corrected_pose(c, time, scratch);
    if let Some(slot) = local.rotation.get_mut(joint) {
        *slot = rotation.normalize();
    }
    correction.record(&local, &[joint], None);
    scratch.local = local;
    c.extra.correction = Some(correction);
    Some(())
}

/// Joint `joint`'s local rotation as drawn (from the world transforms of the last
/// pose), if known.
pub fn drawn_local_rotation(c: &Character, joint: usize) -> Option<mocap::glam::Quat> {
    let clip = c.clip()?;
    let world = c.extra.pose.get(joint)?.rotation;
    // A root's parent frame is the file's axes turned up (Actor::place).
    let parent = clip
        .skeleton()
        .joints()
        .get(joint)?
        .parent
        .and_then(|p| c.extra.pose.get(p))
        .map_or(c.up.rotation(), |t| t.rotation);
    Some((parent.inverse() * world).normalize())
}

/// Moves joint `joint` of a clip character to `world` (metres) at the frame shown
/// at `time`, by IK on its chain (the limb's two bones for a hand or foot found by
/// [`mocap::runtime::ik::default_chains`], else the two bones above it; a root joint moves
/// itself), keeping earlier corrections of that frame. Returns the solve, or
/// `None` for a model, an unknown joint or a non-finite target.
pub fn drag_joint(
    c: &mut Character,
    joint: usize,
    world: mocap::glam::Vec3,
    time: f64,
    scratch: &mut PoseScratch,
) -> Option<mocap::runtime::ik::Solve> {
    use mocap::runtime::ik;
    let clip = c.clip()?;
    let skeleton = clip.skeleton();
    let parent = skeleton.joints().get(joint)?.parent;
    let target = c.to_file(world);
    if !target.is_finite() {
        return None;
    }
    let (mut local, mut correction) = corrected_pose(c, time, scratch);
    let solve = match parent {
        None => {
            // A root: its local translation is its model position.
            if let Some(slot) = local.translation.get_mut(joint) {
                *slot = target;
            }
            correction.record(&local, &[], Some(joint));
            ik::Solve { distance: 0.0, reached: true, iterations: 1 }
        }
        Some(_) => {
            let chain = ik::Chain::for_joint(skeleton, joint).ok()?;
            let length = chain.rest_length(skeleton);
            let options = ik::Options {
                angle_unit: clip.motion().angle_unit(),
                iterations: 64,
                tolerance: 1e-4 * length.max(1e-6),
                ..ik::Options::default()
            };
            let solve = if chain.joints().len() == 3 {
                // Bend the way the limb bends now (knees forward, elbows back).
                let root = ik::model_transform(skeleton, &local, chain.root()).translation;
                let mid = ik::model_transform(skeleton, &local, chain.joints()[1]).translation;
                ik::two_bone(skeleton, &mut local, &chain, target, mid + (mid - root), &options)
            } else {
                ik::fabrik(skeleton, &mut local, &chain, target, &options)
            };
            correction.record(&local, chain.joints(), None);
            solve
        }
    };
    scratch.local = local;
    c.extra.correction = Some(correction);
    Some(solve)
}

/// A clip or model on the viewer's stage.
pub type Character = Actor<Look>;

/// A visible character named `name`, in the first palette colour no character in
/// `open` uses.
pub fn new_character(name: &str, asset: Asset, open: &[Character]) -> Character {
    let look = Look { color: next_color(open), ..Look::default() };
    let mut c = Actor::new(name, asset, look);
    c.extra.drawable = Drawable::of(&c.asset, c.extent);
    if let Some(clip) = c.asset.clip() {
        c.extra.children = clip.skeleton().children();
    }
    c
}

/// Poses the character at `time`: interpolated when `smooth`, else the frame shown
/// at that time in its own frame time (the one rule of [`mocap::model::time`]); a model
/// not interpolating switches frames at the halfway point (Quake's nearest frame).
/// Past its end a clip holds its last pose. The stages after sampling, on the local
/// pose: a correction made by dragging (at its frame; the clip's own pose becomes
/// the ghost), then foot locking when `lock_feet`. The transforms are in metres and
/// placed.
pub fn pose_at(c: &mut Character, time: f64, smooth: Option<Interpolation>, lock_feet: bool, scratch: &mut PoseScratch) {
    let interpolation = match (smooth, c.model().is_some()) {
        (Some(between), _) => between,
        (None, false) => Interpolation::Step,
        (None, true) => Interpolation::Nearest,
    };
    if lock_feet && c.extra.foot_lock.is_none() {
        c.extra.foot_lock = c.clip().map(|clip| mocap::ops::contact::FootLock::with_up(clip, c.up));
    }
    let mut pose = std::mem::take(&mut c.extra.pose);
    let mut ghost = std::mem::take(&mut c.extra.ghost);
    ghost.clear();
    let correction = c.extra.correction.as_ref().filter(|k| k.frame == c.frame_at(time));
    let sampling = if correction.is_some() { Interpolation::Step } else { interpolation };
    if (correction.is_some() || lock_feet) && c.sample_local(time, sampling, scratch) {
        let mut local = std::mem::take(&mut scratch.local);
        if let Some(correction) = correction {
            if correction.ghost {
                c.place(&local, &mut ghost);
            }
            correction.apply(&mut local);
        }
        if let (true, Some(lock), Some(clip)) = (lock_feet, &c.extra.foot_lock, c.clip()) {
            lock.apply(clip, &mut local, time);
        }
        c.place(&local, &mut pose);
        scratch.local = local;
    } else {
        c.pose_at(time, interpolation, scratch, &mut pose);
    }
    c.extra.pose = pose;
    c.extra.ghost = ghost;
    c.extra.morph = c.morph_at(time, interpolation);
    c.extra.shape = c.asset.clip().and_then(|clip| c.extra.shapes.at(clip, time));
}

/// The first palette colour no open character uses, or the palette cycled by count.
pub fn next_color(open: &[Character]) -> [u8; 4] {
    let unused = PALETTE.iter().find(|c| !open.iter().any(|o| o.extra.color == **c));
    unused.copied().unwrap_or(PALETTE[open.len() % PALETTE.len()])
}

/// A character's file name without folders and extension (`walk` for
/// `data/walk.bvh`), for the names of files made from it.
pub fn file_stem(name: &str) -> &str {
    let base = name.rsplit(['/', '\\']).next().unwrap_or(name);
    base.rsplit_once('.').map_or(base, |(s, _)| s)
}
