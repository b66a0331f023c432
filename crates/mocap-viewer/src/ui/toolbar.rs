//! Top bar: Open, Add and Share buttons, layout, draw mode, the View menu (panels
//! and view toggles), foot lock and Edit mode, and the Camera, Edit and Demos menus.

use crate::character::Character;
use crate::command::{Command, OpenMode, button, menu_entry};
use crate::layout::Layout;
use crate::panels::Panels;
use crate::settings::{DrawMode, ViewSettings};
use mocap_scene::Waypoint;

/// What the top bar shows.
pub struct ToolbarView<'a> {
    /// The open characters.
    pub characters: &'a [Character],
    /// Side by side or overlaid.
    pub layout: Layout,
    /// The view settings (draw mode, foot lock, Edit mode, the View menu's toggles).
    pub settings: &'a ViewSettings,
    /// Which panels are shown.
    pub panels: &'a Panels,
    /// The current character's name (what Edit mode edits).
    pub current: Option<&'a str>,
    /// What the Edit menu acts on.
    pub edit: super::edit_menu::EditMenuView<'a>,
    /// Whether the page holds an earlier session to restore.
    pub previous_session: bool,
}

/// Shows the top panel; what the user does comes back as commands in `out`.
pub fn show(ui: &mut egui::Ui, view: &ToolbarView, out: &mut Vec<Command>) {
    let mut settings = view.settings.clone();
    let mut panels = view.panels.clone();
    egui::Panel::top("toolbar").show(ui, |ui| {
        ui.horizontal_wrapped(|ui| {
            button(ui, Command::Open(OpenMode::Replace), out);
            button(ui, Command::Open(OpenMode::Add), out);
            button(ui, Command::Share, out);
            if view.previous_session {
                button(ui, Command::RestorePrevious, out);
            }
            match view.characters {
                [] => {}
                [one] => {
                    ui.strong(&one.name);
                }
                many => {
                    ui.strong(format!("{} characters", many.len()));
                }
            }
            ui.separator();
            layout_choice(ui, view.layout, out);
            ui.separator();
            draw_mode_choice(ui, &mut settings.mode);
            super::menu(ui, "View", &mut |ui| view_menu(ui, &mut settings, &mut panels));
            ui.separator();
            ui.checkbox(&mut settings.foot_lock, "Foot lock").on_hover_text("Pin each foot to the floor while it is in contact (legs solved by IK); contacts show on the timeline");
            let editing = view.current.map_or(String::new(), |name| format!("Editing {name}. "));
            ui.checkbox(&mut settings.pose_mode, "Edit mode").on_hover_text(format!("{editing}Edit mode acts on the selected joint's character: drag a joint and its chain follows by IK, or turn it with its rotation rings; the clip's own pose shows as a ghost. A press on another character's joint switches to it."));
            ui.separator();
            super::menu(ui, "Camera", &mut |ui| camera_menu(ui, out));
            super::menu(ui, "Edit", &mut |ui| super::edit_menu::show(ui, &view.edit, out));
            super::menu(ui, "Demos", &mut |ui| {
                if button(ui, Command::OpenTentacle(2), out) {
                    ui.close();
                }
            });
            ui.label("Keys (?)").on_hover_text(crate::keys::help());
        });
    });
    if settings != *view.settings {
        out.push(Command::SetSettings(settings));
    }
    if panels != *view.panels {
        out.push(Command::SetPanels(panels));
    }
}

/// Front, side and top views, and back to the framing view (also keys 1 2 3 and r).
fn camera_menu(ui: &mut egui::Ui, out: &mut Vec<Command>) {
    for w in [Waypoint::Front, Waypoint::Side, Waypoint::Top] {
        if menu_entry(ui, Command::Waypoint(w), out) {
            ui.close();
        }
    }
    if menu_entry(ui, Command::ResetCamera, out) {
        ui.close();
    }
}

/// Capsules / Sticks / Body.
fn draw_mode_choice(ui: &mut egui::Ui, mode: &mut DrawMode) {
    ui.selectable_value(mode, DrawMode::Capsules, "Capsules").on_hover_text("Lit solids sized to each bone (m)");
    ui.selectable_value(mode, DrawMode::Sticks, "Sticks").on_hover_text("Lines and joint balls (m)");
    ui.selectable_value(mode, DrawMode::Body, "Body").on_hover_text("A smooth skinned body around the bones (m)");
}

/// Panels and view toggles: tree, inspector, shadows, joints, weights, axes,
/// follow root, interpolation.
fn view_menu(ui: &mut egui::Ui, settings: &mut ViewSettings, panels: &mut Panels) {
    ui.checkbox(&mut panels.hierarchy, "Tree").on_hover_text("Show the joint hierarchy");
    ui.checkbox(&mut panels.inspector, "Inspector").on_hover_text("Show clip info and the joint inspector");
    ui.separator();
    ui.checkbox(&mut settings.shadows, "Shadows").on_hover_text("Soft shadows from the key light on the floor");
    ui.checkbox(&mut settings.show_joints, "Joints").on_hover_text("Joint balls in stick mode");
    ui.checkbox(&mut settings.show_weights, "Weights")
        .on_hover_text("Colour the body by its bone influences (body mode)");
    ui.checkbox(&mut settings.show_axes, "Axes").on_hover_text("Bone axes: x red, y green, z blue (a)");
    ui.checkbox(&mut settings.follow_root, "Follow root").on_hover_text("f");
    ui.checkbox(&mut settings.onion, "Onion skin")
        .on_hover_text("Poses before (blue) and after (orange) the frame, fading with distance; they play along");
    ui.add_enabled_ui(settings.onion, |ui| {
        ui.horizontal(|ui| {
            ui.add(egui::DragValue::new(&mut settings.onion_count).range(1..=8).suffix(" each side"));
            ui.add(egui::DragValue::new(&mut settings.onion_step).range(0.02..=2.0).speed(0.01).suffix(" s apart"));
        });
    });
    ui.checkbox(&mut settings.trails, "Trails").on_hover_text(
        "The root's path on the floor (a tick each second, the current point) and the selected joint's path over a second either side",
    );
    ui.separator();
    between_choice(ui, &mut settings.between);
    ui.separator();
    quality_choice(ui, &mut settings.quality);
}

/// Between frames while playing: Nearest / Linear / Cubic.
fn between_choice(ui: &mut egui::Ui, between: &mut mocap::Interpolation) {
    ui.label("Between frames").on_hover_text("How a playing view samples times between the take's frames");
    for (value, label, tip) in crate::settings::BETWEEN_CHOICES {
        ui.radio_value(between, value, label).on_hover_text(tip);
    }
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
fn layout_choice(ui: &mut egui::Ui, current: Layout, out: &mut Vec<Command>) {
    let mut layout = current;
    ui.selectable_value(&mut layout, Layout::Spread, "Spread").on_hover_text("Characters side by side");
    ui.selectable_value(&mut layout, Layout::Overlay, "Overlay")
        .on_hover_text("Characters on top of each other, to compare");
    if layout != current {
        out.push(Command::SetLayout(layout));
    }
}
