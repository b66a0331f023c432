//! The Layer window (Edit ▸ Layer on a joint's subtree): which open clip plays on
//! the subtree, its weight, fades and blend, and which layer joint plays each
//! joint of the subtree, proposed by name across the common conventions and
//! changeable (or left out) joint by joint. "Layer" makes it one undoable edit.

use crate::command::Command;
use crate::layer_dialog::LayerDialog;
use crate::stage::Stage;
use mocap::ops::layer;

use super::joint_map::{self, Row};

/// Shows the Layer window while it is open.
/// Its settings are `shown`; a change comes back as [`Command::SetLayerDialog`].
pub fn show(ctx: &egui::Context, shown: &LayerDialog, stage: &Stage, out: &mut Vec<Command>) {
    let mut edited = shown.clone();
    let dialog = &mut edited;
    let Some(base_name) = stage.actors.get(dialog.character).filter(|c| c.clip().is_some()).map(|c| c.name.clone())
    else {
        out.push(Command::CloseLayerDialog);
        return;
    };
    let others: Vec<(usize, String)> = stage
        .actors
        .iter()
        .enumerate()
        .filter(|(i, c)| *i != dialog.character && c.clip().is_some())
        .map(|(i, c)| (i, c.name.clone()))
        .collect();
    if dialog.source.is_none_or(|s| !others.iter().any(|(i, _)| *i == s)) {
        dialog.source = others.first().map(|(i, _)| *i);
        dialog.map.clear();
    }
    let (rows, names) = dialog.source.map_or_else(|| (Vec::new(), Vec::new()), |s| mapping(stage, dialog, s));
    let mut open = true;
    let mut apply = false;
    egui::Window::new(format!("Layer on {}", dialog.joint))
        .id(egui::Id::unique("layer-window"))
        .open(&mut open)
        .default_pos(egui::pos2(620.0, 90.0))
        .resizable(false)
        .show(ctx, |ui| {
            ui.label(egui::RichText::new(format!("{}'s subtree in {base_name}", dialog.joint)).weak());
            if others.is_empty() {
                ui.label("Open (Add…) the clip to layer first");
                return;
            }
            let shown = others.iter().find(|(i, _)| Some(*i) == dialog.source).map_or("", |(_, n)| n.as_str());
            egui::ComboBox::from_label("layer clip").selected_text(shown).show_ui(ui, |ui| {
                for (i, name) in &others {
                    if ui.selectable_label(dialog.source == Some(*i), name).clicked() && dialog.source != Some(*i) {
                        dialog.source = Some(*i);
                        dialog.map.clear();
                    }
                }
            });
            ui.add(egui::Slider::new(&mut dialog.weight, 0.0..=1.0).text("weight"));
            ui.horizontal(|ui| {
                ui.add(
                    egui::DragValue::new(&mut dialog.fades.0)
                        .range(0.0..=60.0)
                        .speed(0.05)
                        .prefix("fade in ")
                        .suffix(" s"),
                );
                ui.add(
                    egui::DragValue::new(&mut dialog.fades.1)
                        .range(0.0..=60.0)
                        .speed(0.05)
                        .prefix("fade out ")
                        .suffix(" s"),
                );
            });
            ui.checkbox(&mut dialog.additive, "Additive (add the layer's change from its first frame)");
            ui.separator();
            let matched = rows.iter().filter(|r| r.driver.is_some()).count();
            ui.label(format!("Joints: {matched} of {} played by the layer", rows.len()));
            joint_map::grid(ui, "layer-map", "— (keeps the base)", &rows, &names, &mut dialog.map);
            ui.separator();
            ui.horizontal(|ui| {
                apply = ui
                    .add_enabled(matched > 0, egui::Button::new("Layer"))
                    .on_hover_text("One undoable edit")
                    .clicked();
                if ui.button("Proposed names").on_hover_text("Forget the joints chosen by hand").clicked() {
                    dialog.map.clear();
                }
            });
        });
    if apply && let Some(source) = dialog.source {
        out.push(Command::AddLayer { character: dialog.character, source, layer: dialog.layer() });
    } else if *dialog != *shown {
        out.push(Command::SetLayerDialog(edited));
    }
    if !open {
        out.push(Command::CloseLayerDialog);
    }
}

/// The mapping rows of the subtree and the layer's joint names (End Sites aside).
fn mapping(stage: &Stage, dialog: &LayerDialog, source: usize) -> (Vec<Row>, Vec<String>) {
    let clip = |i: usize| stage.actors.get(i).and_then(|c| c.clip());
    let (Some(base), Some(other)) = (clip(dialog.character), clip(source)) else { return (Vec::new(), Vec::new()) };
    let (bs, ls) = (base.skeleton(), other.skeleton());
    let names =
        ls.joints().iter().enumerate().filter(|(k, _)| !ls.is_end_site(*k)).map(|(_, j)| j.name.clone()).collect();
    let Some(root) = bs.find(&dialog.joint) else { return (Vec::new(), names) };
    let pairs = layer::match_joints(bs, ls, root, &dialog.map);
    // The subtree's joints: each matched to itself.
    let rows = layer::match_joints(bs, bs, root, &[])
        .into_iter()
        .filter_map(|(b, _)| {
            let base = bs.joints().get(b)?.name.clone();
            let played =
                pairs.iter().find(|(pb, _)| *pb == b).and_then(|&(_, l)| ls.joints().get(l)).map(|j| j.name.clone());
            Some(Row { joint: base, driver: played, chain: None })
        })
        .collect();
    (rows, names)
}
