//! Left panel: one entry per character (colour, visibility, name, remove, offset)
//! holding its joint tree, or for a model its animation; clicking a joint selects it.
//!
//! The tree is a flat list of rows built by one iterative depth-first pass (no
//! recursion, in this code or in egui's nested containers), drawn with
//! `ScrollArea::show_rows` so only the rows on screen cost anything: a file can
//! hold a 200,000-level-deep skeleton. Deep rows stop indenting at
//! [`MAX_INDENT_LEVELS`] and show their depth instead.

use crate::character::Character;
use crate::command::Command;
use crate::selection::Selection;
use crate::tree::{self, Folds, Row};

/// What the hierarchy panel shows.
pub struct TreeView<'a> {
    /// The open characters.
    pub characters: &'a [Character],
    /// What is folded.
    pub folds: &'a Folds,
    /// The selected joint.
    pub selected: Option<Selection>,
    /// The current character's index.
    pub current: usize,
}

/// Indentation stops growing past this depth (the depth is shown as a number).
pub const MAX_INDENT_LEVELS: usize = 12;
/// Pixels per indentation level.
const INDENT: f32 = 10.0;

/// Shows the hierarchy panel.
pub fn show(ui: &mut egui::Ui, view: &TreeView, out: &mut Vec<Command>) {
    egui::Panel::left("hierarchy").resizable(true).default_size(240.0).show(ui, |ui| {
        ui.heading("Characters");
        let mut selected = view.selected;
        // A selection made elsewhere (a link, JavaScript) is scrolled to once
        // (selecting unfolds its ancestors).
        let shown_id = egui::Id::unique("hierarchy-shown-selection");
        let shown: Option<Selection> = ui.ctx().data(|d| d.get_temp(shown_id)).flatten();
        let reveal = selected.filter(|s| Some(*s) != shown);
        let rows = tree::rows(view.characters, view.folds);
        let row_height = ui.spacing().interact_size.y;
        let mut area = egui::ScrollArea::both().auto_shrink([false, false]);
        if let Some(index) = reveal.and_then(|s| row_of(&rows, s)) {
            let pitch = row_height + ui.spacing().item_spacing.y;
            area = area.vertical_scroll_offset((index as f32 * pitch - ui.available_height() * 0.5).max(0.0));
        }
        let mut remove = None;
        let mut animation = None;
        if view.characters.is_empty() {
            ui.label("No clip open");
        }
        area.show_rows(ui, row_height, rows.len(), |ui, range| {
            for row in rows.get(range).unwrap_or(&[]) {
                match *row {
                    Row::Header(c) => {
                        if let Some(character) = view.characters.get(c) {
                            if header_row(ui, c, character, view.folds.is_folded(c, None), out) {
                                remove = Some(c);
                            }
                        }
                    }
                    Row::Offset(c) => {
                        if let Some(character) = view.characters.get(c) {
                            offset_row(ui, c, character, out);
                        }
                    }
                    Row::Animation(c) => {
                        if let Some(model) = view.characters.get(c).and_then(|a| a.model()) {
                            if let Some(name) = animation_row(ui, c, model) {
                                animation = Some((c, name));
                            }
                        } else if let Some(clip) = view.characters.get(c).and_then(|a| a.clip()) {
                            if let Some(name) = take_row(ui, c, clip) {
                                animation = Some((c, name));
                            }
                        }
                    }
                    Row::Joint { character, joint, depth } => {
                        if let Some(c) = view.characters.get(character) {
                            let folded = view.folds.is_folded(character, Some(joint));
                            joint_row(ui, c, Selection { character, joint }, depth, &mut selected, folded, out);
                        }
                    }
                }
            }
        });
        ui.ctx().data_mut(|d| d.insert_temp(shown_id, selected));
        if selected != view.selected {
            let (character, joint) = selected.map_or((view.current, None), |s| (s.character, Some(s.joint)));
            out.push(Command::Select { character, joint });
        }
        if let Some((index, name)) = animation {
            out.push(Command::SetAnimation(index, name));
        }
        if let Some(index) = remove {
            // A character with unsaved edits is closed only after asking.
            out.push(Command::Close(index));
        }
    });
}

/// The row of a selected joint, when it is listed.
fn row_of(rows: &[Row], s: Selection) -> Option<usize> {
    rows.iter()
        .position(|r| matches!(*r, Row::Joint { character, joint, .. } if character == s.character && joint == s.joint))
}

/// A small triangle that folds or unfolds; returns whether it was clicked.
fn fold_toggle(ui: &mut egui::Ui, open: bool) -> bool {
    let (rect, response) = ui.allocate_exact_size(egui::vec2(12.0, 12.0), egui::Sense::click());
    let color = ui.visuals().widgets.style(&response).fg_stroke.color;
    let c = rect.center();
    let points = if open {
        vec![c + egui::vec2(-4.0, -2.0), c + egui::vec2(4.0, -2.0), c + egui::vec2(0.0, 3.0)]
    } else {
        vec![c + egui::vec2(-2.0, -4.0), c + egui::vec2(3.0, 0.0), c + egui::vec2(-2.0, 4.0)]
    };
    ui.painter().add(egui::Shape::convex_polygon(points, color, egui::Stroke::NONE));
    response.on_hover_text(if open { "Fold" } else { "Unfold" }).clicked()
}

/// One character's header row. Returns whether "remove" was pressed.
fn header_row(ui: &mut egui::Ui, index: usize, c: &Character, folded: bool, out: &mut Vec<Command>) -> bool {
    let mut remove = false;
    ui.horizontal(|ui| {
        if fold_toggle(ui, !folded) {
            out.push(Command::Fold { character: index, joint: None, folded: !folded });
        }
        swatch(ui, c.extra.color);
        let mut visible = c.visible;
        if ui.checkbox(&mut visible, "").on_hover_text("Show this character").changed() {
            out.push(Command::SetVisible(index, visible));
        }
        let name = egui::RichText::new(format!("{}. {}", index + 1, c.name)).strong();
        ui.label(if c.visible { name } else { name.weak() }).on_hover_text(&c.name);
        remove = ui.small_button("×").on_hover_text("Close this character").clicked();
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
fn offset_row(ui: &mut egui::Ui, index: usize, c: &Character, out: &mut Vec<Command>) {
    let mut offset = c.offset;
    ui.horizontal(|ui| {
        ui.add_space(INDENT);
        ui.label("offset").on_hover_text("Moves this character (metres), on top of the layout");
        for (value, axis) in [(&mut offset.x, "x "), (&mut offset.y, "y "), (&mut offset.z, "z ")] {
            ui.add(egui::DragValue::new(value).speed(0.01).max_decimals(2).prefix(axis));
        }
    });
    if offset != c.offset {
        out.push(Command::SetOffset(index, offset));
    }
}

/// A model's animation chooser: "all" (every frame in file order) or one named
/// animation with its frames. Returns the name picked this frame, if any.
fn animation_row(ui: &mut egui::Ui, index: usize, model: &mocap::Model) -> Option<String> {
    let mut picked = None;
    ui.horizontal(|ui| {
        ui.add_space(INDENT);
        ui.label("animation").on_hover_text("Which of the model's animations plays (looped on the timeline)");
        let current = model.animation_name().to_owned();
        egui::ComboBox::from_id_salt(("animation", index)).selected_text(&current).height(400.0).show_ui(ui, |ui| {
            let frames = model.mesh.frame_count();
            if ui.selectable_label(current == "all", format!("all (0–{})", frames.saturating_sub(1))).clicked() {
                picked = Some("all".to_owned());
            }
            for a in model.mesh.animations() {
                let label = format!("{} ({}–{})", a.name, a.first, a.last);
                if ui.selectable_label(current == a.name, label).clicked() {
                    picked = Some(a.name.clone());
                }
            }
        });
    });
    picked
}

/// A character's animation chooser (the takes of a glTF file, with their
/// lengths). Returns the name picked this frame, if any.
fn take_row(ui: &mut egui::Ui, index: usize, clip: &mocap::Clip) -> Option<String> {
    let mut picked = None;
    ui.horizontal(|ui| {
        ui.add_space(INDENT);
        ui.label("animation").on_hover_text("Which of the file's animations plays (looped on the timeline)");
        let current = clip.take_name().unwrap_or("").to_owned();
        egui::ComboBox::from_id_salt(("take", index)).selected_text(&current).height(400.0).show_ui(ui, |ui| {
            for take in clip.takes() {
                let label = format!("{} ({:.2} s)", take.name, take.motion.timeline().duration());
                if ui.selectable_label(current == take.name, label).clicked() {
                    picked = Some(take.name.clone());
                }
            }
        });
    });
    picked
}

/// One joint row: indentation, fold toggle (when it has children), selectable name.
fn joint_row(
    ui: &mut egui::Ui,
    c: &Character,
    here: Selection,
    depth: usize,
    selected: &mut Option<Selection>,
    folded: bool,
    out: &mut Vec<Command>,
) {
    let Some(joint) = c.clip().and_then(|clip| clip.skeleton().joints().get(here.joint)) else { return };
    let has_children = c.extra.children.get(here.joint).is_some_and(|k| !k.is_empty());
    ui.horizontal(|ui| {
        ui.add_space(INDENT * (1 + depth.min(MAX_INDENT_LEVELS)) as f32);
        if depth > MAX_INDENT_LEVELS {
            ui.label(egui::RichText::new(format!("{depth}")).weak().small()).on_hover_text("Depth in the tree");
        }
        if has_children {
            if fold_toggle(ui, !folded) {
                out.push(Command::Fold { character: here.character, joint: Some(here.joint), folded: !folded });
            }
        } else {
            ui.add_space(12.0 + ui.spacing().item_spacing.x);
        }
        let text = if joint.is_end_site() {
            egui::RichText::new(&joint.name).weak()
        } else {
            egui::RichText::new(&joint.name)
        };
        if ui.selectable_label(*selected == Some(here), text).clicked() {
            *selected = Some(here);
        }
    });
}
