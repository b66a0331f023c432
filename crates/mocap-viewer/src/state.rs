//! [`AppState`]: everything the viewer shows and edits, as plain data (no egui or
//! wgpu types). Only [`crate::Viewer::apply`] changes it, one [`crate::Command`]
//! at a time; panels, the URL fragment and the JS API read it.

use crate::capture::{CaptureJob, CaptureResult};
use crate::character::Character;
use crate::history::History;
use crate::layer_dialog::LayerDialog;
use crate::notice::Notice;
use crate::panels::Panels;
use crate::playback::{Playback, Timing};
use crate::rig_edit::RigEdit;
use crate::selection::Selection;
use crate::settings::ViewSettings;
use crate::stage::Stage;
use crate::tentacle::Tentacle;
use crate::tree::Folds;
use mocap_scene::OrbitCamera;

/// The viewer's state: the document (stage and history), playback, camera,
/// settings, selection, notice, panels and the tools' own state.
#[derive(Default)]
pub struct AppState {
    /// The open characters and their layout.
    pub stage: Stage,
    /// Clip edits, for undo and redo.
    pub history: History,
    /// Playback settings and playhead (one clock for every character).
    pub playback: Playback,
    /// Camera (world units are metres).
    pub camera: OrbitCamera,
    /// View settings.
    pub settings: ViewSettings,
    /// Selected joint and its character.
    pub selected: Option<Selection>,
    /// The banner's message: the last failure to open files or refused action, and
    /// what became of what was open.
    pub notice: Option<Notice>,
    /// Which panels are shown.
    pub panels: Panels,
    /// What the hierarchy has folded.
    pub folds: Folds,
    /// The bendy-tentacle demo, when it is open (its tentacle is character 1).
    pub tentacle: Option<Tentacle>,
    /// The Layer window, while it is open.
    pub layer_dialog: Option<LayerDialog>,
    /// The Retarget window's settings, while it is open.
    pub retarget_dialog: Option<crate::retarget_dialog::RetargetDialog>,
    /// A model capture in progress.
    pub capture_job: Option<CaptureJob>,
    /// What the last capture gave.
    pub capture_result: Option<CaptureResult>,
    /// A rig dropped (JSON) or set up for the next capture.
    pub capture_rig: Option<mocap::capture::Rig>,
    /// A capture rig being set up on a model.
    pub rig_edit: Option<RigEdit>,
    /// A character with unsaved edits the user asked to close: the viewer asks first.
    pub pending_close: Option<usize>,
    /// Whether the page holds an earlier session (File ▸ Restore previous session).
    pub previous_session: bool,
    /// Compare ▸ with another character, while on.
    pub comparison: Option<crate::comparison::Comparison>,
    /// Whether the host can export video (Edit ▸ Export video… shows).
    pub video_export: bool,
}

impl AppState {
    /// Index of the current character: the selection's, else the first. The
    /// timeline counts frames in its frame time and the info panel shows it.
    pub fn current(&self) -> usize {
        self.selected.map_or(0, |s| s.character)
    }

    /// The current character (see [`AppState::current`]), if any is open.
    pub fn current_character(&self) -> Option<&Character> {
        let stage = &self.stage.actors;
        stage.get(self.current()).or(stage.first())
    }

    /// The shared timeline: the longest clip, in frames of the current character.
    pub fn timing(&self) -> Option<Timing> {
        self.stage.timeline(self.current())
    }

    /// Current frame of the timeline (0 without a clip).
    pub fn frame(&self) -> usize {
        self.timing().map_or(0, |t| self.playback.frame(t))
    }

    /// The selected joint's name.
    pub fn selected_name(&self) -> Option<&str> {
        let s = self.selected?;
        let joint = self.stage.actors.get(s.character)?.clip()?.skeleton().joints().get(s.joint)?;
        Some(joint.name.as_str())
    }

    /// The first joint called `name` in character `character`.
    pub fn joint_named(&self, character: usize, name: &str) -> Option<usize> {
        self.stage.actors.get(character)?.clip()?.skeleton().joints().iter().position(|j| j.name == name)
    }

    /// Whether any character has a pose correction.
    pub fn has_corrections(&self) -> bool {
        self.stage.actors.iter().any(|c| c.extra.correction.as_ref().is_some_and(|k| k.ghost))
    }

    /// Whether a clip is open and the playhead runs.
    pub fn is_playing(&self) -> bool {
        self.playback.playing && !self.stage.actors.is_empty()
    }

    /// The capture's progress: (steps done, steps in all), while one runs.
    pub fn capture_progress(&self) -> Option<(usize, usize)> {
        self.capture_job.as_ref().map(|j| j.capturer.progress())
    }

    /// The view state as a URL fragment (see [`crate::view_state`]).
    pub fn view_fragment(&self) -> String {
        crate::view_state::ViewState::format(self)
    }
}
