//! Turns posed characters into renderer primitives: bones (capsules or sticks) or a
//! skinned body, joints, axes, models' meshes, the floor.
//! This is the only place that does; [`character_primitives`] draws one character.

use crate::character::Character;
use crate::selection::Selection;
use crate::settings::ViewSettings;
use crate::stage::Stage;
use mocap::Transform;
use mocap::glam::Vec3;
use mocap_render::{
    DrawMode, FigureStyle, Grid, HIGHLIGHT_COLOR, JOINT_COLOR, Line, MeshDraw, NEUTRAL_TINT, Scene, SkinnedDraw,
    push_figure,
};

const AXES: [[u8; 4]; 3] = [[235, 60, 60, 255], [60, 210, 80, 255], [70, 120, 255, 255]];

/// Fills `scene` with the floor grid and every visible character in its last pose
/// ([`crate::character::pose_at`]); empty without characters.
pub fn build_scene(stage: &Stage, settings: &ViewSettings, selected: Option<Selection>, scene: &mut Scene) {
    scene.clear();
    if stage.actors.is_empty() {
        return;
    }
    scene.grid = Some(floor_grid(stage));
    scene.shadows = settings.shadows;
    for (i, c) in stage.visible() {
        if c.model().is_some() {
            mesh_primitive(c, scene);
            continue;
        }
        let joint = selected.filter(|s| s.character == i).map(|s| s.joint);
        character_primitives(c, &c.extra.pose, c.extra.color, settings, joint, scene);
        push_ghost(c, scene);
    }
}

/// Appends a model at its last posed key frames: textured with its skin, or in the
/// neutral material without one.
pub fn mesh_primitive(c: &Character, scene: &mut Scene) {
    let (Some(mesh), Some(at)) = (&c.extra.mesh, c.extra.morph) else { return };
    let tint = if mesh.has_skin() { [255; 4] } else { NEUTRAL_TINT };
    let frames = [at.frame0, at.frame1].map(|f| u32::try_from(f).unwrap_or(u32::MAX));
    scene.meshes.push(MeshDraw { mesh: mesh.clone(), frames, blend: at.blend, transform: c.world_matrix(), tint });
}

/// Appends one character in the chosen draw mode ([`mocap_render::push_figure`]):
/// bones in `color`, joint spheres (stick mode), axes and the highlight of joint
/// `selected`. `transforms` are its world transforms in metres, already placed (one
/// per joint of `doc`, in joint order).
pub fn character_primitives(
    doc: &Character,
    transforms: &[Transform],
    color: [u8; 4],
    settings: &ViewSettings,
    selected: Option<usize>,
    scene: &mut Scene,
) {
    let size = doc.world_extent();
    // Body mode draws the skinned body; a skeleton without one keeps its capsules.
    let body = doc.extra.body.as_ref().and_then(|b| b.as_ref()).filter(|_| settings.mode == DrawMode::Body);
    let mode = match (settings.mode, body) {
        (DrawMode::Body, None) => DrawMode::Capsules,
        (mode, _) => mode,
    };
    if let Some(body) = body {
        let mut matrices = Vec::with_capacity(body.inverse_bind.len());
        mocap::runtime::skin::skinning_matrices(transforms, &body.inverse_bind, &mut matrices);
        scene.skinned.push(SkinnedDraw {
            mesh: body.mesh.clone(),
            coarse: body.coarse.clone(),
            matrices,
            tint: color,
            weights_view: settings.show_weights,
        });
    }
    let style = FigureStyle {
        mode,
        color,
        joint_color: JOINT_COLOR,
        size,
        show_joints: settings.show_joints,
        highlight: selected.map(|j| (j, HIGHLIGHT_COLOR)),
    };
    push_figure(scene, &doc.extra.figure, transforms, &style);
    if settings.show_axes {
        // Joints the figure leaves out (End Sites, simplified huge figures) have no marker.
        for (joint, t) in doc.extra.figure.iter().zip(transforms) {
            if joint.marker {
                push_axes(t, size * 0.06, scene);
            }
        }
    }
}

/// The clip's own pose under a correction: thin translucent lines over everything.
fn push_ghost(c: &Character, scene: &mut Scene) {
    let ghost = &c.extra.ghost;
    for (joint, t) in c.extra.figure.iter().zip(ghost) {
        if let Some(p) = joint.parent.and_then(|p| ghost.get(p)) {
            scene.overlay_lines.push(Line {
                a: p.translation,
                b: t.translation,
                color: [255, 255, 255, 110],
                width_px: 2.0,
            });
        }
    }
}

fn push_axes(t: &Transform, length: f32, scene: &mut Scene) {
    for (axis, color) in [Vec3::X, Vec3::Y, Vec3::Z].into_iter().zip(AXES) {
        scene.overlay_lines.push(Line {
            a: t.translation,
            b: t.translation + t.rotation * axis * length,
            color,
            width_px: 2.0,
        });
    }
}

/// A floor at the stage's floor height ([`mocap::stage::Stage::floor_height`]),
/// with 0.5 m cells (1 m major lines), covering every visible character.
pub fn floor_grid(stage: &Stage) -> Grid {
    let b = stage.floor_bounds();
    Grid::floor(b.min, b.max, stage.extent(), 0.5)
}
