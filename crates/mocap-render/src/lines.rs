//! GPU layout of line instances.

use crate::Line;
use bytemuck::{Pod, Zeroable};

/// One line segment as the line shader reads it.
#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
pub(crate) struct LineInstance {
    pub a: [f32; 3],
    pub b: [f32; 3],
    pub color: [f32; 4],
    pub width: f32,
}

/// Vertex attributes matching [`LineInstance`].
pub(crate) const LINE_ATTRIBUTES: [wgpu::VertexAttribute; 4] =
    wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3, 2 => Float32x4, 3 => Float32];

impl LineInstance {
    pub fn new(line: &Line, pixels_per_point: f32) -> LineInstance {
        LineInstance {
            a: line.a.to_array(),
            b: line.b.to_array(),
            color: crate::srgb_to_linear(line.color),
            width: line.width_px * pixels_per_point,
        }
    }
}
