//! A plain copy of what the viewer shows, for scripting and tests (`window.mocapViewer.state()`).

use crate::character::Character;
use crate::state::AppState;

/// Summary of one open character.
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
    /// Whether it is drawn.
    pub visible: bool,
    /// Bone colour (sRGB, 0-255).
    pub color: [u8; 4],
    /// Where its origin stands in metres: layout offset plus the hand-set offset.
    pub offset: [f32; 3],
    /// For a model: the animation playing (`all` for every frame).
    pub animation: Option<String>,
    /// For a model: its animations' names in file order.
    pub animations: Vec<String>,
    /// For a model: the key frame drawn (the first of the two blended) and its name.
    pub model_frame: Option<(usize, String)>,
    /// For a model: the skin file in use.
    pub skin: Option<String>,
    /// Whether a pose correction (by dragging in Edit mode) is shown at its frame.
    pub corrected: bool,
    /// With foot locking on: frames each foot is in contact (per leg).
    pub foot_contacts: Vec<usize>,
    /// Whether the clip has edits (that undo can take back).
    pub edited: bool,
    /// Whether it has edits made (or undone) since it was last saved.
    pub unsaved: bool,
    /// Frames keyed (pose corrections made keys), in order.
    pub keys: Vec<usize>,
    /// Which file axis points up: `y` or `z` (a model: `y`).
    pub up: &'static str,
}

impl ClipSummary {
    /// The summary of one character.
    pub fn of(c: &Character) -> ClipSummary {
        let timeline = c.asset.timeline();
        let skeleton = c.clip().map(|clip| clip.skeleton());
        let model = c.model();
        ClipSummary {
            name: c.name.clone(),
            frames: timeline.frames(),
            frame_time: timeline.frame_time(),
            joints: skeleton.map_or(0, |s| s.joint_count()),
            joint_names: skeleton.map_or(Vec::new(), |s| s.joints().iter().map(|j| j.name.clone()).collect()),
            visible: c.visible,
            color: c.extra.color,
            offset: c.placement().to_array(),
            animation: model
                .map(|m| m.animation_name().to_owned())
                .or_else(|| c.clip().and_then(|clip| clip.take_name().map(str::to_owned))),
            animations: match (model, c.clip()) {
                (Some(m), _) => m.mesh.animations().iter().map(|a| a.name.clone()).collect(),
                (None, Some(clip)) => clip.takes().iter().map(|t| t.name.clone()).collect(),
                _ => Vec::new(),
            },
            model_frame: model.zip(c.extra.morph).map(|(m, at)| (at.frame0, m.frame_name(at.frame0).to_owned())),
            skin: model.and_then(|m| m.skin.as_ref()).map(|s| s.name.clone()),
            corrected: c.extra.correction.is_some(),
            edited: false,
            unsaved: false,
            keys: Vec::new(),
            foot_contacts: c
                .extra
                .foot_lock
                .as_ref()
                .map_or(Vec::new(), |l| l.contacts().map(|k| k.iter().filter(|x| **x).count()).collect()),
            up: c.up.name(),
        }
    }
}

/// The bendy-tentacle demo's state.
#[derive(Clone, Debug, PartialEq)]
pub struct DemoSummary {
    /// Bones in the chain.
    pub bones: usize,
    /// `two-bone`, `ccd` or `fabrik`.
    pub solver: &'static str,
    /// Soft or rigid skin.
    pub soft: bool,
    /// Whether the tip follows the target.
    pub follow: bool,
    /// The target (world, metres).
    pub target: [f32; 3],
    /// Where the tip was drawn (world, metres).
    pub tip: [f32; 3],
}

/// The observable state of the viewer.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Snapshot {
    /// Open characters, in order.
    pub clips: Vec<ClipSummary>,
    /// Current frame of the timeline (in the current character's frame time).
    pub frame: usize,
    /// Playhead in seconds.
    pub time: f64,
    /// Whether playback runs.
    pub playing: bool,
    /// Playback speed factor.
    pub speed: f32,
    /// Name of the selected joint.
    pub selected_joint: Option<String>,
    /// Index (0-based) of the selected joint's character.
    pub selected_character: Option<usize>,
    /// `spread` or `overlay`.
    pub layout: &'static str,
    /// `capsules`, `sticks` or `body`.
    pub draw_mode: &'static str,
    /// Whether floor shadows are drawn.
    pub shadows: bool,
    /// Whether Edit mode (drag joints by IK) is on.
    pub pose_mode: bool,
    /// The 3D view's quality setting: `auto`, `full` or `fast`.
    pub quality: &'static str,
    /// How a playing view samples between frames: `nearest`, `linear` or `cubic`.
    pub interpolation: &'static str,
    /// Whether the last frame was drawn in the fast look (see [`crate::quality`]).
    pub reduced: bool,
    /// Samples per pixel of the last frame: 1 in the fast look and for scenes
    /// of capsules (outlines blended), 4 for lines, spheres and meshes where
    /// the adapter can; 0 before the first frame.
    pub samples: u32,
    /// The last frame's 3D view as drawn, in pixels (width, height): the
    /// view's pixels, or half of them per axis in the fast look, stretched
    /// over the view; zero before the first frame.
    pub view_pixels: [u32; 2],
    /// Whether the last frame started from the floor drawn for an earlier one
    /// (a still camera) instead of drawing it.
    pub floor_copied: bool,
    /// The banner's message (the last failure to open files, or a refused action).
    pub error: Option<String>,
    /// The banner's line under the message: what became of what was open
    /// ("What was open is still open.", "The other files opened.", "Nothing was
    /// changed."), or `None`.
    pub error_note: Option<&'static str>,
    /// The joint names the hierarchy panel lists, in order (none while it is
    /// hidden; at most [`crate::tree::MAX_LABELS`]).
    pub tree_labels: Vec<String>,
    /// Frames the 3D view has rendered.
    pub frames_rendered: u64,
    /// The view state as a URL fragment (no leading `#`).
    pub view: String,
    /// Whether the embed layout is on.
    pub embed: bool,
    /// Whether the page holds an earlier session to restore.
    pub previous_session: bool,
    /// The wgpu backend drawing the 3D view ("BrowserWebGpu", "Gl", ...).
    pub backend: Option<String>,
    /// The bendy-tentacle demo, when open.
    pub demo: Option<DemoSummary>,
    /// The edit Undo would take back, and the one Redo would make again.
    pub undo: Option<String>,
    /// See [`Snapshot::undo`].
    pub redo: Option<String>,
}

impl Snapshot {
    /// The state `v` shows; what only the 3D view knows (frames drawn, backend,
    /// samples) is left at its default for the viewer to fill in.
    pub fn of(v: &AppState) -> Snapshot {
        Snapshot {
            clips: v
                .stage
                .actors
                .iter()
                .enumerate()
                .map(|(i, c)| ClipSummary {
                    edited: v.history.edited(i),
                    unsaved: v.history.unsaved(i),
                    keys: v.history.keys(i),
                    ..ClipSummary::of(c)
                })
                .collect(),
            frame: v.frame(),
            time: v.playback.time,
            playing: v.playback.playing,
            speed: v.playback.speed,
            selected_joint: v.selected_name().map(str::to_owned),
            selected_character: v.selected.map(|s| s.character),
            layout: v.stage.layout.name(),
            draw_mode: v.settings.mode.name(),
            shadows: v.settings.shadows,
            pose_mode: v.settings.pose_mode,
            quality: v.settings.quality.name(),
            interpolation: v.settings.between.name(),
            error: v.notice.as_ref().map(|n| n.message.clone()),
            error_note: v.notice.as_ref().and_then(|n| n.note(!v.stage.actors.is_empty())),
            tree_labels: if v.panels.show_hierarchy() {
                crate::tree::listed_joints(&v.stage.actors, &v.folds)
            } else {
                Vec::new()
            },
            view: v.view_fragment(),
            embed: v.panels.embed,
            previous_session: v.previous_session,
            undo: v.history.next_undo().map(str::to_owned),
            redo: v.history.next_redo().map(str::to_owned),
            demo: v.tentacle.as_ref().map(|t| DemoSummary {
                bones: t.bones,
                solver: t.solver.name(),
                soft: t.soft,
                follow: t.follow,
                target: t.target.to_array(),
                tip: t.tip.to_array(),
            }),
            ..Snapshot::default()
        }
    }
}
