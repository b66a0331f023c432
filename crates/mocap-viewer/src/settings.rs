//! View settings: plain state, all of it in the URL fragment (see [`crate::view_state`]).

pub use mocap_render::DrawMode;

/// What the 3D view shows and how the camera behaves.
#[derive(Clone, Debug, PartialEq)]
pub struct ViewSettings {
    /// Draw each joint's local axes (x red, y green, z blue).
    pub show_axes: bool,
    /// Draw joint spheres (stick mode).
    pub show_joints: bool,
    /// Capsules, sticks or body.
    pub mode: DrawMode,
    /// In body mode, colour the body by its bone influences.
    pub show_weights: bool,
    /// The key light casts soft shadows on the floor.
    pub shadows: bool,
    /// Keep the camera target over the root joint.
    pub follow_root: bool,
    /// How a playing view samples between frames: nearest frame, linear, or
    /// cubic (Catmull-Rom translations, squad rotations: smooth across frames);
    /// Edit ▸ Resample uses the same in-betweens. Paused views are always
    /// frame-exact. Only `Nearest`, `Linear` and `Cubic` are offered.
    pub between: mocap::Interpolation,
    /// Onion skin: poses before (blue) and after (orange) the frame, fading.
    pub onion: bool,
    /// Onion-skin poses on each side (1 to 8).
    pub onion_count: usize,
    /// Seconds between onion-skin poses.
    pub onion_step: f64,
    /// Trails: the root's path on the floor (a tick each second, the current
    /// point) and the selected joint's path over the second either side.
    pub trails: bool,
    /// Edit mode: dragging a joint in the view moves it and its chain follows by IK.
    pub pose_mode: bool,
    /// Pin each foot to the floor while it is in contact (legs solved by IK).
    pub foot_lock: bool,
    /// Frames on each side over which a key fades in and out.
    pub key_window: usize,
    /// Keys interpolate from key to key (key-frame animation: slerp between the
    /// keyed poses, held before the first and after the last) instead of fading
    /// over `key_window` (corrections of a dense take).
    pub key_between: bool,
    /// The 3D view's quality: full, fast while moving, or automatic.
    pub quality: crate::quality::Quality,
}

/// The choices of [`ViewSettings::between`] the view offers, in menu order:
/// value, label, tooltip.
pub const BETWEEN_CHOICES: [(mocap::Interpolation, &str, &str); 3] = [
    (mocap::Interpolation::Nearest, "Nearest", "The nearest frame: no in-betweens, the take's own steps"),
    (mocap::Interpolation::Linear, "Linear", "Straight blends between frames (slerp rotations)"),
    (
        mocap::Interpolation::Cubic,
        "Cubic",
        "Smooth across frames: Catmull-Rom positions, squad rotations; Edit ▸ Resample uses it too",
    ),
];

impl ViewSettings {
    /// Sets [`ViewSettings::between`] by name (`nearest`, `linear` or
    /// `cubic`); false, and nothing changed, for any other name.
    pub fn set_between(&mut self, name: &str) -> bool {
        match BETWEEN_CHOICES.iter().find(|(i, ..)| i.name() == name) {
            Some((i, ..)) => {
                self.between = *i;
                true
            }
            None => false,
        }
    }
}

impl Default for ViewSettings {
    fn default() -> ViewSettings {
        ViewSettings {
            show_axes: false,
            show_joints: true,
            mode: DrawMode::Capsules,
            show_weights: false,
            shadows: true,
            follow_root: false,
            between: mocap::Interpolation::Linear,
            onion: false,
            onion_count: 3,
            onion_step: 0.2,
            trails: false,
            pose_mode: false,
            foot_lock: false,
            key_window: 3,
            key_between: false,
            quality: crate::quality::Quality::Auto,
        }
    }
}
