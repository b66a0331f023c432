//! The viewer: the open characters, playback, camera, selection and settings, and
//! the frame loop that ties them to the UI.

use crate::character::{self, Character};
use crate::command::{Command, HostRequest, OpenMode};
use crate::keys;
use crate::layout::Layout;
use crate::notice::Notice;

use crate::selection::Selection;
use crate::settings::DrawMode;
use crate::snapshot::Snapshot;
use crate::state::AppState;
use crate::viewport::Viewport;
use crate::{pose_scene, ui};

mod apply;
mod capture;
mod compare;
mod drag;
mod editing;
mod rig;
mod session;
mod view;
mod views;
mod warm_up;

pub use warm_up::{FRAMES as WARM_UP_FRAMES, MAX_JOINTS as WARM_UP_MAX_JOINTS};
use mocap_render::Scene;
use mocap_scene::OrbitCamera;

/// Longest wall-clock step playback takes in one frame (s); longer gaps (a hidden
/// tab, a debugger) do not make the playhead jump.
const MAX_STEP: f64 = 0.5;

/// What a video export starts from ([`Viewer::video_defaults`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VideoDefaults {
    /// The current character's frame rate.
    pub fps: f64,
    /// The stage's length in seconds (the longest clip).
    pub duration: f64,
    /// The loop range, in seconds, when one is set.
    pub range: Option<(f64, f64)>,
    /// The 3D view's size in points.
    pub view: Option<[f32; 2]>,
}

/// The whole viewer. Plain state is public; GPU and scratch state is private.
#[derive(Default)]
pub struct Viewer {
    /// Everything shown and edited, changed only by [`Viewer::apply`].
    state: AppState,
    /// Reads dropped files; remembers the last Acclaim skeleton for motions dropped alone.
    loader: mocap::Loader,
    /// The drags in progress in the 3D view.
    gesture: crate::gesture::Gestures,
    pub(crate) viewport: Viewport,
    pub(crate) scene: Scene,
    /// Whole-clip paths the trails draw from (see [`pose_scene::TrailCache`]).
    trails: pose_scene::TrailCache,
    pose_scratch: mocap::stage::PoseScratch,
    last_time: Option<f64>,
    /// Set by [`Viewer::hold`] while the host reads files.
    held: bool,
    /// Commands sent during this frame, applied after it.
    commands: Vec<Command>,
    /// What the page is asked to do, returned by [`Viewer::ui`].
    requests: Vec<HostRequest>,
}

impl Viewer {
    /// Reads `bytes` (any supported format) and replaces everything open with it.
    /// On error what was open stays and the error is kept for display; the message
    /// is also returned.
    pub fn load(&mut self, file_name: &str, bytes: &[u8]) -> Result<(), String> {
        self.open_files(&[(file_name, bytes)], OpenMode::Replace).into_iter().next().map_or(Ok(()), Err)
    }

    /// Reads `bytes` and adds it as one more character. On error what was open
    /// stays and the error is kept for display; the message is also returned.
    pub fn add(&mut self, file_name: &str, bytes: &[u8]) -> Result<(), String> {
        self.open_files(&[(file_name, bytes)], OpenMode::Add).into_iter().next().map_or(Ok(()), Err)
    }

    /// Opens a set of dropped, picked or linked files through the core's loader
    /// (formats from content; an Acclaim skeleton with its motions makes one
    /// character per motion; a motion alone uses the last skeleton read). With
    /// [`OpenMode::Replace`] what opened replaces everything open; when nothing
    /// opens, what was open stays. Returns every error (also shown in the banner).
    pub fn open_files(&mut self, files: &[(&str, &[u8])], mode: OpenMode) -> Vec<String> {
        let mut errors = Vec::new();
        // A capture rig (JSON) is kept for the next capture, not opened.
        let (rigs, files): (Vec<_>, Vec<_>) =
            files.iter().partition(|(name, _)| name.to_ascii_lowercase().ends_with(".json"));
        for (name, bytes) in rigs {
            if let Err(e) = self.use_rig(name, &String::from_utf8_lossy(bytes)) {
                errors.push(e);
            }
        }
        if files.is_empty() {
            if !errors.is_empty() {
                self.state.notice = Some(Notice::open_failed(errors.join("\n"), false));
            }
            return errors;
        }
        let inputs: Vec<mocap::Input> = files.iter().map(|&(name, bytes)| mocap::Input { name, bytes }).collect();
        let mut assets = Vec::new();
        for result in self.loader.load(&inputs) {
            match result {
                Ok(loaded) => assets.push((loaded.name, loaded.asset)),
                Err(e) => errors.push(e.to_string()),
            }
        }
        self.open_loaded(assets, errors, mode)
    }

    /// Opens BVH clips read elsewhere (a host reading files as they arrive, see
    /// `mocap::formats::bvh::Stream`), named, or the errors reading them gave, as
    /// [`Viewer::open_files`] opens files: the same messages, the same rules.
    pub fn open_clips(
        &mut self,
        clips: Vec<(String, Result<mocap::Clip, mocap::ParseError>)>,
        mode: OpenMode,
    ) -> Vec<String> {
        let mut assets = Vec::new();
        let mut errors = Vec::new();
        for (file, result) in clips {
            match result {
                Ok(clip) => assets.push((file, mocap::Asset::from(clip))),
                Err(error) => errors.push(mocap::LoadError::Parse { file, error }.to_string()),
            }
        }
        self.open_loaded(assets, errors, mode)
    }

    /// Opens what was read (replacing or adding) and shows the errors.
    fn open_loaded(&mut self, assets: Vec<(String, mocap::Asset)>, errors: Vec<String>, mode: OpenMode) -> Vec<String> {
        let opened_any = !assets.is_empty();
        if opened_any {
            match mode {
                OpenMode::Replace => self.open_assets(assets),
                OpenMode::Add => assets.into_iter().for_each(|(name, asset)| self.add_asset(&name, asset)),
            }
        }
        if !errors.is_empty() {
            self.state.notice = Some(Notice::open_failed(errors.join("\n"), opened_any));
        }
        errors
    }

    /// Shows `message` in the banner as an action that was refused (nothing changed).
    pub(crate) fn refuse(&mut self, message: String) {
        self.state.notice = Some(Notice::refused(message));
    }

    /// Replaces everything open with `assets` (name, clip or model): time 0, play
    /// state kept, no loop range or selection, camera framed on the motion. The first
    /// frame drawn afterwards shows frame 0 (the clock restarts).
    pub fn open_assets(&mut self, assets: Vec<(String, mocap::Asset)>) {
        self.state.tentacle = None;
        self.state.rig_edit = None;
        self.state.capture_job = None;
        self.state.history.clear();
        self.state.folds = Default::default();
        self.state.playback.time = 0.0;
        self.last_time = None;
        self.state.playback.range = None;
        self.state.selected = None;
        self.state.notice = None;
        let mut characters: Vec<Character> = Vec::with_capacity(assets.len());
        for (name, asset) in assets {
            let c = character::new_character(&name, asset, &characters);
            characters.push(c);
        }
        self.state.stage.replace(characters);
        self.state.camera.frame(self.state.stage.bounds());
    }

    /// Adds a character, keeping the playhead, selection and play state; the
    /// camera frames everything visible.
    pub fn add_asset(&mut self, name: &str, asset: impl Into<mocap::Asset>) {
        self.state.notice = None;
        let c = character::new_character(name, asset.into(), &self.state.stage.actors);
        self.state.stage.add(c);
        self.state.camera.frame(self.state.stage.bounds());
    }

    /// Plays animation `name` (`all`: every frame) on model `index`; returns whether
    /// that model has it. The playhead stays where it is, within the new timeline.
    pub(crate) fn set_animation(&mut self, index: usize, name: &str) -> bool {
        if !self.state.stage.set_animation(index, name) {
            return false;
        }
        self.state.playback.range = None;
        if let Some(t) = self.state.timing() {
            self.state.playback.time = self.state.playback.time.min(t.duration());
        }
        true
    }

    /// Stands clip `index` up along its file's `up` axis (the unit is guessed again
    /// from the height along it; foot contacts are found again); the camera frames
    /// the stage. False (no change) for a model or no such character.
    pub(crate) fn set_up_axis(&mut self, index: usize, up: mocap::UpAxis) -> bool {
        if !self.state.stage.set_up_axis(index, up) {
            return false;
        }
        if let Some(c) = self.state.stage.actors.get_mut(index) {
            c.extra.foot_lock = None;
        }
        self.state.camera.frame(self.state.stage.bounds());
        true
    }

    /// Closes character `index` (0-based); returns whether it existed.
    pub(crate) fn remove(&mut self, index: usize) -> bool {
        if !self.state.stage.remove(index) {
            return false;
        }
        self.state.folds.remove_character(index);
        if index == 0 {
            self.state.tentacle = None;
        }
        self.state.history.clear();
        self.state.selected = match self.state.selected {
            Some(s) if s.character == index => None,
            Some(s) if s.character > index => Some(Selection { character: s.character - 1, ..s }),
            other => other,
        };
        // A rig set up or a capture running on a model follows it, or ends with it.
        let shift = |model: usize| match model.cmp(&index) {
            std::cmp::Ordering::Equal => None,
            std::cmp::Ordering::Greater => Some(model - 1),
            std::cmp::Ordering::Less => Some(model),
        };
        self.state.rig_edit = self.state.rig_edit.take().and_then(|mut e| {
            shift(e.model).map(|m| {
                e.model = m;
                e
            })
        });
        self.state.capture_job = self.state.capture_job.take().and_then(|mut j| {
            shift(j.model).map(|m| {
                j.model = m;
                j
            })
        });
        true
    }

    /// Closes every character.
    pub(crate) fn clear(&mut self) {
        self.state.tentacle = None;
        self.state.history.clear();
        self.state.stage.replace(Vec::new());
        self.state.selected = None;
    }

    /// Shows or hides character `index`; returns whether it exists.
    pub(crate) fn set_visible(&mut self, index: usize, visible: bool) -> bool {
        self.state.stage.set_visible(index, visible)
    }

    /// Switches the layout and frames the result.
    pub(crate) fn set_layout(&mut self, layout: Layout) {
        self.state.stage.set_layout(layout);
        self.state.camera.frame(self.state.stage.bounds());
    }

    /// Moves to a frame of the timeline (clamped); keeps the play state.
    pub(crate) fn seek(&mut self, frame: usize) {
        if let Some(t) = self.state.timing() {
            self.state.playback.seek(frame, t);
        }
    }

    /// Starts or stops playback.
    pub(crate) fn set_playing(&mut self, playing: bool) {
        match self.state.timing() {
            Some(t) => self.state.playback.set_playing(playing, t),
            None => self.state.playback.playing = playing,
        }
    }

    /// Selects joint `joint` of character `character`, or nothing when either is out of range.
    pub(crate) fn select_in(&mut self, character: usize, joint: Option<usize>) {
        let valid = |j: &usize| {
            self.state
                .stage
                .actors
                .get(character)
                .and_then(|c| c.clip())
                .is_some_and(|c| *j < c.skeleton().joints().len())
        };
        self.state.selected = joint.filter(valid).map(|joint| Selection { character, joint });
        if let Some(s) = self.state.selected {
            self.state.folds.unfold_to(&self.state.stage.actors, s);
        }
    }

    /// Selects the first joint called `name` in character `character`; returns whether one exists.
    pub(crate) fn select_named(&mut self, character: usize, name: &str) -> bool {
        let joint = self
            .state
            .stage
            .actors
            .get(character)
            .and_then(|c| c.clip()?.skeleton().joints().iter().position(|j| j.name == name));
        self.select_in(character, joint);
        joint.is_some()
    }

    /// Applies a URL fragment (see [`crate::view_state`]); unknown parts are ignored.
    pub fn apply_fragment(&mut self, fragment: &str) {
        let _refused_is_shown = self.apply(Command::ApplyFragment(fragment.to_owned()));
    }

    /// Forgets the last frame time so the next frame advances playback by nothing.
    pub(crate) fn restart_clock(&mut self) {
        self.last_time = None;
    }

    /// Holds playback while the host reads files it is about to open (`on`), or
    /// lets it go on (`!on`). Held, the playhead stays where it is and a playing
    /// view asks for no more frames, so drawing does not compete with the read
    /// and the open for the processor (on a software rasteriser a frame's work
    /// goes on in the browser's GPU process long after it was asked for). Let
    /// go, the clock restarts: playback goes on from where it held, without a
    /// jump. The host asks for the next frame itself.
    pub fn hold(&mut self, on: bool) {
        self.held = on;
        self.restart_clock();
    }

    /// Whether playback is held (see [`Viewer::hold`]).
    pub fn is_held(&self) -> bool {
        self.held
    }

    /// Everything shown and edited (change it with [`Viewer::apply`]).
    pub fn state(&self) -> &AppState {
        &self.state
    }

    /// A plain copy of the observable state.
    pub fn snapshot(&self) -> Snapshot {
        Snapshot {
            reduced: self.viewport.reduced,
            samples: self.viewport.samples,
            view_pixels: self.viewport.drawn_pixels,
            floor_copied: self.viewport.floor_copied,
            frames_rendered: self.viewport.frames_rendered,
            backend: self.viewport.backend.clone(),
            ..Snapshot::of(&self.state)
        }
    }

    /// Draws the whole UI for one frame and advances playback. Panels and keys
    /// send [`Command`]s, applied after the frame in order ([`Viewer::apply`]);
    /// returns what the page is asked to do.
    pub fn ui(&mut self, ui: &mut egui::Ui, render_state: Option<&egui_wgpu::RenderState>) -> Vec<HostRequest> {
        self.advance_clock(ui.ctx());
        let mut commands = std::mem::take(&mut self.commands);
        commands.clear();
        keys::read_commands(ui.ctx(), &mut commands);
        // Keys act before the panels are drawn, as they always did.
        for c in commands.drain(..) {
            let _refused_is_shown = self.apply(c);
        }

        if !self.state.panels.embed {
            ui::toolbar::show(ui, &self.toolbar_view(), &mut commands);
        }
        ui::timeline::show(ui, &self.timeline_view(), &mut commands);
        if self.state.panels.show_inspector() {
            ui::side::show(ui, &self.side_view(), &mut commands);
        }
        if self.state.panels.show_hierarchy() {
            ui::hierarchy::show(ui, &self.tree_view(), &mut commands);
        }

        self.pose();
        let handles = self.handles();
        let mut joint_drag = None;
        egui::CentralPanel::no_frame().show(ui, |ui| {
            let (_, dragged) = self.viewport.show(
                ui,
                render_state,
                &mut self.state.camera,
                &self.scene,
                &handles,
                self.state.settings.quality,
                self.state.playback.playing && !self.state.stage.actors.is_empty(),
            );
            joint_drag = dragged;
            if let Some(c) = &self.state.comparison {
                let name = |i: usize| self.state.stage.actors.get(i).map_or("", |x| x.name.as_str());
                ui::compare_legend::show(ui, ui.max_rect(), c, name(c.b), name(c.a));
            }
            if ui::overlay::show(ui, self.state.notice.as_ref(), !self.state.stage.actors.is_empty()) {
                commands.push(Command::DismissNotice);
            }
        });
        if joint_drag.is_none() {
            self.gesture.release();
            self.finish_new_bone();
        }
        if let Some(d) = joint_drag {
            self.drag(d);
            ui.ctx().request_repaint();
        }
        if let Some(tentacle) = &self.state.tentacle {
            ui::tentacle::show(ui, tentacle, self.state.settings.show_weights, &mut commands);
        }
        if let Some(dialog) = &self.state.layer_dialog {
            ui::layer_window::show(ui.ctx(), dialog, &self.state.stage, &mut commands);
        }
        if let Some(dialog) = &self.state.retarget_dialog {
            ui::retarget_window::show(ui.ctx(), dialog, &self.state.stage, &mut commands);
        }
        if self.step_capture() {
            ui.ctx().request_repaint();
        }
        if let Some(index) = self.state.pending_close {
            let name = self.state.stage.actors.get(index).map(|c| c.name.as_str());
            confirm_close(ui.ctx(), index, name, &mut commands);
        }
        let applied = !commands.is_empty();
        for c in commands.drain(..) {
            let _refused_is_shown = self.apply(c);
        }
        self.commands = commands;
        if applied {
            ui.ctx().request_repaint();
        }
        if self.state.playback.playing && !self.state.stage.actors.is_empty() && !self.held {
            ui.ctx().request_repaint();
        }
        std::mem::take(&mut self.requests)
    }

    /// Back to the default view angles, framing every visible character's motion.
    pub(crate) fn reset_camera(&mut self) {
        self.state.camera = OrbitCamera::default();
        self.state.camera.frame(self.state.stage.bounds());
    }

    fn advance_clock(&mut self, ctx: &egui::Context) {
        if self.held {
            return;
        }
        let now = ctx.input(|i| i.time);
        let dt = self.last_time.map_or(0.0, |t| (now - t).clamp(0.0, MAX_STEP));
        self.last_time = Some(now);
        if let Some(t) = self.state.timing() {
            self.state.playback.advance(dt, t);
        }
    }

    /// Poses every visible character at the playhead and rebuilds the scene primitives.
    pub fn pose(&mut self) {
        let smooth = self.state.playback.playing.then_some(self.state.settings.between);
        self.pose_characters(self.state.playback.time, smooth);
        self.refresh_comparison();
        pose_scene::build_scene(&self.state.stage, &self.state.settings, self.state.selected, &mut self.scene);
        self.comparison_overlay();
        pose_scene::push_motion_marks(
            &self.state.stage,
            &self.state.settings,
            self.state.selected,
            self.state.playback.time,
            &mut self.trails,
            &mut self.scene,
        );
        self.drag_overlay();
        self.rig_overlay();
        if let Some(demo) = &mut self.state.tentacle {
            self.scene.spheres.push(mocap_render::Sphere {
                center: demo.target,
                radius: 0.07,
                color: [235, 70, 60, 255],
            });
            if let Some(tip) = self.state.stage.actors.first().and_then(|c| c.extra.pose.last()) {
                demo.tip = tip.translation;
            }
        }
    }

    /// The picture at `time` seconds for a video frame: every visible character
    /// posed at `time` (between frames as the view interpolates), the floor and
    /// the view's draw settings, without selection or editing overlays; seen by
    /// the view's camera at `aspect` (width / height), its target following the
    /// current character's root when `follow`. The view is posed at its
    /// playhead again afterwards, its camera untouched.
    pub fn video_frame(&mut self, time: f64, aspect: f32, follow: bool) -> (Scene, mocap_render::Camera) {
        let (target, follow_setting) = (self.state.camera.target, self.state.settings.follow_root);
        self.state.settings.follow_root = follow;
        self.pose_characters(time, Some(self.state.settings.between));
        let mut scene = Scene::default();
        pose_scene::build_scene(&self.state.stage, &self.state.settings, None, &mut scene);
        pose_scene::push_motion_marks(
            &self.state.stage,
            &self.state.settings,
            self.state.selected,
            time,
            &mut self.trails,
            &mut scene,
        );
        let camera = self.state.camera.to_camera(aspect.max(1e-3));
        self.state.camera.target = target;
        self.state.settings.follow_root = follow_setting;
        self.pose();
        (scene, camera)
    }

    /// What a video export starts from: the timeline's frame rate and
    /// length, the loop range in seconds (when one is set), and the 3D view's
    /// size in points (`None` before it is first drawn).
    pub fn video_defaults(&self) -> VideoDefaults {
        let timing = self.state.timing();
        let fps = timing.map_or(30.0, |t| 1.0 / t.frame_time());
        let duration = timing.map_or(0.0, |t| t.duration()).max(self.state.stage.duration());
        let range = timing.filter(|_| self.state.playback.range.is_some()).map(|t| {
            let (a, b) = self.state.playback.frame_range(t);
            (t.time_of(a), t.time_of(b))
        });
        let view = self.viewport.geometry.map(|g| [g.rect.width(), g.rect.height()]);
        VideoDefaults { fps, duration, range, view }
    }

    /// Poses every visible character at `time` (`smooth`: how to blend between
    /// frames; `None`: the frame shown), and
    /// moves the camera's target with the current character's root when the
    /// view follows it.
    fn pose_characters(&mut self, time: f64, smooth: Option<mocap::Interpolation>) {
        let body = self.state.settings.mode == DrawMode::Body;
        if let (Some(demo), Some(c)) = (&self.state.tentacle, self.state.stage.actors.first_mut()) {
            demo.pose(c);
        }
        for c in self.state.stage.actors.iter_mut().filter(|c| c.visible) {
            character::pose_at(
                c,
                time,
                smooth,
                self.state.settings.foot_lock,
                &mut self.pose_scratch,
            );
            if body {
                c.extra.drawable.ensure_body(c.asset.clip(), c.extent);
            }
        }
        let current = self.state.stage.actors.get(self.state.current()).filter(|c| c.visible);
        if self.state.settings.follow_root
            && let Some(root) = current.and_then(|c| c.extra.pose.first())
        {
            self.state.camera.target.x = root.translation.x;
            self.state.camera.target.z = root.translation.z;
        }
    }

    /// Opens the bendy-tentacle demo with `bones` bones in place of everything open:
    /// its skin drawn in body mode, the tip following the target sphere.
    pub(crate) fn open_tentacle(&mut self, bones: usize) {
        let demo = crate::tentacle::Tentacle::new(bones);
        let clip = mocap::build::demo::tentacle(demo.bones);
        self.open_assets(vec![("tentacle".to_owned(), mocap::Asset::Clip(clip))]);
        self.state.settings.mode = DrawMode::Body;
        self.set_playing(false);
        if let Some(c) = self.state.stage.actors.first_mut() {
            c.extra.drawable.body = Some(c.clip().and_then(|clip| demo.body(clip)));
        }
        self.state.tentacle = Some(demo);
        self.state.camera.pitch = 0.15;
        self.state.camera.yaw = 0.3;
        let length = self.state.tentacle.as_ref().map_or(1.0, |t| t.bones as f32 * mocap::build::demo::BONE_LENGTH);
        self.state.camera.target = mocap::glam::Vec3::new(0.0, length * 0.5, 0.0)
            + self.state.stage.actors.first().map_or(mocap::glam::Vec3::ZERO, |c| c.placement());
        self.state.camera.distance = length * 2.6;
    }

    /// Starts a new character for the creator (a root joint, 60 frames at 30 fps)
    /// in place of everything open, selected and in Edit mode: add joints from the
    /// Edit menu, pose them by dragging and Set key, then Save as BVH.
    pub(crate) fn new_character(&mut self) {
        let clip = mocap::ops::edit::new_character(60, 30.0);
        self.open_assets(vec![("character.bvh".to_owned(), mocap::Asset::Clip(clip))]);
        self.set_playing(false);
        self.state.settings.pose_mode = true;
        self.state.settings.key_between = true;
        self.state.selected = Some(Selection { character: 0, joint: 0 });
        self.state.camera.target = mocap::glam::Vec3::new(0.0, 1.0, 0.0);
        self.state.camera.distance = 4.0;
    }

    /// Rebuilds the tentacle's skin after the demo's softness changed.
    pub(crate) fn refresh_tentacle_skin(&mut self) {
        let (Some(demo), Some(c)) = (&self.state.tentacle, self.state.stage.actors.first_mut()) else { return };
        c.extra.drawable.body = Some(c.clip().and_then(|clip| demo.body(clip)));
    }

    /// Sets joint `joint` of character `character` to a local rotation at the frame
    /// shown (typed values in Edit mode): a correction like a drag, keyed by Set key.
    pub(crate) fn rotate_joint(&mut self, character: usize, joint: usize, rotation: mocap::glam::Quat) -> bool {
        let time = self.state.playback.time;
        let Some(c) = self.state.stage.actors.get_mut(character) else { return false };
        let done = character::rotate_joint(c, joint, rotation, time, &mut self.pose_scratch).is_some();
        self.pose();
        done
    }

    /// Forgets every pose correction made by dragging.
    pub(crate) fn reset_pose(&mut self) {
        for c in &mut self.state.stage.actors {
            c.extra.correction = None;
        }
    }

    /// Where a joint was last drawn on screen (points), if the view has been drawn
    /// and the joint is in front of the camera.
    pub fn joint_on_screen(&self, character: usize, joint: usize) -> Option<egui::Pos2> {
        let world = self.state.stage.actors.get(character)?.extra.pose.get(joint)?.translation;
        self.screen_position(world)
    }

    /// Where a world point is on screen (points) with the last frame's view.
    pub fn screen_position(&self, world: mocap::glam::Vec3) -> Option<egui::Pos2> {
        self.viewport.geometry?.project(world)
    }

    /// The scene primitives built by the last [`Viewer::pose`].
    pub fn scene(&self) -> &Scene {
        &self.scene
    }
}

/// Asks whether to close character `index` (called `name`), whose edits are not saved.
fn confirm_close(ctx: &egui::Context, index: usize, name: Option<&str>, out: &mut Vec<Command>) {
    let Some(name) = name else {
        out.push(Command::KeepOpen);
        return;
    };
    egui::Window::new("Unsaved edits")
        .collapsible(false)
        .resizable(false)
        .anchor(egui::Align2::CENTER_CENTER, egui::vec2(0.0, 0.0))
        .show(ctx, |ui| {
            ui.label(format!("{name} has edits that are not saved."));
            ui.horizontal(|ui| {
                if ui.button("Save as BVH").clicked() {
                    out.push(Command::SaveCharacter(index));
                }
                if ui.button("Close without saving").clicked() {
                    out.push(Command::CloseNow(index));
                }
                if ui.button("Keep it open").clicked() {
                    out.push(Command::KeepOpen);
                }
            });
        });
}
