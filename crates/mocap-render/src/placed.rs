//! Meshes placed on the CPU every frame: vertices and triangles filled by the
//! caller, uploaded to growing buffers and drawn in one plain indexed draw
//! (the capsule impostors, see capsule.rs). Indexed also for the vertices it
//! saves: lavapipe draws tens of thousands of unindexed vertices through
//! buffers it allocates and faults in every draw (about 1,400 page faults a
//! frame at 64 characters, and slower), indexed ones without.

use crate::buffer::GrowingBuffer;

/// One CPU-placed mesh of vertices `V` and its GPU buffers.
pub(crate) struct PlacedMesh<V> {
    vertex_buffer: GrowingBuffer,
    index_buffer: GrowingBuffer,
    /// This frame's vertices (the caller fills them after [`PlacedMesh::clear`]).
    pub vertices: Vec<V>,
    /// This frame's triangles, indices into [`PlacedMesh::vertices`].
    pub indices: Vec<u32>,
}

impl<V: bytemuck::Pod> PlacedMesh<V> {
    /// An empty mesh; `label` names its buffers.
    pub fn new(label: &'static str) -> PlacedMesh<V> {
        PlacedMesh {
            vertex_buffer: GrowingBuffer::new(label),
            index_buffer: GrowingBuffer::indices(label),
            vertices: Vec::new(),
            indices: Vec::new(),
        }
    }

    /// Empties the vertices and triangles for a new frame.
    pub fn clear(&mut self) {
        self.vertices.clear();
        self.indices.clear();
    }

    /// Uploads the vertices and triangles (nothing is drawn when they are empty).
    pub fn upload(&mut self, device: &wgpu::Device, queue: &wgpu::Queue) {
        self.vertex_buffer.upload(device, queue, &self.vertices);
        self.index_buffer.upload(device, queue, &self.indices);
    }

    /// Draws the first `count` uploaded indices (at most all of them) with
    /// `pipeline` (vertex buffer 0); returns the draw calls made (0 when none).
    pub fn draw<'a>(&'a self, pass: &mut wgpu::RenderPass<'a>, pipeline: &'a wgpu::RenderPipeline, count: u32) -> u32 {
        let (Some((vertices, _)), Some((indices, uploaded))) = (self.vertex_buffer.get(), self.index_buffer.get())
        else {
            return 0;
        };
        let count = count.min(uploaded);
        if count == 0 {
            return 0;
        }
        pass.set_pipeline(pipeline);
        pass.set_vertex_buffer(0, vertices.slice(..));
        pass.set_index_buffer(indices.slice(..), wgpu::IndexFormat::Uint32);
        pass.draw_indexed(0..count, 0, 0..1);
        1
    }
}
