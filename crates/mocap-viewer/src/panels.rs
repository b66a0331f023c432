//! Which panels the viewer shows, and the embed layout (3D view and a minimal timeline).

/// Panel visibility; part of the view state in the URL.
#[derive(Clone, Debug, PartialEq)]
pub struct Panels {
    /// The joint tree on the left.
    pub hierarchy: bool,
    /// Clip info and the joint inspector on the right.
    pub inspector: bool,
    /// Embed layout (`?embed=1`): no toolbar or side panels, a minimal timeline.
    pub embed: bool,
}

impl Default for Panels {
    fn default() -> Panels {
        Panels { hierarchy: true, inspector: true, embed: false }
    }
}

impl Panels {
    /// Whether the hierarchy panel is drawn.
    pub fn show_hierarchy(&self) -> bool {
        self.hierarchy && !self.embed
    }

    /// Whether the inspector panel is drawn.
    pub fn show_inspector(&self) -> bool {
        self.inspector && !self.embed
    }
}
