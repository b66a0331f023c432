//! Turns posed characters into renderer primitives: bones, joints, axes, floor.
//! This is the only place that does; [`character_primitives`] draws one character.

use crate::document::Document;
use crate::selection::Selection;
use crate::settings::ViewSettings;
use crate::stage::Stage;
use mocap::Transform;
use mocap::glam::Vec3;
use mocap_render::{Grid, Line, Scene, Sphere};

const JOINT: [u8; 4] = [90, 160, 235, 255];
const SELECTED: [u8; 4] = [255, 200, 40, 255];
const AXES: [[u8; 4]; 3] = [[235, 60, 60, 255], [60, 210, 80, 255], [70, 120, 255, 255]];

/// Fills `scene` with the floor grid and every visible character in its last pose
/// ([`crate::character::Character::pose_at`]); empty without characters.
pub fn build_scene(stage: &Stage, settings: &ViewSettings, selected: Option<Selection>, scene: &mut Scene) {
    scene.clear();
    if stage.characters.is_empty() {
        return;
    }
    scene.grid = Some(floor_grid(stage));
    for (i, c) in stage.visible() {
        let joint = selected.filter(|s| s.character == i).map(|s| s.joint);
        character_primitives(&c.document, c.pose(), c.color, settings, joint, scene);
    }
}

/// Appends one character: bones in `color`, joint spheres, axes and the highlight
/// of joint `selected`. `transforms` are its world transforms in metres, already
/// placed (one per joint of `doc`, in joint order).
pub fn character_primitives(
    doc: &Document,
    transforms: &[Transform],
    color: [u8; 4],
    settings: &ViewSettings,
    selected: Option<usize>,
    scene: &mut Scene,
) {
    let radius = doc.extent * doc.meters_per_unit() * 0.012;
    for (i, joint) in doc.clip.skeleton.joints.iter().enumerate() {
        let Some(t) = transforms.get(i) else { break };
        let is_selected = selected == Some(i);
        if let Some(parent) = joint.parent.and_then(|p| transforms.get(p)) {
            let color = if is_selected { SELECTED } else { color };
            scene.lines.push(Line { a: parent.translation, b: t.translation, color, width_px: 3.0 });
        }
        if joint.end_site {
            continue;
        }
        if settings.show_joints || is_selected {
            let (r, color) = if is_selected { (radius * 1.8, SELECTED) } else { (radius, JOINT) };
            scene.spheres.push(Sphere { center: t.translation, radius: r, color });
        }
        if settings.show_axes {
            push_axes(t, radius * 5.0, scene);
        }
    }
}

fn push_axes(t: &Transform, length: f32, scene: &mut Scene) {
    for (axis, color) in [Vec3::X, Vec3::Y, Vec3::Z].into_iter().zip(AXES) {
        scene.lines.push(Line { a: t.translation, b: t.translation + t.rotation * axis * length, color, width_px: 2.0 });
    }
}

/// A floor at the lowest point the visible motions reach, with 0.5 m cells (1 m
/// major lines), covering all of them.
pub fn floor_grid(stage: &Stage) -> Grid {
    let b = stage.bounds();
    Grid::floor(b.min, b.max, stage.extent(), 0.5)
}
