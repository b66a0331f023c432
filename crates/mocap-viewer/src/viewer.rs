//! The viewer: the open document, playback, camera, selection and settings, and the
//! frame loop that ties them to the UI.

use crate::camera::OrbitCamera;
use crate::document::Document;
use crate::keys::{self, Action};
use crate::panels::Panels;
use crate::playback::Playback;
use crate::settings::ViewSettings;
use crate::snapshot::{ClipSummary, Snapshot};
use crate::viewport::Viewport;
use crate::{pose_scene, ui};
use mocap::{Interpolation, Transform};
use mocap_render::Scene;

/// Longest wall-clock step playback takes in one frame (s); longer gaps (a hidden
/// tab, a debugger) do not make the playhead jump.
const MAX_STEP: f64 = 0.5;

/// The whole viewer. Plain state is public; GPU and scratch state is private.
#[derive(Default)]
pub struct Viewer {
    /// The open clip, if any.
    pub document: Option<Document>,
    /// Playback settings and playhead.
    pub playback: Playback,
    /// Camera.
    pub camera: OrbitCamera,
    /// View settings.
    pub settings: ViewSettings,
    /// Selected joint index.
    pub selected: Option<usize>,
    /// Last load error (the previous clip stays open).
    pub error: Option<String>,
    /// Set when the user pressed "Open…"; the host shows a file picker and clears it.
    pub open_requested: bool,
    /// Set when the user pressed "Share"; the host builds the link and clears it.
    pub share_requested: bool,
    /// Which panels are shown.
    pub panels: Panels,
    viewport: Viewport,
    transforms: Vec<Transform>,
    scene: Scene,
    last_time: Option<f64>,
    actions: Vec<Action>,
    tree_labels: Vec<String>,
}


impl Viewer {
    /// Parses `bytes` and replaces the open clip. On error the old clip stays and the
    /// error is kept for display; the message is also returned.
    pub fn load(&mut self, file_name: &str, bytes: &[u8]) -> Result<(), String> {
        match mocap::load(file_name, bytes) {
            Ok(clip) => {
                self.open(Document::new(file_name, clip));
                Ok(())
            }
            Err(e) => {
                let message = e.to_string();
                self.error = Some(message.clone());
                Err(message)
            }
        }
    }

    /// Opens a document: frame 0, play state kept, camera framed on the motion.
    /// The first frame drawn afterwards shows frame 0 (the clock restarts).
    pub fn open(&mut self, doc: Document) {
        self.playback.time = 0.0;
        self.last_time = None;
        self.playback.range = None;
        self.camera.frame(doc.bounds);
        self.selected = None;
        self.error = None;
        self.document = Some(doc);
    }

    /// Moves to a frame (clamped); keeps the play state.
    pub fn seek(&mut self, frame: usize) {
        if let Some(doc) = &self.document {
            self.playback.seek(frame, doc.timing());
        }
    }

    /// Starts or stops playback.
    pub fn set_playing(&mut self, playing: bool) {
        match &self.document {
            Some(doc) => self.playback.set_playing(playing, doc.timing()),
            None => self.playback.playing = playing,
        }
    }

    /// Selects a joint by index.
    pub fn select(&mut self, joint: Option<usize>) {
        self.selected = joint.filter(|&j| self.document.as_ref().is_some_and(|d| j < d.clip.skeleton.joints.len()));
    }

    /// The view state as a URL fragment (see [`crate::view_state`]).
    pub fn view_fragment(&self) -> String {
        crate::view_state::ViewState::format(self)
    }

    /// Applies a URL fragment (see [`crate::view_state`]); unknown parts are ignored.
    pub fn apply_fragment(&mut self, fragment: &str) {
        crate::view_state::ViewState::parse(fragment).apply(self);
    }

    /// Forgets the last frame time so the next frame advances playback by nothing.
    pub fn restart_clock(&mut self) {
        self.last_time = None;
    }

    /// Current frame of the open clip (0 without one).
    pub fn frame(&self) -> usize {
        self.document.as_ref().map_or(0, |d| self.playback.frame(d.timing()))
    }

    /// A plain copy of the observable state.
    pub fn snapshot(&self) -> Snapshot {
        let clips = self
            .document
            .iter()
            .map(|d| ClipSummary {
                name: d.name.clone(),
                frames: d.clip.frame_count(),
                frame_time: d.clip.frame_time(),
                joints: d.joint_count(),
                joint_names: d.clip.skeleton.joints.iter().map(|j| j.name.clone()).collect(),
            })
            .collect();
        let selected_joint = self
            .selected
            .and_then(|j| self.document.as_ref()?.clip.skeleton.joints.get(j))
            .map(|j| j.name.clone());
        Snapshot {
            clips,
            frame: self.frame(),
            time: self.playback.time,
            playing: self.playback.playing,
            speed: self.playback.speed,
            selected_joint,
            error: self.error.clone(),
            tree_labels: self.tree_labels.clone(),
            frames_rendered: self.viewport.frames_rendered,
            view: self.view_fragment(),
            embed: self.panels.embed,
            backend: self.viewport.backend.clone(),
        }
    }

    /// Draws the whole UI for one frame and advances playback.
    pub fn ui(&mut self, ui: &mut egui::Ui, render_state: Option<&egui_wgpu::RenderState>) {
        self.advance_clock(ui.ctx());
        self.actions.clear();
        keys::read_actions(ui.ctx(), &mut self.actions);
        let actions = std::mem::take(&mut self.actions);
        actions.iter().for_each(|&a| self.apply(a));
        self.actions = actions;

        if !self.panels.embed {
            ui::toolbar::show(ui, self);
        }
        ui::timeline::show(ui, self);
        if self.panels.show_inspector() {
            ui::side::show(ui, self);
        }
        self.tree_labels.clear();
        if self.panels.show_hierarchy() {
            ui::hierarchy::show(ui, self.document.as_ref(), &mut self.selected, &mut self.tree_labels);
        }

        self.pose();
        egui::CentralPanel::no_frame().show(ui, |ui| {
            self.viewport.show(ui, render_state, &mut self.camera, &self.scene);
            ui::overlay::show(ui, self);
        });
        if self.playback.playing && self.document.is_some() {
            ui.ctx().request_repaint();
        }
    }

    /// Applies a user action.
    pub fn apply(&mut self, action: Action) {
        let timing = self.document.as_ref().map(Document::timing);
        match (action, timing) {
            (Action::TogglePlay, _) => self.set_playing(!self.playback.playing),
            (Action::Step(d), Some(t)) => self.playback.step(d, t),
            (Action::First, Some(t)) => {
                let (a, _) = self.playback.frame_range(t);
                self.playback.seek(a, t);
            }
            (Action::Last, Some(t)) => {
                let (_, b) = self.playback.frame_range(t);
                self.playback.playing = false;
                self.playback.seek(b, t);
            }
            (Action::Zoom(f), _) => self.camera.zoom(f),
            (Action::Orbit(px), _) => self.camera.orbit(px, 0.0),
            (Action::Waypoint(w), _) => self.camera.waypoint(w),
            (Action::ToggleFollow, _) => self.settings.follow_root = !self.settings.follow_root,
            (Action::ToggleAxes, _) => self.settings.show_axes = !self.settings.show_axes,
            (Action::ResetCamera, _) => self.reset_camera(),
            (Action::Step(_) | Action::First | Action::Last, None) => {}
        }
    }

    /// Back to the default view angles, framing the whole motion.
    pub fn reset_camera(&mut self) {
        self.camera = OrbitCamera::default();
        if let Some(doc) = &self.document {
            self.camera.frame(doc.bounds);
        }
    }

    fn advance_clock(&mut self, ctx: &egui::Context) {
        let now = ctx.input(|i| i.time);
        let dt = self.last_time.map_or(0.0, |t| (now - t).clamp(0.0, MAX_STEP));
        self.last_time = Some(now);
        if let Some(doc) = &self.document {
            self.playback.advance(dt, doc.timing());
        }
    }

    /// Samples the pose at the playhead and rebuilds the scene primitives.
    fn pose(&mut self) {
        let Some(doc) = &self.document else {
            self.scene.clear();
            return;
        };
        let timing = doc.timing();
        if self.playback.playing && self.settings.interpolate {
            doc.clip.sample_world_transforms_into(self.playback.time, Interpolation::Linear, &mut self.transforms);
        } else {
            doc.clip.world_transforms_into(self.playback.frame(timing), &mut self.transforms);
        }
        if self.settings.follow_root
            && let Some(root) = self.transforms.first() {
                self.camera.target.x = root.translation.x;
                self.camera.target.z = root.translation.z;
            }
        pose_scene::build_scene(doc, &self.transforms, &self.settings, self.selected, &mut self.scene);
    }
}
