//! A vertex buffer that grows as needed.

/// A GPU buffer of instances, reallocated (doubling) when too small.
pub(crate) struct GrowingBuffer {
    label: &'static str,
    usage: wgpu::BufferUsages,
    buffer: Option<wgpu::Buffer>,
    len: u32,
}

impl GrowingBuffer {
    pub fn new(label: &'static str) -> GrowingBuffer {
        GrowingBuffer { label, usage: wgpu::BufferUsages::VERTEX, buffer: None, len: 0 }
    }

    /// The same for indices.
    pub fn indices(label: &'static str) -> GrowingBuffer {
        GrowingBuffer { label, usage: wgpu::BufferUsages::INDEX, buffer: None, len: 0 }
    }

    /// Uploads `items` (the instances to draw), growing the buffer when needed.
    pub fn upload<T: bytemuck::Pod>(&mut self, device: &wgpu::Device, queue: &wgpu::Queue, items: &[T]) {
        self.len = items.len() as u32;
        let data: &[u8] = bytemuck::cast_slice(items);
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

    /// The buffer and instance count, when there is something to draw.
    pub fn get(&self) -> Option<(&wgpu::Buffer, u32)> {
        self.buffer.as_ref().filter(|_| self.len > 0).map(|b| (b, self.len))
    }
}
