//! Skeletons to primitives: one figure (a posed skeleton) becomes bones and joints
//! in the chosen [`DrawMode`]. Knows joint positions and parents, no file formats.

use crate::radius::bone_radius;
use crate::{Capsule, Line, Scene, Sphere};
use glam::Vec3;

/// Bone colours given to figures in turn (sRGB): a light grey first, then hues
/// apart from [`JOINT_COLOR`] and [`HIGHLIGHT_COLOR`].
pub const PALETTE: [[u8; 4]; 6] = [
    [200, 205, 215, 255],
    [240, 160, 80, 255],
    [120, 200, 130, 255],
    [175, 140, 245, 255],
    [225, 120, 190, 255],
    [90, 205, 205, 255],
];

/// Joint marker colour in stick mode (sRGB).
pub const JOINT_COLOR: [u8; 4] = [90, 160, 235, 255];

/// Colour of a highlighted (selected) joint and its bone (sRGB).
pub const HIGHLIGHT_COLOR: [u8; 4] = [255, 200, 40, 255];

/// How figures are drawn.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum DrawMode {
    /// Lit solids: one capsule per bone, sized to the bone (the default).
    #[default]
    Capsules,
    /// Screen-space sticks for bones and small spheres at the joints.
    Sticks,
    /// A skinned body around the bones (the caller adds it as a
    /// [`crate::SkinnedDraw`]; [`push_figure`] adds only the highlight).
    Body,
}

impl DrawMode {
    /// Every mode, in menu order (the `m` key cycles through them).
    pub const ALL: [DrawMode; 3] = [DrawMode::Capsules, DrawMode::Sticks, DrawMode::Body];

    /// Lower-case name used on command lines and in URLs.
    pub fn name(self) -> &'static str {
        match self {
            DrawMode::Capsules => "capsules",
            DrawMode::Sticks => "sticks",
            DrawMode::Body => "body",
        }
    }

    /// The mode after this one in [`DrawMode::ALL`] (cycling).
    pub fn next(self) -> DrawMode {
        let i = DrawMode::ALL.iter().position(|m| *m == self).unwrap_or(0);
        DrawMode::ALL[(i + 1) % DrawMode::ALL.len()]
    }

    /// The mode called `name` (see [`DrawMode::name`]).
    pub fn from_name(name: &str) -> Option<DrawMode> {
        DrawMode::ALL.into_iter().find(|m| m.name().eq_ignore_ascii_case(name.trim()))
    }
}

/// One joint of a figure: its parent (earlier in the list; its bone runs from
/// there), whether it gets a joint marker (end points such as End Sites get a
/// bone but no marker) and how thick its bone is. Build figures with [`figure`],
/// size them once with [`size_figure`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FigureJoint {
    /// Index of the parent joint, `None` for a root.
    pub parent: Option<usize>,
    /// Draw a joint marker (ball, axes) here.
    pub marker: bool,
    /// Radius of the bone from the parent as a share of the figure's size, set
    /// by [`size_figure`]; 0 (unsized): [`bone_radius`] of the length drawn.
    pub radius: f32,
}

/// Looks of one figure.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FigureStyle {
    /// Capsules or sticks.
    pub mode: DrawMode,
    /// Bone colour (sRGB).
    pub color: [u8; 4],
    /// Joint marker colour in stick mode (sRGB).
    pub joint_color: [u8; 4],
    /// Size of the figure (e.g. a standing height) in world units: sets thicknesses.
    pub size: f32,
    /// Draw joint markers (stick mode).
    pub show_joints: bool,
    /// A joint to highlight, and its colour.
    pub highlight: Option<(usize, [u8; 4])>,
}

/// Figures with more bones than this are simplified by [`figure`], so that a file
/// with a 200,000-joint chain stays drawable on a software GPU.
pub const MAX_FIGURE_BONES: usize = 16_384;

/// The figure of a skeleton, from each joint's parent (earlier in the list) and
/// whether it gets a joint marker (not an End Site). Built once per skeleton.
///
/// Up to [`MAX_FIGURE_BONES`] joints every joint is drawn. Past that the figure is
/// simplified here, not per frame: every k-th level of the tree is kept (k =
/// joints / [`MAX_FIGURE_BONES`], rounded up), with the roots and the leaves, each
/// kept joint hanging from its nearest kept ancestor; a joint left out gets neither
/// a parent nor a marker, so nothing is drawn for it. One linear pass.
pub fn figure(joints: impl IntoIterator<Item = (Option<usize>, bool)>) -> Vec<FigureJoint> {
    let mut out: Vec<FigureJoint> =
        joints.into_iter().map(|(parent, marker)| FigureJoint { parent, marker, radius: 0.0 }).collect();
    let stride = out.len().div_ceil(MAX_FIGURE_BONES).max(1);
    if stride == 1 {
        return out;
    }
    let mut leaf = vec![true; out.len()];
    for j in &out {
        if let Some(flag) = j.parent.and_then(|p| leaf.get_mut(p)) {
            *flag = false;
        }
    }
    let mut depth = vec![0usize; out.len()];
    let mut anchor = vec![0usize; out.len()];
    for i in 0..out.len() {
        let parent = out.get(i).and_then(|j| j.parent).filter(|&p| p < i);
        let d = parent.and_then(|p| depth.get(p)).map_or(0, |d| d + 1);
        let kept = parent.is_none() || d % stride == 0 || leaf.get(i).copied().unwrap_or(true);
        let from = parent.and_then(|p| anchor.get(p).copied());
        if let (Some(slot), Some(a), Some(joint)) = (depth.get_mut(i), anchor.get_mut(i), out.get_mut(i)) {
            *slot = d;
            *a = if kept { i } else { from.unwrap_or(i) };
            *joint = if kept {
                FigureJoint { parent: from, ..*joint }
            } else {
                FigureJoint { parent: None, marker: false, radius: 0.0 }
            };
        }
    }
    out
}

/// Appends the figure posed at `positions` (world space, one per joint of `joints`:
/// points, or anything that converts to its position, such as a world transform)
/// to `scene`. Joints with non-finite positions and their bones are skipped.
/// Capsules (and a body's shadow casters) are as thick as the figure was sized
/// ([`FigureJoint::radius`]).
pub fn push_figure<P: Copy + Into<Vec3>>(
    scene: &mut Scene,
    joints: &[FigureJoint],
    positions: &[P],
    style: &FigureStyle,
) {
    let size = if style.size.is_finite() && style.size > 0.0 { style.size } else { 1.0 };
    let joint_radius = size * 0.012;
    let highlight = style.highlight.map(|(j, _)| j);
    let at = |i: usize| positions.get(i).map(|&p| p.into()).filter(|p: &Vec3| p.is_finite());
    let radius_of = |joint: &FigureJoint, length: f32| {
        if joint.radius > 0.0 { joint.radius * size } else { bone_radius(length, size) }
    };
    for (i, joint) in joints.iter().enumerate() {
        let Some(p) = at(i) else {
            continue;
        };
        let is_highlight = highlight == Some(i);
        let color = match style.highlight {
            Some((j, c)) if j == i => c,
            _ => style.color,
        };
        let parent = joint.parent.and_then(at);
        match style.mode {
            DrawMode::Capsules => {
                if let Some(q) = parent {
                    let radius = radius_of(joint, q.distance(p));
                    scene.capsules.push(Capsule { a: q, b: p, radius, color });
                } else if joint.marker {
                    // A root: a ball so a lone root (or the hips) is visible.
                    scene.capsules.push(Capsule { a: p, b: p, radius: size * 0.03, color });
                }
                if is_highlight {
                    scene.capsules.push(Capsule { a: p, b: p, radius: size * 0.04, color });
                }
            }
            DrawMode::Body => {
                // The body's shadow in the fast look: its bones' capsules.
                if let Some(q) = parent {
                    let radius = radius_of(joint, q.distance(p));
                    scene.body_casters.push(Capsule { a: q, b: p, radius, color });
                }
                if is_highlight {
                    scene.capsules.push(Capsule { a: p, b: p, radius: size * 0.045, color });
                }
            }
            DrawMode::Sticks => {
                if let Some(q) = parent {
                    scene.lines.push(Line { a: q, b: p, color, width_px: 3.0 });
                    scene.shadow_casters.push(Capsule { a: q, b: p, radius: size * 0.006, color });
                }
                if joint.marker && (style.show_joints || is_highlight) {
                    let (radius, color) =
                        if is_highlight { (joint_radius * 1.8, color) } else { (joint_radius, style.joint_color) };
                    scene.spheres.push(Sphere { center: p, radius, color });
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn chain() -> (Vec<FigureJoint>, Vec<Vec3>) {
        let joints = vec![
            FigureJoint { parent: None, marker: true, radius: 0.0 },
            FigureJoint { parent: Some(0), marker: true, radius: 0.0 },
            FigureJoint { parent: Some(1), marker: false, radius: 0.0 },
        ];
        (joints, vec![Vec3::ZERO, Vec3::Y, Vec3::new(0.0, 2.0, 0.0)])
    }

    fn style(mode: DrawMode) -> FigureStyle {
        FigureStyle { mode, color: [1; 4], joint_color: [2; 4], size: 1.8, show_joints: true, highlight: None }
    }

    #[test]
    fn capsules_one_per_bone_plus_the_root() {
        let (joints, positions) = chain();
        let mut scene = Scene::default();
        push_figure(&mut scene, &joints, &positions, &style(DrawMode::Capsules));
        assert_eq!(scene.capsules.len(), 3);
        assert!(scene.lines.is_empty() && scene.spheres.is_empty());
        assert_eq!((scene.capsules[1].a, scene.capsules[1].b), (Vec3::ZERO, Vec3::Y));
        assert_eq!(scene.capsules[1].radius, bone_radius(1.0, 1.8));
    }

    #[test]
    fn sticks_lines_joints_and_shadow_casters() {
        let (joints, positions) = chain();
        let mut scene = Scene::default();
        let mut s = style(DrawMode::Sticks);
        s.highlight = Some((1, [9; 4]));
        push_figure(&mut scene, &joints, &positions, &s);
        assert_eq!(scene.lines.len(), 2);
        assert_eq!(scene.shadow_casters.len(), 2);
        assert_eq!(scene.spheres.len(), 2, "End Sites get no joint marker");
        assert_eq!(scene.spheres[1].color, [9; 4]);
    }

    #[test]
    fn body_mode_gives_its_bones_as_fast_look_shadow_casters() {
        let (joints, positions) = chain();
        let mut scene = Scene::default();
        push_figure(&mut scene, &joints, &positions, &style(DrawMode::Body));
        assert!(scene.capsules.is_empty() && scene.shadow_casters.is_empty(), "the body draws and casts itself");
        assert_eq!(scene.body_casters.len(), 2, "one per bone");
        assert_eq!((scene.body_casters[0].a, scene.body_casters[0].b), (Vec3::ZERO, Vec3::Y));
        assert_eq!(
            scene.body_casters[0].radius,
            bone_radius(1.0, 1.8),
            "the capsule mode's radius, as the body's tubes"
        );
    }

    #[test]
    fn non_finite_joints_are_skipped() {
        let (joints, mut positions) = chain();
        positions[1] = Vec3::NAN;
        let mut scene = Scene::default();
        push_figure(&mut scene, &joints, &positions, &style(DrawMode::Capsules));
        assert_eq!(scene.capsules.len(), 1, "only the root remains");
        assert!(DrawMode::from_name("Sticks") == Some(DrawMode::Sticks) && DrawMode::from_name("x").is_none());
    }

    #[test]
    fn a_huge_chain_is_drawn_simplified_from_end_to_end() {
        let n: usize = 200_000;
        let joints = figure((0..n).map(|i| (i.checked_sub(1), i + 1 < n)));
        let positions: Vec<Vec3> = (0..n).map(|i| Vec3::new(0.0, i as f32, 0.0)).collect();
        let mut scene = Scene::default();
        let mut s = style(DrawMode::Capsules);
        s.highlight = Some((12_345, [9; 4]));
        push_figure(&mut scene, &joints, &positions, &s);
        let bones: Vec<&Capsule> = scene.capsules.iter().filter(|c| c.a != c.b).collect();
        assert!(bones.len() <= MAX_FIGURE_BONES + 2, "{} bones", bones.len());
        let covered: f32 = bones.iter().map(|c| c.a.distance(c.b)).sum();
        assert!((covered - (n - 1) as f32).abs() < 1e-3 * n as f32, "the bones still span the chain: {covered}");
        assert!(scene.capsules.iter().any(|c| c.color == [9; 4]), "the highlighted joint is drawn");
        // Small figures are drawn joint by joint.
        let small = figure((0..1000usize).map(|i| (i.checked_sub(1), true)));
        assert!(small.iter().enumerate().all(|(i, j)| j.parent == i.checked_sub(1) && j.marker));
    }
}
