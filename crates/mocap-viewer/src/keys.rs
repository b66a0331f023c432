//! Keyboard shortcuts, turned into [`Command`]s.

use crate::command::Command;
use mocap_scene::Waypoint;

/// One key binding: the key, whether Ctrl (Cmd on a Mac) is held, whether
/// Shift must be held (`Some`) or does not matter (`None`), the command, and
/// how the help writes the key.
pub struct Binding {
    /// The key pressed.
    pub key: egui::Key,
    /// With Ctrl (Cmd on a Mac).
    pub ctrl: bool,
    /// With Shift (`Some(true)`), without (`Some(false)`), or either (`None`).
    pub shift: Option<bool>,
    /// What it sends.
    pub command: Command,
    /// The key as the help and tooltips write it.
    pub written: &'static str,
}

/// Every key binding, in the order the help lists them: the one table keys are
/// read from ([`read_commands`]) and shortcuts are written from
/// ([`Command::shortcut`], [`help`]). `k` also sets the key in Edit mode when
/// there is a correction (see `Viewer::apply`).
pub static BINDINGS: [Binding; 19] = {
    use egui::Key;
    const fn bind(key: Key, shift: Option<bool>, command: Command, written: &'static str) -> Binding {
        Binding { key, ctrl: false, shift, command, written }
    }
    const fn ctrl(key: Key, shift: Option<bool>, command: Command, written: &'static str) -> Binding {
        Binding { key, ctrl: true, shift, command, written }
    }
    [
        bind(Key::Space, None, Command::TogglePlay, "Space"),
        bind(Key::ArrowLeft, None, Command::Step(-1), "←"),
        bind(Key::ArrowRight, None, Command::Step(1), "→"),
        bind(Key::Home, None, Command::First, "Home"),
        bind(Key::End, None, Command::Last, "End"),
        bind(Key::Z, Some(false), Command::Zoom(0.8), "z"),
        bind(Key::Z, Some(true), Command::Zoom(1.25), "Z"),
        bind(Key::J, None, Command::Orbit(-40.0), "j"),
        bind(Key::K, None, Command::Orbit(40.0), "k"),
        bind(Key::Num1, None, Command::Waypoint(Waypoint::Front), "1"),
        bind(Key::Num2, None, Command::Waypoint(Waypoint::Side), "2"),
        bind(Key::Num3, None, Command::Waypoint(Waypoint::Top), "3"),
        bind(Key::F, None, Command::ToggleFollow, "f"),
        bind(Key::A, None, Command::ToggleAxes, "a"),
        bind(Key::M, None, Command::ToggleDrawMode, "m"),
        bind(Key::R, None, Command::ResetCamera, "r"),
        ctrl(Key::Z, Some(false), Command::Undo, "Ctrl+Z"),
        ctrl(Key::Z, Some(true), Command::Redo, "Ctrl+Shift+Z"),
        ctrl(Key::Y, None, Command::Redo, "Ctrl+Y"),
    ]
};

/// What Set key is bound to, as the help writes it (`k` in Edit mode).
const SET_KEY: &str = "k in Edit mode";

/// How the help writes `command`'s keys (`Ctrl+Shift+Z / Ctrl+Y`), if it has any.
pub fn shortcut(command: &Command) -> Option<String> {
    if *command == Command::SetKey {
        return Some(SET_KEY.to_owned());
    }
    let keys: Vec<&str> = BINDINGS.iter().filter(|b| b.command == *command).map(|b| b.written).collect();
    (!keys.is_empty()).then(|| keys.join(" / "))
}

/// The keys help, made once from [`BINDINGS`]: each command with its keys,
/// then the mouse.
pub fn help() -> &'static str {
    static HELP: std::sync::OnceLock<String> = std::sync::OnceLock::new();
    HELP.get_or_init(|| {
        let mut parts: Vec<String> = Vec::new();
        let mut listed: Vec<&Command> = Vec::new();
        for b in &BINDINGS {
            if !listed.contains(&&b.command) {
                listed.push(&b.command);
                let keys = shortcut(&b.command).unwrap_or_default();
                parts.push(format!("{keys} {}", b.command.tooltip_text().to_lowercase()));
            }
        }
        parts.push(format!("{SET_KEY}: {}", Command::SetKey.tooltip_text().to_lowercase()));
        parts.push("drag: left orbit, right/middle pan, wheel zoom".to_owned());
        parts.join(" · ")
    })
}

/// The command bound to `key` pressed with `modifiers`, if any.
fn command_for(key: egui::Key, modifiers: egui::Modifiers) -> Option<Command> {
    let bound =
        |b: &&Binding| b.key == key && b.ctrl == modifiers.command && b.shift.is_none_or(|s| s == modifiers.shift);
    BINDINGS.iter().find(bound).map(|b| b.command.clone())
}

/// Reads this frame's key presses (ignored while a text field has focus).
pub fn read_commands(ctx: &egui::Context, out: &mut Vec<Command>) {
    if ctx.egui_wants_keyboard_input() {
        return;
    }
    ctx.input(|input| {
        for event in &input.events {
            if let egui::Event::Key { key, pressed: true, modifiers, .. } = event
                && let Some(command) = command_for(*key, *modifiers)
            {
                out.push(command);
            }
        }
    });
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shift_z_zooms_out() {
        use egui::Modifiers;
        let (plain, shift, ctrl) = (Modifiers::NONE, Modifiers::SHIFT, Modifiers::COMMAND);
        let action_for = |key, shifted| command_for(key, if shifted { shift } else { plain });
        let command_action = |key, shifted| command_for(key, if shifted { ctrl | shift } else { ctrl });
        assert_eq!(action_for(egui::Key::Z, true), Some(Command::Zoom(1.25)));
        assert_eq!(action_for(egui::Key::Z, false), Some(Command::Zoom(0.8)));
        assert_eq!(action_for(egui::Key::Q, false), None);
        assert_eq!(command_action(egui::Key::Z, false), Some(Command::Undo));
        assert_eq!(command_action(egui::Key::Z, true), Some(Command::Redo));
        assert_eq!(command_action(egui::Key::Y, false), Some(Command::Redo));
    }
}
