//! Everything that changes the viewer, as data. Panels, keys, the URL fragment
//! and the JS API produce [`Command`]s; [`crate::Viewer::apply`] executes them
//! after the frame, one at a time, in order. A command that has a menu entry,
//! a button or a key carries its label, tooltip and shortcut ([`Command::label`],
//! [`Command::tooltip`], [`Command::shortcut`]), so menus, buttons and the keys
//! help ([`crate::keys::help`]) come from one table.

use crate::layout::Layout;
use crate::panels::Panels;
use crate::settings::ViewSettings;
use mocap_scene::Waypoint;

/// What a file picker the user asked for should do with the files.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OpenMode {
    /// Close what is open and open the picked files ("Open…").
    Replace,
    /// Add the picked files to what is open ("Add…").
    Add,
}

/// Something the viewer asks of the page it runs in, returned by
/// [`crate::Viewer::ui`] (the host acts on it; the viewer keeps no flag).
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum HostRequest {
    /// Show a file picker and open the picked files so.
    PickFiles(OpenMode),
    /// Build a link that reproduces this view and offer it.
    Share,
    /// Restore the earlier session the page holds (autosave).
    RestorePrevious,
    /// Open the host's video export dialog.
    ExportVideo,
    /// Save a file: the current character as BVH or glTF, or a capture rig.
    Save {
        /// File name (`walk-edited.bvh`).
        name: String,
        /// Its contents (UTF-8 text for BVH and JSON).
        bytes: Vec<u8>,
    },
}

/// One change to the viewer.
#[derive(Clone, Debug, PartialEq)]
pub enum Command {
    /// Play or pause.
    TogglePlay,
    /// Play (`true`) or pause.
    SetPlaying(bool),
    /// Move the playhead to a time in seconds (clamped to the timeline).
    SetTime(f64),
    /// Step frames (pauses).
    Step(isize),
    /// Go to the first frame of the range.
    First,
    /// Go to the last frame of the range.
    Last,
    /// Go to a frame of the timeline (clamped), keeping the play state.
    Seek(usize),
    /// Loop at the end, or stop there.
    SetLooping(bool),
    /// Playback speed (1 = real time).
    SetSpeed(f32),
    /// The loop range (first, last frame), or none.
    SetRange(Option<(usize, usize)>),
    /// Multiply the camera distance.
    Zoom(f32),
    /// Orbit by pixels (horizontal); in Edit mode with a correction, sets the key.
    Orbit(f32),
    /// Jump to a view.
    Waypoint(Waypoint),
    /// Frame the whole motion again from the default angles.
    ResetCamera,
    /// Put the camera here.
    SetCamera(mocap_scene::OrbitCamera),
    /// Apply the view a URL fragment describes (see [`crate::view_state`];
    /// unknown parts are ignored).
    ApplyFragment(String),
    /// Toggle following the root.
    ToggleFollow,
    /// Toggle bone axes.
    ToggleAxes,
    /// Cycle capsules → sticks → body.
    ToggleDrawMode,
    /// Replace the view settings (a panel edited a copy).
    SetSettings(ViewSettings),
    /// Replace which panels are shown.
    SetPanels(Panels),
    /// Side by side or overlaid, framed again.
    SetLayout(Layout),
    /// Select joint `joint` of character `character` (nothing with `None`).
    Select {
        /// Character index.
        character: usize,
        /// Joint index.
        joint: Option<usize>,
    },
    /// Select the first joint called `name` of character `character` (refused
    /// when it has none).
    SelectNamed {
        /// Character index.
        character: usize,
        /// Joint name.
        name: String,
    },
    /// Fold (hide the rows under) or unfold a character (`joint: None`) or a
    /// joint in the hierarchy.
    Fold {
        /// Character index.
        character: usize,
        /// The joint, or the character's own row.
        joint: Option<usize>,
        /// Folded, or open.
        folded: bool,
    },
    /// Show or hide a character.
    SetVisible(usize, bool),
    /// Play a model's animation by name (`all`: every frame).
    SetAnimation(usize, String),
    /// Stand a clip up along its file's axis.
    SetUpAxis(usize, mocap::UpAxis),
    /// Close a character, asking first when it has unsaved edits.
    Close(usize),
    /// Close a character at once, edits or not.
    CloseNow(usize),
    /// Close every character.
    CloseAll,
    /// Keep the character the close question was about open.
    KeepOpen,
    /// Turn the dragged pose corrections into keys.
    SetKey,
    /// Forget every pose correction made by dragging.
    ResetPose,
    /// Go to the next (`true`) or previous keyed frame.
    StepKey(bool),
    /// Move the current character's key at `from` to `to`, then show `to`.
    MoveKey {
        /// The key's frame.
        from: usize,
        /// Where it goes.
        to: usize,
    },
    /// Delete the current character's key at a frame.
    DeleteKey(usize),
    /// Take back the last clip edit.
    Undo,
    /// Make the last undone edit again.
    Redo,
    /// Apply a clip edit to a character, one undoable step named `label`.
    Edit {
        /// Character index.
        character: usize,
        /// The edit.
        edit: mocap::ops::edit::Edit,
        /// Its name in the undo history.
        label: String,
    },
    /// Layer character `source` on a subtree of character `character`.
    AddLayer {
        /// The base character.
        character: usize,
        /// The layered character.
        source: usize,
        /// Subtree, weight, blend and joint map.
        layer: mocap::ops::layer::Layer,
    },
    /// Set a joint's local rotation at the frame shown (a correction).
    RotateJoint {
        /// Character index.
        character: usize,
        /// Joint index.
        joint: usize,
        /// The local rotation.
        rotation: mocap::glam::Quat,
    },
    /// Start a new character from one root joint (the creator).
    NewCharacter,
    /// Arm "drag out a new bone" from the selected joint, named so.
    GrowBone(String),
    /// Move a character by hand (metres, on top of the layout).
    SetOffset(usize, mocap::glam::Vec3),
    /// Show bodies coloured by their skin weights, or not.
    ShowWeights(bool),
    /// Open the Layer window for a joint's subtree of a character.
    OpenLayerDialog {
        /// Character index.
        character: usize,
        /// The joint whose subtree is layered.
        joint: String,
    },
    /// Change what the Layer window is set to (the window edited a copy).
    SetLayerDialog(crate::layer_dialog::LayerDialog),
    /// Close the Layer window.
    CloseLayerDialog,
    /// Put character `source`'s motion on character `target`'s skeleton (and
    /// look): the result opens as a new character.
    Retarget {
        /// The character whose motion is used.
        source: usize,
        /// The character that receives it.
        target: usize,
        /// Joint map and reference pose.
        options: mocap::ops::retarget::Options,
    },
    /// Open the Retarget window for character `source`'s motion.
    OpenRetargetDialog(usize),
    /// Change what the Retarget window is set to (the window edited a copy).
    SetRetargetDialog(crate::retarget_dialog::RetargetDialog),
    /// Close the Retarget window.
    CloseRetargetDialog,
    /// Start capturing the skeletal motion of model `index`.
    StartCapture(usize),
    /// Do the rest of the capture in progress now.
    FinishCapture,
    /// Fit a skeleton in model `model`'s first frame to set up by hand (the
    /// humanoid, or the first pose of clip `template`).
    FitRig {
        /// The model.
        model: usize,
        /// A clip whose skeleton is fitted instead of the humanoid.
        template: Option<usize>,
    },
    /// How the rig being set up is shown: its binding, and painting it.
    SetRigView {
        /// Colour the model by the bone each vertex is bound to.
        show_binding: bool,
        /// Drags paint vertices onto the selected joint's bone.
        painting: bool,
    },
    /// Bind every vertex of the model to its nearest bone of the rig.
    BindRig,
    /// Keep the rig for the next capture and stop setting it up.
    FinishRigEdit,
    /// Change the tentacle demo's settings (its panel edited a copy); the skin
    /// is rebuilt when the softness changed.
    SetTentacle(crate::tentacle::Tentacle),
    /// Rebuild the tentacle's skin (its softness changed).
    RefreshTentacleSkin,
    /// Give the tentacle this many bones, keeping its other settings.
    ResizeTentacle(usize),
    /// Close the tentacle demo.
    CloseTentacle,
    /// Open the bendy-tentacle demo with this many bones.
    OpenTentacle(usize),
    /// Show a file picker ("Open…" or "Add…").
    Open(OpenMode),
    /// Make a share link.
    Share,
    /// Save the current character as BVH.
    SaveBvh,
    /// Save the current character as binary glTF (`.glb`).
    SaveGltf,
    /// Save character `index` as BVH (from the close question; it becomes current).
    SaveCharacter(usize),
    /// Save the capture rig as JSON.
    SaveRig,
    /// Show a notice in the banner (files that could not be opened by the host).
    Notify(crate::notice::Notice),
    /// Close the banner.
    DismissNotice,
    /// Open a session the page stored (autosave): its characters, edit history and
    /// view replace what is open.
    Restore(Box<crate::session::Restored>),
    /// Character `index` is saved as it is now (the page saved it).
    MarkSaved(usize),
    /// Whether the page holds an earlier session to restore (File ▸ Restore previous session).
    SetPreviousSession(bool),
    /// Ask the page to restore the earlier session it holds.
    RestorePrevious,
    /// Whether the host can export video (set by the host when it can).
    SetVideoExport(bool),
    /// Ask the host to open its video export dialog.
    ExportVideo,
    /// Compare character `.1` against character `.0` (`None`: stop comparing).
    Compare(Option<(usize, usize)>),
}

impl Command {
    /// The label of its button or menu entry.
    pub fn label(&self) -> &'static str {
        match self {
            Command::TogglePlay => "Play / pause",
            Command::First => "|<",
            Command::Last => ">|",
            Command::Step(d) if *d < 0 => "<",
            Command::Step(_) => ">",
            Command::Zoom(f) if *f < 1.0 => "Zoom in",
            Command::Zoom(_) => "Zoom out",
            Command::Orbit(_) => "Orbit",
            Command::Waypoint(Waypoint::Front) => "Front",
            Command::Waypoint(Waypoint::Side) => "Side",
            Command::Waypoint(Waypoint::Top) => "Top",
            Command::ResetCamera => "Reset view",
            Command::ToggleFollow => "Follow root",
            Command::ToggleAxes => "Axes",
            Command::ToggleDrawMode => "Next draw mode",
            Command::SetKey => "Set key",
            Command::ResetPose => "Reset pose",
            Command::Undo => "Undo",
            Command::Redo => "Redo",
            Command::Open(OpenMode::Replace) => "Open…",
            Command::Open(OpenMode::Add) => "Add…",
            Command::Share => "Share",
            Command::SaveBvh => "Save as BVH",
            Command::SaveGltf => "Save as glTF",
            Command::RestorePrevious => "Restore previous session",
            Command::ExportVideo => "Export video…",
            Command::NewCharacter => "New character",
            Command::OpenTentacle(_) => "Bendy tentacle",
            _ => "",
        }
    }

    /// Its label followed by its key, as menus show it (`Front (1)`; the label
    /// alone for a command without a key).
    pub fn label_with_key(&self) -> String {
        match self.shortcut() {
            Some(key) => format!("{} ({key})", self.label()),
            None => self.label().to_owned(),
        }
    }

    /// What its button or menu entry does, for the tooltip (shortcut included).
    pub fn tooltip(&self) -> String {
        let text = self.tooltip_text();
        match self.shortcut() {
            Some(key) if !text.is_empty() => format!("{text} ({key})"),
            _ => text.to_owned(),
        }
    }

    /// What it does, without its shortcut.
    pub fn tooltip_text(&self) -> &'static str {
        match self {
            Command::TogglePlay => "Play / pause",
            Command::First => "First frame",
            Command::Last => "Last frame",
            Command::Step(d) if *d < 0 => "Step back",
            Command::Step(_) => "Step forward",
            Command::Zoom(f) if *f < 1.0 => "Zoom in",
            Command::Zoom(_) => "Zoom out",
            Command::Orbit(px) if *px < 0.0 => "Orbit left",
            Command::Orbit(_) => "Orbit right",
            Command::Waypoint(Waypoint::Front) => "Look at the front",
            Command::Waypoint(Waypoint::Side) => "Look from the side",
            Command::Waypoint(Waypoint::Top) => "Look down from above",
            Command::ResetCamera => "Back to the default view angles, framing everything",
            Command::ToggleFollow => "Keep the camera over the current character's root",
            Command::ToggleAxes => "Bone axes: x red, y green, z blue",
            Command::ToggleDrawMode => "Capsules, sticks, body",
            Command::SetKey => "Key the corrected pose at this frame",
            Command::ResetPose => "Forget the poses corrected by dragging",
            Command::Undo => "Take back the last edit",
            Command::Redo => "Make the last undone edit again",
            Command::Open(OpenMode::Replace) => {
                "Open motion files (.bvh, .bva, .asf with .amc) or Quake 2 models (.md2 with their skins) in place of what is open (or drop them anywhere on the page)"
            }
            Command::Open(OpenMode::Add) => "Add motion files or models to what is open (or drop them with Shift held)",
            Command::Share => "Copy a link that reproduces this view",
            Command::SaveBvh => "Download the current character as BVH, every edit baked in",
            Command::SaveGltf => {
                "Download the current character as glTF (.glb) for Blender, three.js or a game engine: skeleton, skin, a body and the animation, in metres, Y up"
            }
            Command::RestorePrevious => {
                "Open the work that was open before this link: its characters, edits and view replace what is open"
            }
            Command::ExportVideo => {
                "Download the motion as a video (MP4, WebM or GIF), each frame drawn at its exact time at the size you choose"
            }
            Command::NewCharacter => {
                "Start a skeleton from one root joint: add joints here, pose them by dragging (Edit mode) and Set key"
            }
            Command::OpenTentacle(_) => "Soft skinning and IK on a chain of bones (also ?demo=tentacle)",
            _ => "",
        }
    }

    /// Its keyboard shortcut as the help writes it, from the one binding
    /// table ([`crate::keys::BINDINGS`]).
    pub fn shortcut(&self) -> Option<String> {
        crate::keys::shortcut(self)
    }
}

/// A button that sends `command` (its label and tooltip from the table).
pub fn button(ui: &mut egui::Ui, command: Command, out: &mut Vec<Command>) -> bool {
    button_with(ui, command.label(), command, out)
}

/// A menu entry that sends `command`: its label with its key (`Front (1)`),
/// its tooltip while hovered.
pub fn menu_entry(ui: &mut egui::Ui, command: Command, out: &mut Vec<Command>) -> bool {
    button_with(ui, &command.label_with_key(), command, out)
}

/// A button reading `text` that sends `command` (its tooltip from the table;
/// made only while the button is hovered).
pub fn button_with(ui: &mut egui::Ui, text: &str, command: Command, out: &mut Vec<Command>) -> bool {
    let response = ui.button(text).on_hover_ui(|ui| {
        ui.label(command.tooltip());
    });
    let clicked = response.clicked();
    if clicked {
        out.push(command);
    }
    clicked
}

#[cfg(test)]
mod tests {
    #[test]
    fn every_command_with_a_key_has_a_label_and_a_tooltip_naming_its_key() {
        for c in crate::keys::BINDINGS.iter().map(|b| &b.command) {
            let key = c.shortcut().expect("a key");
            assert!(!c.label().is_empty(), "{c:?}");
            assert!(c.tooltip().ends_with(&format!("({key})")), "{c:?}: {}", c.tooltip());
        }
    }
}
