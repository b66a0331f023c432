//! Capsules on the GPU as impostors: each capsule (and each sphere, as a
//! capsule of zero length) is one or two triangles that cover its outline, and the
//! capsule shader finds the surface by casting the pixel's ray at the capsule:
//! exact depth and normal, round at any size, and the outline anti-aliased from
//! the ray's distance to the capsule. The triangles are placed on the CPU into
//! one vertex buffer and drawn in one plain draw: a software rasteriser's cost
//! is mostly per triangle and per instance (it sets up each instance of an
//! instanced draw like a draw of its own), and it shades whole blocks of pixels
//! per triangle. A capsule mesh took 24 to 144 triangles; a rectangle around
//! the outline takes two, which share most of their blocks on a small capsule,
//! so a capsule under 16 pixels wide is one triangle around it instead, the
//! rectangle's second triangle then having no area (a crowd of 64 frames about
//! 10% faster on lavapipe). The shader places the corners (`capsule_corner` in
//! capsule.wgsl), in each pass by the capsule's size there; a capsule the CPU
//! finds small in every pass ([`is_one_triangle`]) is given as that triangle
//! alone, its corners numbered 4-6.

use crate::{Camera, Capsule};
use bytemuck::{Pod, Zeroable};
use glam::Vec3;

/// In the fast look, capsules whose bounding sphere spans fewer pixels than
/// this are left out, with their shadows: at one sample such a capsule covers
/// at most a few pixel centres, yet costs as much set-up and shading as a
/// large one (a crowd's fingers, for example).
pub(crate) const FAST_LOOK_MIN_SPAN_PX: f32 = 2.0;

/// How many pixels `c`'s bounding sphere spans at most, seen by `camera` on a
/// target `height_px` pixels tall (at its nearest depth); infinite when it
/// reaches the eye's plane or is not finite.
pub(crate) fn span_px(c: &Capsule, camera: &Camera, height_px: f32) -> f32 {
    span_px_at(c, middle_depth(c, camera), camera, height_px)
}

/// The view-space z of `c`'s middle (more negative is farther): the depth the
/// lit capsules are ordered by, and [`span_px_at`]'s.
pub(crate) fn middle_depth(c: &Capsule, camera: &Camera) -> f32 {
    camera.view.transform_point3((c.a + c.b) * 0.5).z
}

/// [`span_px`] of `c` whose middle is at view-space z `middle_z`
/// ([`middle_depth`], for a caller that has it already).
pub(crate) fn span_px_at(c: &Capsule, middle_z: f32, camera: &Camera, height_px: f32) -> f32 {
    let radius = c.a.distance(c.b) * 0.5 + c.radius.abs();
    let scale = camera.pixels_per_unit(height_px);
    let span = if camera.is_perspective() {
        let depth = -middle_z - radius;
        if depth <= 0.0 { f32::INFINITY } else { 2.0 * radius * scale / depth }
    } else {
        2.0 * radius * scale
    };
    if span.is_finite() { span } else { f32::INFINITY }
}

/// One capsule as the CPU describes it (linear colour).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub(crate) struct CapsuleInstance {
    pub a: [f32; 3],
    pub radius: f32,
    pub b: [f32; 3],
    pub color: [f32; 4],
}

impl CapsuleInstance {
    /// The scene's capsule, its colour made linear.
    pub fn new(c: &Capsule) -> CapsuleInstance {
        CapsuleInstance {
            a: c.a.to_array(),
            radius: c.radius,
            b: c.b.to_array(),
            color: crate::srgb_to_linear(c.color),
        }
    }

    /// A capsule that only casts a shadow (no colour; a sphere is `a` = `b`).
    pub fn caster(a: Vec3, b: Vec3, radius: f32) -> CapsuleInstance {
        CapsuleInstance { a: a.to_array(), radius, b: b.to_array(), color: [0.0; 4] }
    }
}

/// One corner of a capsule's quad: the capsule and which corner (0-3). The
/// shader places the corner (`capsule_corner` in capsule.wgsl).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub(crate) struct CapsuleVertex {
    pub a: [f32; 3],
    pub radius: f32,
    pub b: [f32; 3],
    pub corner: f32,
    /// Linear colour.
    pub color: [f32; 4],
}

/// Vertex attributes of [`CapsuleVertex`] (locations 0-4).
pub(crate) const ATTRIBUTES: [wgpu::VertexAttribute; 5] =
    wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32, 2 => Float32x3, 3 => Float32, 4 => Float32x4];

/// Corners of a capsule's quad.
const CORNERS: u32 = 4;

/// The two triangles of a quad over its corners (either winding: the
/// pipelines do not cull them).
const QUAD: [u32; 6] = [0, 1, 2, 2, 1, 3];

/// What a forced triangle's corners add to their number (capsule.wgsl's
/// `capsule_corner` reads corners 4-6 as the triangle's 0-2 whatever the
/// capsule's size).
const TRIANGLE_CORNER: f32 = 4.0;

use crate::shader_text::ONE_TRIANGLE_BELOW;

/// Whether a capsule of `radius` is surely drawn as one triangle in every
/// pass: its bounding sphere spans under [`ONE_TRIANGLE_BELOW`] pixels
/// (`span_px`, see [`span_px`]), and, when there is a shadow map of texels
/// `texel` units large, the shader would make it one triangle there too. Such
/// a capsule is given as that triangle alone ([`expand`]): three corners
/// instead of four and no collapsed second triangle, which a software
/// rasteriser still fetched, shaded and set up (about 3% of a 64-character
/// frame). The rule only saves work: a triangle holds the outline at any size.
pub(crate) fn is_one_triangle(span_px: f32, radius: f32, texel: Option<f32>) -> bool {
    span_px < ONE_TRIANGLE_BELOW && texel.is_none_or(|t| is_one_triangle_in_map(radius, t))
}

/// Whether the shader draws a capsule of `radius` as one triangle in a shadow
/// map of texels `texel` units large (with its texel of room, as `vs_shadow`).
pub(crate) fn is_one_triangle_in_map(radius: f32, texel: f32) -> bool {
    2.0 * (radius.abs() + texel) < ONE_TRIANGLE_BELOW * texel
}

/// Appends each capsule to `vertices` and `indices`: one that is one triangle
/// in every pass (the flag, see [`is_one_triangle`]) as its three corners
/// and that triangle, any other as its quad's [`CORNERS`] corners and two
/// triangles (the shader makes it one triangle or a rectangle in each pass).
/// Stops before an index would pass `u32::MAX`.
pub(crate) fn expand(
    capsules: impl Iterator<Item = (CapsuleInstance, bool)>,
    vertices: &mut Vec<CapsuleVertex>,
    indices: &mut Vec<u32>,
) {
    let (fewest, _) = capsules.size_hint();
    vertices.reserve(fewest * CORNERS as usize);
    indices.reserve(fewest * QUAD.len());
    for (c, one_triangle) in capsules {
        let Some(base) = u32::try_from(vertices.len()).ok().filter(|b| b.checked_add(CORNERS).is_some()) else {
            return;
        };
        let vertex = |corner: f32| CapsuleVertex { a: c.a, radius: c.radius.abs(), b: c.b, corner, color: c.color };
        if one_triangle {
            vertices.extend((0..3).map(|k| vertex(TRIANGLE_CORNER + k as f32)));
            indices.extend([base, base + 1, base + 2]);
        } else {
            vertices.extend((0..CORNERS).map(|k| vertex(k as f32)));
            indices.extend(QUAD.map(|q| base + q));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_capsule_spans_its_bounding_spheres_size_in_pixels() {
        let camera = Camera::look_at(Vec3::new(0.0, 0.0, 10.0), Vec3::ZERO, 0.8, 1.0);
        let capsule = |a: Vec3, b: Vec3, radius: f32| Capsule { a, b, radius, color: [255; 4] };
        // A ball of radius 0.1 ten units away on a 1000-pixel-tall target:
        // 0.2 / (9.9 · tan 0.4) · 500 pixels.
        let ball = span_px(&capsule(Vec3::ZERO, Vec3::ZERO, 0.1), &camera, 1000.0);
        let expected = 0.2 / (9.9 * 0.4f32.tan()) * 500.0;
        assert!((ball - expected).abs() < 1e-3 * expected, "{ball} vs {expected}");
        // Its length counts, and farther is smaller.
        let long = span_px(&capsule(Vec3::new(-1.0, 0.0, 0.0), Vec3::new(1.0, 0.0, 0.0), 0.1), &camera, 1000.0);
        assert!(long > 10.0 * ball);
        assert!(
            span_px(&capsule(Vec3::new(0.0, 0.0, -20.0), Vec3::new(0.0, 0.0, -20.0), 0.1), &camera, 1000.0)
                < ball / 2.0
        );
        // At or behind the eye, or not finite: no bound.
        assert_eq!(
            span_px(&capsule(Vec3::new(0.0, 0.0, 10.0), Vec3::new(0.0, 0.0, 10.0), 0.1), &camera, 1000.0),
            f32::INFINITY
        );
        assert_eq!(span_px(&capsule(Vec3::splat(f32::NAN), Vec3::ZERO, 0.1), &camera, 1000.0), f32::INFINITY);
    }

    #[test]
    fn each_capsule_is_four_corners_and_two_triangles_of_its_own_or_one_forced_triangle() {
        let capsules = [
            CapsuleInstance { a: [0.0, 0.0, 0.0], radius: 0.5, b: [1.0, 0.0, 0.0], color: [1.0; 4] },
            CapsuleInstance { a: [5.0, 5.0, 5.0], radius: -1.0, b: [5.0, 5.0, 5.0], color: [0.5; 4] },
            CapsuleInstance { a: [1.0, 2.0, 3.0], radius: -0.25, b: [3.0, 2.0, 1.0], color: [0.25; 4] },
        ];
        let mut vertices = vec![CapsuleVertex::zeroed()];
        let mut indices = Vec::new();
        expand(capsules.into_iter().zip([false, false, true]), &mut vertices, &mut indices);
        assert_eq!(vertices.len(), 1 + 4 + 4 + 3);
        assert_eq!(indices, [1, 2, 3, 3, 2, 4, 5, 6, 7, 7, 6, 8, 9, 10, 11]);
        let corners = [0.0, 1.0, 2.0, 3.0, 0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0];
        for (k, v) in vertices[1..].iter().enumerate() {
            let c = &capsules[(k / 4).min(2)];
            assert_eq!((v.a, v.b, v.color, v.corner), (c.a, c.b, c.color, corners[k]));
            assert_eq!(v.radius, c.radius.abs(), "a negative radius is drawn as its size");
        }
    }

    #[test]
    fn a_capsule_is_one_triangle_when_small_on_screen_and_in_the_shadow_map() {
        let camera = Camera::look_at(Vec3::new(0.0, 0.0, 10.0), Vec3::ZERO, 0.8, 1.0);
        let capsule = |radius: f32| Capsule {
            a: Vec3::new(-0.05, 0.0, 0.0),
            b: Vec3::new(0.05, 0.0, 0.0),
            radius,
            color: [255; 4],
        };
        // About 0.2 / (9.95 tan 0.4) * 360 = 17 pixels across on 720 rows; 8 on 360.
        let c = capsule(0.05);
        let one = |c: &Capsule, height: f32, texel| is_one_triangle(span_px(c, &camera, height), c.radius, texel);
        assert!(!one(&c, 720.0, None));
        assert!(one(&c, 360.0, None));
        // In a map of 1 cm texels its radius is 5 texels (one triangle under 7).
        assert!(one(&c, 360.0, Some(0.01)));
        assert!(!one(&c, 360.0, Some(0.005)));
        // Without a bound (reaching the eye), never.
        let at_eye =
            Capsule { a: Vec3::new(0.0, 0.0, 10.0), b: Vec3::new(0.0, 0.0, 10.0), radius: 0.01, color: [255; 4] };
        assert!(!one(&at_eye, 360.0, None));
        // The span from a middle depth the caller has is the same.
        assert_eq!(span_px_at(&c, middle_depth(&c, &camera), &camera, 360.0), span_px(&c, &camera, 360.0));
    }
}
