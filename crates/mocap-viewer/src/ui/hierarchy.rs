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
        // A selection made elsewhere (a link, JavaScript) scrolls its row into view once.
        let shown_id = egui::Id::unique("hierarchy-shown-selection");
        let shown: Option<Selection> = ui.ctx().data(|d| d.get_temp(shown_id)).flatten();
        let reveal = selected.filter(|s| Some(*s) != shown);
        // The scroll area fills the panel even when empty, so the panel keeps its width.
        egui::ScrollArea::both().auto_shrink([false, false]).show(ui, |ui| {
            if viewer.stage.characters.is_empty() {
                ui.label("No clip open");
            }
            for (index, c) in viewer.stage.characters.iter_mut().enumerate() {
                if character_entry(ui, index, c, Tree { selected: &mut selected, reveal, labels }) {
                    remove = Some(index);
                }
            }
        });
        ui.ctx().data_mut(|d| d.insert_temp(shown_id, selected));
        if selected != viewer.selected {
            viewer.selected = selected;
        }
        if let Some(index) = remove {
            viewer.remove(index);
        }
    });
}

/// What the joint rows read and write: the selection, the row to scroll to, the labels drawn.
struct Tree<'a> {
    selected: &'a mut Option<Selection>,
    reveal: Option<Selection>,
    labels: &'a mut Vec<String>,
}

/// One character: header row, offset row and joint tree. Returns whether "remove" was pressed.
fn character_entry(ui: &mut egui::Ui, index: usize, c: &mut Character, mut tree: Tree<'_>) -> bool {
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
            let joints = &c.document.clip.skeleton().joints();
            let roots = joints.iter().enumerate().filter(|(_, j)| j.parent.is_none()).map(|(i, _)| i);
            for root in roots {
                joint_row(ui, c, index, root, &mut tree);
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

fn joint_row(ui: &mut egui::Ui, c: &Character, character: usize, index: usize, tree: &mut Tree<'_>) {
    let doc = &c.document;
    let Some(joint) = doc.clip.skeleton().joints().get(index) else { return };
    tree.labels.push(joint.name.clone());
    let children = doc.children.get(index).map_or(&[][..], Vec::as_slice);
    let here = Selection { character, joint: index };
    let is_selected = *tree.selected == Some(here);
    let text = if joint.is_end_site() { egui::RichText::new(&joint.name).weak() } else { egui::RichText::new(&joint.name) };
    let label = |ui: &mut egui::Ui, tree: &mut Tree<'_>| {
        let response = ui.selectable_label(is_selected, text.clone());
        if response.clicked() {
            *tree.selected = Some(here);
        }
        if tree.reveal == Some(here) {
            response.scroll_to_me(Some(egui::Align::Center));
        }
    };
    if children.is_empty() {
        label(ui, tree);
        return;
    }
    let id = ui.make_persistent_id(("joint", character, index));
    egui::collapsing_header::CollapsingState::load_with_default_open(ui.ctx(), id, true)
        .show_header(ui, |ui| label(ui, tree))
        .body(|ui| {
            for &child in children {
                joint_row(ui, c, character, child, tree);
            }
        });
}
