//! A plain copy of what the viewer shows, for scripting and tests (`window.mocapViewer.state()`).

/// Summary of one open clip.
#[derive(Clone, Debug, PartialEq)]
pub struct ClipSummary {
    /// File name.
    pub name: String,
    /// Frame count.
    pub frames: usize,
    /// Seconds per frame.
    pub frame_time: f64,
    /// Joints, not counting End Sites.
    pub joints: usize,
    /// Names of all joints (End Sites included) in file order.
    pub joint_names: Vec<String>,
}

/// The observable state of the viewer.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Snapshot {
    /// Open clips (zero or one for now).
    pub clips: Vec<ClipSummary>,
    /// Current frame.
    pub frame: usize,
    /// Playhead in seconds.
    pub time: f64,
    /// Whether playback runs.
    pub playing: bool,
    /// Playback speed factor.
    pub speed: f32,
    /// Name of the selected joint.
    pub selected_joint: Option<String>,
    /// Last load error, shown in the page.
    pub error: Option<String>,
    /// Joint labels the hierarchy panel drew in its last frame.
    pub tree_labels: Vec<String>,
    /// Frames the 3D view has rendered.
    pub frames_rendered: u64,
    /// The view state as a URL fragment (no leading `#`).
    pub view: String,
    /// Whether the embed layout is on.
    pub embed: bool,
    /// The wgpu backend drawing the 3D view ("BrowserWebGpu", "Gl", ...).
    pub backend: Option<String>,
}
