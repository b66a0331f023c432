//! The model panel's capture section: Capture skeleton (with a progress bar
//! while it runs), what the last capture gave (joints tracked, residuals, joints
//! without vertices, the animations as frame ranges), and Save rig.

use crate::viewer::Viewer;

/// Shows the capture section for model `index`.
pub fn show(ui: &mut egui::Ui, viewer: &mut Viewer, index: usize) {
    ui.separator();
    ui.heading("Skeleton capture");
    if let Some((done, total)) = viewer.capture_progress() {
        let share = done as f32 / total.max(1) as f32;
        ui.add(egui::ProgressBar::new(share).show_percentage().text(format!("capturing: step {done} of {total}")));
        return;
    }
    let rig_note = viewer.capture_rig.as_ref().map(|r| format!("with the dropped rig ({} joints)", r.joints.len()));
    let hint = "Turn the model's vertex animation into skeletal motion: a humanoid fitted in its first frame (or a rig dropped as JSON), four tracked vertices per joint";
    if ui.button("Capture skeleton").on_hover_text(hint).clicked() {
        if let Err(e) = viewer.start_capture(index) {
            viewer.error = Some(e);
        }
    }
    ui.label(egui::RichText::new(rig_note.unwrap_or_else(|| "automatic fit (drop a rig .json to use yours)".to_owned())).weak());
    let Some(result) = viewer.capture_result.clone() else { return };
    let joints = &result.report.joints;
    let tracked = joints.iter().filter(|j| j.tracked.is_ok()).count();
    let worst = joints.iter().map(|j| j.max_residual).fold(0.0, f64::max);
    let failed: usize = joints.iter().map(|j| j.failures.len()).sum();
    egui::Grid::new("capture").num_columns(2).striped(true).show(ui, |ui| {
        let mut row = |k: &str, v: String| {
            ui.label(k);
            ui.label(v);
            ui.end_row();
        };
        row("Captured", format!("{} → {}", result.model, result.clip));
        row("Joints", format!("{tracked} of {} tracked", joints.len()));
        row("Residual", format!("≤ {worst:.3} ({:.2} % of the height)", worst / f64::from(result.report.height.max(1e-6)) * 100.0));
        row("Not converged", format!("{failed} joint-frames"));
    });
    for j in joints.iter().filter(|j| j.tracked.is_err()) {
        ui.label(egui::RichText::new(format!("{}: follows its bones' vertices (no rigid four)", j.name)).weak());
    }
    ui.collapsing("Animations (frame ranges)", |ui| {
        for (name, first, last) in &result.animations {
            ui.label(format!("{name}: {first}–{last}"));
        }
    });
    if ui.button("Save rig").on_hover_text("Download the rig used (JSON); drop it back with the model to capture with it").clicked() {
        viewer.download = viewer.rig_download();
        viewer.save_requested = true;
    }
}
