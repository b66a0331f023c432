//! Forward kinematics: a [`LocalPose`] to model-space transforms in one linear pass
//! over parent indices (parents always come first). This is the only FK in the
//! project; [`crate::runtime::batch`] runs the same arithmetic on several frames at once and
//! a test checks the two agree.

use crate::model::channel::AngleUnit;
use crate::model::skeleton::{Joint, Skeleton};
use crate::runtime::fastmath::quat_mul;
use crate::runtime::pose::{LocalPose, plain_joint_local};
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
}

// The hot path works on plain arrays with scalar math: glam's SIMD types carry a
// padding lane whose garbage can be a denormal, and denormal assists made FK ~30×
// slower. Quaternions are [x, y, z, w].

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
fn compose_arrays(
    pr: [f32; 4],
    pt: [f32; 3],
    ps: [f32; 3],
    cr: [f32; 4],
    ct: [f32; 3],
    cs: [f32; 3],
) -> ([f32; 4], [f32; 3], [f32; 3]) {
    let moved = quat_rotate(pr, [ps[0] * ct[0], ps[1] * ct[1], ps[2] * ct[2]]);
    (
        quat_mul(pr, cr),
        [pt[0] + moved[0], pt[1] + moved[1], pt[2] + moved[2]],
        [ps[0] * cs[0], ps[1] * cs[1], ps[2] * cs[2]],
    )
}

/// Local to model: `out[i] = out[parent(i)] ∘ local[i]`, roots as they are.
///
/// Inputs: the skeleton (parent indices, parents first) and a local pose with one
/// entry per joint (a shorter pose leaves the remaining joints out). Output: one
/// model-space transform per joint, in joint order; `out` is reused without
/// allocating once sized.
pub fn local_to_model(skeleton: &Skeleton, local: &LocalPose, out: &mut Vec<Transform>) {
    let n = skeleton.len().min(local.len());
    let (ts, rs, ss) = (&local.translation, &local.rotation, &local.scale);
    let entry = |i: usize, _: &Joint| {
        let t = ts.get(i).map_or([0.0; 3], |v| v.to_array());
        let r = rs.get(i).map_or([0.0, 0.0, 0.0, 1.0], |q| q.to_array());
        let s = ss.get(i).map_or([1.0; 3], |v| v.to_array());
        (t, r, s)
    };
    // One body; skeletons without scale channels skip composing unit scales.
    if skeleton.has_scale_channels() {
        compose_each::<true>(skeleton, n, entry, out);
    } else {
        compose_each::<false>(skeleton, n, entry, out);
    }
}

/// Model transforms of a plain skeleton ([`Skeleton::is_plain`], e.g. every BVH
/// file) straight from a motion row: [`crate::runtime::pose::from_row`]'s per-joint rule fed
/// to the same local-to-model pass, without storing the local pose in between
/// (that store and reload costs a fifth of the time). Other skeletons go through
/// `scratch`: `from_row` then [`local_to_model`]. Either way the result equals
/// `from_row` followed by `local_to_model` (a test checks it bit for bit).
pub fn model_from_row(
    skeleton: &Skeleton,
    row: &[f32],
    unit: AngleUnit,
    scratch: &mut LocalPose,
    out: &mut Vec<Transform>,
) {
    if skeleton.is_plain() {
        let half = unit.radians_per_unit() * 0.5;
        let entry = |_: usize, joint: &Joint| {
            let (t, r) = plain_joint_local(joint, row, half);
            (t, r, [1.0; 3])
        };
        compose_each::<false>(skeleton, skeleton.len(), entry, out);
    } else {
        crate::runtime::pose::from_row(skeleton, row, unit, scratch);
        local_to_model(skeleton, scratch, out);
    }
}

/// The one local-to-model loop: joint `i`'s local (translation, rotation, scale)
/// comes from `local(i, joint)`, its model transform is its parent's composed with it.
#[inline(always)]
fn compose_each<const SCALED: bool>(
    skeleton: &Skeleton,
    n: usize,
    local: impl Fn(usize, &Joint) -> ([f32; 3], [f32; 4], [f32; 3]),
    out: &mut Vec<Transform>,
) {
    out.clear();
    out.reserve(n);
    for (i, joint) in skeleton.joints().iter().enumerate().take(n) {
        let (t, r, s) = local(i, joint);
        let s = if SCALED { s } else { [1.0; 3] };
        let (r, t, s) = match joint.parent.and_then(|p| out.get(p)) {
            Some(p) if SCALED => {
                compose_arrays(p.rotation.to_array(), p.translation.to_array(), p.scale.to_array(), r, t, s)
            }
            Some(p) => {
                let (pr, pt) = (p.rotation.to_array(), p.translation.to_array());
                let moved = quat_rotate(pr, t);
                (quat_mul(pr, r), [pt[0] + moved[0], pt[1] + moved[1], pt[2] + moved[2]], s)
            }
            None => (r, t, s),
        };
        out.push(Transform {
            rotation: Quat::from_array(r),
            translation: Vec3::from_array(t),
            scale: Vec3::from_array(s),
        });
    }
}

/// Model-space positions of the rest pose (channels ignored): the rest local pose
/// through [`local_to_model`].
pub fn rest_positions(skeleton: &Skeleton) -> Vec<Vec3> {
    let mut model = Vec::new();
    local_to_model(skeleton, &LocalPose::rest(skeleton), &mut model);
    model.into_iter().map(|t| t.translation).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn model_from_row_equals_from_row_then_local_to_model_bit_for_bit() {
        let src = "HIERARCHY\nROOT R\n{\nOFFSET 1 2 3\nCHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation\nJOINT C\n{\nOFFSET 0 1 0\nCHANNELS 4 Yrotation Xposition Xrotation Zrotation\nEnd Site\n{\nOFFSET 1 0.5 0\n}\n}\n}\nMOTION\nFrames: 1\nFrame Time: 0.1\n0.5 -1 2 33 -71 150 12 0.25 -8 95\n";
        let clip = crate::formats::bvh::parse(src.as_bytes()).unwrap();
        assert!(clip.skeleton().is_plain());
        let (mut local, mut a, mut b) = (LocalPose::default(), Vec::new(), Vec::new());
        crate::runtime::pose::from_row(clip.skeleton(), clip.channel_values(0), AngleUnit::Degrees, &mut local);
        local_to_model(clip.skeleton(), &local, &mut a);
        model_from_row(clip.skeleton(), clip.channel_values(0), AngleUnit::Degrees, &mut local, &mut b);
        let bits = |v: &[Transform]| {
            v.iter()
                .flat_map(|t| {
                    t.rotation.to_array().into_iter().chain(t.translation.to_array()).chain(t.scale.to_array())
                })
                .map(f32::to_bits)
                .collect::<Vec<_>>()
        };
        assert_eq!(bits(&a), bits(&b));
    }
}
