//! The Edit menu: clip edits on the current character (each one undoable), undo
//! and redo, and Save as BVH.

use crate::character::Character;
use crate::command::{Command, button};
use mocap::ops::edit::Edit;

/// What the Edit menu acts on.
pub struct EditMenuView<'a> {
    /// The current character and its index, if any is open.
    pub character: Option<(usize, &'a Character)>,
    /// The selected joint, when it is the current character's.
    pub joint: Option<usize>,
    /// The loop range (what Trim keeps).
    pub range: Option<(usize, usize)>,
    /// The edit Undo would take back.
    pub undo: Option<&'a str>,
    /// The edit Redo would make again.
    pub redo: Option<&'a str>,
    /// Other open characters with a skeleton (what a motion can be retargeted onto).
    pub others: usize,
    /// Whether the host exports video (Export video… shows).
    pub video_export: bool,
    /// The view's in-betweens (View ▸ Between frames): Resample is cubic when
    /// they are, else linear.
    pub between: mocap::Interpolation,
    /// Other open clips the current one can be compared with: (index, name).
    pub compare_with: Vec<(usize, &'a str)>,
    /// Whether a comparison is on.
    pub comparing: bool,
}

/// Shows the Edit menu's entries (inside the toolbar's menu button); what the
/// user picks comes back as commands in `out`.
pub fn show(ui: &mut egui::Ui, view: &EditMenuView, out: &mut Vec<Command>) {
    if button(ui, Command::NewCharacter, out) {
        ui.close();
        return;
    }
    ui.separator();
    let Some((index, c)) = view.character else {
        ui.label("No clip open");
        return;
    };
    let Some(clip) = c.clip() else {
        ui.label(format!("{}: a model has no motion to edit", c.name));
        // A model saves as glTF: its frames as morph targets, its animations.
        if button(ui, Command::SaveGltf, out) {
            ui.close();
        }
        export_video(ui, view, out);
        return;
    };
    let (name, fps, units) = (c.name.clone(), 1.0 / clip.frame_time(), c.units);
    let selected = view.joint.and_then(|j| clip.skeleton().joints().get(j)).map(|j| j.name.clone());
    ui.label(egui::RichText::new(format!("Editing {name}")).weak());
    let mut edit: Option<(Edit, String)> = None;
    let mut grow: Option<String> = None;
    if let Some((a, b)) = view.range {
        if ui.button(format!("Trim to the loop range ({a}–{b})")).clicked() {
            edit = Some((Edit::Trim { first: a.min(b), last: a.max(b) }, format!("Trim {a}–{b}")));
        }
    } else {
        ui.add_enabled(false, egui::Button::new("Trim to the loop range"))
            .on_disabled_hover_text("Set a loop range under the timeline first");
    }
    super::menu(ui, "Resample", &mut |ui| {
        for target in [24.0, 30.0, 60.0, 120.0] {
            if ui.button(format!("{target} fps")).clicked() {
                edit = Some(if view.between == mocap::Interpolation::Cubic {
                    (Edit::ResampleCubic { fps: target }, format!("Resample to {target} fps (cubic)"))
                } else {
                    (Edit::Resample { fps: target }, format!("Resample to {target} fps"))
                });
            }
        }
        ui.label(egui::RichText::new(format!("now {fps:.2} fps")).weak());
    });
    for (label, e) in [
        ("Reverse", Edit::Reverse),
        ("Ping-pong", Edit::PingPong),
        ("Loop knit (8 frames)", Edit::LoopKnit { frames: 8 }),
        ("In place", Edit::InPlace { remove_turning: false }),
        ("In place, no turning", Edit::InPlace { remove_turning: true }),
        ("Stand up a Z-up file", Edit::UpAxis { from: 2, negative: false }),
    ] {
        if ui.button(label).clicked() {
            edit = Some((e, label.to_owned()));
        }
    }
    if units != mocap::Units::Meters && ui.button(format!("Lengths to metres (from {})", units.name())).clicked() {
        edit = Some((Edit::Scale { factor: units.meters_per_unit() }, "Lengths to metres".to_owned()));
    }
    match &selected {
        Some(joint) => {
            if ui.button(format!("Remove {joint} (keep positions)")).clicked() {
                edit = Some((Edit::RemoveJoint { name: joint.clone(), fold: true }, format!("Remove {joint}")));
            }
            if ui.button(format!("Remove {joint} (drop its motion)")).clicked() {
                edit = Some((Edit::RemoveJoint { name: joint.clone(), fold: false }, format!("Drop {joint}")));
            }
            rename(ui, joint, &mut edit);
            let is_end = clip.skeleton().find(joint).is_some_and(|j| clip.skeleton().is_end_site(j));
            if !is_end {
                add_child(ui, joint, &mut edit, &mut grow);
                channels(ui, joint, &mut edit);
            }
            let offset = clip.skeleton().find(joint).and_then(|j| clip.skeleton().joints().get(j)).map(|j| j.offset);
            if let Some(offset) = offset {
                set_offset(ui, joint, offset, &mut edit);
            }
            layer_menu(ui, index, joint, out);
        }
        None => {
            ui.label(egui::RichText::new("Select a joint to rename or remove it").weak());
        }
    }
    let hint = "Put this motion on another open character (a glTF character, or any skeleton): pick it and check which joint drives which";
    if ui
        .add_enabled(view.others > 0, egui::Button::new("Retarget onto…"))
        .on_hover_text(hint)
        .on_disabled_hover_text("Open (Add…) the character to put this motion on first")
        .clicked()
    {
        out.push(Command::OpenRetargetDialog(index));
        ui.close();
    }
    compare_menu(ui, index, view, out);
    ui.separator();
    history_entry(ui, Command::Undo, view.undo, out);
    history_entry(ui, Command::Redo, view.redo, out);
    ui.separator();
    if button(ui, Command::SaveBvh, out) {
        ui.close();
    }
    if button(ui, Command::SaveGltf, out) {
        ui.close();
    }
    export_video(ui, view, out);
    if let Some(name) = grow {
        out.push(Command::GrowBone(name));
        ui.close();
    }
    if let Some((edit, label)) = edit {
        out.push(Command::Edit { character: index, edit, label });
        ui.close();
    }
}

/// Compare with ▸ each other open clip (its errors against this one), or stop.
fn compare_menu(ui: &mut egui::Ui, index: usize, view: &EditMenuView, out: &mut Vec<Command>) {
    if view.compare_with.is_empty() {
        ui.add_enabled(false, egui::Button::new("Compare with…"))
            .on_disabled_hover_text("Open (Add…) a second take of a skeleton to compare them");
    } else {
        super::menu(ui, "Compare with", &mut |ui| {
            for (other, name) in &view.compare_with {
                if ui
                    .button(*name)
                    .on_hover_text("Draw it as a ghost here, each bone coloured by its error; the error per frame under the timeline")
                    .clicked()
                {
                    out.push(Command::Compare(Some((index, *other))));
                    ui.close();
                }
            }
        });
    }
    if view.comparing && ui.button("Stop comparing").clicked() {
        out.push(Command::Compare(None));
        ui.close();
    }
}

/// Export video… where the host can export video.
fn export_video(ui: &mut egui::Ui, view: &EditMenuView, out: &mut Vec<Command>) {
    if view.video_export && button(ui, Command::ExportVideo, out) {
        ui.close();
    }
}

/// Opens the Layer window for the selected joint's subtree.
fn layer_menu(ui: &mut egui::Ui, index: usize, joint: &str, out: &mut Vec<Command>) {
    let hint = "Play another open clip on this joint's subtree: weight, fades, override or additive, and which joint plays which";
    if ui.button(format!("Layer on {joint}'s subtree…")).on_hover_text(hint).clicked() {
        out.push(Command::OpenLayerDialog { character: index, joint: joint.to_owned() });
        ui.close();
    }
}

/// Adds a child joint to the selected joint: its name and offset, or dragged out
/// in the view (`grow` gets the name).
fn add_child(ui: &mut egui::Ui, joint: &str, edit: &mut Option<(Edit, String)>, grow: &mut Option<String>) {
    super::menu(ui, &format!("Add a child to {joint}"), &mut |ui| {
        let id = egui::Id::unique("add-child");
        let (mut name, mut xyz): (String, [f32; 3]) =
            ui.ctx().data(|d| d.get_temp(id)).unwrap_or_else(|| ("Joint".to_owned(), [0.0, 0.3, 0.0]));
        ui.horizontal(|ui| {
            ui.label("name");
            ui.add(egui::TextEdit::singleline(&mut name).desired_width(110.0));
        });
        ui.horizontal(|ui| {
            ui.label("offset");
            for (v, axis) in xyz.iter_mut().zip(["x ", "y ", "z "]) {
                ui.add(egui::DragValue::new(v).speed(0.01).prefix(axis));
            }
        });
        ui.horizontal(|ui| {
            if ui.button("Add").clicked() {
                let offset = mocap::glam::Vec3::from_array(xyz);
                *edit = Some((
                    Edit::AddJoint { parent: joint.to_owned(), name: name.trim().to_owned(), offset },
                    format!("Add {}", name.trim()),
                ));
            }
            if ui
                .button("Drag it out in the view")
                .on_hover_text("Then drag from the selected joint: the new bone ends where you let go")
                .clicked()
            {
                *grow = Some(name.trim().to_owned());
            }
        });
        ui.ctx().data_mut(|d| d.insert_temp(id, (name, xyz)));
    });
}

/// Sets the selected joint's offset from its parent.
fn set_offset(ui: &mut egui::Ui, joint: &str, current: mocap::glam::Vec3, edit: &mut Option<(Edit, String)>) {
    super::menu(ui, &format!("Offset of {joint}"), &mut |ui| {
        let id = egui::Id::unique(("offset", joint));
        let mut xyz: [f32; 3] = ui.ctx().data(|d| d.get_temp(id)).unwrap_or(current.to_array());
        ui.horizontal(|ui| {
            for (v, axis) in xyz.iter_mut().zip(["x ", "y ", "z "]) {
                ui.add(egui::DragValue::new(v).speed(0.01).prefix(axis));
            }
        });
        if ui.button("Set").clicked() {
            *edit = Some((
                Edit::SetOffset { name: joint.to_owned(), offset: mocap::glam::Vec3::from_array(xyz) },
                format!("Offset {joint}"),
            ));
        }
        ui.ctx().data_mut(|d| d.insert_temp(id, xyz));
    });
}

/// Sets the selected joint's channels: position or not, and the rotation order.
fn channels(ui: &mut egui::Ui, joint: &str, edit: &mut Option<(Edit, String)>) {
    super::menu(ui, &format!("Channels of {joint}"), &mut |ui| {
        for order in ["ZXY", "XYZ", "XZY", "YXZ", "YZX", "ZYX"] {
            for position in [false, true] {
                let label = if position { format!("position + {order} rotation") } else { format!("{order} rotation") };
                if ui.button(label).clicked() {
                    *edit = Some((
                        Edit::SetChannels { name: joint.to_owned(), position, order: order.to_owned() },
                        format!("Channels of {joint}"),
                    ));
                }
            }
        }
    });
}

/// A text field to rename the selected joint.
fn rename(ui: &mut egui::Ui, joint: &str, edit: &mut Option<(Edit, String)>) {
    let id = egui::Id::unique("rename-joint");
    let mut text: String = ui.ctx().data(|d| d.get_temp(id)).unwrap_or_else(|| joint.to_owned());
    ui.horizontal(|ui| {
        ui.label("Rename to");
        let field = ui.add(egui::TextEdit::singleline(&mut text).desired_width(120.0));
        let enter = field.lost_focus() && ui.input(|i| i.key_pressed(egui::Key::Enter));
        if (ui.button("OK").clicked() || enter) && text.trim() != joint {
            *edit =
                Some((Edit::Rename { from: joint.to_owned(), to: text.trim().to_owned() }, format!("Rename {joint}")));
        }
    });
    ui.ctx().data_mut(|d| d.insert_temp(id, text));
}

/// Undo or Redo, naming the edit it takes back or makes again, with its key
/// (`Undo Reverse (Ctrl+Z)`); disabled when there is none.
fn history_entry(ui: &mut egui::Ui, command: Command, edit: Option<&str>, out: &mut Vec<Command>) {
    let key = command.shortcut().map_or(String::new(), |k| format!(" ({k})"));
    let label = match edit {
        Some(edit) => format!("{} {edit}{key}", command.label()),
        None => format!("{}{key}", command.label()),
    };
    if ui.add_enabled(edit.is_some(), egui::Button::new(label)).clicked() {
        out.push(command);
    }
}
