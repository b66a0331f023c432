//! Offscreen colour + depth (+ MSAA) textures the renderer draws into.

/// Where a frame is drawn: a sampleable colour texture (resolved when multisampled)
/// and the matching depth buffer.
pub struct RenderTarget {
    /// Final colour texture (single-sampled; usable as a texture and copy source).
    pub color: wgpu::Texture,
    /// View of [`RenderTarget::color`].
    pub color_view: wgpu::TextureView,
    /// The multisampled attachment, when there is one.
    msaa: Option<(wgpu::Texture, wgpu::TextureView)>,
    depth: wgpu::Texture,
    depth_view: wgpu::TextureView,
    size: [u32; 2],
    format: wgpu::TextureFormat,
    sample_count: u32,
}

impl RenderTarget {
    /// Allocates a target of `size` pixels (clamped to at least 1×1).
    pub fn new(device: &wgpu::Device, format: wgpu::TextureFormat, sample_count: u32, size: [u32; 2]) -> RenderTarget {
        let max = device.limits().max_texture_dimension_2d;
        let size = [size[0].clamp(1, max), size[1].clamp(1, max)];
        let extent = wgpu::Extent3d { width: size[0], height: size[1], depth_or_array_layers: 1 };
        let texture = |label, format, samples, usage| {
            device.create_texture(&wgpu::TextureDescriptor {
                label: Some(label),
                size: extent,
                mip_level_count: 1,
                sample_count: samples,
                dimension: wgpu::TextureDimension::D2,
                format,
                usage,
                view_formats: &[],
            })
        };
        // Copy destinations too, where the device can copy them: a frame may
        // start from the floor drawn before (floor_cache.rs).
        let copies_all = crate::floor_cache::Copies::of(device).all();
        let copy_dst = if copies_all { wgpu::TextureUsages::COPY_DST } else { wgpu::TextureUsages::empty() };
        let color = texture(
            "mocap color",
            format,
            1,
            wgpu::TextureUsages::RENDER_ATTACHMENT
                | wgpu::TextureUsages::TEXTURE_BINDING
                | wgpu::TextureUsages::COPY_SRC
                | wgpu::TextureUsages::COPY_DST,
        );
        let msaa = (sample_count > 1).then(|| {
            let msaa = texture("mocap msaa", format, sample_count, wgpu::TextureUsages::RENDER_ATTACHMENT | copy_dst);
            let view = msaa.create_view(&Default::default());
            (msaa, view)
        });
        let depth = texture(
            "mocap depth",
            crate::DEPTH_FORMAT,
            sample_count,
            wgpu::TextureUsages::RENDER_ATTACHMENT | copy_dst,
        );
        RenderTarget {
            color_view: color.create_view(&Default::default()),
            color,
            msaa,
            depth_view: depth.create_view(&Default::default()),
            depth,
            size,
            format,
            sample_count,
        }
    }

    /// Size in pixels.
    pub fn size(&self) -> [u32; 2] {
        self.size
    }

    /// Colour format.
    pub fn format(&self) -> wgpu::TextureFormat {
        self.format
    }

    /// Samples per pixel of the attachments.
    pub fn sample_count(&self) -> u32 {
        self.sample_count
    }

    /// Whether this target can be reused for the given parameters.
    pub fn matches(&self, format: wgpu::TextureFormat, sample_count: u32, size: [u32; 2]) -> bool {
        self.format == format && self.sample_count == sample_count && self.size == [size[0].max(1), size[1].max(1)]
    }

    /// The attachment to render into and the texture to resolve to, if any.
    pub(crate) fn color_attachment(&self) -> (&wgpu::TextureView, Option<&wgpu::TextureView>) {
        match &self.msaa {
            Some((_, msaa)) => (msaa, Some(&self.color_view)),
            None => (&self.color_view, None),
        }
    }

    /// The texture drawn into: the multisampled one, or else the colour texture.
    pub(crate) fn attachment_texture(&self) -> &wgpu::Texture {
        self.msaa.as_ref().map_or(&self.color, |(texture, _)| texture)
    }

    /// The depth texture.
    pub(crate) fn depth_texture(&self) -> &wgpu::Texture {
        &self.depth
    }

    /// The depth attachment.
    pub(crate) fn depth_view(&self) -> &wgpu::TextureView {
        &self.depth_view
    }
}
