//! GPU layout of sphere instances.

use crate::Sphere;
use bytemuck::{Pod, Zeroable};

/// One sphere as the sphere shader reads it.
#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
pub(crate) struct SphereInstance {
    pub center: [f32; 3],
    pub radius: f32,
    pub color: [f32; 4],
}

/// Vertex attributes matching [`SphereInstance`].
pub(crate) const SPHERE_ATTRIBUTES: [wgpu::VertexAttribute; 3] =
    wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32, 2 => Float32x4];

impl SphereInstance {
    pub fn new(sphere: &Sphere) -> SphereInstance {
        SphereInstance {
            center: sphere.center.to_array(),
            radius: sphere.radius,
            color: crate::srgb_to_linear(sphere.color),
        }
    }
}
