//! A body for any skeleton: BVH and Acclaim files carry no mesh, so one is built
//! around the bones, skinned to the skeleton ([`crate::runtime::skin`]).
//!
//! Every bone (a joint and its parent at different places in the bind pose) gets a
//! closed tube with round ends (a capsule mesh) of the radius the caller's rule
//! gives for it (the viewer passes the capsule mode's radii, thicker, so fingers,
//! toes, the torso and long helper bones look the same in both modes). A tube is owned by the
//! bone's parent joint (whose rotation swings it); near its far end the weight
//! fades half-way to the child joint, near its near end half-way to the parent's
//! parent. Where two bones meet both ends share the same blend, so a bent elbow is
//! a smooth turn with no crack or crease. Each tube is closed (every edge is shared
//! by two triangles) and every vertex's weights sum to 1. A skeleton with no bone
//! at all gets a ball at each root.
//!
//! Inputs: the skeleton, its model transforms in the bind pose, and the radius
//! rule. Output: a [`Skin`]. One pass over the joints, no recursion.

use crate::model::skeleton::Skeleton;
use crate::runtime::fk::Transform;
use crate::runtime::skin::{MAX_INFLUENCES, Skin, SkinError};
use glam::Vec3;
use std::f32::consts::{FRAC_PI_2, TAU};

/// Vertices around a tube.
pub const SEGMENTS: u32 = 10;
/// Rings in each round end (the equator included).
pub const CAP_RINGS: u32 = 2;
/// Spans along a tube's straight part (rings between the ends: one less).
pub const SPANS: u32 = 3;
/// Most bones a body is built for; past that (a 200,000-joint chain) building one
/// is refused and the viewer keeps the capsules.
pub const MAX_BODY_BONES: usize = 8192;

/// Why no body was built.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum BodyError {
    /// More bones than [`MAX_BODY_BONES`].
    #[error("{0} bones: too many for a body (at most {MAX_BODY_BONES})")]
    TooManyBones(usize),
    /// The bind pose is not one transform per joint, or not finite.
    #[error("the bind pose has {given} transforms for {joints} joints, or non-finite ones")]
    BindPose {
        /// Transforms given.
        given: usize,
        /// Joints in the skeleton.
        joints: usize,
    },
    /// Binding failed (should not happen for a valid bind pose).
    #[error(transparent)]
    Skin(#[from] SkinError),
}

/// Vertices of one tube.
pub const TUBE_VERTICES: u32 = 2 + SEGMENTS * (2 * CAP_RINGS + SPANS - 1);

/// How finely the tubes are cut.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Detail {
    /// Vertices around a tube (at least 3).
    pub segments: u32,
    /// Rings in each round end, the equator included (at least 1).
    pub cap_rings: u32,
    /// Spans along the straight part (at least 1).
    pub spans: u32,
}

impl Detail {
    /// The body as drawn: [`SEGMENTS`], [`CAP_RINGS`], [`SPANS`]
    /// ([`TUBE_VERTICES`] a tube, 120 triangles).
    pub const FULL: Detail = Detail { segments: SEGMENTS, cap_rings: CAP_RINGS, spans: SPANS };
    /// About a third of the triangles (20 vertices and 36 triangles a tube:
    /// hexagonal, with pointed ends): for a body too small on screen for the
    /// difference to show, on a slow GPU.
    pub const COARSE: Detail = Detail { segments: 6, cap_rings: 1, spans: 2 };

    /// Vertices of one tube.
    pub fn tube_vertices(self) -> u32 {
        2 + self.segments * (2 * self.cap_rings + self.spans - 1)
    }

    /// The same, each count raised to its least.
    fn at_least(self) -> Detail {
        Detail { segments: self.segments.max(3), cap_rings: self.cap_rings.max(1), spans: self.spans.max(1) }
    }
}

/// The mesh being built.
#[derive(Default)]
struct Builder {
    detail: Option<Detail>,
    positions: Vec<Vec3>,
    normals: Vec<Vec3>,
    indices: Vec<u32>,
    joints: Vec<[u32; MAX_INFLUENCES]>,
    weights: Vec<[f32; MAX_INFLUENCES]>,
}

/// Who moves a tube: its owner, the child at its far end, the grandparent at its
/// near end (both optional).
#[derive(Clone, Copy)]
struct Owners {
    owner: u32,
    far: Option<u32>,
    near: Option<u32>,
}

fn smoothstep(edge0: f32, edge1: f32, x: f32) -> f32 {
    if edge1 <= edge0 {
        return if x >= edge1 { 1.0 } else { 0.0 };
    }
    let t = ((x - edge0) / (edge1 - edge0)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

impl Builder {
    /// A capsule from `a` to `b` of `radius`, weighted along its axis.
    fn tube(&mut self, a: Vec3, b: Vec3, radius: f32, who: Owners) {
        let Detail { segments, cap_rings, spans } = self.detail.unwrap_or(Detail::FULL).at_least();
        let length = a.distance(b);
        let z = if length > 0.0 { (b - a) / length } else { Vec3::Y };
        let x = z.any_orthonormal_vector();
        let y = z.cross(x);
        let zone = (1.5 * radius).min(0.45 * length);
        let base = self.positions.len() as u32;
        // Rings from the near pole to the far one: (axial position, ring radius, normal's axial part).
        let mut rings: Vec<(f32, f32, f32)> = Vec::new();
        for k in 1..=cap_rings {
            let phi = -FRAC_PI_2 + k as f32 * FRAC_PI_2 / cap_rings as f32;
            rings.push((radius * phi.sin(), radius * phi.cos(), phi.sin()));
        }
        for k in 1..spans {
            rings.push((length * k as f32 / spans as f32, radius, 0.0));
        }
        for k in 0..cap_rings {
            let phi = k as f32 * FRAC_PI_2 / cap_rings as f32;
            rings.push((length + radius * phi.sin(), radius * phi.cos(), phi.sin()));
        }
        self.vertex(a - z * radius, -z, -radius, length, zone, who);
        for &(along, ring, nz) in &rings {
            for s in 0..segments {
                let angle = s as f32 * TAU / segments as f32;
                let radial = x * angle.cos() + y * angle.sin();
                let normal = (radial * (1.0 - nz * nz).max(0.0).sqrt() + z * nz).normalize_or_zero();
                self.vertex(a + z * along + radial * ring, normal, along, length, zone, who);
            }
        }
        self.vertex(b + z * radius, z, length + radius, length, zone, who);
        // Triangles, counter-clockwise seen from outside.
        let ring_start = |r: u32| base + 1 + r * segments;
        let next = |s: u32| (s + 1) % segments;
        let top = base + 1 + rings.len() as u32 * segments;
        for s in 0..segments {
            self.indices.extend([base, ring_start(0) + next(s), ring_start(0) + s]);
        }
        for r in 0..rings.len() as u32 - 1 {
            let (lo, hi) = (ring_start(r), ring_start(r + 1));
            for s in 0..segments {
                self.indices.extend([lo + s, lo + next(s), hi + next(s)]);
                self.indices.extend([lo + s, hi + next(s), hi + s]);
            }
        }
        let last = ring_start(rings.len() as u32 - 1);
        for s in 0..segments {
            self.indices.extend([top, last + s, last + next(s)]);
        }
    }

    /// One vertex at axial position `along` of a tube of `length`.
    fn vertex(&mut self, p: Vec3, n: Vec3, along: f32, length: f32, zone: f32, who: Owners) {
        let far = if who.far.is_some() { 0.5 * smoothstep(length - zone, length, along) } else { 0.0 };
        let near = if who.near.is_some() { 0.5 * (1.0 - smoothstep(0.0, zone, along)) } else { 0.0 };
        self.positions.push(p);
        self.normals.push(n);
        self.joints.push([who.owner, who.far.unwrap_or(who.owner), who.near.unwrap_or(who.owner), who.owner]);
        self.weights.push([1.0 - far - near, far, near, 0.0]);
    }
}

/// Builds the body of `skeleton` around its bind pose (`bind`: one model
/// transform per joint, file units, e.g. [`crate::model::clip::Clip::bind_pose`]); `radius(joint, length)` gives the tube
/// radius of the bone from `joint`'s parent to `joint` (a radius that is not a
/// positive number gives a tenth of the length). A skeleton with no bone asks
/// `radius(root, 0.0)` for each root's ball.
pub fn build(skeleton: &Skeleton, bind: &[Transform], radius: impl Fn(usize, f32) -> f32) -> Result<Skin, BodyError> {
    build_with(skeleton, bind, radius, Detail::FULL)
}

/// [`build`] with tubes cut as `detail` says.
pub fn build_with(
    skeleton: &Skeleton,
    bind: &[Transform],
    radius: impl Fn(usize, f32) -> f32,
    detail: Detail,
) -> Result<Skin, BodyError> {
    let joints = skeleton.joints();
    if bind.len() != joints.len() || bind.iter().any(|t| !t.translation.is_finite()) {
        return Err(BodyError::BindPose { given: bind.len(), joints: joints.len() });
    }
    let at = |j: usize| bind.get(j).map_or(Vec3::ZERO, |t| t.translation);
    let bones: Vec<(usize, usize)> = joints
        .iter()
        .enumerate()
        .filter_map(|(j, joint)| joint.parent.filter(|&p| p < j).map(|p| (p, j)))
        .filter(|&(p, j)| at(p).distance(at(j)) > 0.0)
        .collect();
    if bones.len() > MAX_BODY_BONES {
        return Err(BodyError::TooManyBones(bones.len()));
    }
    let mut b = Builder { detail: Some(detail), ..Builder::default() };
    let index = |j: usize| u32::try_from(j).unwrap_or(u32::MAX);
    for &(p, j) in &bones {
        let length = at(p).distance(at(j));
        let r = radius(j, length);
        let r = if r.is_finite() && r > 0.0 { r } else { length * 0.1 };
        let near = joints.get(p).and_then(|x| x.parent).map(index);
        b.tube(at(p), at(j), r, Owners { owner: index(p), far: Some(index(j)), near });
    }
    if bones.is_empty() {
        for root in skeleton.roots() {
            let r = radius(root, 0.0);
            let r = if r.is_finite() && r > 0.0 { r } else { 0.05 };
            b.tube(at(root), at(root), r, Owners { owner: index(root), far: None, near: None });
        }
    }
    Ok(Skin::new(b.positions, b.normals, b.indices, b.joints, b.weights, bind)?)
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use std::collections::HashMap;

    /// Every undirected edge and how many triangles use it.
    pub(crate) fn edge_uses(indices: &[u32]) -> HashMap<(u32, u32), usize> {
        let mut edges = HashMap::new();
        for t in indices.chunks(3) {
            for (a, b) in [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])] {
                *edges.entry((a.min(b), a.max(b))).or_insert(0) += 1;
            }
        }
        edges
    }

    /// Every triangle of a tube around the +Y axis from `bottom` to `top`
    /// winds counter-clockwise seen from outside (the renderer draws front
    /// faces only).
    pub(crate) fn assert_wound_outward(positions: &[Vec3], indices: &[u32], bottom: f32, top: f32) {
        for t in indices.chunks(3) {
            let [p0, p1, p2] = [0, 1, 2].map(|k| positions[t[k] as usize]);
            let centre = (p0 + p1 + p2) / 3.0;
            let outward = centre - Vec3::new(0.0, centre.y.clamp(bottom, top), 0.0);
            assert!((p1 - p0).cross(p2 - p0).dot(outward) > 0.0, "{p0} {p1} {p2} winds inward");
        }
    }

    #[test]
    fn a_coarse_tube_is_closed_with_its_ends_weighted_the_same() {
        let mut b = Builder { detail: Some(Detail::COARSE), ..Builder::default() };
        b.tube(Vec3::ZERO, Vec3::Y * 2.0, 0.2, Owners { owner: 1, far: Some(2), near: Some(0) });
        assert_eq!(b.positions.len() as u32, Detail::COARSE.tube_vertices());
        assert_eq!((b.positions.len(), b.indices.len() / 3), (20, 36));
        assert!(edge_uses(&b.indices).values().all(|&n| n == 2), "closed");
        assert_wound_outward(&b.positions, &b.indices, 0.0, 2.0);
        let last = b.weights.len() - 1;
        assert_eq!((b.joints[last], b.weights[last]), ([1, 2, 0, 1], [0.5, 0.5, 0.0, 0.0]));
        assert_eq!((b.joints[0], b.weights[0]), ([1, 2, 0, 1], [0.5, 0.0, 0.5, 0.0]));
        assert!(b.weights.iter().all(|w| (w.iter().sum::<f32>() - 1.0).abs() < 1e-6));
        // Counts below their least are raised (no empty or degenerate tube).
        let mut z = Builder { detail: Some(Detail { segments: 0, cap_rings: 0, spans: 0 }), ..Builder::default() };
        z.tube(Vec3::ZERO, Vec3::Y, 0.1, Owners { owner: 0, far: None, near: None });
        assert!(edge_uses(&z.indices).values().all(|&n| n == 2) && !z.indices.is_empty());
    }

    #[test]
    fn a_tube_is_closed_and_weighted_toward_its_ends() {
        let mut b = Builder::default();
        b.tube(Vec3::ZERO, Vec3::Y * 2.0, 0.2, Owners { owner: 1, far: Some(2), near: Some(0) });
        assert_eq!(b.positions.len() as u32, TUBE_VERTICES);
        assert!(edge_uses(&b.indices).values().all(|&n| n == 2), "closed");
        // The far pole is half the child's, the middle all the owner's, the near pole half the grandparent's.
        let last = b.weights.len() - 1;
        assert_eq!((b.joints[last], b.weights[last]), ([1, 2, 0, 1], [0.5, 0.5, 0.0, 0.0]));
        assert_eq!((b.joints[0], b.weights[0]), ([1, 2, 0, 1], [0.5, 0.0, 0.5, 0.0]));
        let middle = (0..b.positions.len())
            .min_by(|&i, &j| (b.positions[i].y - 1.0).abs().total_cmp(&(b.positions[j].y - 1.0).abs()))
            .unwrap();
        assert_eq!(b.weights[middle], [1.0, 0.0, 0.0, 0.0]);
        // Outward normals: from the axis.
        for (p, n) in b.positions.iter().zip(&b.normals) {
            let axis = Vec3::new(0.0, p.y.clamp(0.0, 2.0), 0.0);
            assert!((*p - axis).normalize().dot(*n) > 0.99, "{p} {n}");
        }
        assert_wound_outward(&b.positions, &b.indices, 0.0, 2.0);
    }
}
