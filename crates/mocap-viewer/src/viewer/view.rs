//! Applying a URL fragment ([`ViewState`]) to the viewer.

use super::Viewer;
use crate::view_state::ViewState;
use mocap::glam::Vec3;

impl Viewer {
    /// Applies the present fields of a URL fragment (the clips should be open already).
    pub(super) fn apply_view(&mut self, view: &ViewState) {
        if let Some(layout) = view.layout
            && layout != self.state.stage.layout
        {
            self.state.stage.set_layout(layout);
        }
        if let Some(up) = &view.up {
            for (i, &axis) in up.iter().enumerate() {
                if self.state.stage.actors.get(i).is_some_and(|c| c.clip().is_some() && c.up != axis) {
                    self.set_up_axis(i, axis);
                }
            }
        }
        if let Some(hidden) = &view.hidden {
            for (i, c) in self.state.stage.actors.iter_mut().enumerate() {
                c.visible = !hidden.contains(&i);
            }
        }
        if let Some(offsets) = &view.offsets {
            for (i, c) in self.state.stage.actors.iter_mut().enumerate() {
                c.offset = offsets.iter().find(|(n, _)| *n == i).map_or(Vec3::ZERO, |(_, o)| *o);
            }
        }
        if let Some(animations) = &view.animations {
            for i in 0..self.state.stage.actors.len() {
                let first_take =
                    self.state.stage.actors.get(i).and_then(|c| c.clip()?.takes().first().map(|t| t.name.clone()));
                let default = first_take.as_deref().unwrap_or("all");
                let name = animations.iter().find(|(n, _)| *n == i).map_or(default, |(_, a)| a.as_str());
                self.set_animation(i, name);
            }
        }
        if let Some(speed) = view.speed {
            self.state.playback.speed =
                speed.clamp(*crate::playback::SPEED_RANGE.start(), *crate::playback::SPEED_RANGE.end());
        }
        if let Some(looping) = view.looping {
            self.state.playback.looping = looping;
        }
        if let Some(range) = view.range {
            self.state.playback.range = range;
        }
        if let Some([joints, axes, follow, interp, weights, pose, footlock, cubic, onion, trails]) = view.draw {
            self.state.settings.between = match (interp, cubic) {
                (false, _) => mocap::Interpolation::Nearest,
                (true, false) => mocap::Interpolation::Linear,
                (true, true) => mocap::Interpolation::Cubic,
            };
            self.state.settings.onion = onion;
            self.state.settings.trails = trails;
            self.state.settings.pose_mode = pose;
            self.state.settings.foot_lock = footlock;
            self.state.settings.show_joints = joints;
            self.state.settings.show_axes = axes;
            self.state.settings.follow_root = follow;
            self.state.settings.show_weights = weights;
        }
        if let Some((count, step)) = view.onion {
            (self.state.settings.onion_count, self.state.settings.onion_step) = (count, step);
        }
        if let Some(mode) = view.mode {
            self.state.settings.mode = mode;
        }
        if let Some(shadows) = view.shadows {
            self.state.settings.shadows = shadows;
        }
        if let Some(quality) = view.quality {
            self.state.settings.quality = quality;
        }
        if let Some([tree, inspector]) = view.panels {
            self.state.panels.hierarchy = tree;
            self.state.panels.inspector = inspector;
        }
        if let Some((yaw, pitch, distance, target)) = view.camera {
            self.state.camera.yaw = yaw;
            self.state.camera.pitch = pitch;
            self.state.camera.distance = distance;
            self.state.camera.target = target;
        }
        match &view.selected {
            Some(Some((character, name))) => {
                // `sel=2%3AHead` (the whole value encoded once more, as URLSearchParams
                // does) names no joint of character 1: then it is read as `sel=2:Head`.
                let numbered = || crate::view_state::split_numbered(name).filter(|_| *character == 0);
                if !self.select_named(*character, name)
                    && let Some((c, n)) = numbered()
                {
                    self.select_named(c, &crate::view_state::percent_decode(n));
                }
            }
            Some(None) => self.state.selected = None,
            None => {}
        }
        if let Some(playing) = view.playing {
            self.state.playback.playing = playing;
        }
        if let Some(timing) = self.state.timing() {
            let end = timing.time_of(timing.last());
            if let Some(t) = view.time {
                self.state.playback.time = t.min(end);
            } else if let Some(f) = view.frame {
                self.state.playback.seek(f, timing);
            }
        }
        self.restart_clock();
    }
}
