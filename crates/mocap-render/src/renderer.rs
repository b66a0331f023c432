//! The scene renderer: owns pipelines and buffers, draws a [`Scene`] into a [`RenderTarget`].

use crate::buffer::GrowingBuffer;
use crate::lines::{LINE_ATTRIBUTES, LineInstance};
use crate::pipeline::{PipelineSpec, instanced_pipeline};
use crate::spheres::{SPHERE_ATTRIBUTES, SphereInstance};
use crate::uniforms::FrameUniforms;
use crate::{Camera, RenderTarget, Scene};

/// Draws [`Scene`]s with one device, colour format and sample count.
pub struct SceneRenderer {
    format: wgpu::TextureFormat,
    sample_count: u32,
    uniforms: wgpu::Buffer,
    bind_group: wgpu::BindGroup,
    line_pipeline: wgpu::RenderPipeline,
    sphere_pipeline: wgpu::RenderPipeline,
    lines: GrowingBuffer,
    spheres: GrowingBuffer,
    line_scratch: Vec<LineInstance>,
    sphere_scratch: Vec<SphereInstance>,
    grid_scratch: Vec<crate::Line>,
    /// Physical pixels per logical pixel; scales line widths.
    pub pixels_per_point: f32,
}

impl SceneRenderer {
    /// Creates pipelines for targets of `format` with `sample_count` samples.
    pub fn new(device: &wgpu::Device, format: wgpu::TextureFormat, sample_count: u32) -> SceneRenderer {
        let uniforms = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("mocap frame uniforms"),
            size: std::mem::size_of::<FrameUniforms>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let bind_group_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("mocap frame"),
            entries: &[wgpu::BindGroupLayoutEntry {
                binding: 0,
                visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
                ty: wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Uniform,
                    has_dynamic_offset: false,
                    min_binding_size: None,
                },
                count: None,
            }],
        });
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("mocap frame"),
            layout: &bind_group_layout,
            entries: &[wgpu::BindGroupEntry { binding: 0, resource: uniforms.as_entire_binding() }],
        });
        let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("mocap"),
            bind_group_layouts: &[Some(&bind_group_layout)],
            immediate_size: 0,
        });
        let line_pipeline = instanced_pipeline(
            device,
            &layout,
            format,
            sample_count,
            &PipelineSpec {
                label: "mocap lines",
                shader: concat!(include_str!("shaders/frame.wgsl"), include_str!("shaders/lines.wgsl")),
                attributes: &LINE_ATTRIBUTES,
                stride: std::mem::size_of::<LineInstance>() as u64,
                blend: wgpu::BlendState::ALPHA_BLENDING,
                depth_write: true,
            },
        );
        let sphere_pipeline = instanced_pipeline(
            device,
            &layout,
            format,
            sample_count,
            &PipelineSpec {
                label: "mocap spheres",
                shader: concat!(include_str!("shaders/frame.wgsl"), include_str!("shaders/spheres.wgsl")),
                attributes: &SPHERE_ATTRIBUTES,
                stride: std::mem::size_of::<SphereInstance>() as u64,
                blend: wgpu::BlendState::REPLACE,
                depth_write: true,
            },
        );
        SceneRenderer {
            format,
            sample_count,
            uniforms,
            bind_group,
            line_pipeline,
            sphere_pipeline,
            lines: GrowingBuffer::new("mocap lines"),
            spheres: GrowingBuffer::new("mocap spheres"),
            line_scratch: Vec::new(),
            sphere_scratch: Vec::new(),
            grid_scratch: Vec::new(),
            pixels_per_point: 1.0,
        }
    }

    /// Colour format the pipelines were built for.
    pub fn format(&self) -> wgpu::TextureFormat {
        self.format
    }

    /// Sample count the pipelines were built for.
    pub fn sample_count(&self) -> u32 {
        self.sample_count
    }

    /// Records the draw of `scene` into `encoder`, targeting `target`.
    pub fn encode(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        target: &RenderTarget,
        scene: &Scene,
        camera: &Camera,
    ) {
        self.upload(device, queue, target.size(), scene, camera);
        let (view, resolve_target) = target.color_attachment();
        let [r, g, b, a] = crate::color::for_target(scene.background, self.format);
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("mocap scene"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view,
                depth_slice: None,
                resolve_target,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color { r: r as f64, g: g as f64, b: b as f64, a: a as f64 }),
                    store: wgpu::StoreOp::Store,
                },
            })],
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: target.depth_view(),
                depth_ops: Some(wgpu::Operations { load: wgpu::LoadOp::Clear(1.0), store: wgpu::StoreOp::Discard }),
                stencil_ops: None,
            }),
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_bind_group(0, &self.bind_group, &[]);
        if let Some((buffer, count)) = self.spheres.get() {
            pass.set_pipeline(&self.sphere_pipeline);
            pass.set_vertex_buffer(0, buffer.slice(..));
            pass.draw(0..6, 0..count);
        }
        if let Some((buffer, count)) = self.lines.get() {
            pass.set_pipeline(&self.line_pipeline);
            pass.set_vertex_buffer(0, buffer.slice(..));
            pass.draw(0..6, 0..count);
        }
    }

    /// Draws `scene` into `target` and submits the work to `queue`.
    pub fn render(&mut self, device: &wgpu::Device, queue: &wgpu::Queue, target: &RenderTarget, scene: &Scene, camera: &Camera) {
        let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("mocap scene") });
        self.encode(device, queue, &mut encoder, target, scene, camera);
        queue.submit([encoder.finish()]);
    }

    fn upload(&mut self, device: &wgpu::Device, queue: &wgpu::Queue, size: [u32; 2], scene: &Scene, camera: &Camera) {
        queue.write_buffer(&self.uniforms, 0, bytemuck::bytes_of(&FrameUniforms::new(camera, size)));
        self.grid_scratch.clear();
        if let Some(grid) = &scene.grid {
            grid.lines_into(&mut self.grid_scratch);
        }
        let (format, ppp) = (self.format, self.pixels_per_point);
        self.line_scratch.clear();
        // Grid first so bones blend over it.
        self.line_scratch.extend(self.grid_scratch.iter().chain(&scene.lines).map(|l| LineInstance::new(l, format, ppp)));
        self.sphere_scratch.clear();
        self.sphere_scratch.extend(scene.spheres.iter().map(|s| SphereInstance::new(s, format)));
        self.lines.upload(device, queue, bytemuck::cast_slice(&self.line_scratch), self.line_scratch.len() as u32);
        self.spheres.upload(device, queue, bytemuck::cast_slice(&self.sphere_scratch), self.sphere_scratch.len() as u32);
    }
}
