//! One posed actor → renderer primitives: bones (capsules or sticks) or a skinned
//! body, joints, axes, a correction's ghost, or a model's mesh; and the floor.

use crate::drawable::Drawable;
use mocap::Transform;
use mocap::glam::{Mat4, Vec3};
use mocap::model::mesh::MorphSample;
use mocap::stage::Stage;
use mocap_render::{
    DrawMode, FigureStyle, Grid, HIGHLIGHT_COLOR, JOINT_COLOR, Line, MeshDraw, NEUTRAL_TINT, Scene, SkinnedDraw,
    push_figure,
};

/// Colours of a joint's local X, Y and Z axes.
const AXES: [[u8; 4]; 3] = [[235, 60, 60, 255], [60, 210, 80, 255], [70, 120, 255, 255]];
/// Colour of the ghost lines (the clip's own pose under a correction).
const GHOST: [u8; 4] = [255, 255, 255, 110];

/// How every actor of a frame is drawn.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SceneStyle {
    /// Capsules, sticks or body (a skeleton without a body keeps its capsules).
    pub mode: DrawMode,
    /// Joint spheres in stick mode.
    pub show_joints: bool,
    /// Each joint's local axes.
    pub show_axes: bool,
    /// Bodies coloured by their skin weights.
    pub show_weights: bool,
}

impl Default for SceneStyle {
    fn default() -> SceneStyle {
        SceneStyle { mode: DrawMode::default(), show_joints: true, show_axes: false, show_weights: false }
    }
}

/// One actor posed at the frame drawn.
#[derive(Clone, Copy, Debug)]
pub struct ActorDraw<'a> {
    /// What it is drawn with.
    pub drawable: &'a Drawable,
    /// A clip's world transforms (metres, placed), one per joint in joint order.
    pub pose: &'a [Transform],
    /// A model's key frames at this time.
    pub morph: Option<MorphSample>,
    /// The actor's placement (a model's mesh is drawn through it).
    pub world_matrix: Mat4,
    /// Bone colour (sRGB).
    pub color: [u8; 4],
    /// The actor's size in metres (bone radii and axis lengths scale with it).
    pub extent: f32,
    /// The joint drawn highlighted.
    pub selected: Option<usize>,
    /// The clip's own pose under a correction (world, metres), drawn as thin
    /// translucent lines over everything; empty for none.
    pub ghost: &'a [Transform],
    /// A character's own look under its morph-target weights ([`crate::MorphShape`]),
    /// when they move it.
    pub shape: Option<&'a std::sync::Arc<[mocap::glam::Vec3]>>,
}

/// Appends one actor to `scene` in `style` ([`mocap_render::push_figure`] for a
/// clip; a model's mesh textured with its skin, or the neutral material without one).
pub fn push_actor(scene: &mut Scene, actor: &ActorDraw, style: &SceneStyle) {
    if let Some(mesh) = &actor.drawable.mesh {
        let Some(at) = actor.morph else { return };
        let tint = if mesh.has_skin() { [255; 4] } else { NEUTRAL_TINT };
        let frames = [at.frame0, at.frame1].map(|f| u32::try_from(f).unwrap_or(u32::MAX));
        scene.meshes.push(MeshDraw {
            mesh: mesh.clone(),
            frames,
            blend: at.blend,
            transform: actor.world_matrix,
            tint,
        });
        return;
    }
    let figure = &actor.drawable.figure;
    if figure.is_empty() {
        return;
    }
    // Body mode draws the skinned body; a skeleton without one keeps its capsules.
    // A character's own look is drawn in every mode but sticks, in place of the bones.
    let own = actor.drawable.built_body().filter(|b| b.own && style.mode != DrawMode::Sticks);
    let body = own.or(actor.drawable.built_body().filter(|_| style.mode == DrawMode::Body));
    let mode = if style.mode == DrawMode::Body && body.is_none() { DrawMode::Capsules } else { style.mode };
    if let Some(body) = body {
        let mut matrices = Vec::with_capacity(body.inverse_bind.len());
        mocap::runtime::skin::skinning_matrices(actor.pose, &body.inverse_bind, &mut matrices);
        scene.skinned.push(SkinnedDraw {
            mesh: body.mesh.clone(),
            coarse: body.coarse.clone(),
            matrices,
            tint: if body.own { [255; 4] } else { actor.color },
            weights_view: style.show_weights,
            shape: actor.shape.filter(|_| body.own).cloned(),
        });
        if body.own {
            // The look stands for the bones; joints and axes still show on request.
            push_overlays(scene, actor, style);
            return;
        }
    }
    let figure_style = FigureStyle {
        mode,
        color: actor.color,
        joint_color: JOINT_COLOR,
        size: actor.extent,
        show_joints: style.show_joints,
        highlight: actor.selected.map(|j| (j, HIGHLIGHT_COLOR)),
    };
    push_figure(scene, figure, actor.pose, &figure_style);
    push_overlays(scene, actor, style);
}

/// Each joint's axes when asked for, and a correction's ghost.
fn push_overlays(scene: &mut Scene, actor: &ActorDraw, style: &SceneStyle) {
    let figure = &actor.drawable.figure;
    if style.show_axes {
        // Joints the figure leaves out (End Sites, simplified huge figures) have no marker.
        for (joint, t) in figure.iter().zip(actor.pose) {
            if joint.marker {
                push_axes(t, actor.extent * 0.06, scene);
            }
        }
    }
    push_ghost(figure, actor.ghost, scene);
}

/// The clip's own pose under a correction: thin translucent lines over everything.
fn push_ghost(figure: &[mocap_render::FigureJoint], ghost: &[Transform], scene: &mut Scene) {
    for (joint, t) in figure.iter().zip(ghost) {
        if let Some(p) = joint.parent.and_then(|p| ghost.get(p)) {
            scene.overlay_lines.push(Line { a: p.translation, b: t.translation, color: GHOST, width_px: 2.0 });
        }
    }
}

/// A joint's local axes, `length` metres long.
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
/// with 0.5 m cells (1 m major lines), covering every visible actor.
pub fn floor_grid<E>(stage: &Stage<E>) -> Grid {
    let b = stage.floor_bounds();
    Grid::floor(b.min, b.max, stage.extent(), 0.5)
}
