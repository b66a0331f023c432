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
    /// Floor area under the shadow casters: min x, min z, max x, max z.
    pub shadow_rect: [f32; 4],
    /// The least coverage of a pixel an impostor's outline draws (see
    /// [`OutlineRule`]).
    pub samples: [f32; 4],
    /// Rows z and w of projection × view (clip-space depth and w of a world point).
    pub clip_z: [f32; 4],
    pub clip_w: [f32; 4],
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
    pub fn new(camera: &Camera, size: [u32; 2], outline: OutlineRule, format: wgpu::TextureFormat, grid: Option<&Grid>, light: Option<&LightFit>) -> FrameUniforms {
        let eye = camera.eye().extend(0.0);
        let view_proj = camera.projection * camera.view;
        let (light_view_proj, texel, strength, shadow_rect) = match light {
            Some(fit) => (fit.view_proj, fit.texel, 1.0, fit.floor_rect),
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
