//! Turns the posed characters into renderer primitives through the shared scene
//! builder ([`mocap_scene::push_actor`], the one `mocap render` uses too).

use crate::character::Character;
use crate::selection::Selection;
use crate::settings::ViewSettings;
use crate::stage::Stage;
use mocap_render::Scene;
use mocap_scene::{ActorDraw, SceneStyle};

/// Fills `scene` with the floor grid and every visible character in its last pose
/// ([`crate::character::pose_at`]); empty without characters.
pub fn build_scene(stage: &Stage, settings: &ViewSettings, selected: Option<Selection>, scene: &mut Scene) {
    scene.clear();
    if stage.actors.is_empty() {
        return;
    }
    scene.grid = Some(mocap_scene::floor_grid(stage));
    scene.shadows = settings.shadows;
    let style = style(settings);
    for (i, c) in stage.visible() {
        let joint = selected.filter(|s| s.character == i).map(|s| s.joint);
        mocap_scene::push_actor(scene, &draw(c, c.extra.color, joint), &style);
    }
}

/// The scene builder's style for the view settings.
pub fn style(settings: &ViewSettings) -> SceneStyle {
    SceneStyle {
        mode: settings.mode,
        show_joints: settings.show_joints,
        show_axes: settings.show_axes,
        show_weights: settings.show_weights,
    }
}

/// Character `c` in its last pose, in `color`, joint `selected` highlighted.
pub fn draw(c: &Character, color: [u8; 4], selected: Option<usize>) -> ActorDraw<'_> {
    ActorDraw {
        drawable: &c.extra.drawable,
        pose: &c.extra.pose,
        morph: c.extra.morph,
        world_matrix: c.world_matrix(),
        color,
        extent: c.world_extent(),
        selected,
        ghost: &c.extra.ghost,
    }
}
