//! Capturing a model's skeletal motion in the viewer ([`mocap::capture`]): the
//! job runs a few milliseconds per drawn frame (the page stays responsive and a
//! progress bar moves), then the captured clip joins the stage beside its model,
//! both in overlay so the skeleton shows inside the mesh, playing every frame in
//! step. A rig dropped as JSON is used for the next capture of a model with as
//! many vertices; otherwise a humanoid is fitted and bound.

use mocap::capture::{Capturer, Report, Rig};

/// Milliseconds of capture work per drawn frame.
pub const BUDGET_MS: f64 = 12.0;

/// A capture in progress.
pub struct CaptureJob {
    /// The model's character index.
    pub model: usize,
    /// The model's name.
    pub name: String,
    pub(crate) capturer: Capturer,
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
