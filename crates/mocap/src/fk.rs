//! Forward kinematics: channel values to local transforms, local to world in one
//! linear pass over parent indices (parents always come first).

use crate::fastmath::sin_cos;
use crate::skeleton::{Joint, Skeleton};
use glam::{Quat, Vec3};

/// A rigid transform: rotate, then translate.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Transform {
    /// Orientation.
    pub rotation: Quat,
    /// Position.
    pub translation: Vec3,
}

/// A transform's position (so world transforms can stand where points are expected).
impl From<Transform> for Vec3 {
    fn from(t: Transform) -> Vec3 {
        t.translation
    }
}

impl Transform {
    /// No rotation, no translation.
    pub const IDENTITY: Transform = Transform { rotation: Quat::IDENTITY, translation: Vec3::ZERO };

    /// `self ∘ child`: the child's transform expressed in `self`'s parent space.
    #[inline]
    pub fn compose(&self, child: &Transform) -> Transform {
        let (r, t) = compose_arrays(self.rotation.to_array(), self.translation.to_array(), child.rotation.to_array(), child.translation.to_array());
        Transform { rotation: Quat::from_array(r), translation: Vec3::from_array(t) }
    }
}

/// Half-angle in radians per degree.
const HALF_RAD_PER_DEG: f32 = core::f32::consts::PI / 360.0;

/// Quaternion for a rotation of `degrees` about one axis (0 = X, 1 = Y, 2 = Z).
#[inline]
pub fn axis_rotation(axis: usize, degrees: f32) -> Quat {
    Quat::from_array(rotate_about_axis([0.0, 0.0, 0.0, 1.0], axis, degrees))
}

// The hot path works on plain arrays with scalar math: glam's SIMD types carry a
// padding lane whose garbage can be a denormal, and denormal assists made FK ~30×
// slower. Quaternions are [x, y, z, w].

/// `q · axis_rotation(axis, degrees)`, using the zeros of the axis quaternion.
#[inline]
fn rotate_about_axis(q: [f32; 4], axis: usize, degrees: f32) -> [f32; 4] {
    let (s, c) = sin_cos(degrees * HALF_RAD_PER_DEG);
    let [x, y, z, w] = q;
    match axis {
        0 => [w * s + x * c, y * c + z * s, z * c - y * s, w * c - x * s],
        1 => [x * c - z * s, w * s + y * c, z * c + x * s, w * c - y * s],
        _ => [x * c + y * s, y * c - x * s, w * s + z * c, w * c - z * s],
    }
}

/// Hamilton product `a · b`.
#[inline]
fn quat_mul(a: [f32; 4], b: [f32; 4]) -> [f32; 4] {
    let [ax, ay, az, aw] = a;
    let [bx, by, bz, bw] = b;
    [
        aw * bx + ax * bw + ay * bz - az * by,
        aw * by - ax * bz + ay * bw + az * bx,
        aw * bz + ax * by - ay * bx + az * bw,
        aw * bw - ax * bx - ay * by - az * bz,
    ]
}

/// Rotates `v` by unit quaternion `q`: v + 2w(u×v) + 2u×(u×v).
#[inline]
fn quat_rotate(q: [f32; 4], v: [f32; 3]) -> [f32; 3] {
    let [qx, qy, qz, w] = q;
    let t = [2.0 * (qy * v[2] - qz * v[1]), 2.0 * (qz * v[0] - qx * v[2]), 2.0 * (qx * v[1] - qy * v[0])];
    [
        v[0] + w * t[0] + (qy * t[2] - qz * t[1]),
        v[1] + w * t[1] + (qz * t[0] - qx * t[2]),
        v[2] + w * t[2] + (qx * t[1] - qy * t[0]),
    ]
}

/// `parent ∘ child` on arrays.
#[inline]
fn compose_arrays(pr: [f32; 4], pt: [f32; 3], cr: [f32; 4], ct: [f32; 3]) -> ([f32; 4], [f32; 3]) {
    let moved = quat_rotate(pr, ct);
    (quat_mul(pr, cr), [pt[0] + moved[0], pt[1] + moved[1], pt[2] + moved[2]])
}

/// A joint's local rotation and translation as arrays (see [`local_transform`]).
#[inline]
fn local_arrays(joint: &Joint, row: &[f32]) -> ([f32; 4], [f32; 3]) {
    let mut translation = joint.offset.to_array();
    let mut rotation = [0.0, 0.0, 0.0, 1.0];
    let values = row.get(joint.first_channel..joint.first_channel + joint.channels.len());
    for (k, channel) in joint.channels.iter().enumerate() {
        let value = values.and_then(|v| v.get(k)).copied().unwrap_or(0.0);
        if channel.is_rotation() {
            rotation = rotate_about_axis(rotation, channel.axis(), value);
        } else {
            translation[channel.axis()] = value;
        }
    }
    (rotation, translation)
}

/// A joint's local transform for one motion row.
///
/// Position channels replace that component of the offset; rotation channels are
/// multiplied in file order (intrinsic). Values missing from a short row count as 0.
#[inline]
pub fn local_transform(joint: &Joint, row: &[f32]) -> Transform {
    let (rotation, translation) = local_arrays(joint, row);
    Transform { rotation: Quat::from_array(rotation), translation: Vec3::from_array(translation) }
}

/// Fills `out` with every joint's local transform for one motion row.
pub fn local_transforms(skeleton: &Skeleton, row: &[f32], out: &mut Vec<Transform>) {
    out.clear();
    out.extend(skeleton.joints.iter().map(|j| local_transform(j, row)));
}

/// Turns local transforms into world transforms in place, in one pass.
///
/// `transforms` holds one local transform per joint on entry and one world transform
/// per joint on return. Works because each parent precedes its children.
pub fn local_to_world_in_place(skeleton: &Skeleton, transforms: &mut [Transform]) {
    for (i, joint) in skeleton.joints.iter().enumerate().take(transforms.len()) {
        if let Some(p) = joint.parent.filter(|&p| p < i) {
            transforms[i] = transforms[p].compose(&transforms[i]);
        }
    }
}

/// World transforms of all joints for one motion row: local and world in a single
/// fused pass. `out` is resized to the joint count and reused without allocating.
pub fn world_transforms(skeleton: &Skeleton, row: &[f32], out: &mut Vec<Transform>) {
    out.clear();
    out.reserve(skeleton.joints.len());
    for (i, joint) in skeleton.joints.iter().enumerate() {
        let (rotation, translation) = local_arrays(joint, row);
        let (rotation, translation) = match joint.parent.filter(|&p| p < i).and_then(|p| out.get(p)) {
            Some(parent) => compose_arrays(parent.rotation.to_array(), parent.translation.to_array(), rotation, translation),
            None => (rotation, translation),
        };
        out.push(Transform { rotation: Quat::from_array(rotation), translation: Vec3::from_array(translation) });
    }
}

/// World positions of the rest pose: offsets only, channels ignored.
pub fn rest_positions(skeleton: &Skeleton) -> Vec<Vec3> {
    let mut out: Vec<Vec3> = Vec::with_capacity(skeleton.joints.len());
    for (i, joint) in skeleton.joints.iter().enumerate() {
        let base = joint.parent.filter(|&p| p < i).and_then(|p| out.get(p)).copied().unwrap_or(Vec3::ZERO);
        out.push(base + joint.offset);
    }
    out
}
