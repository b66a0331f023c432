//! Keyboard shortcuts, turned into [`Action`]s.

use mocap_scene::Waypoint;

/// Something the user asked for from the keyboard or a button.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Action {
    /// Play/pause.
    TogglePlay,
    /// Step frames (pauses).
    Step(isize),
    /// Go to the first frame of the range.
    First,
    /// Go to the last frame of the range.
    Last,
    /// Multiply the camera distance.
    Zoom(f32),
    /// Orbit by pixels (horizontal).
    Orbit(f32),
    /// Jump to a view.
    Waypoint(Waypoint),
    /// Toggle following the root.
    ToggleFollow,
    /// Toggle bone axes.
    ToggleAxes,
    /// Switch between capsules and sticks.
    ToggleDrawMode,
    /// Frame the whole motion again.
    ResetCamera,
    /// Turn the dragged pose corrections into keys (k in Edit mode with a correction).
    SetKey,
    /// Take back the last clip edit (Ctrl+Z).
    Undo,
    /// Make the last undone edit again (Ctrl+Shift+Z, Ctrl+Y).
    Redo,
}

/// Key bindings, listed for the help text.
pub const HELP: &str = "Space play/pause · ←/→ step · Home/End first/last · z/Z zoom · j/k orbit · 1 2 3 views · f follow root · a axes · m capsules/sticks/body · r reset view · k in Edit mode: set key · Ctrl+Z undo · Ctrl+Shift+Z / Ctrl+Y redo · drag: left orbit, right/middle pan, wheel zoom";

/// Reads this frame's key presses (ignored while a text field has focus).
pub fn read_actions(ctx: &egui::Context, out: &mut Vec<Action>) {
    if ctx.egui_wants_keyboard_input() {
        return;
    }
    ctx.input(|input| {
        for event in &input.events {
            if let egui::Event::Key { key, pressed: true, modifiers, .. } = event {
                let action = if modifiers.command {
                    command_action(*key, modifiers.shift)
                } else {
                    action_for(*key, modifiers.shift)
                };
                if let Some(action) = action {
                    out.push(action);
                }
            }
        }
    });
}

/// Shortcuts with Ctrl (Cmd on a Mac).
fn command_action(key: egui::Key, shift: bool) -> Option<Action> {
    match key {
        egui::Key::Z if shift => Some(Action::Redo),
        egui::Key::Z => Some(Action::Undo),
        egui::Key::Y => Some(Action::Redo),
        _ => None,
    }
}

fn action_for(key: egui::Key, shift: bool) -> Option<Action> {
    use egui::Key;
    Some(match key {
        Key::Space => Action::TogglePlay,
        Key::ArrowLeft => Action::Step(-1),
        Key::ArrowRight => Action::Step(1),
        Key::Home => Action::First,
        Key::End => Action::Last,
        Key::Z => Action::Zoom(if shift { 1.25 } else { 0.8 }),
        Key::J => Action::Orbit(-40.0),
        Key::K => Action::Orbit(40.0),
        Key::Num1 => Action::Waypoint(Waypoint::Front),
        Key::Num2 => Action::Waypoint(Waypoint::Side),
        Key::Num3 => Action::Waypoint(Waypoint::Top),
        Key::F => Action::ToggleFollow,
        Key::A => Action::ToggleAxes,
        Key::M => Action::ToggleDrawMode,
        Key::R => Action::ResetCamera,
        _ => return None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shift_z_zooms_out() {
        assert_eq!(action_for(egui::Key::Z, true), Some(Action::Zoom(1.25)));
        assert_eq!(action_for(egui::Key::Z, false), Some(Action::Zoom(0.8)));
        assert_eq!(action_for(egui::Key::Q, false), None);
        assert_eq!(command_action(egui::Key::Z, false), Some(Action::Undo));
        assert_eq!(command_action(egui::Key::Z, true), Some(Action::Redo));
        assert_eq!(command_action(egui::Key::Y, false), Some(Action::Redo));
    }
}
