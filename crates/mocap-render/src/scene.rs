//! Scene primitives: what gets drawn, independent of where it came from.

use crate::Grid;
use glam::Vec3;

/// A line segment drawn `width_px` pixels wide whatever its distance.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Line {
    /// Start point (world space).
    pub a: Vec3,
    /// End point (world space).
    pub b: Vec3,
    /// sRGB colour with straight alpha, 0-255.
    pub color: [u8; 4],
    /// Width on screen in logical pixels (scaled by [`crate::SceneRenderer::pixels_per_point`]).
    pub width_px: f32,
}

/// A lit sphere (drawn as a camera-facing impostor).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sphere {
    /// Centre (world space).
    pub center: Vec3,
    /// Radius (world units).
    pub radius: f32,
    /// sRGB colour, 0-255.
    pub color: [u8; 4],
}

/// Everything to draw in one frame. Reuse it between frames to avoid allocation.
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    /// Clear colour (sRGB, 0-255).
    pub background: [u8; 4],
    /// The floor grid, if any.
    pub grid: Option<Grid>,
    /// Line segments (bones, axes, ...).
    pub lines: Vec<Line>,
    /// Spheres (joints, ...).
    pub spheres: Vec<Sphere>,
}

impl Default for Scene {
    fn default() -> Scene {
        Scene { background: [38, 40, 46, 255], grid: None, lines: Vec::new(), spheres: Vec::new() }
    }
}

impl Scene {
    /// Empties the primitive lists, keeping their allocations.
    pub fn clear(&mut self) {
        self.grid = None;
        self.lines.clear();
        self.spheres.clear();
    }
}
