//! The per-frame uniform block shared by all pipelines.

use crate::Camera;
use bytemuck::{Pod, Zeroable};

/// Must match `Frame` in the WGSL shaders.
#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
pub(crate) struct FrameUniforms {
    pub view: [[f32; 4]; 4],
    pub projection: [[f32; 4]; 4],
    /// Viewport width, height in pixels; unused; unused.
    pub viewport: [f32; 4],
}

impl FrameUniforms {
    pub fn new(camera: &Camera, size: [u32; 2]) -> FrameUniforms {
        FrameUniforms {
            view: camera.view.to_cols_array_2d(),
            projection: camera.projection.to_cols_array_2d(),
            viewport: [size[0].max(1) as f32, size[1].max(1) as f32, 0.0, 0.0],
        }
    }
}
