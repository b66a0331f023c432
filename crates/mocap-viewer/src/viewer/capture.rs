//! Model capture steps on the viewer.

use super::Viewer;
use crate::capture::{BUDGET_MS, CaptureJob, CaptureResult};
use crate::layout::Layout;
use mocap::capture::{Capturer, Options, Rig, RigChoice};
impl Viewer {
    /// Starts capturing model `index` (with the rig being set up on it, else the
    /// dropped one if it fits the model, else an automatic fit). The work is done a little per frame ([`BUDGET_MS`]).
    pub(crate) fn start_capture(&mut self, index: usize) -> Result<(), String> {
        if self.state.rig_edit.as_ref().is_some_and(|e| e.model == index) {
            self.finish_rig_edit();
        }
        let c = self.state.stage.actors.get(index).ok_or_else(|| format!("no character {}", index + 1))?;
        let model = c.model().ok_or_else(|| format!("{}: only a model (MD2) can be captured", c.name))?;
        let vertices = model.mesh.source_counts.vertices;
        if let Some(rig) = self.state.capture_rig.as_ref().filter(|r| r.binding.len() != vertices) {
            return Err(format!("the rig binds {} vertices but {} has {vertices}", rig.binding.len(), c.name));
        }
        let rig = self.state.capture_rig.take();
        let choice = rig.as_ref().map_or(RigChoice::Fit(None), RigChoice::Given);
        let capturer =
            Capturer::from_mesh(&model.mesh, choice, &Options::default()).map_err(|e| format!("{}: {e}", c.name))?;
        self.state.capture_job = Some(CaptureJob { model: index, name: c.name.clone(), capturer });
        Ok(())
    }

    /// Does up to [`BUDGET_MS`] of capture work; when the capture is done, adds
    /// the clip beside its model. Returns whether a capture is running.
    pub fn step_capture(&mut self) -> bool {
        let Some(job) = self.state.capture_job.as_mut() else { return false };
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
    pub(crate) fn finish_capture_now(&mut self) {
        if let Some(job) = self.state.capture_job.as_mut() {
            while job.capturer.step() {}
            self.finish_capture();
        }
    }

    fn finish_capture(&mut self) {
        let Some(job) = self.state.capture_job.take() else { return };
        let model_placement = self.state.stage.actors.get(job.model).map(|c| c.offset);
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
        let added = self.state.stage.actors.len() - 1;
        if let (Some(offset), Some(c)) = (model_placement, self.state.stage.actors.get_mut(added)) {
            c.offset = offset;
            // The skeleton lives in the model's axes (Y-up), whatever way its
            // motion lies (a swimming dolphin lies along Z).
            c.set_up(mocap::UpAxis::Y);
        }
        self.set_layout(Layout::Overlay);
        self.state.capture_result = Some(CaptureResult {
            model: job.name,
            clip: clip_name,
            report: capture.report,
            rig: capture.rig,
            animations: capture.animations.iter().map(|a| (a.name.clone(), a.first, a.last)).collect(),
        });
    }

    /// Keeps a rig (JSON text) for the next capture; returns what is wrong with it.
    pub(crate) fn use_rig(&mut self, name: &str, text: &str) -> Result<(), String> {
        let rig = Rig::from_json(text).map_err(|e| format!("{name}: {e}"))?;
        self.state.capture_rig = Some(rig);
        Ok(())
    }

    /// The rig being set up, else the last capture's, as a JSON download
    /// (`NAME-rig.json`).
    pub fn rig_download(&self) -> Option<(String, String)> {
        let stem = crate::character::file_stem;
        if let Some(e) = &self.state.rig_edit {
            let name = self.state.stage.actors.get(e.model).map_or("model".to_owned(), |c| stem(&c.name).to_owned());
            return Some((format!("{name}-rig.json"), e.rig.to_json()));
        }
        let r = self.state.capture_result.as_ref()?;
        Some((format!("{}-rig.json", stem(&r.model)), r.rig.to_json()))
    }
}
