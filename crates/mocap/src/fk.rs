//! Forward kinematics: a [`LocalPose`] to model-space transforms in one linear pass
//! over parent indices (parents always come first). This is the only FK in the
//! project; [`crate::batch`] runs the same arithmetic on several frames at once and
//! a test checks the two agree.

use crate::pose::LocalPose;
use crate::skeleton::Skeleton;
use glam::{Quat, Vec3};

/// A transform: scale, then rotate, then translate.
///
/// Composing keeps scale per axis (`parent.scale × child.scale`) and applies the
/// parent's scale to the child's translation; there is no shear (as in most game
/// engines), which is exact for uniform scales and for the BVA segments that are
/// the only scaled joints the formats have.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Transform {
    /// Orientation.
    pub rotation: Quat,
    /// Position.
    pub translation: Vec3,
    /// Scale along the local axes (1 at rest).
    pub scale: Vec3,
}

/// A transform's position (so model transforms can stand where points are expected).
impl From<Transform> for Vec3 {
    fn from(t: Transform) -> Vec3 {
        t.translation
    }
}

impl Default for Transform {
    fn default() -> Transform {
        Transform::IDENTITY
    }
}

impl Transform {
    /// No rotation, no translation, unit scale.
    pub const IDENTITY: Transform = Transform { rotation: Quat::IDENTITY, translation: Vec3::ZERO, scale: Vec3::ONE };

    /// A rotation and a translation with unit scale.
    pub fn from_rotation_translation(rotation: Quat, translation: Vec3) -> Transform {
        Transform { rotation, translation, scale: Vec3::ONE }
    }

    /// `self ∘ child`: the child's transform expressed in `self`'s parent space.
    #[inline]
    pub fn compose(&self, child: &Transform) -> Transform {
        let (r, t, s) = compose_arrays(
            self.rotation.to_array(),
            self.translation.to_array(),
            self.scale.to_array(),
            child.rotation.to_array(),
            child.translation.to_array(),
            child.scale.to_array(),
        );
        Transform { rotation: Quat::from_array(r), translation: Vec3::from_array(t), scale: Vec3::from_array(s) }
    }

    /// A point in this transform's local space, in its parent's space.
    pub fn transform_point(&self, p: Vec3) -> Vec3 {
        self.translation + self.rotation * (self.scale * p)
    }
}

// The hot path works on plain arrays with scalar math: glam's SIMD types carry a
// padding lane whose garbage can be a denormal, and denormal assists made FK ~30×
// slower. Quaternions are [x, y, z, w].

/// Hamilton product `a · b`.
#[inline(always)]
pub(crate) fn quat_mul(a: [f32; 4], b: [f32; 4]) -> [f32; 4] {
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
#[inline(always)]
fn quat_rotate(q: [f32; 4], v: [f32; 3]) -> [f32; 3] {
    let [qx, qy, qz, w] = q;
    let t = [2.0 * (qy * v[2] - qz * v[1]), 2.0 * (qz * v[0] - qx * v[2]), 2.0 * (qx * v[1] - qy * v[0])];
    [
        v[0] + w * t[0] + (qy * t[2] - qz * t[1]),
        v[1] + w * t[1] + (qz * t[0] - qx * t[2]),
        v[2] + w * t[2] + (qx * t[1] - qy * t[0]),
    ]
}

/// `parent ∘ child` on arrays: rotation, translation, scale.
#[inline(always)]
fn compose_arrays(pr: [f32; 4], pt: [f32; 3], ps: [f32; 3], cr: [f32; 4], ct: [f32; 3], cs: [f32; 3]) -> ([f32; 4], [f32; 3], [f32; 3]) {
    let moved = quat_rotate(pr, [ps[0] * ct[0], ps[1] * ct[1], ps[2] * ct[2]]);
    (quat_mul(pr, cr), [pt[0] + moved[0], pt[1] + moved[1], pt[2] + moved[2]], [ps[0] * cs[0], ps[1] * cs[1], ps[2] * cs[2]])
}

/// Local to model: `out[i] = out[parent(i)] ∘ local[i]`, roots as they are.
///
/// Inputs: the skeleton (parent indices, parents first) and a local pose with one
/// entry per joint (missing entries count as the identity). Output: one model-space
/// transform per joint, in joint order; `out` is reused without allocating once sized.
pub fn local_to_model(skeleton: &Skeleton, local: &LocalPose, out: &mut Vec<Transform>) {
    out.clear();
    out.reserve(skeleton.len());
    let (ts, rs, ss) = (local.translation.as_slice(), local.rotation.as_slice(), local.scale.as_slice());
    for (i, joint) in skeleton.joints().iter().enumerate() {
        let t = ts.get(i).map_or([0.0; 3], |v| v.to_array());
        let r = rs.get(i).map_or([0.0, 0.0, 0.0, 1.0], |q| q.to_array());
        let s = ss.get(i).map_or([1.0; 3], |v| v.to_array());
        let (r, t, s) = match joint.parent.and_then(|p| out.get(p)) {
            Some(p) => compose_arrays(p.rotation.to_array(), p.translation.to_array(), p.scale.to_array(), r, t, s),
            None => (r, t, s),
        };
        out.push(Transform { rotation: Quat::from_array(r), translation: Vec3::from_array(t), scale: Vec3::from_array(s) });
    }
}

/// Model-space positions of the rest pose (channels ignored): the rest local pose
/// through [`local_to_model`].
pub fn rest_positions(skeleton: &Skeleton) -> Vec<Vec3> {
    let mut model = Vec::new();
    local_to_model(skeleton, &LocalPose::rest(skeleton), &mut model);
    model.into_iter().map(|t| t.translation).collect()
}
