//! Left panel: one collapsible entry per character (colour, visibility, name,
//! remove, offset) holding its joint tree; clicking a joint selects it.

use crate::character::Character;
use crate::selection::Selection;
use crate::viewer::Viewer;

/// Shows the hierarchy panel; records the label of every joint drawn in `labels`.
pub fn show(ui: &mut egui::Ui, viewer: &mut Viewer, labels: &mut Vec<String>) {
    egui::Panel::left("hierarchy").resizable(true).default_size(240.0).show(ui, |ui| {
        ui.heading("Characters");
        ui.spacing_mut().indent = 10.0;
        let mut remove = None;
        let mut selected = viewer.selected;
        // The scroll area fills the panel even when empty, so the panel keeps its width.
        egui::ScrollArea::both().auto_shrink([false, false]).show(ui, |ui| {
            if viewer.stage.characters.is_empty() {
                ui.label("No clip open");
            }
            for (index, c) in viewer.stage.characters.iter_mut().enumerate() {
                if character_entry(ui, index, c, &mut selected, labels) {
                    remove = Some(index);
                }
            }
        });
        if selected != viewer.selected {
            viewer.selected = selected;
        }
        if let Some(index) = remove {
            viewer.remove(index);
        }
    });
}

/// One character: header row, offset row and joint tree. Returns whether "remove" was pressed.
fn character_entry(ui: &mut egui::Ui, index: usize, c: &mut Character, selected: &mut Option<Selection>, labels: &mut Vec<String>) -> bool {
    let mut remove = false;
    let id = ui.make_persistent_id(("character", index));
    egui::collapsing_header::CollapsingState::load_with_default_open(ui.ctx(), id, true)
        .show_header(ui, |ui| {
            swatch(ui, c.color);
            ui.checkbox(&mut c.visible, "").on_hover_text("Show this character");
            let name = egui::RichText::new(format!("{}. {}", index + 1, c.document.name)).strong();
            ui.label(if c.visible { name } else { name.weak() }).on_hover_text(&c.document.name);
            remove = ui.small_button("✕").on_hover_text("Close this character").clicked();
        })
        .body(|ui| {
            offset_row(ui, c);
            let joints = &c.document.clip.skeleton.joints;
            let roots = joints.iter().enumerate().filter(|(_, j)| j.parent.is_none()).map(|(i, _)| i);
            for root in roots {
                joint_row(ui, c, index, root, selected, labels);
            }
        });
    remove
}

/// A small filled square in the character's colour.
fn swatch(ui: &mut egui::Ui, color: [u8; 4]) {
    let (rect, _) = ui.allocate_exact_size(egui::vec2(12.0, 12.0), egui::Sense::hover());
    let [r, g, b, _] = color;
    ui.painter().rect_filled(rect, 2.0, egui::Color32::from_rgb(r, g, b));
}

/// The hand-set offset in metres (on top of the layout's).
fn offset_row(ui: &mut egui::Ui, c: &mut Character) {
    ui.horizontal(|ui| {
        ui.label("offset").on_hover_text("Moves this character (metres), on top of the layout");
        for (value, axis) in [(&mut c.offset.x, "x "), (&mut c.offset.y, "y "), (&mut c.offset.z, "z ")] {
            ui.add(egui::DragValue::new(value).speed(0.01).max_decimals(2).prefix(axis));
        }
    });
}

fn joint_row(ui: &mut egui::Ui, c: &Character, character: usize, index: usize, selected: &mut Option<Selection>, labels: &mut Vec<String>) {
    let doc = &c.document;
    let Some(joint) = doc.clip.skeleton.joints.get(index) else { return };
    labels.push(joint.name.clone());
    let children = doc.children.get(index).map_or(&[][..], Vec::as_slice);
    let here = Selection { character, joint: index };
    let is_selected = *selected == Some(here);
    let text = if joint.end_site { egui::RichText::new(&joint.name).weak() } else { egui::RichText::new(&joint.name) };
    if children.is_empty() {
        if ui.selectable_label(is_selected, text).clicked() {
            *selected = Some(here);
        }
        return;
    }
    let id = ui.make_persistent_id(("joint", character, index));
    egui::collapsing_header::CollapsingState::load_with_default_open(ui.ctx(), id, true)
        .show_header(ui, |ui| {
            if ui.selectable_label(is_selected, text).clicked() {
                *selected = Some(here);
            }
        })
        .body(|ui| {
            for &child in children {
                joint_row(ui, c, character, child, selected, labels);
            }
        });
}
