//! Clip facts of the current character: file name, joints, frames, fps, duration,
//! units, what the file says about itself (Acclaim name, version, units,
//! documentation), reader warnings.

use crate::character::Character;

/// Shows the info section for `doc`, one of `count` open characters; returns the
/// up axis the user picked for it, if they picked another.
pub fn show(ui: &mut egui::Ui, doc: Option<&Character>, count: usize) -> Option<mocap::UpAxis> {
    ui.heading("Clip").on_hover_text("The selected joint's character, else the first one");
    let Some(doc) = doc else {
        ui.label("No clip open");
        return None;
    };
    let Some(clip) = doc.clip() else {
        model_facts(ui, doc, count);
        return None;
    };
    let mut picked = None;
    egui::Grid::new("info").num_columns(2).striped(true).show(ui, |ui| {
        let mut row = |k: &str, v: String| {
            ui.label(k);
            ui.label(v);
            ui.end_row();
        };
        row("File", doc.name.clone());
        if count > 1 {
            row("Open", format!("{count} characters"));
        }
        let joints = clip.skeleton().joint_count();
        row("Joints", format!("{joints} (+{} End Sites)", clip.skeleton().len().saturating_sub(joints)));
        row("Frames", clip.frame_count().to_string());
        row("FPS", format!("{:.2}", clip.fps()));
        row("Duration", format!("{:.3} s", clip.duration()));
        row("Units", format!("{} (guessed; × {} to metres)", doc.units.name(), doc.scale()));
        row("Angles", clip.motion().angle_unit().name().to_owned());
        for (key, value) in clip.metadata.iter().filter(|(k, _)| k != "documentation") {
            row(key, value.clone());
        }
        ui.label("Up")
            .on_hover_text("Which file axis points up (guessed from the motion: BVH is Y-up, some tools write Z-up)");
        ui.horizontal(|ui| {
            for up in [mocap::UpAxis::Y, mocap::UpAxis::Z] {
                let label = if up == mocap::UpAxis::Y { "Y" } else { "Z" };
                if ui
                    .selectable_label(doc.up == up, label)
                    .on_hover_text(format!("Stand the character up along the file's {label} axis"))
                    .clicked()
                    && doc.up != up
                {
                    picked = Some(up);
                }
            }
        });
        ui.end_row();
    });
    if let Some((_, text)) = clip.metadata.iter().find(|(k, _)| k == "documentation") {
        egui::CollapsingHeader::new("Documentation").id_salt("documentation").show(ui, |ui| {
            ui.label(text.as_str());
        });
    }
    if !clip.warnings.is_empty() {
        egui::CollapsingHeader::new(format!("{} warnings", clip.warnings.len())).id_salt("warnings").show(ui, |ui| {
            for w in clip.warnings.iter().take(100) {
                ui.label(w.to_string());
            }
            if clip.warnings.len() > 100 {
                ui.label(format!("… and {} more", clip.warnings.len() - 100));
            }
        });
    }
    picked
}

/// The file facts of a model: name, frames and rate, units.
fn model_facts(ui: &mut egui::Ui, doc: &Character, count: usize) {
    let timeline = doc.asset.timeline();
    egui::Grid::new("info").num_columns(2).striped(true).show(ui, |ui| {
        let mut row = |k: &str, v: String| {
            ui.label(k);
            ui.label(v);
            ui.end_row();
        };
        row("File", doc.name.clone());
        row("Format", "Quake 2 MD2 model".to_owned());
        if count > 1 {
            row("Open", format!("{count} characters"));
        }
        row("Frames", format!("{} in this animation", timeline.frames()));
        row("FPS", format!("{:.2} (Quake 2 models)", 1.0 / timeline.frame_time()));
        row("Duration", format!("{:.3} s", timeline.duration()));
        row("Units", format!("{} (Quake units; × {} to metres)", doc.units.name(), doc.scale()));
    });
}
