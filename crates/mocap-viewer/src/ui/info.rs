//! Clip facts of the current character: file name, joints, frames, fps, duration,
//! units, reader warnings.

use crate::document::Document;

/// Shows the info section for `doc`, one of `count` open characters.
pub fn show(ui: &mut egui::Ui, doc: Option<&Document>, count: usize) {
    ui.heading("Clip").on_hover_text("The selected joint's character, else the first one");
    let Some(doc) = doc else {
        ui.label("No clip open");
        return;
    };
    let clip = &doc.clip;
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
        row("Joints", format!("{} (+{} End Sites)", doc.joint_count(), clip.skeleton().joints().len().saturating_sub(doc.joint_count())));
        row("Frames", clip.frame_count().to_string());
        row("FPS", format!("{:.2}", clip.fps()));
        row("Duration", format!("{:.3} s", clip.duration()));
        row("Units", format!("{} (guessed; × {} to metres)", doc.units.name(), doc.meters_per_unit()));
    });
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
}
