//! The renderer's pipelines: one set per sample count, look and shadow setting
//! drawn with ([`PipelineKey`]), made on first use.

use crate::capsule::{self, CapsuleVertex};
use crate::lines::{LINE_ATTRIBUTES, LineInstance};
use crate::pipeline::{self, PipelineSpec, quad_corners};
use crate::shadow;
use crate::spheres::{SPHERE_ATTRIBUTES, SphereInstance};
use crate::uniforms::OutlineRule;

/// What a set of pipelines is made for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct PipelineKey {
    pub(crate) samples: u32,
    /// The shaders' `FAST_LOOK` constant (one shadow lookup per pixel).
    pub(crate) fast_look: bool,
    /// The shaders' `SHADOWS` constant (off: no pixel looks at the shadow map).
    pub(crate) shadows: bool,
}

impl PipelineKey {
    /// Whether capsule, line and sphere outlines are blended by their
    /// coverage (drawn farthest first): full quality on one sample.
    pub(crate) fn blends_outlines(self) -> bool {
        self.samples == 1 && !self.fast_look
    }

    /// How impostor outlines meet the pixels: a pixel-centre test in the fast
    /// look on one sample, else filtered (samples, or blending).
    pub(crate) fn outline(self) -> OutlineRule {
        if self.samples == 1 && self.fast_look { OutlineRule::PixelCentres } else { OutlineRule::Filtered }
    }
}

pub(crate) struct Pipelines {
    /// Capsule impostors into the shadow map.
    pub(crate) shadow: wgpu::RenderPipeline,
    pub(crate) floor: wgpu::RenderPipeline,
    pub(crate) floor_shadow: wgpu::RenderPipeline,
    /// The fast look's floor shadows without a map (only in the fast look's
    /// sets without shadow lookups, which such frames draw with): the capsule
    /// casters' footprints mark the floor's depth, then the quad over the
    /// shadow's rect darkens what they marked.
    pub(crate) footprints: Option<Footprints>,
    pub(crate) capsules: wgpu::RenderPipeline,
    /// Made with the others ahead of use ([`crate::SceneRenderer::prepare_pipelines`]),
    /// else when a frame first has spheres, lines or a copied floor: a page's
    /// first frame of capsules does not wait for their shaders.
    pub(crate) extras: Option<ExtraPipelines>,
    /// Made with the others ahead of use ([`crate::SceneRenderer::prepare_pipelines`]),
    /// else when a frame first has meshes: a page's first frame without any
    /// does not wait for their shaders.
    pub(crate) meshes: Option<MeshPipelines>,
}

/// The fast look's floor shadows without a map (capsule.wgsl's `vs_footprint`).
pub(crate) struct Footprints {
    /// The casters' footprints into the floor's depth, pulled towards the eye.
    pub(crate) mark: wgpu::RenderPipeline,
    /// The shadow's quad, drawn where the depth was marked.
    pub(crate) darken: wgpu::RenderPipeline,
}

/// The pipelines of spheres, lines and the floor's depth.
pub(crate) struct ExtraPipelines {
    /// The floor's depth only (under a floor whose colour was copied).
    pub(crate) floor_depth: wgpu::RenderPipeline,
    pub(crate) spheres: wgpu::RenderPipeline,
    pub(crate) lines: wgpu::RenderPipeline,
    pub(crate) overlay_lines: wgpu::RenderPipeline,
}

/// The pipelines of vertex-animated and skinned meshes.
pub(crate) struct MeshPipelines {
    pub(crate) morph: wgpu::RenderPipeline,
    pub(crate) morph_shadow: wgpu::RenderPipeline,
    pub(crate) skinned: wgpu::RenderPipeline,
    pub(crate) skinned_shadow: wgpu::RenderPipeline,
}

/// How impostors' colour is blended: their alpha is the outline's coverage,
/// blended where `key` blends outlines (one sample at full quality), else
/// written (samples on a multisampled target).
fn outline_coverage(key: PipelineKey) -> wgpu::BlendComponent {
    if key.blends_outlines() { wgpu::BlendState::ALPHA_BLENDING.color } else { wgpu::BlendComponent::REPLACE }
}

/// Multiplies the colour below by the fragment's colour (floor shadows).
pub(crate) const MULTIPLY: wgpu::BlendState = wgpu::BlendState {
    color: wgpu::BlendComponent {
        src_factor: wgpu::BlendFactor::Dst,
        dst_factor: wgpu::BlendFactor::Zero,
        operation: wgpu::BlendOperation::Add,
    },
    alpha: wgpu::BlendComponent {
        src_factor: wgpu::BlendFactor::Zero,
        dst_factor: wgpu::BlendFactor::One,
        operation: wgpu::BlendOperation::Add,
    },
};

/// Keeps the target's value (the capsules' alpha channel).
pub(crate) const KEEP: wgpu::BlendComponent = wgpu::BlendComponent {
    src_factor: wgpu::BlendFactor::Zero,
    dst_factor: wgpu::BlendFactor::One,
    operation: wgpu::BlendOperation::Add,
};

use crate::shader_source::first_frame_module;
use crate::shader_text::{CAPSULES, FLOOR, lit_source};

/// The pipelines made for `key` among `made`, if they are.
pub(crate) fn pipelines_for(made: &[(PipelineKey, Pipelines)], key: PipelineKey) -> Option<&Pipelines> {
    made.iter().find(|(k, _)| *k == key).map(|(_, p)| p)
}

/// The bind group layouts the pipelines use.
pub(crate) struct Layouts<'a> {
    pub(crate) frame: &'a wgpu::BindGroupLayout,
    pub(crate) shadow: &'a wgpu::BindGroupLayout,
    pub(crate) skin: &'a wgpu::BindGroupLayout,
    pub(crate) joints: &'a wgpu::BindGroupLayout,
    /// A skinned mesh's colour texture.
    pub(crate) surface: &'a wgpu::BindGroupLayout,
}

impl Pipelines {
    /// The pipelines for `key`, with the extras when `extras` and the
    /// meshes' when `meshes`.
    pub(crate) fn new(
        device: &wgpu::Device,
        layouts: &Layouts,
        format: wgpu::TextureFormat,
        key: PipelineKey,
        extras: bool,
        meshes: bool,
    ) -> Pipelines {
        let (frame_layout, shadow_layout) = (layouts.frame, layouts.shadow);
        let lit_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("mocap lit"),
            bind_group_layouts: &[Some(frame_layout), Some(shadow_layout)],
            immediate_size: 0,
        });
        let shadow_pass_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("mocap shadow pass"),
            bind_group_layouts: &[Some(frame_layout)],
            immediate_size: 0,
        });
        let capsule_shader = first_frame_module(device, "mocap capsules", CAPSULES);
        let floor_shader = first_frame_module(device, "mocap floor", FLOOR);
        let capsule_buffers = [Some(wgpu::VertexBufferLayout {
            array_stride: std::mem::size_of::<CapsuleVertex>() as u64,
            step_mode: wgpu::VertexStepMode::Vertex,
            attributes: &capsule::ATTRIBUTES,
        })];
        let base = base_spec("mocap capsules", &capsule_shader, &capsule_buffers, format, key);
        let depth_only = depth_only(&base);
        let shadow = pipeline::build(
            device,
            &shadow_pass_layout,
            &PipelineSpec {
                label: "mocap shadow casters",
                fragment_entry: "fs_shadow",
                depth_fragment: true,
                ..depth_only
            },
        );
        let floor = pipeline::build(
            device,
            &lit_layout,
            &PipelineSpec {
                label: "mocap floor",
                shader: &floor_shader,
                buffers: &[],
                color: Some((format, wgpu::BlendState::ALPHA_BLENDING)),
                cull_back: false,
                ..base
            },
        );
        let floor_shadow = pipeline::build(
            device,
            &lit_layout,
            &PipelineSpec {
                label: "mocap floor shadow",
                shader: &floor_shader,
                vertex_entry: "vs_shadow",
                fragment_entry: "fs_shadow",
                buffers: &[],
                color: Some((format, MULTIPLY)),
                depth_write: false,
                depth_compare: wgpu::CompareFunction::Always,
                cull_back: false,
                ..base
            },
        );
        let footprints = (key.fast_look && !key.shadows).then(|| Footprints {
            mark: pipeline::build(
                device,
                &lit_layout,
                &PipelineSpec {
                    label: "mocap shadow footprints",
                    vertex_entry: "vs_footprint",
                    fragment_entry: "fs_footprint",
                    color_writes: wgpu::ColorWrites::empty(),
                    depth_compare: wgpu::CompareFunction::Always,
                    cull_back: false,
                    ..base
                },
            ),
            // Passes only where the depth is farther than its own: marked.
            darken: pipeline::build(
                device,
                &lit_layout,
                &PipelineSpec {
                    label: "mocap marked floor shadow",
                    shader: &floor_shader,
                    vertex_entry: "vs_shadow",
                    fragment_entry: "fs_marked",
                    buffers: &[],
                    color: Some((format, MULTIPLY)),
                    depth_write: false,
                    depth_compare: wgpu::CompareFunction::Less,
                    cull_back: false,
                    ..base
                },
            ),
        });
        // Impostors: triangles of either winding; alpha is the outline's coverage
        // (samples on a multisampled target, blended on one sample at full
        // quality) and the target keeps its alpha.
        let coverage = outline_coverage(key);
        let capsules = pipeline::build(
            device,
            &lit_layout,
            &PipelineSpec {
                color: Some((format, wgpu::BlendState { color: coverage, alpha: KEEP })),
                cull_back: false,
                alpha_to_coverage: true,
                ..base
            },
        );
        Pipelines {
            shadow,
            floor,
            floor_shadow,
            footprints,
            capsules,
            extras: extras.then(|| ExtraPipelines::new(device, layouts, format, key)),
            meshes: meshes.then(|| MeshPipelines::new(device, layouts, format, key)),
        }
    }
}

impl ExtraPipelines {
    /// The extra pipelines for `key`.
    pub(crate) fn new(device: &wgpu::Device, layouts: &Layouts, format: wgpu::TextureFormat, key: PipelineKey) -> ExtraPipelines {
        let lit_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("mocap lit"),
            bind_group_layouts: &[Some(layouts.frame), Some(layouts.shadow)],
            immediate_size: 0,
        });
        let module = |label: &str, body: &str| lit_module(device, label, body);
        let floor_shader = first_frame_module(device, "mocap floor", FLOOR);
        let sphere_shader = module("mocap spheres", include_str!("shaders/spheres.wgsl"));
        let line_shader = module("mocap lines", include_str!("shaders/lines.wgsl"));
        let spheres = [quad_corners(&SPHERE_ATTRIBUTES, std::mem::size_of::<SphereInstance>())];
        let line_buffers = [quad_corners(&LINE_ATTRIBUTES, std::mem::size_of::<LineInstance>())];
        let base = base_spec("mocap lines", &line_shader, &line_buffers, format, key);
        let coverage = outline_coverage(key);
        let floor_depth = pipeline::build(
            device,
            &lit_layout,
            &PipelineSpec {
                label: "mocap floor depth",
                shader: &floor_shader,
                fragment_entry: "fs_depth",
                buffers: &[],
                color_writes: wgpu::ColorWrites::empty(),
                cull_back: false,
                ..base
            },
        );
        let spheres = pipeline::build(
            device,
            &lit_layout,
            &PipelineSpec {
                label: "mocap spheres",
                shader: &sphere_shader,
                buffers: &spheres,
                color: Some((format, wgpu::BlendState { color: coverage, alpha: KEEP })),
                cull_back: false,
                ..base
            },
        );
        let lines = pipeline::build(
            device,
            &lit_layout,
            &PipelineSpec {
                label: "mocap lines",
                shader: &line_shader,
                buffers: &line_buffers,
                color: Some((format, wgpu::BlendState::ALPHA_BLENDING)),
                cull_back: false,
                ..base
            },
        );
        let overlay_lines = pipeline::build(
            device,
            &lit_layout,
            &PipelineSpec {
                label: "mocap overlay lines",
                shader: &line_shader,
                buffers: &line_buffers,
                color: Some((format, wgpu::BlendState::ALPHA_BLENDING)),
                depth_write: false,
                depth_compare: wgpu::CompareFunction::Always,
                cull_back: false,
                ..base
            },
        );
        ExtraPipelines { floor_depth, spheres, lines, overlay_lines }
    }
}

impl MeshPipelines {
    /// The meshes' pipelines for `key`.
    pub(crate) fn new(device: &wgpu::Device, layouts: &Layouts, format: wgpu::TextureFormat, key: PipelineKey) -> MeshPipelines {
        let (frame_layout, shadow_layout) = (layouts.frame, layouts.shadow);
        let skinned_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("mocap skinned"),
            bind_group_layouts: &[Some(frame_layout), Some(shadow_layout), Some(layouts.joints), Some(layouts.surface)],
            immediate_size: 0,
        });
        let skinned_shadow_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("mocap skinned shadow"),
            bind_group_layouts: &[Some(frame_layout), None, Some(layouts.joints)],
            immediate_size: 0,
        });
        let textured_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("mocap textured"),
            bind_group_layouts: &[Some(frame_layout), Some(shadow_layout), Some(layouts.skin)],
            immediate_size: 0,
        });
        let shadow_pass_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("mocap shadow pass"),
            bind_group_layouts: &[Some(frame_layout)],
            immediate_size: 0,
        });
        let morph_shader = lit_module(device, "mocap meshes", include_str!("shaders/morph.wgsl"));
        let morph_buffers = crate::mesh::buffer_layouts();
        let skinned_shader = lit_module(device, "mocap skinned", include_str!("shaders/skinned.wgsl"));
        let skinned_buffers = crate::skinned::buffer_layouts();
        let base = base_spec("mocap meshes", &morph_shader, &morph_buffers, format, key);
        let depth_only = depth_only(&base);
        let morph = pipeline::build(
            device,
            &textured_layout,
            &PipelineSpec {
                label: "mocap meshes",
                shader: &morph_shader,
                buffers: &morph_buffers,
                cull_back: false,
                ..base
            },
        );
        let morph_shadow = pipeline::build(
            device,
            &shadow_pass_layout,
            &PipelineSpec { label: "mocap mesh shadows", shader: &morph_shader, buffers: &morph_buffers, ..depth_only },
        );
        let skinned = pipeline::build(
            device,
            &skinned_layout,
            // Bodies are closed and wound counter-clockwise seen from outside
            // (`SkinnedMeshData`): their back faces lie behind their front
            // faces, so they are not drawn (about a third of a body frame's
            // time on lavapipe). The shadow pass draws both: culling either
            // side there moves shadow edges.
            &PipelineSpec {
                label: "mocap skinned",
                shader: &skinned_shader,
                buffers: &skinned_buffers,
                cull_back: true,
                ..base
            },
        );
        let skinned_shadow = pipeline::build(
            device,
            &skinned_shadow_layout,
            &PipelineSpec {
                label: "mocap skinned shadows",
                shader: &skinned_shader,
                buffers: &skinned_buffers,
                ..depth_only
            },
        );
        MeshPipelines { morph, morph_shadow, skinned, skinned_shadow }
    }
}

/// A shader module of `body` after the shared uniform and lighting code.
fn lit_module(device: &wgpu::Device, label: &str, body: &str) -> crate::shader_source::Shader {
    crate::shader_source::module(device, label, lit_source(body))
}

/// The lit pipelines' common spec for `key`: `shader`'s `vs_main` and
/// `fs_main` over `buffers`, opaque into `format`, depth tested and written,
/// back faces culled.
fn base_spec<'a>(
    label: &'static str,
    shader: &'a crate::shader_source::Shader,
    buffers: &'a [Option<wgpu::VertexBufferLayout<'a>>],
    format: wgpu::TextureFormat,
    key: PipelineKey,
) -> PipelineSpec<'a> {
    PipelineSpec {
        label,
        shader,
        vertex_entry: "vs_main",
        fragment_entry: "fs_main",
        buffers,
        color: Some((format, wgpu::BlendState::REPLACE)),
        depth_format: crate::DEPTH_FORMAT,
        depth_write: true,
        depth_compare: wgpu::CompareFunction::LessEqual,
        depth_bias: Default::default(),
        cull_back: true,
        sample_count: key.samples,
        alpha_to_coverage: false,
        depth_fragment: false,
        color_writes: wgpu::ColorWrites::ALL,
        fast_look: key.fast_look,
        shadows: key.shadows,
        blend_outlines: key.blends_outlines(),
    }
}

/// Depth-only passes into the shadow map: every caster's `vs_shadow`, no colour.
fn depth_only<'a>(base: &PipelineSpec<'a>) -> PipelineSpec<'a> {
    PipelineSpec {
        vertex_entry: "vs_shadow",
        color: None,
        depth_format: shadow::FORMAT,
        depth_bias: wgpu::DepthBiasState { constant: 2, slope_scale: 2.0, clamp: 0.0 },
        cull_back: false,
        sample_count: 1,
        ..*base
    }
}
