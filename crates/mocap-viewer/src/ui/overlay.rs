//! Messages drawn over the 3D view: the error banner and a hint when nothing is open.

use crate::notice::Notice;

/// Shows the banner for `notice` over the view, and a hint to drop files when
/// nothing is open; returns whether the banner's Close was pressed.
pub fn show(ui: &mut egui::Ui, notice: Option<&Notice>, anything_open: bool) -> bool {
    let rect = ui.max_rect();
    let mut close = false;
    if let Some(n) = notice {
        let area = egui::Area::new(egui::Id::unique("mocap-error")).fixed_pos(rect.left_top() + egui::vec2(12.0, 12.0));
        area.show(ui.ctx(), |ui| {
            egui::Frame::popup(ui.style()).fill(egui::Color32::from_rgb(90, 20, 24)).show(ui, |ui| {
                ui.set_max_width((rect.width() - 40.0).max(200.0));
                ui.horizontal(|ui| {
                    ui.colored_label(egui::Color32::WHITE, egui::RichText::new(n.headline()).strong());
                    close = ui.button("Close").clicked();
                });
                if let Some(note) = n.note(anything_open) {
                    ui.colored_label(egui::Color32::LIGHT_GRAY, note);
                }
            });
        });
    }
    if !anything_open {
        ui.painter().text(
            rect.center(),
            egui::Align2::CENTER_CENTER,
            "Drop motion files here (.bvh, .bva, .asf + .amc, .md2 + skin)",
            egui::FontId::proportional(20.0),
            egui::Color32::GRAY,
        );
    }
    close
}
