//! Local poses: what sampling produces and what [`crate::runtime::fk::local_to_model`]
//! consumes. Later stages (layering, IK, editing) work on a [`LocalPose`] between
//! the two; this is that seam.
//!
//! A motion row becomes a local pose by [`from_row`]; two local poses blend by
//! [`blend`]. Both are single linear passes over flat arrays in joint order.

use crate::model::channel::{AngleUnit, ChannelKind};
use crate::model::skeleton::{EulerConvention, Skeleton};
use crate::runtime::fastmath::{quat_mul, sin_cos};
use glam::{Quat, Vec3};

/// Translation, rotation and scale of every joint relative to its parent, in joint
/// order (three arrays of equal length).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LocalPose {
    /// Translation from the parent joint, in its frame.
    pub translation: Vec<Vec3>,
    /// Rotation relative to the parent's frame.
    pub rotation: Vec<Quat>,
    /// Scale along the joint's axes.
    pub scale: Vec<Vec3>,
    /// Bone-length change of each joint (its children move along their rest direction).
    stretch: Vec<f32>,
}

impl LocalPose {
    /// The rest pose: rest translations and rotations, unit scale.
    pub fn rest(skeleton: &Skeleton) -> LocalPose {
        let mut pose = LocalPose::default();
        from_row(skeleton, &[], AngleUnit::Degrees, &mut pose);
        pose
    }

    /// Number of joints.
    pub fn len(&self) -> usize {
        self.translation.len()
    }

    /// True when the pose has no joints.
    pub fn is_empty(&self) -> bool {
        self.translation.is_empty()
    }

    /// Sizes the arrays to `n` joints (rest values where they grow).
    fn resize(&mut self, n: usize) {
        self.translation.resize(n, Vec3::ZERO);
        self.rotation.resize(n, Quat::IDENTITY);
        self.scale.resize(n, Vec3::ONE);
        self.stretch.resize(n, 0.0);
    }

    fn clear(&mut self, capacity: usize) {
        self.translation.clear();
        self.rotation.clear();
        self.scale.clear();
        self.stretch.clear();
        self.translation.reserve(capacity);
        self.rotation.reserve(capacity);
        self.scale.reserve(capacity);
        self.stretch.reserve(capacity);
    }
}

/// `q · R(axis, angle)` where `(s, c)` are the sine and cosine of half the angle.
#[inline(always)]
fn post_rotate(q: [f32; 4], axis: usize, s: f32, c: f32) -> [f32; 4] {
    let [x, y, z, w] = q;
    match axis {
        0 => [w * s + x * c, y * c + z * s, z * c - y * s, w * c - x * s],
        1 => [x * c - z * s, w * s + y * c, z * c + x * s, w * c - y * s],
        _ => [x * c + y * s, y * c - x * s, w * s + z * c, w * c - z * s],
    }
}

/// `R(axis, angle) · q` where `(s, c)` are the sine and cosine of half the angle.
#[inline(always)]
fn pre_rotate(q: [f32; 4], axis: usize, s: f32, c: f32) -> [f32; 4] {
    let mut r = [0.0, 0.0, 0.0, c];
    if let Some(slot) = r.get_mut(axis) {
        *slot = s;
    }
    quat_mul(r, q)
}

/// A quaternion for `angle` in `unit` about one axis (0 = X, 1 = Y, 2 = Z).
pub fn axis_rotation(axis: usize, angle: f32, unit: AngleUnit) -> Quat {
    let (s, c) = sin_cos(angle * unit.radians_per_unit() * 0.5);
    Quat::from_array(post_rotate([0.0, 0.0, 0.0, 1.0], axis, s, c))
}

/// One motion row to a local pose.
///
/// Inputs: the skeleton (rest transforms, channel layout, Euler convention), one
/// row of channel values (values missing from a short row count as 0, as do all
/// values for an empty row: the rest pose), and the unit of the rotation values.
/// Output: `out`, resized to the joint count. Per joint:
/// - translation: the rest translation, moved along its direction by the parent's
///   bone-length channel, then each translation channel sets its component;
/// - rotation: the rest rotation times the channel rotations, composed by the
///   skeleton's [`EulerConvention`];
/// - scale: 1, each scale channel sets its component.
pub fn from_row(skeleton: &Skeleton, row: &[f32], unit: AngleUnit, out: &mut LocalPose) {
    let half = unit.radians_per_unit() * 0.5;
    out.resize(skeleton.len());
    if skeleton.is_plain() {
        return fill_plain(skeleton, row, half, out);
    }
    // One body, specialised: BVH skeletons skip the Acclaim-only work.
    match (skeleton.euler() == EulerConvention::Extrinsic, skeleton.has_length_channels()) {
        (false, false) => fill::<false, false>(skeleton, row, half, out),
        (false, true) => fill::<false, true>(skeleton, row, half, out),
        (true, false) => fill::<true, false>(skeleton, row, half, out),
        (true, true) => fill::<true, true>(skeleton, row, half, out),
    }
}

/// The body of [`from_row`] for plain skeletons (BVH's: intrinsic rotations,
/// translation and rotation channels only, no rest rotations): the same rules as
/// [`fill`] with nothing to skip at run time.
#[inline(always)]
fn fill_plain(skeleton: &Skeleton, row: &[f32], half: f32, out: &mut LocalPose) {
    let slots = out.translation.iter_mut().zip(out.rotation.iter_mut()).zip(out.scale.iter_mut());
    for (joint, ((t_out, r_out), s_out)) in skeleton.joints().iter().zip(slots) {
        let (t, r) = plain_joint_local(joint, row, half);
        *t_out = Vec3::from_array(t);
        *r_out = Quat::from_array(r);
        *s_out = Vec3::ONE;
    }
}

/// One joint of a plain skeleton ([`Skeleton::is_plain`]): its local translation
/// and rotation (`[x, y, z, w]`) for a row, `half` being half a radian per angle
/// unit. The per-joint rule of [`from_row`] for such skeletons, shared with
/// [`crate::runtime::fk::model_from_row`].
#[inline(always)]
pub(crate) fn plain_joint_local(joint: &crate::model::skeleton::Joint, row: &[f32], half: f32) -> ([f32; 3], [f32; 4]) {
    let mut t = joint.offset.to_array();
    let mut r = [0.0, 0.0, 0.0, 1.0];
    let values = row.get(joint.columns()).unwrap_or(&[]);
    for (k, channel) in joint.channels.iter().enumerate() {
        let v = values.get(k).copied().unwrap_or(0.0);
        if channel.is_rotation() {
            let (sn, cs) = sin_cos(v * half);
            r = post_rotate(r, channel.axis(), sn, cs);
        } else if let Some(slot) = t.get_mut(channel.axis()) {
            *slot = v;
        }
    }
    (t, r)
}

/// The body of [`from_row`] for one Euler convention, with or without bone-length
/// channels; `out` is already sized.
#[inline(always)]
fn fill<const EXTRINSIC: bool, const STRETCH: bool>(skeleton: &Skeleton, row: &[f32], half: f32, out: &mut LocalPose) {
    let joints = skeleton.joints();
    for (i, joint) in joints.iter().enumerate() {
        let mut t = joint.offset.to_array();
        if STRETCH {
            if let Some(&d) = joint.parent.and_then(|p| out.stretch.get(p)) {
                if d != 0.0 {
                    let dir = joint.offset.normalize_or_zero() * d;
                    t = [t[0] + dir.x, t[1] + dir.y, t[2] + dir.z];
                }
            }
        }
        let rest = joint.rest_rotation.to_array();
        let mut r = if EXTRINSIC { [0.0, 0.0, 0.0, 1.0] } else { rest };
        let mut s = [1.0f32; 3];
        let mut stretch = 0.0;
        let values = row.get(joint.columns()).unwrap_or(&[]);
        for (k, channel) in joint.channels.iter().enumerate() {
            let v = values.get(k).copied().unwrap_or(0.0);
            let axis = channel.axis();
            match channel.kind() {
                ChannelKind::Rotation => {
                    let (sn, cs) = sin_cos(v * half);
                    r = if EXTRINSIC { pre_rotate(r, axis, sn, cs) } else { post_rotate(r, axis, sn, cs) };
                }
                ChannelKind::Translation => {
                    if let Some(slot) = t.get_mut(axis) {
                        *slot = v;
                    }
                }
                ChannelKind::Scale => {
                    if let Some(slot) = s.get_mut(axis) {
                        *slot = v;
                    }
                }
                ChannelKind::Length => stretch = v,
            }
        }
        if EXTRINSIC {
            r = quat_mul(rest, r);
        }
        if let Some(slot) = out.translation.get_mut(i) {
            *slot = Vec3::from_array(t);
        }
        if let Some(slot) = out.rotation.get_mut(i) {
            *slot = Quat::from_array(r);
        }
        if let Some(slot) = out.scale.get_mut(i) {
            *slot = Vec3::from_array(s);
        }
        if STRETCH {
            if let Some(slot) = out.stretch.get_mut(i) {
                *slot = stretch;
            }
        }
    }
}

/// Blends two local poses of the same skeleton: rotations by shortest-arc slerp,
/// translations and scales by lerp; `alpha` 0 gives `a`, 1 gives `b`. Joints only
/// one pose has are taken from `a`.
pub fn blend(a: &LocalPose, b: &LocalPose, alpha: f32, out: &mut LocalPose) {
    out.clear(a.len());
    for i in 0..a.len() {
        let (Some(&ta), Some(&ra), Some(&sa)) = (a.translation.get(i), a.rotation.get(i), a.scale.get(i)) else {
            break;
        };
        let (t, r, s) = match (b.translation.get(i), b.rotation.get(i), b.scale.get(i)) {
            (Some(&tb), Some(&rb), Some(&sb)) => (ta.lerp(tb, alpha), ra.slerp(rb, alpha), sa.lerp(sb, alpha)),
            _ => (ta, ra, sa),
        };
        out.translation.push(t);
        out.rotation.push(r);
        out.scale.push(s);
        out.stretch.push(0.0);
    }
}

/// Cubic in-betweens of four consecutive poses at `alpha` (0 = `a`, 1 = `b`;
/// `before` precedes `a`, `after` follows `b`): translations and scales by
/// uniform Catmull-Rom, rotations by squad on the shortest arc (each quaternion
/// on the hemisphere of the one before), C¹ across frames and through every
/// frame. Joints missing from a pose keep `a`'s values.
pub fn cubic(before: &LocalPose, a: &LocalPose, b: &LocalPose, after: &LocalPose, alpha: f32, out: &mut LocalPose) {
    out.clear(a.len());
    for i in 0..a.len() {
        let (Some(&ta), Some(&ra), Some(&sa)) = (a.translation.get(i), a.rotation.get(i), a.scale.get(i)) else {
            break;
        };
        let at = |p: &LocalPose| (p.translation.get(i).copied(), p.rotation.get(i).copied(), p.scale.get(i).copied());
        let (t, r, s) = match (at(before), at(b), at(after)) {
            ((Some(t0), Some(r0), Some(s0)), (Some(tb), Some(rb), Some(sb)), (Some(t3), Some(r3), Some(s3))) => (
                catmull_rom(t0, ta, tb, t3, alpha),
                squad(r0, ra, rb, r3, alpha),
                catmull_rom(s0, sa, sb, s3, alpha),
            ),
            _ => (ta, ra, sa),
        };
        out.translation.push(t);
        out.rotation.push(r);
        out.scale.push(s);
        out.stretch.push(0.0);
    }
}

/// Uniform Catmull-Rom between `p1` and `p2` at `t`.
fn catmull_rom(p0: Vec3, p1: Vec3, p2: Vec3, p3: Vec3, t: f32) -> Vec3 {
    let (t2, t3) = (t * t, t * t * t);
    0.5 * ((2.0 * p1) + (p2 - p0) * t + (2.0 * p0 - 5.0 * p1 + 4.0 * p2 - p3) * t2 + (3.0 * p1 - p0 - 3.0 * p2 + p3) * t3)
}

/// Squad between `q1` and `q2` at `t`, its inner controls from the neighbours.
fn squad(q0: Quat, q1: Quat, q2: Quat, q3: Quat, t: f32) -> Quat {
    let same_side = |q: Quat, reference: Quat| if q.dot(reference) < 0.0 { -q } else { q };
    let q0 = same_side(q0, q1);
    let q2 = same_side(q2, q1);
    let q3 = same_side(q3, q2);
    let s1 = inner(q0, q1, q2);
    let s2 = inner(q1, q2, q3);
    let path = q1.slerp(q2, t);
    let controls = s1.slerp(s2, t);
    path.slerp(controls, 2.0 * t * (1.0 - t)).normalize()
}

/// Squad's inner control at `q` between its neighbours.
fn inner(prev: Quat, q: Quat, next: Quat) -> Quat {
    let inv = q.conjugate();
    let sum = log(inv * next) + log(inv * prev);
    (q * exp(-0.25 * sum)).normalize()
}

/// The logarithm of a unit quaternion: its rotation vector halved.
fn log(q: Quat) -> Vec3 {
    let v = Vec3::new(q.x, q.y, q.z);
    let s = v.length();
    if s < 1e-7 {
        return v;
    }
    v * (s.atan2(q.w) / s)
}

/// The exponential of a pure quaternion `v` (inverse of [`log`]).
fn exp(v: Vec3) -> Quat {
    let theta = v.length();
    if theta < 1e-7 {
        return Quat::from_xyzw(v.x, v.y, v.z, 1.0).normalize();
    }
    let k = theta.sin() / theta;
    Quat::from_xyzw(v.x * k, v.y * k, v.z * k, theta.cos())
}
