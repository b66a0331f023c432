//! Foot contacts and foot locking: find the frames where each foot rests on the
//! floor (low and slow), and pin it there while it does by solving the leg with
//! IK, to remove foot skating.
//!
//! Inputs: a clip (and for locking, the local pose being drawn and the time).
//! [`FootLock::new`] finds the legs ([`crate::runtime::ik::default_chains`], the two with
//! the lowest effectors), the contact frames of each foot, and for each run of
//! contact frames the anchor where the foot stays (its position at the run's first
//! frame). [`FootLock::apply`] pulls each foot toward its anchor with the two-bone
//! solver, fully inside a run and easing in and out over [`EASE_FRAMES`] frames at
//! its ends, so a locked foot never pops.

use crate::model::clip::Clip;
use crate::model::up::UpAxis;
use crate::runtime::fk::Transform;
use crate::runtime::ik::{self, Chain};
use crate::runtime::pose::LocalPose;
use glam::Vec3;

/// Frames over which a lock eases in before a contact run and out after it.
pub const EASE_FRAMES: usize = 3;
/// A foot is low when it is within this share of the figure's size above its
/// lowest point in the clip.
pub const HEIGHT_SHARE: f32 = 0.04;
/// A foot is slow when it moves less than this share of the figure's size per second.
pub const SPEED_SHARE: f32 = 0.35;

/// One leg: its chain and, per frame, whether its foot is in contact and where it
/// is anchored (model space, file units).
#[derive(Clone, Debug, PartialEq)]
pub struct Leg {
    /// Hip → knee → ankle.
    pub chain: Chain,
    /// Per frame: the foot rests on the floor.
    pub contact: Vec<bool>,
    /// Per frame: the lock's weight (1 inside a contact run, easing to 0 around it).
    pub weight: Vec<f32>,
    /// Per frame: where the foot is pinned (the run's anchor; the foot's own
    /// position outside runs).
    pub anchor: Vec<Vec3>,
}

/// The legs of a clip and their contacts.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct FootLock {
    /// The legs found (none for a skeleton without two-bone legs).
    pub legs: Vec<Leg>,
}

impl FootLock {
    /// Finds the legs of `clip` and the contact frames of their feet, with up
    /// along the clip's guessed axis ([`Clip::up_axis`]).
    pub fn new(clip: &Clip) -> FootLock {
        FootLock::with_up(clip, clip.up_axis())
    }

    /// [`FootLock::new`] with up along the file axis `up` (heights and the floor
    /// are measured along it; the anchors stay in the file's axes).
    pub fn with_up(clip: &Clip, up: UpAxis) -> FootLock {
        let skeleton = clip.skeleton();
        let chains = ik::default_chains(skeleton);
        let rest = crate::runtime::fk::rest_positions(skeleton);
        let height = |p: &Vec3| up.to_y_up(*p).y;
        let root_y = skeleton.roots().next().and_then(|r| rest.get(r)).map_or(0.0, height);
        // Legs: the chains ending below the root in the rest pose, the lowest two.
        let legs: Vec<Chain> = chains
            .into_iter()
            .map(|(_, c)| c)
            .filter(|c| rest.get(c.effector()).is_some_and(|p| height(p) < root_y))
            .take(2)
            .collect();
        let frames = clip.frame_count();
        if legs.is_empty() || frames == 0 {
            return FootLock::default();
        }
        let size = clip.pose_extent().max(1e-6);
        let dt = clip.frame_time() as f32;
        let mut tracks: Vec<Vec<Vec3>> = vec![Vec::with_capacity(frames); legs.len()];
        let mut model: Vec<Transform> = Vec::new();
        for f in 0..frames {
            clip.world_transforms_into(f, &mut model);
            for (track, leg) in tracks.iter_mut().zip(&legs) {
                track.push(model.get(leg.effector()).map_or(Vec3::ZERO, |t| t.translation));
            }
        }
        let legs = legs.into_iter().zip(tracks).map(|(chain, track)| leg(chain, &track, up, size, dt)).collect();
        FootLock { legs }
    }

    /// Pins the feet of `local` (the clip's pose at `time`, possibly corrected) to
    /// their anchors by two-bone IK, weighted by the lock's weight at that time.
    pub fn apply(&self, clip: &Clip, local: &mut LocalPose, time: f64) {
        let position = clip.timeline().position(time);
        let skeleton = clip.skeleton();
        let options = ik::Options { angle_unit: clip.motion().angle_unit(), ..ik::Options::default() };
        for leg in &self.legs {
            let at = |v: &[f32], f: usize| v.get(f).copied().unwrap_or(0.0);
            let w = at(&leg.weight, position.frame0) * (1.0 - position.alpha)
                + at(&leg.weight, position.frame1) * position.alpha;
            if w <= 0.0 {
                continue;
            }
            let anchor = leg.anchor.get(position.frame0).copied().unwrap_or(Vec3::ZERO);
            let anchor = if position.alpha > 0.0 {
                anchor.lerp(leg.anchor.get(position.frame1).copied().unwrap_or(anchor), position.alpha)
            } else {
                anchor
            };
            let foot = ik::model_transform(skeleton, local, leg.chain.effector()).translation;
            let target = foot.lerp(anchor, w.min(1.0));
            let joints = leg.chain.joints();
            let (hip, knee) = (
                ik::model_transform(skeleton, local, leg.chain.root()).translation,
                ik::model_transform(skeleton, local, joints[1]).translation,
            );
            ik::two_bone(skeleton, local, &leg.chain, target, knee + (knee - hip), &options);
        }
    }

    /// Contact frames of each leg (for the timeline).
    pub fn contacts(&self) -> impl Iterator<Item = &[bool]> {
        self.legs.iter().map(|l| l.contact.as_slice())
    }
}

/// Contacts, weights and anchors of one foot's track (file axes, up along `up`).
fn leg(chain: Chain, track: &[Vec3], up: UpAxis, size: f32, dt: f32) -> Leg {
    let n = track.len();
    let upright: Vec<Vec3> = track.iter().map(|p| up.to_y_up(*p)).collect();
    let floor = upright.iter().map(|p| p.y).filter(|y| y.is_finite()).fold(f32::INFINITY, f32::min);
    let speed = |f: usize| {
        let (a, b) = (upright[f.saturating_sub(1)], upright[(f + 1).min(n - 1)]);
        let span = ((f + 1).min(n - 1) - f.saturating_sub(1)).max(1) as f32 * dt.max(1e-6);
        Vec3::new(b.x - a.x, 0.0, b.z - a.z).length() / span
    };
    let contact: Vec<bool> =
        (0..n).map(|f| upright[f].y <= floor + HEIGHT_SHARE * size && speed(f) <= SPEED_SHARE * size).collect();
    let mut weight = vec![0.0f32; n];
    let mut anchor = track.to_vec();
    let mut f = 0;
    while f < n {
        if !contact[f] {
            f += 1;
            continue;
        }
        let start = f;
        while f < n && contact[f] {
            f += 1;
        }
        let pin = track[start];
        for g in start..f {
            weight[g] = 1.0;
            anchor[g] = pin;
        }
        // Ease in before and out after the run, toward the same anchor.
        for k in 1..=EASE_FRAMES {
            let w = 1.0 - k as f32 / (EASE_FRAMES + 1) as f32;
            for g in [start.checked_sub(k), Some(f - 1 + k).filter(|&g| g < n)].into_iter().flatten() {
                if w > weight[g] {
                    weight[g] = w;
                    anchor[g] = pin;
                }
            }
        }
    }
    Leg { chain, contact, weight, anchor }
}
