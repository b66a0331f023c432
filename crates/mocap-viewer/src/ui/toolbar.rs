//! Top bar: Open and Share buttons, panel toggles, view toggles and camera buttons.

use crate::camera::Waypoint;
use crate::keys::{Action, HELP};
use crate::viewer::Viewer;

/// Shows the top panel.
pub fn show(ui: &mut egui::Ui, viewer: &mut Viewer) {
    egui::Panel::top("toolbar").show(ui, |ui| {
        ui.horizontal_wrapped(|ui| {
            if ui.button("Open…").on_hover_text("Open a .bvh file (or drop one anywhere on the page)").clicked() {
                viewer.open_requested = true;
            }
            if ui.button("Share").on_hover_text("Copy a link that reproduces this view").clicked() {
                viewer.share_requested = true;
            }
            if let Some(doc) = &viewer.document {
                ui.strong(&doc.name);
            }
            ui.separator();
            ui.checkbox(&mut viewer.panels.hierarchy, "Tree").on_hover_text("Show the joint hierarchy");
            ui.checkbox(&mut viewer.panels.inspector, "Inspector").on_hover_text("Show clip info and the joint inspector");
            ui.separator();
            ui.checkbox(&mut viewer.settings.show_joints, "Joints");
            ui.checkbox(&mut viewer.settings.show_axes, "Axes").on_hover_text("Bone axes: x red, y green, z blue (a)");
            ui.checkbox(&mut viewer.settings.follow_root, "Follow root").on_hover_text("f");
            ui.checkbox(&mut viewer.settings.interpolate, "Interpolate").on_hover_text("Blend between frames while playing");
            ui.separator();
            for (label, w) in [("Front", Waypoint::Front), ("Side", Waypoint::Side), ("Top", Waypoint::Top)] {
                if ui.small_button(label).clicked() {
                    viewer.apply(Action::Waypoint(w));
                }
            }
            if ui.small_button("Reset view").on_hover_text("r").clicked() {
                viewer.reset_camera();
            }
            ui.label("Keys (?)").on_hover_text(HELP);
        });
    });
}
