//! The Edit menu: clip edits on the current character (each one undoable), undo
//! and redo, and Save as BVH.

use crate::viewer::Viewer;
use mocap::edit::Edit;

/// Shows the Edit menu's entries (inside the toolbar's menu button).
pub fn show(ui: &mut egui::Ui, viewer: &mut Viewer) {
    if ui.button("New character").on_hover_text("Start a skeleton from one root joint: add joints here, pose them by dragging (Edit mode) and Set key").clicked() {
        viewer.new_character();
        ui.close();
        return;
    }
    ui.separator();
    let index = viewer.current();
    let Some(c) = viewer.stage.actors.get(index) else {
        ui.label("No clip open");
        return;
    };
    let Some(clip) = c.clip() else {
        ui.label(format!("{}: a model has no motion to edit", c.name));
        return;
    };
    let (name, fps, units) = (c.name.clone(), 1.0 / clip.frame_time(), clip.units());
    let selected = viewer.selected.filter(|s| s.character == index).and_then(|s| clip.skeleton().joints().get(s.joint)).map(|j| j.name.clone());
    ui.label(egui::RichText::new(format!("Editing {name}")).weak());
    let mut edit: Option<(Edit, String)> = None;
    let mut grow: Option<String> = None;
    if let Some((a, b)) = viewer.playback.range {
        if ui.button(format!("Trim to the loop range ({a}–{b})")).clicked() {
            edit = Some((Edit::Trim { first: a.min(b), last: a.max(b) }, format!("Trim {a}–{b}")));
        }
    } else {
        ui.add_enabled(false, egui::Button::new("Trim to the loop range")).on_disabled_hover_text("Set a loop range under the timeline first");
    }
    ui.menu_button("Resample", |ui| {
        for target in [24.0, 30.0, 60.0, 120.0] {
            if ui.button(format!("{target} fps")).clicked() {
                edit = Some((Edit::Resample { fps: target }, format!("Resample to {target} fps")));
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
            layer_menu(ui, viewer, index, joint);
        }
        None => {
            ui.label(egui::RichText::new("Select a joint to rename or remove it").weak());
        }
    }
    ui.separator();
    let undo = viewer.history.next_undo().map(|l| format!("Undo {l} (Ctrl+Z)"));
    if ui.add_enabled(undo.is_some(), egui::Button::new(undo.as_deref().unwrap_or("Undo (Ctrl+Z)"))).clicked() {
        viewer.undo();
    }
    let redo = viewer.history.next_redo().map(|l| format!("Redo {l} (Ctrl+Shift+Z)"));
    if ui.add_enabled(redo.is_some(), egui::Button::new(redo.as_deref().unwrap_or("Redo (Ctrl+Shift+Z)"))).clicked() {
        viewer.redo();
    }
    ui.separator();
    if ui.button("Save as BVH").on_hover_text("Download this character with every edit baked in").clicked() {
        viewer.save_requested = true;
        ui.close();
    }
    if let Some(name) = grow {
        viewer.grow_bone(&name);
        ui.close();
    }
    if let Some((e, label)) = edit {
        if let Err(message) = viewer.edit(index, &e, &label) {
            viewer.error = Some(message);
        }
        ui.close();
    }
}

/// Layers another open clip on the selected joint's subtree: weight, fades,
/// override or additive, and which layer joint plays each joint of the subtree
/// (proposed by name across the common conventions; the user can change each or
/// leave it out).
fn layer_menu(ui: &mut egui::Ui, viewer: &mut Viewer, index: usize, joint: &str) {
    let others: Vec<(usize, String)> = (viewer.stage.actors.iter().enumerate()).filter(|(i, c)| *i != index && c.clip().is_some()).map(|(i, c)| (i, c.name.clone())).collect();
    ui.menu_button(format!("Layer on {joint}'s subtree"), |ui| {
        if others.is_empty() {
            ui.label("Open (Add…) the clip to layer first");
            return;
        }
        let id = egui::Id::unique("layer-settings");
        let (mut weight, mut fade_in, mut fade_out, mut additive): (f32, f64, f64, bool) = ui.ctx().data(|d| d.get_temp(id)).unwrap_or((1.0, 0.0, 0.0, false));
        ui.add(egui::Slider::new(&mut weight, 0.0..=1.0).text("weight"));
        ui.horizontal(|ui| {
            ui.add(egui::DragValue::new(&mut fade_in).range(0.0..=60.0).speed(0.05).prefix("fade in ").suffix(" s"));
            ui.add(egui::DragValue::new(&mut fade_out).range(0.0..=60.0).speed(0.05).prefix("fade out ").suffix(" s"));
        });
        ui.checkbox(&mut additive, "Additive (add the layer's change from its first frame)");
        ui.ctx().data_mut(|d| d.insert_temp(id, (weight, fade_in, fade_out, additive)));
        for (source, name) in others {
            ui.separator();
            let map_id = egui::Id::unique(("layer-map", index, source, joint));
            let mut map: Vec<(String, String)> = ui.ctx().data(|d| d.get_temp(map_id)).unwrap_or_default();
            let rows = mapping_rows(viewer, index, source, joint, &map);
            let matched = rows.iter().filter(|r| r.1.is_some()).count();
            ui.collapsing(format!("Joints of {name} ({matched} of {} matched)", rows.len()), |ui| {
                mapping_grid(ui, &rows, &mut map, (index, source));
            });
            ui.ctx().data_mut(|d| d.insert_temp(map_id, map.clone()));
            if ui.button(format!("Layer {name}")).on_hover_text("Each joint of the subtree plays the layer joint shown above it").clicked() {
                let blend = if additive { mocap::layer::Blend::Additive } else { mocap::layer::Blend::Override };
                let layer = mocap::layer::Layer { weight, fade_in, fade_out, blend, map, ..mocap::layer::Layer::on(joint) };
                if let Err(message) = viewer.add_layer(index, source, &layer) {
                    viewer.error = Some(message);
                }
                ui.close();
            }
        }
    });
}

/// For each joint of the base's subtree under `joint`: its name, the layer
/// joint that would play it with `map` (or none), and every layer joint name.
type MappingRow = (String, Option<String>, std::rc::Rc<Vec<String>>);

fn mapping_rows(viewer: &Viewer, index: usize, source: usize, joint: &str, map: &[(String, String)]) -> Vec<MappingRow> {
    let (Some(base), Some(layer)) = (viewer.stage.actors.get(index).and_then(|c| c.clip()), viewer.stage.actors.get(source).and_then(|c| c.clip())) else {
        return Vec::new();
    };
    let (bs, ls) = (base.skeleton(), layer.skeleton());
    let Some(root) = bs.find(joint) else { return Vec::new() };
    let names = std::rc::Rc::new(ls.joints().iter().enumerate().filter(|(k, _)| !ls.is_end_site(*k)).map(|(_, j)| j.name.clone()).collect::<Vec<_>>());
    let pairs = mocap::layer::match_joints(bs, ls, root, map);
    let inside = mocap::layer::match_joints(bs, bs, root, &[]);
    inside
        .iter()
        .filter_map(|&(b, _)| {
            let base_name = bs.joints().get(b)?.name.clone();
            let played = pairs.iter().find(|(pb, _)| *pb == b).and_then(|&(_, l)| ls.joints().get(l)).map(|j| j.name.clone());
            Some((base_name, played, names.clone()))
        })
        .collect()
}

/// The mapping table: a row per subtree joint with a menu of layer joints.
fn mapping_grid(ui: &mut egui::Ui, rows: &[MappingRow], map: &mut Vec<(String, String)>, ids: (usize, usize)) {
    egui::ScrollArea::vertical().max_height(240.0).show(ui, |ui| {
        egui::Grid::new(("layer-map-grid", ids)).striped(true).show(ui, |ui| {
            for (base, played, names) in rows {
                ui.label(base);
                let shown = played.as_deref().unwrap_or("— (keeps the base)");
                let mut choice: Option<Option<String>> = None;
                egui::ComboBox::from_id_salt(("layer-map-row", ids, base.as_str())).selected_text(shown).show_ui(ui, |ui| {
                    if ui.selectable_label(played.is_none(), "— (keeps the base)").clicked() {
                        choice = Some(None);
                    }
                    for n in names.iter() {
                        if ui.selectable_label(played.as_deref() == Some(n.as_str()), n).clicked() {
                            choice = Some(Some(n.clone()));
                        }
                    }
                });
                if let Some(choice) = choice {
                    map.retain(|(b, _)| b != base);
                    map.push((base.clone(), choice.unwrap_or_default()));
                }
                ui.end_row();
            }
        });
    });
}

/// Adds a child joint to the selected joint: its name and offset, or dragged out
/// in the view (`grow` gets the name).
fn add_child(ui: &mut egui::Ui, joint: &str, edit: &mut Option<(Edit, String)>, grow: &mut Option<String>) {
    ui.menu_button(format!("Add a child to {joint}"), |ui| {
        let id = egui::Id::unique("add-child");
        let (mut name, mut xyz): (String, [f32; 3]) = ui.ctx().data(|d| d.get_temp(id)).unwrap_or_else(|| ("Joint".to_owned(), [0.0, 0.3, 0.0]));
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
                *edit = Some((Edit::AddJoint { parent: joint.to_owned(), name: name.trim().to_owned(), offset }, format!("Add {}", name.trim())));
            }
            if ui.button("Drag it out in the view").on_hover_text("Then drag from the selected joint: the new bone ends where you let go").clicked() {
                *grow = Some(name.trim().to_owned());
            }
        });
        ui.ctx().data_mut(|d| d.insert_temp(id, (name, xyz)));
    });
}

/// Sets the selected joint's offset from its parent.
fn set_offset(ui: &mut egui::Ui, joint: &str, current: mocap::glam::Vec3, edit: &mut Option<(Edit, String)>) {
    ui.menu_button(format!("Offset of {joint}"), |ui| {
        let id = egui::Id::unique(("offset", joint));
        let mut xyz: [f32; 3] = ui.ctx().data(|d| d.get_temp(id)).unwrap_or(current.to_array());
        ui.horizontal(|ui| {
            for (v, axis) in xyz.iter_mut().zip(["x ", "y ", "z "]) {
                ui.add(egui::DragValue::new(v).speed(0.01).prefix(axis));
            }
        });
        if ui.button("Set").clicked() {
            *edit = Some((Edit::SetOffset { name: joint.to_owned(), offset: mocap::glam::Vec3::from_array(xyz) }, format!("Offset {joint}")));
        }
        ui.ctx().data_mut(|d| d.insert_temp(id, xyz));
    });
}

/// Sets the selected joint's channels: position or not, and the rotation order.
fn channels(ui: &mut egui::Ui, joint: &str, edit: &mut Option<(Edit, String)>) {
    ui.menu_button(format!("Channels of {joint}"), |ui| {
        for order in ["ZXY", "XYZ", "XZY", "YXZ", "YZX", "ZYX"] {
            for position in [false, true] {
                let label = if position { format!("position + {order} rotation") } else { format!("{order} rotation") };
                if ui.button(label).clicked() {
                    *edit = Some((Edit::SetChannels { name: joint.to_owned(), position, order: order.to_owned() }, format!("Channels of {joint}")));
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
            *edit = Some((Edit::Rename { from: joint.to_owned(), to: text.trim().to_owned() }, format!("Rename {joint}")));
        }
    });
    ui.ctx().data_mut(|d| d.insert_temp(id, text));
}
