//! Scene primitives: what gets drawn, independent of where it came from.

use crate::{Grid, MeshDraw, SkinnedDraw};
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

/// A lit, shadow-casting capsule: a cylinder from `a` to `b` with round ends of
/// `radius`. With `a == b` it is a sphere.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Capsule {
    /// One end (world space).
    pub a: Vec3,
    /// The other end (world space).
    pub b: Vec3,
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
    /// The floor (a shaded plane with grid lines that fades with distance), if any.
    pub grid: Option<Grid>,
    /// Line segments (bones, axes, ...).
    pub lines: Vec<Line>,
    /// Line segments drawn over everything, not hidden by what is in front (e.g.
    /// bone axes inside capsules).
    pub overlay_lines: Vec<Line>,
    /// Spheres (joints, ...); they also cast shadows.
    pub spheres: Vec<Sphere>,
    /// Shaded capsules (bones drawn as solids); they cast shadows.
    pub capsules: Vec<Capsule>,
    /// Capsules that only cast shadows and are not drawn (e.g. under stick figures,
    /// whose screen-space lines cast none).
    pub shadow_casters: Vec<Capsule>,
    /// Vertex-animated meshes (lit, textured, shadow-casting), blended on the GPU.
    pub meshes: Vec<MeshDraw>,
    /// Skinned meshes (bodies), lit and shadow-casting, skinned on the GPU.
    pub skinned: Vec<SkinnedDraw>,
    /// Capsules around the bodies' bones that cast the bodies' shadows in the
    /// fast look instead of the skinned meshes (on a software GPU a body's
    /// vertices cost far more than its bones' impostors); unused otherwise.
    /// Without them the skinned meshes cast in the fast look too.
    pub body_casters: Vec<Capsule>,
    /// Whether the floor receives the key light's soft shadow.
    pub shadows: bool,
}

impl Default for Scene {
    fn default() -> Scene {
        Scene {
            background: [38, 40, 46, 255],
            grid: None,
            lines: Vec::new(),
            overlay_lines: Vec::new(),
            spheres: Vec::new(),
            capsules: Vec::new(),
            shadow_casters: Vec::new(),
            meshes: Vec::new(),
            skinned: Vec::new(),
            body_casters: Vec::new(),
            shadows: true,
        }
    }
}

impl Scene {
    /// Whether everything in the scene is anti-aliased without multisampling:
    /// capsules, lines and spheres (whose outlines [`crate::SceneRenderer`]
    /// filters on one sample), shadow casters and the floor (whose lines and
    /// edge are filtered in its shader), but no meshes or bodies. Such a scene
    /// is drawn at full quality into a single-sampled target; meshes have hard
    /// edges there.
    pub fn smooth_on_one_sample(&self) -> bool {
        self.meshes.is_empty() && self.skinned.is_empty()
    }

    /// Empties the primitive lists, keeping their allocations.
    pub fn clear(&mut self) {
        self.grid = None;
        self.lines.clear();
        self.overlay_lines.clear();
        self.spheres.clear();
        self.capsules.clear();
        self.shadow_casters.clear();
        self.meshes.clear();
        self.skinned.clear();
        self.body_casters.clear();
    }
}
