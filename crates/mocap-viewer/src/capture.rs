//! Capturing a model's skeletal motion in the viewer ([`mocap::capture`]): the
//! job runs a few milliseconds per drawn frame (the page stays responsive and a
//! progress bar moves), then the captured clip joins the stage beside its model,
//! both in overlay so the skeleton shows inside the mesh, playing every frame in
//! step. A rig dropped as JSON is used for the next capture of a model with as
//! many vertices; otherwise a humanoid is fitted and bound.

use crate::layout::Layout;
use crate::viewer::Viewer;
use mocap::capture::{Capturer, Options, Report, Rig, RigChoice};

/// Milliseconds of capture work per drawn frame.
pub const BUDGET_MS: f64 = 12.0;

/// A capture in progress.
pub struct CaptureJob {
    /// The model's character index.
    pub model: usize,
    /// The model's name.
    pub name: String,
    capturer: Capturer,
}

/// What the last capture gave, for the model's panel.
#[derive(Clone, Debug)]
pub struct CaptureResult {
    /// The model's name.
    pub model: String,
    /// The captured clip's character name.
    pub clip: String,
    /// The per-joint report.
    pub report: Report,
    /// The rig used (for Save rig).
    pub rig: Rig,
    /// The model's animations as frame ranges of the clip.
    pub animations: Vec<(String, usize, usize)>,
}

impl Viewer {
    /// Starts capturing model `index` (with the rig being set up on it, else the
    /// dropped one if it fits the model, else an automatic fit). The work is done a little per frame ([`BUDGET_MS`]).
    pub fn start_capture(&mut self, index: usize) -> Result<(), String> {
        if self.rig_edit.as_ref().is_some_and(|e| e.model == index) {
            self.finish_rig_edit();
        }
        let c = self.stage.actors.get(index).ok_or_else(|| format!("no character {}", index + 1))?;
        let model = c.model().ok_or_else(|| format!("{}: only a model (MD2) can be captured", c.name))?;
        let vertices = model.mesh.source_counts.vertices;
        if let Some(rig) = self.capture_rig.as_ref().filter(|r| r.binding.len() != vertices) {
            return Err(format!("the rig binds {} vertices but {} has {vertices}", rig.binding.len(), c.name));
        }
        let rig = self.capture_rig.take();
        let choice = rig.as_ref().map_or(RigChoice::Fit(None), RigChoice::Given);
        let capturer =
            Capturer::from_mesh(&model.mesh, choice, &Options::default()).map_err(|e| format!("{}: {e}", c.name))?;
        self.capture_job = Some(CaptureJob { model: index, name: c.name.clone(), capturer });
        Ok(())
    }

    /// The capture's progress: (steps done, steps in all), while one runs.
    pub fn capture_progress(&self) -> Option<(usize, usize)> {
        self.capture_job.as_ref().map(|j| j.capturer.progress())
    }

    /// Does up to [`BUDGET_MS`] of capture work; when the capture is done, adds
    /// the clip beside its model. Returns whether a capture is running.
    pub fn step_capture(&mut self) -> bool {
        let Some(job) = self.capture_job.as_mut() else { return false };
        let start = web_time::Instant::now();
        while start.elapsed().as_secs_f64() * 1000.0 < BUDGET_MS {
            if !job.capturer.step() {
                self.finish_capture();
                return false;
            }
        }
        true
    }

    /// Runs the capture in progress to its end at once (tests, the JS API).
    pub fn finish_capture_now(&mut self) {
        if let Some(job) = self.capture_job.as_mut() {
            while job.capturer.step() {}
            self.finish_capture();
        }
    }

    fn finish_capture(&mut self) {
        let Some(job) = self.capture_job.take() else { return };
        let model_placement = self.stage.actors.get(job.model).map(|c| c.offset);
        let capture = match job.capturer.finish() {
            Ok(c) => c,
            Err(e) => {
                self.refuse(format!("{}: {e}", job.name));
                return;
            }
        };
        let clip_name = format!("{}-capture.bvh", crate::character::file_stem(&job.name));
        // Both play every frame, in step.
        self.set_animation(job.model, "all");
        self.add_asset(&clip_name, capture.clip);
        let added = self.stage.actors.len() - 1;
        if let (Some(offset), Some(c)) = (model_placement, self.stage.actors.get_mut(added)) {
            c.offset = offset;
            // The skeleton lives in the model's axes (Y-up), whatever way its
            // motion lies (a swimming dolphin lies along Z).
            c.set_up(mocap::UpAxis::Y);
        }
        self.set_layout(Layout::Overlay);
        self.capture_result = Some(CaptureResult {
            model: job.name,
            clip: clip_name,
            report: capture.report,
            rig: capture.rig,
            animations: capture.animations.iter().map(|a| (a.name.clone(), a.first, a.last)).collect(),
        });
    }

    /// Keeps a rig (JSON text) for the next capture; returns what is wrong with it.
    pub fn use_rig(&mut self, name: &str, text: &str) -> Result<(), String> {
        let rig = Rig::from_json(text).map_err(|e| format!("{name}: {e}"))?;
        self.capture_rig = Some(rig);
        Ok(())
    }

    /// The rig being set up, else the last capture's, as a JSON download
    /// (`NAME-rig.json`).
    pub fn rig_download(&self) -> Option<(String, String)> {
        let stem = crate::character::file_stem;
        if let Some(e) = &self.rig_edit {
            let name = self.stage.actors.get(e.model).map_or("model".to_owned(), |c| stem(&c.name).to_owned());
            return Some((format!("{name}-rig.json"), e.rig.to_json()));
        }
        let r = self.capture_result.as_ref()?;
        Some((format!("{}-rig.json", stem(&r.model)), r.rig.to_json()))
    }
}
