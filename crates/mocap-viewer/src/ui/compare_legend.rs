//! The comparison's legend over the 3D view: which take is the ghost, and the
//! colour scale of its bones' errors.

use crate::comparison::{Comparison, color};

/// Draws the legend in the top-left corner of `rect`.
pub fn show(ui: &egui::Ui, rect: egui::Rect, comparison: &Comparison, ghost: &str, reference: &str) {
    let painter = ui.painter_at(rect);
    let origin = rect.left_top() + egui::vec2(12.0, 10.0);
    let font = egui::FontId::proportional(13.0);
    let text = egui::Color32::from_gray(225);
    let background = egui::Rect::from_min_size(origin - egui::vec2(6.0, 4.0), egui::vec2(250.0, 62.0));
    painter.rect_filled(background, 5.0, egui::Color32::from_black_alpha(170));
    painter.text(origin, egui::Align2::LEFT_TOP, format!("Ghost: {ghost} against {reference}"), font.clone(), text);
    let bar = egui::Rect::from_min_size(origin + egui::vec2(0.0, 22.0), egui::vec2(200.0, 10.0));
    let scale = comparison.scale();
    let steps = 40;
    for i in 0..steps {
        let t = i as f32 / steps as f32;
        let [r, g, b, _] = color(t * scale, scale);
        let x0 = bar.left() + bar.width() * t;
        let cell = egui::Rect::from_min_max(egui::pos2(x0, bar.top()), egui::pos2(x0 + bar.width() / steps as f32 + 0.5, bar.bottom()));
        painter.rect_filled(cell, 0.0, egui::Color32::from_rgb(r, g, b));
    }
    let small = egui::FontId::proportional(12.0);
    painter.text(bar.left_bottom() + egui::vec2(0.0, 3.0), egui::Align2::LEFT_TOP, format!("0 {}", comparison.units), small.clone(), text);
    painter.text(
        bar.right_bottom() + egui::vec2(0.0, 3.0),
        egui::Align2::RIGHT_TOP,
        format!("{scale:.2} {} (mean per joint)", comparison.units),
        small,
        text,
    );
}
