//! The Retarget window (Edit ▸ Retarget onto…): which open character receives
//! the current one's motion, the reference pose, and which source joint drives
//! each target joint, proposed by name across the common conventions
//! (`LeftArm` = `lShldr` = `mixamorig:LeftArm` = `lhumerus` …) and, where names
//! fail, by the shape of the tree (each row shows the chain found: spine, left
//! arm, …), changeable joint by joint. "Retarget" adds the result as a new character beside them.

use super::joint_map::{self, Row};
use crate::command::Command;
use crate::retarget_dialog::RetargetDialog;
use crate::stage::Stage;
use mocap::ops::retarget::{self, Reference};

/// Shows the Retarget window while it is open. Its settings are `shown`; a
/// change comes back as [`Command::SetRetargetDialog`].
pub fn show(ctx: &egui::Context, shown: &RetargetDialog, stage: &Stage, out: &mut Vec<Command>) {
    let mut edited = shown.clone();
    let dialog = &mut edited;
    let Some(source_name) = stage.actors.get(dialog.source).filter(|c| c.clip().is_some()).map(|c| c.name.clone())
    else {
        out.push(Command::CloseRetargetDialog);
        return;
    };
    // Characters with a look of their own (glTF) first: they are what motion goes onto.
    let mut targets: Vec<(usize, String, bool)> = stage
        .actors
        .iter()
        .enumerate()
        .filter(|(i, c)| *i != dialog.source && c.clip().is_some())
        .map(|(i, c)| (i, c.name.clone(), c.clip().is_some_and(|clip| clip.character.is_some())))
        .collect();
    targets.sort_by_key(|t| !t.2);
    if dialog.target.is_none_or(|t| !targets.iter().any(|(i, _, _)| *i == t)) {
        dialog.target = targets.first().map(|(i, _, _)| *i);
        dialog.map.clear();
    }
    let (rows, names) = dialog.target.map_or_else(|| (Vec::new(), Vec::new()), |t| mapping(stage, dialog, t));
    let (mut open, mut apply) = (true, false);
    egui::Window::new(format!("Retarget {source_name}"))
        .id(egui::Id::unique("retarget-window"))
        .open(&mut open)
        .default_pos(egui::pos2(620.0, 90.0))
        .resizable(false)
        .show(ctx, |ui| {
            ui.label(egui::RichText::new("Every mapped bone points where its source bone points").weak());
            if targets.is_empty() {
                ui.label("Open (Add…) the character to put this motion on first");
                return;
            }
            let shown = targets.iter().find(|(i, _, _)| Some(*i) == dialog.target).map_or("", |(_, n, _)| n.as_str());
            egui::ComboBox::from_label("onto").selected_text(shown).show_ui(ui, |ui| {
                for (i, name, _) in &targets {
                    if ui.selectable_label(dialog.target == Some(*i), name).clicked() && dialog.target != Some(*i) {
                        dialog.target = Some(*i);
                        dialog.map.clear();
                    }
                }
            });
            ui.horizontal(|ui| {
                ui.label("match in");
                ui.radio_value(&mut dialog.reference, Reference::FirstFrame, "first frames")
                    .on_hover_text("For files whose rest pose is not a pose (MotionBuilder exports lie down at rest)");
                ui.radio_value(&mut dialog.reference, Reference::Rest, "rest poses");
            });
            ui.separator();
            let mapped = rows.iter().filter(|r| r.driver.is_some()).count();
            ui.label(format!("Joints: {mapped} of {} driven by {source_name}", rows.len()));
            joint_map::grid(ui, "retarget-map", "— (keeps its rest pose)", &rows, &names, &mut dialog.map);
            ui.separator();
            ui.horizontal(|ui| {
                apply = ui
                    .add_enabled(mapped > 0, egui::Button::new("Retarget"))
                    .on_hover_text("Adds the result as a new character: save it as BVH or glTF")
                    .clicked();
                if ui.button("Proposed names").on_hover_text("Forget the joints chosen by hand").clicked() {
                    dialog.map.clear();
                }
            });
        });
    if apply && let Some(target) = dialog.target {
        out.push(Command::Retarget { source: dialog.source, target, options: dialog.options() });
    } else if *dialog != *shown {
        out.push(Command::SetRetargetDialog(edited));
    }
    if !open {
        out.push(Command::CloseRetargetDialog);
    }
}

/// The rows (target joints, End Sites aside) with their proposed drivers, and
/// the source's joint names.
fn mapping(stage: &Stage, dialog: &RetargetDialog, target: usize) -> (Vec<Row>, Vec<String>) {
    let clip = |i: usize| stage.actors.get(i).and_then(|c| c.clip());
    let (Some(source), Some(onto)) = (clip(dialog.source), clip(target)) else { return (Vec::new(), Vec::new()) };
    let (ss, ts) = (source.skeleton(), onto.skeleton());
    let names =
        ss.joints().iter().enumerate().filter(|(k, _)| !ss.is_end_site(*k)).map(|(_, j)| j.name.clone()).collect();
    let pairs = retarget::map_joints(ts, ss, &dialog.map).unwrap_or_default();
    let chains = retarget::chains::find_body(ts, &retarget::chains::rest_positions(ts)).map(|b| b.labels());
    let chain = |k: usize| chains.as_ref().and_then(|c| c.iter().find(|(j, _)| *j == k)).map(|(_, name)| *name);
    let rows = ts
        .joints()
        .iter()
        .enumerate()
        .filter(|(k, _)| !ts.is_end_site(*k))
        .map(|(k, j)| Row {
            joint: j.name.clone(),
            driver: pairs.iter().find(|(t, _)| *t == k).and_then(|&(_, s)| ss.joints().get(s)).map(|s| s.name.clone()),
            chain: chain(k),
        })
        .collect();
    (rows, names)
}
