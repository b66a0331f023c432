//! View settings: plain, serialisable-in-spirit state (a later issue puts it in the URL).

/// What the 3D view shows and how the camera behaves.
#[derive(Clone, Debug, PartialEq)]
pub struct ViewSettings {
    /// Draw each joint's local axes (x red, y green, z blue).
    pub show_axes: bool,
    /// Draw joint spheres.
    pub show_joints: bool,
    /// Keep the camera target over the root joint.
    pub follow_root: bool,
    /// Interpolate between frames while playing (paused views are always frame-exact).
    pub interpolate: bool,
}

impl Default for ViewSettings {
    fn default() -> ViewSettings {
        ViewSettings { show_axes: false, show_joints: true, follow_root: false, interpolate: true }
    }
}
