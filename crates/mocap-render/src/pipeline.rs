//! Shared pipeline construction.

use crate::shader_text::OVERRIDES;

/// What differs between the pipelines.
pub(crate) struct PipelineSpec<'a> {
    pub label: &'static str,
    pub shader: &'a crate::shader_source::Shader,
    pub vertex_entry: &'static str,
    pub fragment_entry: &'static str,
    /// Vertex buffers: per-vertex and/or per-instance layouts.
    pub buffers: &'a [Option<wgpu::VertexBufferLayout<'a>>],
    /// Colour output (format and blend); `None` for a depth-only pass.
    pub color: Option<(wgpu::TextureFormat, wgpu::BlendState)>,
    pub depth_format: wgpu::TextureFormat,
    pub depth_write: bool,
    pub depth_compare: wgpu::CompareFunction,
    pub depth_bias: wgpu::DepthBiasState,
    pub cull_back: bool,
    pub sample_count: u32,
    /// Multisampled targets only: the fragment's alpha is its coverage, turned
    /// into samples (ignored on one sample, where wgpu does not allow it).
    pub alpha_to_coverage: bool,
    /// A depth-only pass whose fragment shader discards fragments (so it has one).
    pub depth_fragment: bool,
    /// The shaders' `FAST_LOOK` constant (lighting.wgsl).
    pub fast_look: bool,
    /// The shaders' `SHADOWS` constant (lighting.wgsl).
    pub shadows: bool,
    /// The shaders' `BLEND_OUTLINES` constant (frame.wgsl).
    pub blend_outlines: bool,
    /// The colour channels written (none: depth only, in a pass with colour).
    pub color_writes: wgpu::ColorWrites,
}

/// Buffer layout with `attributes` and `stride` for quads whose six corners
/// each repeat their item's record ([`crate::buffer::GrowingBuffer::upload_quads`]):
/// the shader takes the corner from `vertex_index % 6`. Not instanced: a
/// software rasteriser (SwiftShader) sets each instance of a draw up as a draw
/// of its own, which made a few hundred lines cost milliseconds.
pub(crate) fn quad_corners<'a>(
    attributes: &'a [wgpu::VertexAttribute],
    stride: usize,
) -> Option<wgpu::VertexBufferLayout<'a>> {
    Some(wgpu::VertexBufferLayout {
        array_stride: stride as u64,
        step_mode: wgpu::VertexStepMode::Vertex,
        attributes,
    })
}

/// Builds a triangle-list pipeline from `spec`.
pub(crate) fn build(device: &wgpu::Device, layout: &wgpu::PipelineLayout, spec: &PipelineSpec) -> wgpu::RenderPipeline {
    // frame.wgsl and lighting.wgsl: the shaders encode sRGB for plain unorm targets.
    let encode_srgb = spec.color.is_some_and(|(format, _)| !format.is_srgb());
    let values = [spec.fast_look, spec.shadows, encode_srgb, spec.blend_outlines];
    let constants: [(&str, f64); 4] = std::array::from_fn(|i| (OVERRIDES[i], if values[i] { 1.0 } else { 0.0 }));
    let options = || wgpu::PipelineCompilationOptions { constants: &constants, ..Default::default() };
    let has_fragment = spec.color.is_some() || spec.depth_fragment;
    // On WebGL2 the GLSL written at build time, where it was.
    let written = crate::shader_source::written_modules(
        device,
        spec.shader,
        spec.vertex_entry,
        has_fragment.then_some(spec.fragment_entry),
        values,
    );
    let vertex_module = written.as_ref().map_or_else(|| spec.shader.module(), |(v, _)| v);
    let fragment_module = match &written {
        Some((_, Some(f))) => f,
        _ => spec.shader.module(),
    };
    let targets = [spec.color.map(|(format, blend)| wgpu::ColorTargetState {
        format,
        blend: Some(blend),
        write_mask: spec.color_writes,
    })];
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some(spec.label),
        layout: Some(layout),
        vertex: wgpu::VertexState {
            module: vertex_module,
            entry_point: Some(spec.vertex_entry),
            compilation_options: options(),
            buffers: spec.buffers,
        },
        primitive: wgpu::PrimitiveState {
            topology: wgpu::PrimitiveTopology::TriangleList,
            cull_mode: spec.cull_back.then_some(wgpu::Face::Back),
            ..Default::default()
        },
        depth_stencil: Some(wgpu::DepthStencilState {
            format: spec.depth_format,
            depth_write_enabled: Some(spec.depth_write),
            depth_compare: Some(spec.depth_compare),
            stencil: Default::default(),
            bias: spec.depth_bias,
        }),
        multisample: wgpu::MultisampleState {
            count: spec.sample_count,
            alpha_to_coverage_enabled: spec.alpha_to_coverage && spec.sample_count > 1,
            ..Default::default()
        },
        fragment: has_fragment.then(|| wgpu::FragmentState {
            module: fragment_module,
            entry_point: Some(spec.fragment_entry),
            compilation_options: options(),
            targets: if spec.color.is_some() { &targets } else { &[] },
        }),
        multiview_mask: None,
        cache: None,
    })
}

/// A bind group layout of one 2D texture of `sample_type` (binding 0) and a
/// sampler of `sampler` type (binding 1), read by fragment shaders.
pub(crate) fn texture_layout(
    device: &wgpu::Device,
    label: &'static str,
    sample_type: wgpu::TextureSampleType,
    sampler: wgpu::SamplerBindingType,
) -> wgpu::BindGroupLayout {
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some(label),
        entries: &[
            wgpu::BindGroupLayoutEntry {
                binding: 0,
                visibility: wgpu::ShaderStages::FRAGMENT,
                ty: wgpu::BindingType::Texture {
                    sample_type,
                    view_dimension: wgpu::TextureViewDimension::D2,
                    multisampled: false,
                },
                count: None,
            },
            wgpu::BindGroupLayoutEntry {
                binding: 1,
                visibility: wgpu::ShaderStages::FRAGMENT,
                ty: wgpu::BindingType::Sampler(sampler),
                count: None,
            },
        ],
    })
}

/// [`texture_layout`] for a filterable colour texture and a filtering sampler.
pub(crate) fn color_texture_layout(device: &wgpu::Device, label: &'static str) -> wgpu::BindGroupLayout {
    texture_layout(
        device,
        label,
        wgpu::TextureSampleType::Float { filterable: true },
        wgpu::SamplerBindingType::Filtering,
    )
}
