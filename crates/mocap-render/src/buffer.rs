//! A vertex buffer that grows as needed.

/// A GPU buffer of instances, reallocated (doubling) when too small.
pub(crate) struct GrowingBuffer {
    label: &'static str,
    usage: wgpu::BufferUsages,
    buffer: Option<wgpu::Buffer>,
    len: u32,
    /// The records repeated per corner ([`GrowingBuffer::upload_quads`]).
    staging: Vec<u8>,
}

impl GrowingBuffer {
    pub fn new(label: &'static str) -> GrowingBuffer {
        GrowingBuffer { label, usage: wgpu::BufferUsages::VERTEX, buffer: None, len: 0, staging: Vec::new() }
    }

    /// The same for indices.
    pub fn indices(label: &'static str) -> GrowingBuffer {
        GrowingBuffer { label, usage: wgpu::BufferUsages::INDEX, buffer: None, len: 0, staging: Vec::new() }
    }

    /// Uploads `items` (the instances to draw), growing the buffer when needed.
    pub fn upload<T: bytemuck::Pod>(&mut self, device: &wgpu::Device, queue: &wgpu::Queue, items: &[T]) {
        self.write(device, queue, bytemuck::cast_slice(items), items.len());
    }

    /// Writes `data`, `len` records, growing the buffer when needed.
    fn write(&mut self, device: &wgpu::Device, queue: &wgpu::Queue, data: &[u8], len: usize) {
        self.len = u32::try_from(len).unwrap_or(u32::MAX);
        if data.is_empty() {
            return;
        }
        let needed = data.len() as u64;
        if self.buffer.as_ref().is_none_or(|b| b.size() < needed) {
            self.buffer = Some(device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(self.label),
                size: needed.next_power_of_two().max(1024),
                usage: self.usage | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            }));
        }
        if let Some(buffer) = &self.buffer {
            queue.write_buffer(buffer, 0, data);
        }
    }

    /// Uploads `items` as quads: each record six times, once per corner of its
    /// two triangles (see [`crate::pipeline::quad_corners`]); the count is the vertices'.
    pub fn upload_quads<T: bytemuck::Pod>(&mut self, device: &wgpu::Device, queue: &wgpu::Queue, items: &[T]) {
        let mut staging = std::mem::take(&mut self.staging);
        staging.clear();
        for item in items {
            let bytes = bytemuck::bytes_of(item);
            for _ in 0..6 {
                staging.extend_from_slice(bytes);
            }
        }
        self.write(device, queue, &staging, items.len() * 6);
        self.staging = staging;
    }

    /// The buffer and its count of records (instances, or vertices after
    /// [`GrowingBuffer::upload_quads`]), when there is something to draw.
    pub fn get(&self) -> Option<(&wgpu::Buffer, u32)> {
        self.buffer.as_ref().filter(|_| self.len > 0).map(|b| (b, self.len))
    }

    /// Draws the vertices uploaded by [`GrowingBuffer::upload_quads`] (lines'
    /// or spheres' quads) with `pipeline`; returns the draw calls made.
    pub fn draw(&self, pass: &mut wgpu::RenderPass<'_>, pipeline: &wgpu::RenderPipeline) -> u32 {
        let Some((buffer, count)) = self.get() else { return 0 };
        pass.set_pipeline(pipeline);
        pass.set_vertex_buffer(0, buffer.slice(..));
        pass.draw(0..count, 0..1);
        1
    }
}
