//! Dragging in the view: a joint (IK), one of its rotation rings, a rig handle,
//! the tentacle's target, or a new bone pulled out of a joint (the creator); and
//! the handles the view offers for them.

use super::Viewer;
use crate::character;
use crate::gesture::{Grab, Grow, RingDrag};

impl Viewer {
    /// A joint, ring, rig handle or the tentacle's target dragged in the view.
    pub(super) fn drag(&mut self, d: crate::drag::JointDrag) {
        if let Some(grow) =
            self.gesture.grow.as_mut().filter(|g| g.character == d.handle.character && g.parent == d.handle.joint)
        {
            // Growing a new bone: its end follows the pointer until release.
            grow.end = Some(d.target);
        } else if let Some(axis) = d.handle.ring {
            self.set_playing(false);
            self.drag_ring(d, axis);
        } else if [crate::rig_edit::RIG_JOINT, crate::rig_edit::RIG_SPIN, crate::rig_edit::RIG_PAINT]
            .contains(&d.handle.character)
        {
            self.drag_rig(d.handle, d.target, d.pointer);
        } else if d.handle.character == crate::drag::TARGET {
            if let Some(t) = &mut self.state.tentacle {
                t.target = d.target;
            }
        } else {
            let switching = match self.gesture.grab {
                Some(grab) if grab.press == d.press => grab.switching,
                _ => {
                    let switching = d.handle.character != self.state.current();
                    self.gesture.grab = Some(Grab { press: d.press, switching });
                    switching
                }
            };
            self.set_playing(false);
            self.select_in(d.handle.character, Some(d.handle.joint));
            if !switching {
                self.drag_joint(d.handle.character, d.handle.joint, d.target);
            }
        }
    }

    /// The joints that can be grabbed in Edit mode: every joint of every visible
    /// clip character (End Sites included: a finger tip is a fine handle), where it
    /// was last drawn. Empty outside Edit mode.
    pub fn handles(&self) -> Vec<crate::drag::Handle> {
        let mut out = Vec::new();
        if let Some(t) = &self.state.tentacle {
            out.push(crate::drag::Handle { character: crate::drag::TARGET, joint: 0, world: t.target, ring: None });
        }
        if self.state.rig_edit.is_some() {
            out.extend(self.rig_handles());
            return out;
        }
        if !self.state.settings.pose_mode {
            return out;
        }
        for (character, c) in self.state.stage.visible().filter(|(_, c)| c.clip().is_some()) {
            out.extend(c.extra.pose.iter().enumerate().map(|(joint, t)| crate::drag::Handle {
                character,
                joint,
                world: t.translation,
                ring: None,
            }));
        }
        if let Some((handles, _)) = self.rings() {
            out.extend(handles);
        }
        out
    }

    /// Moves joint `joint` of character `character` to `world` (metres) at the frame
    /// shown, by IK ([`character::drag_joint`]); the corrected pose is drawn over
    /// the clip's own (ghosted) until [`Viewer::reset_pose`]. Returns the solve, or
    /// `None` when there is no such joint.
    pub fn drag_joint(
        &mut self,
        character: usize,
        joint: usize,
        world: mocap::glam::Vec3,
    ) -> Option<mocap::runtime::ik::Solve> {
        let time = self.state.playback.time;
        let c = self.state.stage.actors.get_mut(character)?;
        let solve = character::drag_joint(c, joint, world, time, &mut self.pose_scratch);
        self.pose();
        solve
    }

    /// Arms the creator's drag: the next drag from the selected joint in the view
    /// pulls out a new child bone named `name`, added (one undoable edit) where
    /// the pointer lets go. Returns false without a selected clip joint.
    pub(crate) fn grow_bone(&mut self, name: &str) -> bool {
        let Some(s) = self.state.selected else { return false };
        let ok = self
            .state
            .stage
            .actors
            .get(s.character)
            .and_then(|c| c.clip())
            .is_some_and(|clip| !clip.skeleton().is_end_site(s.joint));
        if ok {
            self.state.settings.pose_mode = true;
            self.gesture.grow =
                Some(Grow { character: s.character, parent: s.joint, name: name.trim().to_owned(), end: None });
        }
        ok
    }

    /// Whether a new bone is being dragged out (armed or held).
    pub fn growing(&self) -> bool {
        self.gesture.grow.is_some()
    }

    /// At the release of a bone drag: adds the joint where its end was let go.
    pub(super) fn finish_new_bone(&mut self) {
        let Some(Grow { character, parent, name, end: Some(end) }) = self.gesture.grow.clone() else { return };
        self.gesture.grow = None;
        let Some(c) = self.state.stage.actors.get(character) else { return };
        let (Some(clip), Some(at)) = (c.clip(), c.extra.pose.get(parent)) else { return };
        // The offset in the parent joint's frame and the file's units.
        let offset = at.rotation.inverse() * (end - at.translation) / (at.scale.x.abs().max(1e-9));
        let parent_name = clip.skeleton().joints().get(parent).map(|j| j.name.clone()).unwrap_or_default();
        let edit = mocap::ops::edit::Edit::AddJoint { parent: parent_name, name: name.clone(), offset };
        match self.edit(character, &edit, &format!("Add {name}")) {
            Ok(()) => {
                let joint = self.state.stage.actors.get(character).and_then(|c| c.clip()?.skeleton().find(&name));
                self.select_in(character, joint);
                self.pose();
            }
            Err(message) => self.refuse(message),
        }
    }

    /// Edit mode: the rotation rings of the selected joint (its local X, Y, Z in
    /// red, green, blue), as handles and as segments to draw; `None` when there is
    /// no selected joint of a clip, or outside Edit mode.
    pub(super) fn rings(
        &self,
    ) -> Option<(Vec<crate::drag::Handle>, Vec<(mocap::glam::Vec3, mocap::glam::Vec3, usize)>)> {
        if !self.state.settings.pose_mode {
            return None;
        }
        let s = self.state.selected?;
        let c = self.state.stage.actors.get(s.character)?;
        if c.clip()?.skeleton().is_end_site(s.joint) || !c.visible {
            return None;
        }
        let t = c.extra.pose.get(s.joint)?;
        Some(crate::drag::rings(s.character, s.joint, t.translation, t.rotation, c.world_extent() * 0.12))
    }

    /// Turns the selected joint by dragging one of its rings: the pointer's angle
    /// around the ring since the press turns the joint about that axis.
    fn drag_ring(&mut self, d: crate::drag::JointDrag, axis: mocap::glam::Vec3) {
        let Some(view) = self.viewport.geometry else { return };
        let Some(c) = self.state.stage.actors.get(d.handle.character) else { return };
        let Some(t) = c.extra.pose.get(d.handle.joint).copied() else { return };
        let fresh = self
            .gesture
            .ring
            .is_none_or(|r| r.joint != d.handle.joint || r.character != d.handle.character || r.axis != axis);
        if fresh {
            let from = d.handle.world - t.translation;
            // From the press, not from where the drag was first noticed.
            let Some(start) = crate::drag::ring_angle(&view, d.press, t.translation, axis, from) else { return };
            self.gesture.ring = Some(RingDrag {
                character: d.handle.character,
                joint: d.handle.joint,
                axis,
                center: t.translation,
                from,
                start,
                world: t.rotation,
            });
        }
        let Some(r) = self.gesture.ring else { return };
        let Some(angle) = crate::drag::ring_angle(&view, d.pointer, r.center, r.axis, r.from) else { return };
        let turned = mocap::glam::Quat::from_axis_angle(r.axis, angle - r.start) * r.world;
        // A root's parent frame is the file's axes turned up (Actor::place).
        let parent = c
            .clip()
            .and_then(|clip| clip.skeleton().joints().get(r.joint)?.parent)
            .and_then(|p| c.extra.pose.get(p))
            .map_or(c.up.rotation(), |p| p.rotation);
        self.rotate_joint(r.character, r.joint, (parent.inverse() * turned).normalize());
    }

    /// Draws the drag tools over the scene: the new bone being pulled out, and
    /// the selected joint's rotation rings in Edit mode.
    pub(super) fn drag_overlay(&mut self) {
        if let Some(Grow { character, parent, end: Some(end), .. }) = &self.gesture.grow {
            if let Some(from) = self.state.stage.actors.get(*character).and_then(|c| c.extra.pose.get(*parent)) {
                self.scene.overlay_lines.push(mocap_render::Line {
                    a: from.translation,
                    b: *end,
                    color: [255, 200, 40, 255],
                    width_px: 4.0,
                });
            }
        }
        if let Some((_, segments)) = self.rings() {
            const RING: [[u8; 4]; 3] = [[235, 70, 70, 230], [80, 220, 90, 230], [80, 130, 255, 230]];
            for (a, b, k) in segments {
                self.scene.overlay_lines.push(mocap_render::Line { a, b, color: RING[k % 3], width_px: 2.5 });
            }
        }
    }
}
