//! Copying a rendered frame back to memory: one buffer a frame's size, rows
//! padded as wgpu requires; the pixels come out tightly packed. Waiting for the
//! buffer to map is the caller's (a native process blocks on the device; a page
//! awaits the browser).

/// A buffer that frames of one size are copied into and read from.
pub struct Readback {
    buffer: wgpu::Buffer,
    size: [u32; 2],
    padded_row: u32,
}

impl Readback {
    /// A buffer for RGBA8 frames of `size` pixels.
    pub fn new(device: &wgpu::Device, size: [u32; 2]) -> Readback {
        let [w, h] = size;
        let padded_row = (w * 4).div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT) * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
        let buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("mocap readback"),
            size: u64::from(padded_row) * u64::from(h),
            usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
            mapped_at_creation: false,
        });
        Readback { buffer, size, padded_row }
    }

    /// The frame size.
    pub fn size(&self) -> [u32; 2] {
        self.size
    }

    /// The buffer, for `map_async` once the copy is submitted.
    pub fn buffer(&self) -> &wgpu::Buffer {
        &self.buffer
    }

    /// Records the copy of `texture` (RGBA8, [`Readback::size`]) into the buffer.
    pub fn copy(&self, encoder: &mut wgpu::CommandEncoder, texture: &wgpu::Texture) {
        let [w, h] = self.size;
        encoder.copy_texture_to_buffer(
            wgpu::TexelCopyTextureInfo {
                texture,
                mip_level: 0,
                origin: wgpu::Origin3d::ZERO,
                aspect: wgpu::TextureAspect::All,
            },
            wgpu::TexelCopyBufferInfo {
                buffer: &self.buffer,
                layout: wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(self.padded_row),
                    rows_per_image: Some(h),
                },
            },
            wgpu::Extent3d { width: w, height: h, depth_or_array_layers: 1 },
        );
    }

    /// The mapped buffer's pixels, rows top to bottom, tightly packed; unmaps it.
    pub fn read(&self) -> Result<Vec<u8>, String> {
        let [w, h] = self.size;
        let mut pixels = Vec::with_capacity((w * h * 4) as usize);
        {
            let data = self.buffer.slice(..).get_mapped_range().map_err(|e| format!("GPU readback failed: {e:?}"))?;
            for row in data.chunks(self.padded_row as usize).take(h as usize) {
                pixels.extend_from_slice(row.get(..(w * 4) as usize).unwrap_or(row));
            }
        }
        self.buffer.unmap();
        Ok(pixels)
    }
}
