//! Right panel: the current character's clip info, then the selected joint's inspector.

use crate::character::Character;
use crate::command::Command;
use crate::selection::Selection;

/// What the right-hand panel shows.
pub struct SideView<'a> {
    /// The open characters.
    pub characters: &'a [Character],
    /// The current character's index.
    pub current: usize,
    /// The selected joint.
    pub selected: Option<Selection>,
    /// The playhead (s).
    pub time: f64,
    /// Edit mode: the selected joint's rotation is editable.
    pub pose_mode: bool,
    /// The model panel's capture section.
    pub capture: super::capture::CaptureView<'a>,
}

/// Shows the right-hand panel; what the user does comes back as commands in `out`.
pub fn show(ui: &mut egui::Ui, view: &SideView, out: &mut Vec<Command>) {
    egui::Panel::right("side").resizable(true).default_size(280.0).show(ui, |ui| {
        egui::ScrollArea::vertical().auto_shrink([false, false]).show(ui, |ui| {
            let current = view.characters.get(view.current);
            if let Some(up) = super::info::show(ui, current, view.characters.len()) {
                out.push(Command::SetUpAxis(view.current, up));
            }
            let current = view.characters.get(view.current);
            ui.separator();
            if let Some((c, model)) = current.and_then(|c| Some((c, c.model()?))) {
                super::model_info::show(ui, c, model);
                let index = view.current.min(view.characters.len().saturating_sub(1));
                super::capture::show(ui, &view.capture, index, out);
                return;
            }
            if view.pose_mode {
                rotate_row(ui, view, out);
            }
            let selected = view.selected.and_then(|s| Some((view.characters.get(s.character)?, s.joint)));
            let frame = selected.map_or(0, |(c, _)| c.frame_at(view.time));
            super::inspector::show(ui, selected, frame, view.time);
        });
    });
}

/// Edit mode: the selected joint's local rotation as Z, X, Y degrees (intrinsic, the
/// usual BVH order), editable; a change is a correction at this frame (Set key keys it).
fn rotate_row(ui: &mut egui::Ui, view: &SideView, out: &mut Vec<Command>) {
    use mocap::glam::{EulerRot, Quat};
    let Some(s) = view.selected else { return };
    let Some(c) = view.characters.get(s.character) else { return };
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
