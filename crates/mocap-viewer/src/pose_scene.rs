//! Turns a posed skeleton into renderer primitives: bones, joints, axes, floor.

use crate::document::Document;
use crate::settings::ViewSettings;
use mocap::Transform;
use mocap::glam::Vec3;
use mocap_render::{Grid, Line, Scene, Sphere};

const BONE: [u8; 4] = [200, 205, 215, 255];
const JOINT: [u8; 4] = [90, 160, 235, 255];
const SELECTED: [u8; 4] = [255, 200, 40, 255];
const AXES: [[u8; 4]; 3] = [[235, 60, 60, 255], [60, 210, 80, 255], [70, 120, 255, 255]];

/// Fills `scene` with the floor grid and the skeleton posed by `transforms`.
pub fn build_scene(doc: &Document, transforms: &[Transform], settings: &ViewSettings, selected: Option<usize>, scene: &mut Scene) {
    scene.clear();
    scene.grid = Some(floor_grid(doc));
    let radius = doc.extent * 0.012;
    for (i, joint) in doc.clip.skeleton.joints.iter().enumerate() {
        let Some(t) = transforms.get(i) else { break };
        let is_selected = selected == Some(i);
        if let Some(parent) = joint.parent.and_then(|p| transforms.get(p)) {
            let color = if is_selected { SELECTED } else { BONE };
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

/// A floor at the lowest point the motion reaches, with 0.5 m cells (1 m major lines)
/// in the clip's units, covering the whole motion.
pub fn floor_grid(doc: &Document) -> Grid {
    Grid::floor(doc.bounds.min, doc.bounds.max, doc.extent, 0.5 * doc.units_per_meter())
}
