//! Clip facts: file name, joints, frames, fps, duration, units, reader warnings.

use crate::document::Document;

/// Shows the info section.
pub fn show(ui: &mut egui::Ui, doc: Option<&Document>) {
    ui.heading("Clip");
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
        row("Joints", format!("{} (+{} End Sites)", doc.joint_count(), clip.skeleton.joints.len() - doc.joint_count()));
        row("Frames", clip.frame_count().to_string());
        row("FPS", format!("{:.2}", clip.fps()));
        row("Duration", format!("{:.3} s", clip.duration()));
        row("Units", format!("{} (guessed)", doc.units.name()));
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
