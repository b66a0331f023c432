//! Turns the posed characters into renderer primitives through the shared scene
//! builder ([`mocap_scene::push_actor`], the one `mocap render` uses too).

use crate::character::Character;
use crate::selection::Selection;
use crate::settings::ViewSettings;
use crate::stage::Stage;
use mocap::glam::Vec3;
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
        shape: c.extra.shape.as_ref(),
    }
}

/// Paths over a whole clip (a joint's, at most 30 samples a second, with their
/// times and the whole seconds' points), kept while the clip, its place and
/// the floor are unchanged, so a playing view only picks the window it shows.
#[derive(Default)]
pub struct TrailCache {
    entries: Vec<(TrailKey, Vec<(f64, Vec3)>, Vec<(f64, Vec3)>)>,
}

/// What a cached path depends on: the character, the joint, the clip's data
/// (its buffer and length change with every edit), its place and the floor.
#[derive(Clone, Copy, Debug, PartialEq)]
struct TrailKey {
    character: usize,
    joint: usize,
    data: (usize, usize),
    placement: [u32; 3],
    floor: Option<u32>,
}

impl TrailCache {
    /// The path of `joint` of character `i` (on the floor when `floor`), whole clip.
    fn path(&mut self, i: usize, c: &crate::character::Character, joint: usize, floor: Option<f32>) -> usize {
        let Some(clip) = c.clip() else { return usize::MAX };
        let data = clip.motion().data();
        let key = TrailKey {
            character: i,
            joint,
            data: (data.as_ptr() as usize, data.len()),
            placement: c.placement().to_array().map(f32::to_bits),
            floor: floor.map(f32::to_bits),
        };
        if let Some(n) = self.entries.iter().position(|(k, ..)| *k == key) {
            return n;
        }
        let step = clip.frame_time().max(1.0 / 30.0);
        let duration = c.asset.duration();
        let mut scratch = Default::default();
        let (points, ticks) = mocap_scene::joint_path(c, joint, (0.0, duration), step, floor, &mut scratch);
        let timed = points.into_iter().enumerate().map(|(k, p)| ((k as f64 * step).min(duration), p)).collect();
        let ticks = ticks.into_iter().enumerate().map(|(k, p)| (k as f64, p)).collect();
        // A few paths at most: the roots and one selected joint.
        if self.entries.len() >= 8 {
            self.entries.remove(0);
        }
        self.entries.push((key, timed, ticks));
        self.entries.len() - 1
    }

    /// The cached path `n` between `from` and `to` seconds: points and ticks.
    fn window(&self, n: usize, from: f64, to: f64) -> (Vec<Vec3>, Vec<Vec3>) {
        let Some((_, points, ticks)) = self.entries.get(n) else { return (Vec::new(), Vec::new()) };
        let inside = |list: &[(f64, Vec3)]| list.iter().filter(|(t, _)| (from..=to).contains(t)).map(|(_, p)| *p).collect();
        (inside(points), inside(ticks))
    }
}

/// Onion skin and trails ([`mocap_scene::push_onion`], [`mocap_scene::push_trail`])
/// for every visible clip at `time`, as the view settings ask.
pub fn push_motion_marks(
    stage: &Stage,
    settings: &ViewSettings,
    selected: Option<Selection>,
    time: f64,
    cache: &mut TrailCache,
    scene: &mut Scene,
) {
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
            let root = clip.skeleton().roots().next().unwrap_or(0);
            let n = cache.path(i, c, root, Some(floor));
            let (path, ticks) = cache.window(n, time - 5.0, time + 5.0);
            let current = c.extra.pose.get(root).map(|t| Vec3::new(t.translation.x, floor, t.translation.z));
            let [r, g, b, _] = c.extra.color;
            mocap_scene::push_trail(scene, &path, &ticks, current, [r, g, b, 220], c.world_extent());
            if let Some(s) = selected.filter(|s| s.character == i && s.joint != root) {
                let n = cache.path(i, c, s.joint, None);
                let (path, ticks) = cache.window(n, time - 1.0, time + 1.0);
                let current = c.extra.pose.get(s.joint).map(|t| t.translation);
                mocap_scene::push_trail(scene, &path, &ticks, current, [255, 220, 90, 230], c.world_extent());
            }
        }
    }
}
