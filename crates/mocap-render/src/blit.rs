//! Showing a finished frame inside another render pass (for example a UI's):
//! the [`RenderTarget`]'s colour texture copied onto the pass's viewport by one
//! triangle, one texel per pixel, without blending.
//!
//! On software rasterisers a UI's own image drawing (texture filtering, colour
//! conversions, blending, dithering) costs several times this copy per pixel,
//! and the 3D view is most of the window.

use crate::target::RenderTarget;

/// The copy pipeline for one output format (single-sampled), made on its first
/// draw: where finished frames are shown by a texture copy instead (the web
/// page on WebGL2) it never is, and a page's first frame compiles one shader
/// program fewer.
pub struct Blit {
    device: wgpu::Device,
    format: wgpu::TextureFormat,
    pipeline: std::sync::OnceLock<wgpu::RenderPipeline>,
    layout: wgpu::BindGroupLayout,
    sampler: wgpu::Sampler,
    /// Bilinear, for frames drawn smaller than where they are shown.
    linear: wgpu::Sampler,
}

/// A [`RenderTarget`]'s colour texture bound for [`Blit::draw`]; make a new one
/// when the target is made again.
pub struct BlitSource {
    bind_group: wgpu::BindGroup,
}

impl Blit {
    /// A copy into passes whose colour attachment has `format` and one sample.
    /// The frames copied hold sRGB-encoded colours in a non-sRGB format (as
    /// [`RenderTarget`]s drawn with such a format do): into an sRGB `format` they
    /// are decoded first, so the pass stores what the frame shows.
    pub fn new(device: &wgpu::Device, format: wgpu::TextureFormat) -> Blit {
        let layout = crate::pipeline::color_texture_layout(device, "mocap blit");
        let sampler =
            device.create_sampler(&wgpu::SamplerDescriptor { label: Some("mocap blit"), ..Default::default() });
        let linear = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("mocap blit (scaled)"),
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            ..Default::default()
        });
        Blit { device: device.clone(), format, pipeline: std::sync::OnceLock::new(), layout, sampler, linear }
    }

    /// The copy pipeline, made when first asked for.
    fn pipeline(&self) -> &wgpu::RenderPipeline {
        self.pipeline.get_or_init(|| make_pipeline(&self.device, &self.layout, self.format))
    }

    /// Binds `target`'s colour texture, read one texel per pixel.
    pub fn source(&self, device: &wgpu::Device, target: &RenderTarget) -> BlitSource {
        self.bind(device, target, &self.sampler)
    }

    /// Binds `target`'s colour texture, filtered bilinearly: for a frame drawn
    /// at a lower resolution than the viewport it is shown on.
    pub fn scaled_source(&self, device: &wgpu::Device, target: &RenderTarget) -> BlitSource {
        self.bind(device, target, &self.linear)
    }

    fn bind(&self, device: &wgpu::Device, target: &RenderTarget, sampler: &wgpu::Sampler) -> BlitSource {
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("mocap blit"),
            layout: &self.layout,
            entries: &[
                wgpu::BindGroupEntry { binding: 0, resource: wgpu::BindingResource::TextureView(&target.color_view) },
                wgpu::BindGroupEntry { binding: 1, resource: wgpu::BindingResource::Sampler(sampler) },
            ],
        });
        BlitSource { bind_group }
    }

    /// Copies `source` onto `pass`'s current viewport (the caller sets it to
    /// where the frame goes: the frame's size for one texel per pixel, or
    /// larger for a [`Blit::scaled_source`]).
    pub fn draw(&self, pass: &mut wgpu::RenderPass<'_>, source: &BlitSource) {
        pass.set_pipeline(self.pipeline());
        pass.set_bind_group(0, &source.bind_group, &[]);
        pass.draw(0..3, 0..1);
    }
}

/// The copy's pipeline into `format` (see [`Blit::new`]), binding its source through `layout`.
fn make_pipeline(
    device: &wgpu::Device,
    layout: &wgpu::BindGroupLayout,
    format: wgpu::TextureFormat,
) -> wgpu::RenderPipeline {
    let shader = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("mocap blit"),
        source: wgpu::ShaderSource::Wgsl(include_str!("shaders/blit.wgsl").into()),
    });
    let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some("mocap blit"),
        bind_group_layouts: &[Some(layout)],
        immediate_size: 0,
    });
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some("mocap blit"),
        layout: Some(&pipeline_layout),
        vertex: wgpu::VertexState {
            module: &shader,
            entry_point: Some("vs_main"),
            compilation_options: Default::default(),
            buffers: &[],
        },
        primitive: wgpu::PrimitiveState::default(),
        depth_stencil: None,
        multisample: wgpu::MultisampleState::default(),
        fragment: Some(wgpu::FragmentState {
            module: &shader,
            entry_point: Some(if format.is_srgb() { "fs_decode" } else { "fs_copy" }),
            compilation_options: Default::default(),
            targets: &[Some(wgpu::ColorTargetState { format, blend: None, write_mask: wgpu::ColorWrites::ALL })],
        }),
        multiview_mask: None,
        cache: None,
    })
}
