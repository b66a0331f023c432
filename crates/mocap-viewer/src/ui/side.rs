//! Right panel: the current character's clip info, then the selected joint's inspector.

use crate::command::Command;
use crate::viewer::Viewer;

/// Shows the right-hand panel; what the user does comes back as commands in `out`.
pub fn show(ui: &mut egui::Ui, viewer: &Viewer, out: &mut Vec<Command>) {
    egui::Panel::right("side").resizable(true).default_size(280.0).show(ui, |ui| {
        egui::ScrollArea::vertical().auto_shrink([false, false]).show(ui, |ui| {
            let current = viewer.stage.actors.get(viewer.current());
            if let Some(up) = super::info::show(ui, current, viewer.stage.actors.len()) {
                out.push(Command::SetUpAxis(viewer.current(), up));
            }
            let current = viewer.stage.actors.get(viewer.current());
            ui.separator();
            if let Some((c, model)) = current.and_then(|c| Some((c, c.model()?))) {
                super::model_info::show(ui, c, model);
                let index = viewer.current().min(viewer.stage.actors.len().saturating_sub(1));
                super::capture::show(ui, viewer, index, out);
                return;
            }
            if viewer.settings.pose_mode {
                rotate_row(ui, viewer, out);
            }
            let selected = viewer.selected.and_then(|s| Some((viewer.stage.actors.get(s.character)?, s.joint)));
            let frame = selected.map_or(0, |(c, _)| c.frame_at(viewer.playback.time));
            super::inspector::show(ui, selected, frame, viewer.playback.time);
        });
    });
}

/// Edit mode: the selected joint's local rotation as Z, X, Y degrees (intrinsic, the
/// usual BVH order), editable; a change is a correction at this frame (Set key keys it).
fn rotate_row(ui: &mut egui::Ui, viewer: &Viewer, out: &mut Vec<Command>) {
    use mocap::glam::{EulerRot, Quat};
    let Some(s) = viewer.selected else { return };
    let Some(c) = viewer.stage.actors.get(s.character) else { return };
    let Some(q) = crate::character::drawn_local_rotation(c, s.joint) else { return };
    if c.clip().is_some_and(|clip| clip.skeleton().is_end_site(s.joint)) {
        return;
    }
    let (z, x, y) = q.to_euler(EulerRot::ZXY);
    let mut degrees = [z.to_degrees(), x.to_degrees(), y.to_degrees()];
    let mut changed = false;
    ui.horizontal(|ui| {
        ui.label("Rotate")
            .on_hover_text("The selected joint's rotation at this frame (Z, X, Y degrees); Set key keeps it");
        for (v, axis) in degrees.iter_mut().zip(["z ", "x ", "y "]) {
            changed |= ui.add(egui::DragValue::new(v).speed(0.5).max_decimals(1).prefix(axis)).changed();
        }
    });
    if changed {
        let [z, x, y] = degrees.map(f32::to_radians);
        let rotation = Quat::from_euler(EulerRot::ZXY, z, x, y);
        out.push(Command::RotateJoint { character: s.character, joint: s.joint, rotation });
    }
}
