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
use crate::state::AppState;
use std::collections::HashSet;

/// Indentation stops growing past this depth (the depth is shown as a number).
pub const MAX_INDENT_LEVELS: usize = 12;
/// At most this many joint names are recorded for [`crate::Snapshot::tree_labels`].
pub const MAX_LABELS: usize = 10_000;
/// Pixels per indentation level.
const INDENT: f32 = 10.0;

/// One row of the panel.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Row {
    /// A character's header: colour, visibility, name, remove.
    Header(usize),
    /// A character's hand-set offset.
    Offset(usize),
    /// A model's animation chooser.
    Animation(usize),
    /// A joint of a character at a depth (roots are 0).
    Joint { character: usize, joint: usize, depth: usize },
}

/// What is folded: characters and joints (per character) whose rows are hidden.
#[derive(Clone, Debug, Default)]
struct Folded {
    characters: HashSet<usize>,
    joints: HashSet<(usize, usize)>,
}

/// Shows the hierarchy panel; records the label of every listed joint in `labels`.
pub fn show(ui: &mut egui::Ui, state: &AppState, labels: &mut Vec<String>, out: &mut Vec<Command>) {
    egui::Panel::left("hierarchy").resizable(true).default_size(240.0).show(ui, |ui| {
        ui.heading("Characters");
        let folded_id = egui::Id::unique("hierarchy-folded");
        let mut folded: Folded = ui.ctx().data(|d| d.get_temp(folded_id)).unwrap_or_default();
        let mut selected = state.selected;
        // A selection made elsewhere (a link, JavaScript) is unfolded and scrolled to once.
        let shown_id = egui::Id::unique("hierarchy-shown-selection");
        let shown: Option<Selection> = ui.ctx().data(|d| d.get_temp(shown_id)).flatten();
        let reveal = selected.filter(|s| Some(*s) != shown);
        if let Some(s) = reveal {
            unfold_to(&mut folded, &state.stage.actors, s);
        }
        let rows = rows(&state.stage.actors, &folded);
        record_labels(&rows, &state.stage.actors, labels);
        let row_height = ui.spacing().interact_size.y;
        let mut area = egui::ScrollArea::both().auto_shrink([false, false]);
        if let Some(index) = reveal.and_then(|s| row_of(&rows, s)) {
            let pitch = row_height + ui.spacing().item_spacing.y;
            area = area.vertical_scroll_offset((index as f32 * pitch - ui.available_height() * 0.5).max(0.0));
        }
        let mut remove = None;
        let mut animation = None;
        if state.stage.actors.is_empty() {
            ui.label("No clip open");
        }
        area.show_rows(ui, row_height, rows.len(), |ui, range| {
            for row in rows.get(range).unwrap_or(&[]) {
                match *row {
                    Row::Header(c) => {
                        if let Some(character) = state.stage.actors.get(c) {
                            if header_row(ui, c, character, &mut folded, out) {
                                remove = Some(c);
                            }
                        }
                    }
                    Row::Offset(c) => {
                        if let Some(character) = state.stage.actors.get(c) {
                            offset_row(ui, c, character, out);
                        }
                    }
                    Row::Animation(c) => {
                        if let Some(model) = state.stage.actors.get(c).and_then(|a| a.model()) {
                            if let Some(name) = animation_row(ui, c, model) {
                                animation = Some((c, name));
                            }
                        }
                    }
                    Row::Joint { character, joint, depth } => {
                        if let Some(c) = state.stage.actors.get(character) {
                            joint_row(ui, c, Selection { character, joint }, depth, &mut selected, &mut folded);
                        }
                    }
                }
            }
        });
        ui.ctx().data_mut(|d| {
            d.insert_temp(shown_id, selected);
            d.insert_temp(folded_id, folded);
        });
        if selected != state.selected {
            let (character, joint) = selected.map_or((state.current(), None), |s| (s.character, Some(s.joint)));
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

/// Every row shown, in order: per character its header, then (unless folded) its
/// offset and its joints depth-first, skipping the children of folded joints.
fn rows(characters: &[Character], folded: &Folded) -> Vec<Row> {
    let mut rows = Vec::new();
    let mut stack: Vec<(usize, usize)> = Vec::new();
    for (c, character) in characters.iter().enumerate() {
        rows.push(Row::Header(c));
        if folded.characters.contains(&c) {
            continue;
        }
        rows.push(Row::Offset(c));
        let Some(clip) = character.clip() else {
            rows.push(Row::Animation(c));
            continue;
        };
        let children = &character.extra.children;
        stack.clear();
        stack.extend(clip.skeleton().roots().collect::<Vec<_>>().into_iter().rev().map(|r| (r, 0)));
        while let Some((joint, depth)) = stack.pop() {
            rows.push(Row::Joint { character: c, joint, depth });
            if folded.joints.contains(&(c, joint)) {
                continue;
            }
            if let Some(kids) = children.get(joint) {
                stack.extend(kids.iter().rev().map(|&k| (k, depth + 1)));
            }
        }
    }
    rows
}

/// Unfolds the character and every ancestor of the selected joint.
fn unfold_to(folded: &mut Folded, characters: &[Character], s: Selection) {
    folded.characters.remove(&s.character);
    let Some(clip) = characters.get(s.character).and_then(|c| c.clip()) else { return };
    let joints = clip.skeleton().joints();
    let mut at = joints.get(s.joint).and_then(|j| j.parent);
    while let Some(p) = at {
        folded.joints.remove(&(s.character, p));
        at = joints.get(p).and_then(|j| j.parent).filter(|&q| q < p);
    }
}

/// Names of the listed joints, in row order (at most [`MAX_LABELS`]).
fn record_labels(rows: &[Row], characters: &[Character], labels: &mut Vec<String>) {
    let names = rows.iter().filter_map(|r| match *r {
        Row::Joint { character, joint, .. } => {
            characters.get(character)?.clip()?.skeleton().joints().get(joint).map(|j| j.name.clone())
        }
        _ => None,
    });
    labels.extend(names.take(MAX_LABELS));
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
fn header_row(ui: &mut egui::Ui, index: usize, c: &Character, folded: &mut Folded, out: &mut Vec<Command>) -> bool {
    let mut remove = false;
    ui.horizontal(|ui| {
        let open = !folded.characters.contains(&index);
        if fold_toggle(ui, open) && !folded.characters.remove(&index) {
            folded.characters.insert(index);
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

/// One joint row: indentation, fold toggle (when it has children), selectable name.
fn joint_row(
    ui: &mut egui::Ui,
    c: &Character,
    here: Selection,
    depth: usize,
    selected: &mut Option<Selection>,
    folded: &mut Folded,
) {
    let Some(joint) = c.clip().and_then(|clip| clip.skeleton().joints().get(here.joint)) else { return };
    let has_children = c.extra.children.get(here.joint).is_some_and(|k| !k.is_empty());
    ui.horizontal(|ui| {
        ui.add_space(INDENT * (1 + depth.min(MAX_INDENT_LEVELS)) as f32);
        if depth > MAX_INDENT_LEVELS {
            ui.label(egui::RichText::new(format!("{depth}")).weak().small()).on_hover_text("Depth in the tree");
        }
        let key = (here.character, here.joint);
        if has_children {
            let open = !folded.joints.contains(&key);
            if fold_toggle(ui, open) && !folded.joints.remove(&key) {
                folded.joints.insert(key);
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
