//! How characters are placed: side by side in lanes, or all on top of each other.

/// The stage layout; part of the view state (`layout=spread|overlay`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Layout {
    /// Side by side along X, wrapping into rows past eight (see [`mocap::arrange::spread`]).
    #[default]
    Spread,
    /// Every layout offset zero, to compare motions in place.
    Overlay,
}

impl Layout {
    /// The name used in the fragment and from JavaScript.
    pub fn name(self) -> &'static str {
        match self {
            Layout::Spread => "spread",
            Layout::Overlay => "overlay",
        }
    }

    /// Reads `spread` or `overlay`.
    pub fn parse(name: &str) -> Option<Layout> {
        match name {
            "spread" => Some(Layout::Spread),
            "overlay" => Some(Layout::Overlay),
            _ => None,
        }
    }
}
