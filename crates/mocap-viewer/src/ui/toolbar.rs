//! Top bar: Open, Add and Share buttons, layout, draw mode, the View menu (panels
//! and view toggles), foot lock and Edit mode, and the Camera, Edit and Demos menus.

use crate::keys::{Action, HELP};
use crate::layout::Layout;
use crate::settings::DrawMode;
use crate::viewer::{OpenMode, Viewer};
use mocap_scene::Waypoint;

/// Shows the top panel.
pub fn show(ui: &mut egui::Ui, viewer: &mut Viewer) {
    egui::Panel::top("toolbar").show(ui, |ui| {
        ui.horizontal_wrapped(|ui| {
            if ui.button("Open…").on_hover_text("Open motion files (.bvh, .bva, .asf with .amc) or Quake 2 models (.md2 with their skins) in place of what is open (or drop them anywhere on the page)").clicked() {
                viewer.open_requested = Some(OpenMode::Replace);
            }
            if ui.button("Add…").on_hover_text("Add motion files or models to what is open (or drop them with Shift held)").clicked() {
                viewer.open_requested = Some(OpenMode::Add);
            }
            if ui.button("Share").on_hover_text("Copy a link that reproduces this view").clicked() {
                viewer.share_requested = true;
            }
            match viewer.stage.actors.as_slice() {
                [] => {}
                [one] => {
                    ui.strong(&one.name);
                }
                many => {
                    ui.strong(format!("{} characters", many.len()));
                }
            }
            ui.separator();
            layout_choice(ui, viewer);
            ui.separator();
            draw_mode_choice(ui, viewer);
            ui.menu_button("View", |ui| view_menu(ui, viewer));
            ui.separator();
            ui.checkbox(&mut viewer.settings.foot_lock, "Foot lock").on_hover_text("Pin each foot to the floor while it is in contact (legs solved by IK); contacts show on the timeline");
            let editing = viewer.current_character().map_or(String::new(), |c| format!("Editing {}. ", c.name));
            ui.checkbox(&mut viewer.settings.pose_mode, "Edit mode").on_hover_text(format!("{editing}Edit mode acts on the selected joint's character: drag a joint and its chain follows by IK, or turn it with its rotation rings; the clip's own pose shows as a ghost. A press on another character's joint switches to it."));
            ui.separator();
            ui.menu_button("Camera", |ui| camera_menu(ui, viewer));
            ui.menu_button("Edit", |ui| super::edit_menu::show(ui, viewer));
            ui.menu_button("Demos", |ui| {
                if ui.button("Bendy tentacle").on_hover_text("Soft skinning and IK on a chain of bones (also ?demo=tentacle)").clicked() {
                    viewer.open_tentacle(2);
                    ui.close();
                }
            });
            ui.label("Keys (?)").on_hover_text(HELP);
        });
    });
}

/// Front, side and top views, and back to the framing view (also keys 1 2 3 and r).
fn camera_menu(ui: &mut egui::Ui, viewer: &mut Viewer) {
    for (label, w) in [("Front (1)", Waypoint::Front), ("Side (2)", Waypoint::Side), ("Top (3)", Waypoint::Top)] {
        if ui.button(label).clicked() {
            viewer.apply(Action::Waypoint(w));
            ui.close();
        }
    }
    if ui.button("Reset view (r)").clicked() {
        viewer.reset_camera();
        ui.close();
    }
}

/// Capsules / Sticks / Body.
fn draw_mode_choice(ui: &mut egui::Ui, viewer: &mut Viewer) {
    let mode = &mut viewer.settings.mode;
    ui.selectable_value(mode, DrawMode::Capsules, "Capsules").on_hover_text("Lit solids sized to each bone (m)");
    ui.selectable_value(mode, DrawMode::Sticks, "Sticks").on_hover_text("Lines and joint balls (m)");
    ui.selectable_value(mode, DrawMode::Body, "Body").on_hover_text("A smooth skinned body around the bones (m)");
}

/// Panels and view toggles: tree, inspector, shadows, joints, weights, axes,
/// follow root, interpolation.
fn view_menu(ui: &mut egui::Ui, viewer: &mut Viewer) {
    ui.checkbox(&mut viewer.panels.hierarchy, "Tree").on_hover_text("Show the joint hierarchy");
    ui.checkbox(&mut viewer.panels.inspector, "Inspector").on_hover_text("Show clip info and the joint inspector");
    ui.separator();
    ui.checkbox(&mut viewer.settings.shadows, "Shadows").on_hover_text("Soft shadows from the key light on the floor");
    ui.checkbox(&mut viewer.settings.show_joints, "Joints").on_hover_text("Joint balls in stick mode");
    ui.checkbox(&mut viewer.settings.show_weights, "Weights")
        .on_hover_text("Colour the body by its bone influences (body mode)");
    ui.checkbox(&mut viewer.settings.show_axes, "Axes").on_hover_text("Bone axes: x red, y green, z blue (a)");
    ui.checkbox(&mut viewer.settings.follow_root, "Follow root").on_hover_text("f");
    ui.checkbox(&mut viewer.settings.interpolate, "Interpolate").on_hover_text("Blend between frames while playing");
    ui.separator();
    quality_choice(ui, &mut viewer.settings.quality);
}

/// Quality: Auto / Full / Fast while moving.
fn quality_choice(ui: &mut egui::Ui, quality: &mut crate::quality::Quality) {
    use crate::quality::Quality;
    ui.label("Quality");
    ui.radio_value(quality, Quality::Auto, "Auto").on_hover_text("Full quality at rest; while moving, when frames are slow: one sample per pixel and, in the browser, a lower resolution");
    ui.radio_value(quality, Quality::Full, "Full").on_hover_text("Smooth edges and full resolution always");
    ui.radio_value(quality, Quality::Fast, "Fast while moving").on_hover_text("One sample per pixel (and, in the browser, a lower resolution) while playing or dragging; full quality at rest");
}

/// Spread / Overlay.
fn layout_choice(ui: &mut egui::Ui, viewer: &mut Viewer) {
    let mut layout = viewer.stage.layout;
    ui.selectable_value(&mut layout, Layout::Spread, "Spread").on_hover_text("Characters side by side");
    ui.selectable_value(&mut layout, Layout::Overlay, "Overlay")
        .on_hover_text("Characters on top of each other, to compare");
    if layout != viewer.stage.layout {
        viewer.set_layout(layout);
    }
}
