//! The per-frame uniform block shared by all pipelines.

use crate::shadow::LightFit;
use crate::{Camera, Grid};
use bytemuck::{Pod, Zeroable};
use glam::Mat4;

/// Must match `Frame` in frame.wgsl.
#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
pub(crate) struct FrameUniforms {
    pub view: [[f32; 4]; 4],
    pub projection: [[f32; 4]; 4],
    /// Width, height in pixels; unused (the shaders' ENCODE_SRGB constant); shadow strength.
    pub viewport: [f32; 4],
    pub light_view_proj: [[f32; 4]; 4],
    /// Towards the key light; shadow texel size in world units.
    pub light_dir: [f32; 4],
    /// Camera position; w unused.
    pub eye: [f32; 4],
    /// Floor centre and fade radius.
    pub floor_center: [f32; 4],
    /// Cell size, cells per major line, half extent, unused.
    pub floor_grid: [f32; 4],
    /// Floor colours (minor lines, major lines, the floor) as the target stores
    /// them: linear for an sRGB target, sRGB-encoded for a plain unorm one.
    pub floor_minor: [f32; 4],
    pub floor_major: [f32; 4],
    pub floor_color: [f32; 4],
    /// The part of the floor its shadow is drawn over: min x, min z, max x,
    /// max z (see `shadow::floor_shadow_rect`).
    pub shadow_rect: [f32; 4],
    /// The least coverage of a pixel an impostor's outline draws (see
    /// [`OutlineRule`]).
    pub samples: [f32; 4],
    /// Rows z and w of projection × view (clip-space depth and w of a world point).
    pub clip_z: [f32; 4],
    pub clip_w: [f32; 4],
    /// The view's six planes in view space (normal towards the inside, unit
    /// length, and offset), see [`view_planes`].
    pub view_planes: [[f32; 4]; 6],
}

/// The planes bounding what `projection` shows (left, right, bottom, top,
/// near, far), in view space: a point `p` is inside where
/// `dot(n.xyz, p) + n.w >= 0` for every plane `n`, and `dot(n.xyz, p) + n.w`
/// is its distance from the plane. The capsule shader's `outside_view` (once a
/// frame here instead of at every corner, where a software rasteriser
/// computed them for every capsule). A degenerate plane leaves nothing outside.
fn view_planes(projection: &Mat4) -> [[f32; 4]; 6] {
    let row = |i| projection.row(i);
    let (x, y, z, w) = (row(0), row(1), row(2), row(3));
    // w ± x, w ± y >= 0 (the sides), z >= 0 (near), w - z >= 0 (far).
    [w + x, w - x, w + y, w - y, z, w - z].map(|n| {
        let length = n.truncate().length();
        if length > 0.0 && length.is_finite() { (n / length).to_array() } else { [0.0, 0.0, 0.0, 1.0] }
    })
}

/// How impostors' outlines meet the pixels.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum OutlineRule {
    /// Anti-aliased: every pixel with some coverage is drawn, its coverage
    /// becoming samples on a multisampled target or its blend alpha on one
    /// sample.
    Filtered,
    /// One sample, the fast look: a pixel is drawn when its centre's ray meets
    /// the impostor (coverage at least a half).
    PixelCentres,
}

impl FrameUniforms {
    /// The block for one frame into a target of `size` pixels and `format`,
    /// with impostor outlines drawn by `outline`.
    pub fn new(
        camera: &Camera,
        size: [u32; 2],
        outline: OutlineRule,
        format: wgpu::TextureFormat,
        grid: Option<&Grid>,
        light: Option<&LightFit>,
    ) -> FrameUniforms {
        let eye = camera.eye().extend(0.0);
        let view_proj = camera.projection * camera.view;
        let (light_view_proj, texel, strength, shadow_rect) = match light {
            Some(fit) => (fit.view_proj, fit.texel, 1.0, fit.floor_shadow),
            None => (Mat4::IDENTITY, 0.0, 0.0, [0.0; 4]),
        };
        let mut u = FrameUniforms {
            view: camera.view.to_cols_array_2d(),
            projection: camera.projection.to_cols_array_2d(),
            viewport: [size[0].max(1) as f32, size[1].max(1) as f32, 0.0, strength],
            light_view_proj: light_view_proj.to_cols_array_2d(),
            light_dir: crate::shadow::key_light_direction().extend(texel).to_array(),
            eye: eye.to_array(),
            shadow_rect,
            samples: [if outline == OutlineRule::Filtered { 0.0 } else { 0.5 }, 0.0, 0.0, 0.0],
            clip_z: view_proj.row(2).to_array(),
            clip_w: view_proj.row(3).to_array(),
            view_planes: view_planes(&camera.projection),
            ..Zeroable::zeroed()
        };
        if let Some(g) = grid {
            let half = g.half_cells.clamp(1, 1000) as f32 * g.cell;
            u.floor_center = g.center.extend(half).to_array();
            u.floor_grid = [g.cell, g.major_every.max(1) as f32, half, 0.0];
            // As the target stores colours: the floor shader does no encoding.
            u.floor_minor = crate::color::for_target(g.color, format);
            u.floor_major = crate::color::for_target(g.major_color, format);
            u.floor_color = crate::color::for_target(g.floor_color, format);
        }
        u
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::{Vec3, Vec4};

    /// The signed distance of view-space `p` from each plane.
    fn distances(planes: &[[f32; 4]; 6], p: Vec3) -> [f32; 6] {
        planes.map(|n| Vec4::from_array(n).truncate().dot(p) + n[3])
    }

    #[test]
    fn view_planes_bound_what_the_projection_shows_at_true_distances() {
        // Perspective: 90 degrees tall, square, near 0.1, far 100.
        let perspective = glam::camera::rh::proj::directx::perspective(std::f32::consts::FRAC_PI_2, 1.0, 0.1, 100.0);
        let planes = view_planes(&perspective);
        assert!(distances(&planes, Vec3::new(0.0, 0.0, -5.0)).iter().all(|&d| d > 0.0), "the axis is inside");
        // 2 units left of the 45-degree left plane at depth 5, and beyond the far plane.
        let [left, right, ..] = distances(&planes, Vec3::new(-5.0 - 2.0 * 2f32.sqrt(), 0.0, -5.0));
        assert!((left + 2.0).abs() < 1e-4 && right > 0.0, "{left} {right}");
        let [.., near, far] = distances(&planes, Vec3::new(0.0, 0.0, -103.0));
        assert!((far + 3.0).abs() < 1e-3 && near > 0.0, "{near} {far}");
        assert!(distances(&planes, Vec3::new(0.0, 0.0, 1.0))[4] < 0.0, "behind the eye is outside the near plane");
        // Orthographic: a box 2 x 2 wide.
        let ortho = glam::camera::rh::proj::directx::orthographic(-1.0, 1.0, -1.0, 1.0, 0.1, 10.0);
        let [_, _, bottom, top, ..] = distances(&view_planes(&ortho), Vec3::new(0.0, 1.5, -1.0));
        assert!((top + 0.5).abs() < 1e-5 && (bottom - 2.5).abs() < 1e-5, "{bottom} {top}");
        // A degenerate projection leaves nothing outside.
        assert!(distances(&view_planes(&Mat4::ZERO), Vec3::splat(1e6)).iter().all(|&d| d > 0.0));
    }
}
