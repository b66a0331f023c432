//! Keyboard shortcuts, turned into [`Command`]s.

use crate::command::Command;
use mocap_scene::Waypoint;

/// The keys help: every command with a key, from the command table, and the mouse.
pub fn help() -> String {
    let mut parts: Vec<String> = Command::WITH_KEYS
        .iter()
        .chain(&[Command::Redo, Command::SetKey])
        .filter_map(|c| Some(format!("{} {}", c.shortcut()?, c.tooltip_text())))
        .collect();
    parts.push("drag: left orbit, right/middle pan, wheel zoom".to_owned());
    parts.join(" · ")
}

/// Reads this frame's key presses (ignored while a text field has focus).
pub fn read_commands(ctx: &egui::Context, out: &mut Vec<Command>) {
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
fn command_action(key: egui::Key, shift: bool) -> Option<Command> {
    match key {
        egui::Key::Z if shift => Some(Command::Redo),
        egui::Key::Z => Some(Command::Undo),
        egui::Key::Y => Some(Command::Redo),
        _ => None,
    }
}

fn action_for(key: egui::Key, shift: bool) -> Option<Command> {
    use egui::Key;
    Some(match key {
        Key::Space => Command::TogglePlay,
        Key::ArrowLeft => Command::Step(-1),
        Key::ArrowRight => Command::Step(1),
        Key::Home => Command::First,
        Key::End => Command::Last,
        Key::Z => Command::Zoom(if shift { 1.25 } else { 0.8 }),
        Key::J => Command::Orbit(-40.0),
        Key::K => Command::Orbit(40.0),
        Key::Num1 => Command::Waypoint(Waypoint::Front),
        Key::Num2 => Command::Waypoint(Waypoint::Side),
        Key::Num3 => Command::Waypoint(Waypoint::Top),
        Key::F => Command::ToggleFollow,
        Key::A => Command::ToggleAxes,
        Key::M => Command::ToggleDrawMode,
        Key::R => Command::ResetCamera,
        _ => return None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shift_z_zooms_out() {
        assert_eq!(action_for(egui::Key::Z, true), Some(Command::Zoom(1.25)));
        assert_eq!(action_for(egui::Key::Z, false), Some(Command::Zoom(0.8)));
        assert_eq!(action_for(egui::Key::Q, false), None);
        assert_eq!(command_action(egui::Key::Z, false), Some(Command::Undo));
        assert_eq!(command_action(egui::Key::Z, true), Some(Command::Redo));
        assert_eq!(command_action(egui::Key::Y, false), Some(Command::Redo));
    }
}
