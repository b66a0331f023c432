//! Right panel: the current character's clip info, then the selected joint's inspector.

use crate::viewer::Viewer;

/// Shows the right-hand panel.
pub fn show(ui: &mut egui::Ui, viewer: &mut Viewer) {
    egui::Panel::right("side").resizable(true).default_size(280.0).show(ui, |ui| {
        egui::ScrollArea::vertical().auto_shrink([false, false]).show(ui, |ui| {
            let current = viewer.stage.actors.get(viewer.current());
            super::info::show(ui, current, viewer.stage.actors.len());
            ui.separator();
            if let Some((c, model)) = current.and_then(|c| Some((c, c.model()?))) {
                super::model_info::show(ui, c, model);
                return;
            }
            let selected = viewer.selected.and_then(|s| Some((viewer.stage.actors.get(s.character)?, s.joint)));
            let frame = selected.map_or(0, |(c, _)| c.frame_at(viewer.playback.time));
            super::inspector::show(ui, selected, frame, viewer.playback.time);
        });
    });
}
