//! Messages drawn over the 3D view: load errors and a hint when nothing is open.

use crate::viewer::Viewer;

/// Shows the error banner (with a close button) over the view.
pub fn show(ui: &mut egui::Ui, viewer: &mut Viewer) {
    let rect = ui.max_rect();
    if let Some(error) = viewer.error.clone() {
        let area = egui::Area::new(egui::Id::unique("mocap-error")).fixed_pos(rect.left_top() + egui::vec2(12.0, 12.0));
        area.show(ui.ctx(), |ui| {
            egui::Frame::popup(ui.style()).fill(egui::Color32::from_rgb(90, 20, 24)).show(ui, |ui| {
                ui.set_max_width((rect.width() - 40.0).max(200.0));
                ui.horizontal(|ui| {
                    ui.colored_label(egui::Color32::WHITE, egui::RichText::new(format!("Could not open file: {error}")).strong());
                    if ui.button("Close").clicked() {
                        viewer.error = None;
                    }
                });
                if !viewer.stage.actors.is_empty() {
                    ui.colored_label(egui::Color32::LIGHT_GRAY, "What was open is still open.");
                }
            });
        });
    }
    if viewer.stage.actors.is_empty() {
        ui.painter().text(rect.center(), egui::Align2::CENTER_CENTER, "Drop .bvh files here", egui::FontId::proportional(20.0), egui::Color32::GRAY);
    }
}
