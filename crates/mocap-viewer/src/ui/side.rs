//! Right panel: clip info, then the selected joint's inspector.

use crate::viewer::Viewer;

/// Shows the right-hand panel.
pub fn show(ui: &mut egui::Ui, viewer: &mut Viewer) {
    egui::Panel::right("side").resizable(true).default_size(280.0).show(ui, |ui| {
        egui::ScrollArea::vertical().auto_shrink([false, false]).show(ui, |ui| {
            super::info::show(ui, viewer.document.as_ref());
            ui.separator();
            let frame = viewer.frame();
            super::inspector::show(ui, viewer.document.as_ref(), viewer.selected, frame, viewer.playback.time);
        });
    });
}
