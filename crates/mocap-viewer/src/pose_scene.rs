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

/// Onion skin and trails ([`mocap_scene::push_onion`], [`mocap_scene::push_trail`])
/// for every visible clip at `time`, as the view settings ask.
pub fn push_motion_marks(stage: &Stage, settings: &ViewSettings, selected: Option<Selection>, time: f64, scene: &mut Scene) {
    if !settings.onion && !settings.trails {
        return;
    }
    let mut scratch = Default::default();
    let floor = stage.floor_height() + 0.003;
    for (i, c) in stage.visible() {
        let Some(clip) = c.clip() else { continue };
        if settings.onion {
            let onion = mocap_scene::Onion { count: settings.onion_count, step: settings.onion_step };
            mocap_scene::push_onion(scene, c, &c.extra.drawable.figure, time, onion, &mut scratch);
        }
        if settings.trails {
            // Sampled at the clip's rate, at most 30 times a second.
            let step = clip.frame_time().max(1.0 / 30.0);
            let root = clip.skeleton().roots().next().unwrap_or(0);
            let window = (time - 5.0).max(0.0)..=(time + 5.0).min(c.asset.duration());
            let (path, ticks) =
                mocap_scene::joint_path(c, root, (*window.start(), *window.end()), step, Some(floor), &mut scratch);
            let current = c.extra.pose.get(root).map(|t| mocap::glam::Vec3::new(t.translation.x, floor, t.translation.z));
            let [r, g, b, _] = c.extra.color;
            mocap_scene::push_trail(scene, &path, &ticks, current, [r, g, b, 220], c.world_extent());
            if let Some(s) = selected.filter(|s| s.character == i && s.joint != root) {
                let window = ((time - 1.0).max(0.0), (time + 1.0).min(c.asset.duration()));
                let (path, ticks) = mocap_scene::joint_path(c, s.joint, window, step, None, &mut scratch);
                let current = c.extra.pose.get(s.joint).map(|t| t.translation);
                mocap_scene::push_trail(scene, &path, &ticks, current, [255, 220, 90, 230], c.world_extent());
            }
        }
    }
}
