//! How thick a figure's bones are drawn: capsules in capsule mode, and the tubes of
//! a generated body (a fixed factor thicker).
//!
//! Each bone gets the larger of two radii:
//! - its own, from its length ([`bone_radius`]): long limbs thick, fingers thin,
//!   helper bones (longer than [`HELPER_BONE`] of the figure) thin rods;
//! - what it carries: the bones that start where it ends, together. A trunk is as
//!   thick as its branches' cross-sections added up (the square root of the sum of
//!   their squared radii, da Vinci's rule for trees), up to [`MAX_CARRIED`] of the
//!   figure's size. So a spine that carries the arms and the head is the thickest
//!   part of the figure, as a torso is, though its bones are short, and the bones
//!   from the hips to the legs are as thick as the thighs, like a pelvis.
//!
//! Helper bones stay thin whatever they carry. Inputs: each joint's parent (a bone
//! runs from the parent to the joint) and position; one pass from the last joint
//! to the first, no recursion.

use crate::figure::FigureJoint;
use glam::Vec3;

/// Bones longer than this share of the figure's size are helpers, not limbs.
pub const HELPER_BONE: f32 = 0.75;

/// The thickest a bone gets from what it carries, as a share of the figure's size
/// (a bone's own rule stops at 0.04).
pub const MAX_CARRIED: f32 = 0.06;

/// How much thicker a generated body's tubes are than the capsules, so that they
/// read as a body rather than a stick figure.
pub const BODY_THICKNESS: f32 = 1.8;

/// A bone's own radius (capsule mode) for a bone of `length` in a figure of `size`:
/// thick for long limbs, thin for fingers, within 0.8%–4% of the figure's size.
/// Bones longer than [`HELPER_BONE`] × `size` are no limb (a rig helper joint, a
/// root left on the floor far from the hips): they are drawn as thin rods (0.4%)
/// so that they stay visible without hiding the figure.
pub fn bone_radius(length: f32, size: f32) -> f32 {
    if length > size * HELPER_BONE {
        return size * 0.004;
    }
    (length * 0.2).clamp(size * 0.008, size * 0.04)
}

/// The radius of every bone of a figure of `size` with `count` joints, in `radii`
/// (one per joint: the bone from its parent to it; 0 where there is none), by the
/// rule in this module's documentation. `parent(j)` is joint `j`'s parent (a parent
/// at or after `j` is ignored), `position(j)` where joint `j` is (none, or not
/// finite: no bone to or from it).
pub fn bone_radii(
    count: usize,
    parent: impl Fn(usize) -> Option<usize>,
    position: impl Fn(usize) -> Option<Vec3>,
    size: f32,
    radii: &mut Vec<f32>,
) {
    let size = if size.is_finite() && size > 0.0 { size } else { 1.0 };
    let at = |j: usize| position(j).filter(|p| p.is_finite());
    radii.clear();
    radii.resize(count, 0.0);
    // Squared radii of the bones that start at each joint, added up.
    let mut carried = vec![0.0f32; count];
    for j in (0..count).rev() {
        let Some(p) = parent(j).filter(|&p| p < j) else { continue };
        let (Some(a), Some(b)) = (at(p), at(j)) else { continue };
        let length = a.distance(b);
        let own = bone_radius(length, size);
        let r = if length > size * HELPER_BONE {
            own
        } else {
            let load = carried.get(j).copied().unwrap_or(0.0).sqrt().min(size * MAX_CARRIED);
            own.max(load)
        };
        if let Some(slot) = radii.get_mut(j) {
            *slot = r;
        }
        if let Some(sum) = carried.get_mut(p) {
            *sum += r * r;
        }
    }
}

/// Sizes `figure` once, when it is built: each bone's [`bone_radii`] in the pose
/// `positions` (one per joint: the bind pose a generated body is built around,
/// so capsules and body agree), stored as a share of the figure's `size`.
pub fn size_figure(figure: &mut [FigureJoint], positions: &[Vec3], size: f32) {
    let size = if size.is_finite() && size > 0.0 { size } else { 1.0 };
    let mut radii = Vec::new();
    bone_radii(figure.len(), |j| figure.get(j).and_then(|x| x.parent), |j| positions.get(j).copied(), size, &mut radii);
    for (joint, r) in figure.iter_mut().zip(radii) {
        joint.radius = r / size;
    }
}

/// [`bone_radii`] for a generated body's tubes: [`BODY_THICKNESS`] times thicker.
pub fn body_radii(
    count: usize,
    parent: impl Fn(usize) -> Option<usize>,
    position: impl Fn(usize) -> Option<Vec3>,
    size: f32,
) -> Vec<f32> {
    let mut radii = Vec::new();
    bone_radii(count, parent, position, size, &mut radii);
    radii.iter_mut().for_each(|r| *r *= BODY_THICKNESS);
    radii
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn own_radius_is_bounded() {
        assert_eq!(bone_radius(0.3, 1.0), 0.04);
        assert_eq!(bone_radius(100.0, 1.0), 0.004, "a helper bone is a thin rod");
        assert_eq!(bone_radius(0.0, 1.0), 0.008);
    }

    /// A figure 1.7 high: hips (0), a short spine bone (1) to the chest (2), which
    /// carries two long arms (3, 4) and a short neck (5); a helper (6) from the hips
    /// down to a root marker far below; a leg (7) from the hips.
    fn torso() -> (Vec<Option<usize>>, Vec<Vec3>) {
        let parents = vec![None, Some(0), Some(1), Some(2), Some(2), Some(2), Some(0), Some(0)];
        let positions = vec![
            Vec3::new(0.0, 1.0, 0.0),
            Vec3::new(0.0, 1.1, 0.0),
            Vec3::new(0.0, 1.2, 0.0),
            Vec3::new(0.5, 1.2, 0.0),
            Vec3::new(-0.5, 1.2, 0.0),
            Vec3::new(0.0, 1.3, 0.0),
            Vec3::new(0.0, -0.5, 0.0),
            Vec3::new(0.1, 0.5, 0.0),
        ];
        (parents, positions)
    }

    #[test]
    fn a_spine_is_as_thick_as_what_it_carries() {
        let (parents, positions) = torso();
        let size = 1.7;
        let mut radii = Vec::new();
        bone_radii(parents.len(), |j| parents[j], |j| positions.get(j).copied(), size, &mut radii);
        assert_eq!(radii[0], 0.0, "the root has no bone");
        let arm = bone_radius(0.5, size);
        assert_eq!((radii[3], radii[4]), (arm, arm), "limbs keep their own radius");
        let neck = bone_radius(positions[2].distance(positions[5]), size);
        assert_eq!(radii[5], neck);
        let chest = (2.0 * arm * arm + neck * neck).sqrt();
        assert!((radii[2] - chest).abs() < 1e-6, "the chest carries the arms and the neck: {} vs {chest}", radii[2]);
        assert!(radii[2] > arm && radii[2] <= MAX_CARRIED * size);
        assert!((radii[1] - chest).abs() < 1e-6, "and so does the spine below it");
        assert!(radii[1] > 2.0 * bone_radius(0.1, size), "thicker than its length alone makes it");
        assert_eq!(radii[6], size * 0.004, "a helper stays a thin rod");
        assert_eq!(radii[7], bone_radius(positions[0].distance(positions[7]), size), "a leg keeps its own radius");
    }

    #[test]
    fn what_is_carried_stops_at_its_limit_and_bad_input_gives_no_bone() {
        // A hub carrying 40 thick bones.
        let n = 42;
        let parents: Vec<Option<usize>> = (0..n)
            .map(|j| match j {
                0 => None,
                1 => Some(0),
                _ => Some(1),
            })
            .collect();
        let positions: Vec<Vec3> = (0..n)
            .map(|j| {
                if j < 2 {
                    Vec3::new(0.0, j as f32 * 0.01, 0.0)
                } else {
                    Vec3::new(j as f32, 0.5, 0.0).normalize() * 0.5
                }
            })
            .collect();
        let mut radii = Vec::new();
        bone_radii(n, |j| parents[j], |j| positions.get(j).copied(), 1.0, &mut radii);
        assert_eq!(radii[1], MAX_CARRIED);
        // A parent after its child, a missing position and a NaN: no bone, no panic.
        bone_radii(
            3,
            |j| [Some(2), Some(0), None][j],
            |j| [Some(Vec3::ZERO), None, Some(Vec3::NAN)][j],
            1.0,
            &mut radii,
        );
        assert_eq!(radii, [0.0, 0.0, 0.0]);
        // A body's tubes are thicker by the body factor.
        let body = body_radii(2, |j| j.checked_sub(1), |j| Some(Vec3::Y * j as f32 * 0.3), 1.0);
        assert_eq!(body, [0.0, bone_radius(0.3, 1.0) * BODY_THICKNESS]);
    }

    #[test]
    fn a_sized_figure_draws_its_capsules_as_thick_as_the_rule() {
        let (parents, positions) = torso();
        let mut figure = crate::figure(parents.iter().map(|&p| (p, true)));
        size_figure(&mut figure, &positions, 1.7);
        let mut radii = Vec::new();
        bone_radii(parents.len(), |j| parents[j], |j| positions.get(j).copied(), 1.7, &mut radii);
        for (joint, r) in figure.iter().zip(&radii) {
            assert!((joint.radius * 1.7 - r).abs() < 1e-6);
        }
        // Drawn at another size (metres instead of file units) the shares hold.
        let mut scene = crate::Scene::default();
        let style = crate::FigureStyle {
            mode: crate::DrawMode::Capsules,
            color: [1; 4],
            joint_color: [2; 4],
            size: 3.4,
            show_joints: false,
            highlight: None,
        };
        let doubled: Vec<Vec3> = positions.iter().map(|p| *p * 2.0).collect();
        crate::push_figure(&mut scene, &figure, &doubled, &style);
        let chest = scene.capsules.iter().find(|c| c.b == doubled[2]).expect("the chest bone");
        assert!((chest.radius - 2.0 * radii[2]).abs() < 1e-5, "{} vs {}", chest.radius, 2.0 * radii[2]);
    }

    #[test]
    fn a_deep_chain_takes_no_recursion() {
        let n = 200_000;
        let mut radii = Vec::new();
        bone_radii(n, |j| j.checked_sub(1), |j| Some(Vec3::Y * j as f32 * 0.01), 2000.0, &mut radii);
        assert_eq!(radii.len(), n);
        assert!(radii[1..].iter().all(|&r| r == 2000.0 * 0.008));
    }
}
