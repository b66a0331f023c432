//! Rig set-up steps on the viewer.

use super::Viewer;
use crate::drag::Handle;
use crate::rig_edit::{BRUSH, RIG_JOINT, RIG_PAINT, RIG_SPIN, RigEdit, bone_color};
use mocap::capture::Rig;
use mocap::glam::{Mat4, Vec3};
impl Viewer {
    /// Starts setting up a rig on model `index`: fitted in its first frame (with
    /// `template`, an open clip's character index, its skeleton in its first
    /// pose; else a humanoid) and bound; the model shows its set-up frame.
    pub(crate) fn start_rig_edit(&mut self, index: usize, template: Option<usize>) -> Result<(), String> {
        let c = self.state.stage.actors.get(index).ok_or_else(|| format!("no character {}", index + 1))?;
        let model = c.model().ok_or_else(|| format!("{}: a rig is set up on a model (MD2)", c.name))?;
        let frames = model.mesh.source_frames();
        let setup = frames.first().cloned().unwrap_or_default();
        let rig = match template.and_then(|t| self.state.stage.actors.get(t)).and_then(|t| t.clip()) {
            Some(clip) => {
                let mut pose = Vec::new();
                clip.world_transforms_into(0, &mut pose);
                Rig::fit(&setup, 0, Some((clip.skeleton(), &pose)))
            }
            None => Rig::fit(&setup, 0, None),
        };
        self.set_animation(index, "all");
        self.set_playing(false);
        self.seek(0);
        self.state.rig_edit =
            Some(RigEdit { model: index, rig, selected: None, painting: false, show_binding: true, setup });
        Ok(())
    }

    /// The model's file units to the world (its scale and placement).
    fn rig_matrix(&self) -> Option<Mat4> {
        let e = self.state.rig_edit.as_ref()?;
        Some(self.state.stage.actors.get(e.model)?.world_matrix())
    }

    /// The rig's handles: its joints and spins, or while painting the vertices.
    pub fn rig_handles(&self) -> Vec<Handle> {
        let (Some(e), Some(m)) = (&self.state.rig_edit, self.rig_matrix()) else { return Vec::new() };
        if e.painting {
            return e
                .setup
                .iter()
                .enumerate()
                .map(|(v, p)| Handle { character: RIG_PAINT, joint: v, world: m.transform_point3(*p), ring: None })
                .collect();
        }
        let mut out: Vec<Handle> = e
            .rig
            .joints
            .iter()
            .enumerate()
            .map(|(j, x)| Handle {
                character: RIG_JOINT,
                joint: j,
                world: m.transform_point3(Vec3::from_array(x.position)),
                ring: None,
            })
            .collect();
        out.extend(spins(&e.rig).into_iter().map(|(j, _, p)| Handle {
            character: RIG_SPIN,
            joint: j,
            world: m.transform_point3(p),
            ring: None,
        }));
        out
    }

    /// A rig handle dragged to `world` (or, painting, the pointer at `pointer`).
    pub fn drag_rig(&mut self, handle: Handle, world: Vec3, pointer: egui::Pos2) {
        let Some(m) = self.rig_matrix() else { return };
        let local = m.inverse().transform_point3(world);
        let view = self.viewport.geometry;
        let Some(e) = self.state.rig_edit.as_mut() else { return };
        match handle.character {
            RIG_JOINT => {
                e.selected = Some(handle.joint);
                if let Some(j) = e.rig.joints.get_mut(handle.joint) {
                    j.position = local.to_array();
                }
            }
            RIG_SPIN => {
                let children = e.rig.children();
                let Some(&[c]) = children.get(handle.joint).map(Vec::as_slice) else { return };
                let (a, b) =
                    (Vec3::from_array(e.rig.joints[handle.joint].position), Vec3::from_array(e.rig.joints[c].position));
                let axis = (b - a).normalize_or_zero();
                let out = local - (a + b) * 0.5;
                let across = (out - axis * out.dot(axis)).normalize_or_zero();
                if across != Vec3::ZERO {
                    e.rig.joints[handle.joint].spin = Some(across.to_array());
                }
                e.selected = Some(handle.joint);
            }
            RIG_PAINT => {
                let (Some(bone), Some(view)) =
                    (e.selected.filter(|&j| e.rig.joints.get(j).is_some_and(|x| x.parent.is_some())), view)
                else {
                    return;
                };
                for (v, p) in e.setup.iter().enumerate() {
                    let near = view.project(m.transform_point3(*p)).is_some_and(|s| s.distance(pointer) <= BRUSH);
                    if let (true, Some(slot)) = (near, e.rig.binding.get_mut(v)) {
                        *slot = Some(bone);
                    }
                }
            }
            _ => {}
        }
    }

    /// Binds every vertex to its nearest bone.
    pub(crate) fn bind_rig(&mut self) {
        if let Some(e) = self.state.rig_edit.as_mut() {
            let setup = e.setup.clone();
            e.rig.bind(&setup);
        }
    }

    /// Ends the set-up; the rig is kept for the next capture of this model.
    pub(crate) fn finish_rig_edit(&mut self) {
        if let Some(e) = self.state.rig_edit.take() {
            self.state.capture_rig = Some(e.rig);
        }
    }

    /// The rig drawn over the model (see the module documentation).
    pub(crate) fn rig_overlay(&mut self) {
        let (Some(e), Some(m)) = (&self.state.rig_edit, self.rig_matrix()) else { return };
        let lines = &mut self.scene.overlay_lines;
        let at = |p: Vec3| m.transform_point3(p);
        let size = (m.transform_vector3(Vec3::Y).length() * 0.8).max(1e-4);
        for (j, joint) in e.rig.joints.iter().enumerate() {
            let p = at(Vec3::from_array(joint.position));
            if let Some(parent) = joint.parent.and_then(|q| e.rig.joints.get(q)) {
                lines.push(mocap_render::Line {
                    a: at(Vec3::from_array(parent.position)),
                    b: p,
                    color: [255, 210, 60, 255],
                    width_px: 3.0,
                });
            }
            let color = if e.selected == Some(j) { [255, 255, 255, 255] } else { [255, 120, 40, 255] };
            for d in [Vec3::X, Vec3::Y, Vec3::Z] {
                lines.push(mocap_render::Line { a: p - d * size, b: p + d * size, color, width_px: 3.0 });
            }
        }
        for (_, mid, tip) in spins(&e.rig) {
            lines.push(mocap_render::Line { a: at(mid), b: at(tip), color: [60, 230, 240, 255], width_px: 2.0 });
        }
        if e.show_binding || e.painting {
            for (v, p) in e.setup.iter().enumerate() {
                let color = e.rig.binding.get(v).copied().flatten().map_or([90, 90, 90, 255], bone_color);
                let q = at(*p);
                lines.push(mocap_render::Line { a: q, b: q + Vec3::Y * size * 0.3, color, width_px: 5.0 });
            }
        }
    }
}

/// Spin handles: per single-child joint, the middle of its bone and the tip of
/// its spin drawn from there (a third of the bone long), in file units.
fn spins(rig: &Rig) -> Vec<(usize, Vec3, Vec3)> {
    let children = rig.children();
    rig.joints
        .iter()
        .enumerate()
        .filter_map(|(j, joint)| {
            let &[c] = children.get(j)?.as_slice() else { return None };
            let (a, b) = (Vec3::from_array(joint.position), Vec3::from_array(rig.joints.get(c)?.position));
            let axis = (b - a).normalize_or_zero();
            let spin = Vec3::from_array(joint.spin?);
            let across = (spin - axis * spin.dot(axis)).normalize_or_zero();
            let mid = (a + b) * 0.5;
            (across != Vec3::ZERO).then(|| (j, mid, mid + across * a.distance(b) / 3.0))
        })
        .collect()
}
