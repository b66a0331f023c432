//! The scene renderer: owns pipelines and buffers, draws a [`Scene`] into a [`RenderTarget`].
//!
//! A frame is two passes and at most seven draw calls, whatever the number of
//! figures, plus two per vertex-animated mesh: the shadow map (every caster as a
//! capsule impostor, and each mesh; encoded after the floor's copies, see
//! `encode`), then the floor and its shadows, the capsule
//! impostors (one or two triangles each, see capsule.rs), the meshes, the sphere impostors,
//! the lines and the overlay lines (drawn over everything, e.g. bone axes inside
//! capsules). Under a still camera the floor is drawn once, into a third pass,
//! and later frames start from copies of its colour and depth (floor_cache.rs).

use crate::bounds;
use crate::damage;
use crate::buffer::GrowingBuffer;
use crate::capsule::{self, CapsuleInstance, CapsuleVertex};
use crate::floor_cache::{Copies, FloorCache, FloorCopy, FloorKey};
use crate::lines::LineInstance;
use crate::mesh::MeshCache;
use crate::pipeline_set::{ExtraPipelines, Layouts, MeshPipelines, PipelineKey, Pipelines, pipelines_for};
use crate::placed::PlacedMesh;
use crate::shadow::{self, ShadowMap};
use crate::skinned::SkinnedCache;
use crate::spheres::SphereInstance;
use crate::uniforms::FrameUniforms;
use crate::{Camera, RenderTarget, Scene, SkinnedDraw};
use glam::Vec3;
use overlays::sort_farthest_first;

mod overlays;

/// Draws [`Scene`]s with one device and colour format, into targets of any
/// sample count. Pipelines are made per sample count and look when first drawn
/// with (or ahead, [`SceneRenderer::prepare_pipelines`]), so a renderer that
/// only ever draws capsules on one sample never compiles its multisampled set.
///
/// Outlines of capsules are anti-aliased in every look but the fast one: on a
/// multisampled target their coverage (computed from each pixel's ray) is
/// turned into samples; on a single-sampled target it is the alpha the pixel
/// is blended with, and the capsules are drawn farthest first, so that an
/// outline's fringe is blended over what lies behind it. Lines and spheres
/// are filtered the same way on a single-sampled target (a pixel's coverage
/// by the line's strip or the sphere's disc; each drawn farthest first, the
/// lines before the spheres). So a scene whose every primitive is smooth on
/// one sample ([`Scene::smooth_on_one_sample`]: all but meshes and bodies) is
/// drawn at full quality into a single-sampled target, without the cost of
/// multisampling.
pub struct SceneRenderer {
    format: wgpu::TextureFormat,
    sample_count: u32,
    uniforms: wgpu::Buffer,
    frame_layout: wgpu::BindGroupLayout,
    frame_group: wgpu::BindGroup,
    shadow_layout: wgpu::BindGroupLayout,
    /// The shadow map, sized to the casters each frame (shadow.rs).
    shadow: ShadowMap,
    /// The fast look's map (texels twice as large), made when first used.
    fast_shadow: Option<ShadowMap>,
    /// The pipelines made so far, for each sample count, look and shadow
    /// setting drawn with.
    pipelines: Vec<(PipelineKey, Pipelines)>,
    lines: GrowingBuffer,
    overlay_lines: GrowingBuffer,
    spheres: GrowingBuffer,
    /// Capsule impostors: the scene's capsules (drawn lit), then the other
    /// shadow casters (spheres, and capsules that only cast).
    capsules: PlacedMesh<CapsuleVertex>,
    /// Indices of the lit capsules' triangles (the first of `capsules`).
    lit_indices: u32,
    /// Indices of every caster's triangles (none without a shadow this frame).
    caster_indices: u32,
    /// This frame's shadow casters as capsules (ends, radius) and as mesh
    /// boxes, when the scene has shadows: what the map is fitted to, and
    /// where the floor's shadow can change (damage.rs).
    casters: (Vec<(Vec3, Vec3, f32)>, Vec<(Vec3, Vec3)>),
    meshes: MeshCache,
    skinned: SkinnedCache,
    /// Whether this frame's bodies cast their shadows as their bones' capsules
    /// (the fast look, with [`Scene::body_casters`]) rather than as meshes.
    bodies_cast_as_capsules: bool,
    /// Whether this frame's shadow falls on the floor as the casters'
    /// footprints, without a map (the fast look where capsules are all
    /// that cast: [`SceneRenderer::fast_look`]).
    footprints: bool,
    /// The floor of a still camera, drawn once (floor_cache.rs).
    floor_cache: FloorCache,
    /// Whether the last frame's floor was copied from the cache.
    floor_copied: bool,
    /// The target texture the last frame was drawn into, and where its
    /// figures and their shadow were (damage.rs; `None`: not bounded on
    /// screen).
    last_frame: Option<(wgpu::Texture, Option<[damage::PxRect; 2]>)>,
    /// The parts of the target the last frame changed, around the figures
    /// and around their shadow (each min x, min y, max x, max y; empty:
    /// none); `None`: all of it.
    changed: Option<[damage::PxRect; 2]>,
    /// Whether every capsule gets four corners (see [`TestPaths`]).
    four_corners_always: bool,
    line_scratch: Vec<LineInstance>,
    /// The lit capsules' view depths (their middles'), spans in pixels and
    /// indices, in the order they are drawn: farthest first where outlines
    /// are blended.
    capsule_order: Vec<(f32, f32, usize)>,
    sphere_scratch: Vec<SphereInstance>,
    draw_calls: u32,
    /// Physical pixels per logical pixel; scales line widths.
    pub pixels_per_point: f32,
    /// The fast look, for a view that moves on a slow (software) GPU: shadows
    /// from a map of texels twice as large (a quarter of the texels to clear and
    /// fill each frame; unless screen pixels, which no texel is smaller than,
    /// are larger still) with one lookup per pixel instead of four (harder
    /// edges) or, where capsules are all that cast (bodies as below), no map
    /// at all: the floor's shadow drawn as their footprints and none on the
    /// figures themselves; capsules spanning under two pixels left out (with
    /// their shadows), bodies casting their shadows as their bones' capsules
    /// ([`Scene::body_casters`]), and bodies spanning under
    /// [`crate::COARSE_BODY_SPAN_PX`] drawn with their coarse meshes
    /// ([`SkinnedDraw::coarse`]). Off by default.
    pub fast_look: bool,
}

/// Paths a renderer can be made to take whatever the device, so that tests
/// can compare their pixels with the usual ones (feature `test-support`).
#[cfg(feature = "test-support")]
#[derive(Clone, Copy, Debug, Default)]
pub struct TestPaths {
    /// Give every capsule its quad's four corners, leaving the shader to make
    /// it one triangle or a rectangle in each pass (capsules small in every
    /// pass are otherwise given as their triangle alone).
    pub four_corners_always: bool,
    /// Copy only the floor's colour of single-sampled frames and draw its
    /// depth, as on OpenGL.
    pub floor_color_only: bool,
}

impl SceneRenderer {
    /// A renderer for targets of `format`; `sample_count` is what scenes that
    /// need multisampling are drawn with ([`SceneRenderer::samples_for`]).
    /// Pipelines are made when first drawn with.
    pub fn new(device: &wgpu::Device, format: wgpu::TextureFormat, sample_count: u32) -> SceneRenderer {
        SceneRenderer::build(device, format, sample_count, Copies::of(device), false)
    }

    /// A renderer as [`SceneRenderer::new`] makes it, taking the paths `paths`
    /// chooses whatever the device (tests compare them with the usual ones).
    #[cfg(feature = "test-support")]
    pub fn with_test_paths(
        device: &wgpu::Device,
        format: wgpu::TextureFormat,
        sample_count: u32,
        paths: TestPaths,
    ) -> SceneRenderer {
        let copies = if paths.floor_color_only { Copies::SingleSampledColor } else { Copies::of(device) };
        SceneRenderer::build(device, format, sample_count, copies, paths.four_corners_always)
    }

    fn build(
        device: &wgpu::Device,
        format: wgpu::TextureFormat,
        sample_count: u32,
        copies: Copies,
        four_corners_always: bool,
    ) -> SceneRenderer {
        let uniforms = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("mocap frame uniforms"),
            size: std::mem::size_of::<FrameUniforms>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let frame_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
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
        let frame_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("mocap frame"),
            layout: &frame_layout,
            entries: &[wgpu::BindGroupEntry { binding: 0, resource: uniforms.as_entire_binding() }],
        });
        let shadow_layout = shadow::layout(device);
        let shadow = ShadowMap::small(device, &shadow_layout);
        let meshes = MeshCache::new(device);
        let skinned = SkinnedCache::new(device);
        SceneRenderer {
            format,
            sample_count,
            uniforms,
            frame_layout,
            frame_group,
            shadow_layout,
            shadow,
            fast_shadow: None,
            pipelines: Vec::new(),
            lines: GrowingBuffer::new("mocap lines"),
            overlay_lines: GrowingBuffer::new("mocap overlay lines"),
            spheres: GrowingBuffer::new("mocap spheres"),
            capsules: PlacedMesh::new("mocap capsules"),
            lit_indices: 0,
            caster_indices: 0,
            casters: (Vec::new(), Vec::new()),
            meshes,
            skinned,
            bodies_cast_as_capsules: false,
            footprints: false,
            floor_cache: FloorCache::new(copies),
            floor_copied: false,
            last_frame: None,
            changed: None,
            four_corners_always,
            line_scratch: Vec::new(),
            capsule_order: Vec::new(),
            sphere_scratch: Vec::new(),
            draw_calls: 0,
            pixels_per_point: 1.0,
            fast_look: false,
        }
    }

    /// Colour format of the targets drawn into.
    pub fn format(&self) -> wgpu::TextureFormat {
        self.format
    }

    /// The samples per pixel of scenes that need multisampling (see
    /// [`SceneRenderer::samples_for`]).
    pub fn sample_count(&self) -> u32 {
        self.sample_count
    }

    /// The samples per pixel a frame of `scene` is drawn with at this look:
    /// one in the fast look and for a scene smooth on one sample
    /// ([`Scene::smooth_on_one_sample`], whose capsule outlines are then
    /// blended), else the renderer's own count. The viewer and
    /// `mocap render` draw each frame into a target of this count.
    pub fn samples_for(&self, scene: &Scene) -> u32 {
        if self.fast_look || scene.smooth_on_one_sample() { 1 } else { self.sample_count }
    }

    /// Draw calls recorded for the last frame (at most 8 plus 2 per mesh drawn).
    pub fn draw_calls(&self) -> u32 {
        self.draw_calls
    }

    /// How many sets of pipelines (one per sample count, look and shadow
    /// setting drawn with) are made so far. Shader compilation is slow on some
    /// platforms: a page whose first frame needs one set should make one.
    pub fn pipeline_sets(&self) -> usize {
        self.pipelines.len()
    }

    /// The part of its target the last frame changed, as `[x, y, width,
    /// height]` in pixels (a zero size: nothing); `None`: maybe all of it.
    /// A frame under a still camera, drawn into the target of the frame
    /// before, redraws only the rect around both frames' figures (see
    /// damage.rs); a view shown by copying the target (the web page's
    /// painter) needs to copy only this part.
    pub fn changed_rect(&self) -> Option<[u32; 4]> {
        self.changed.map(|[a, b]| size_form(damage::union(a, b)))
    }

    /// [`SceneRenderer::changed_rect`] as two rects, around the figures and
    /// around their shadow on the floor (either may be empty): a long shadow
    /// and a tall figure leave much of the rect around both unchanged.
    pub fn changed_rects(&self) -> Option<[[u32; 4]; 2]> {
        self.changed.map(|rects| rects.map(size_form))
    }

    /// Whether the last frame started from the floor drawn for an earlier one
    /// (see floor_cache.rs) instead of drawing it.
    pub fn floor_copied(&self) -> bool {
        self.floor_copied
    }

    /// Makes the pipelines for targets of `sample_count` samples, in the fast
    /// look or not ([`SceneRenderer::fast_look`]), for frames with shadows or
    /// without ([`Scene::shadows`]), if they are not made yet
    /// ([`SceneRenderer::encode`] does on first use; doing it ahead moves the
    /// shader compilation, slow on some platforms, to a chosen moment).
    pub fn prepare_pipelines(&mut self, device: &wgpu::Device, sample_count: u32, fast_look: bool, shadows: bool) {
        let key = |shadows| PipelineKey { samples: sample_count, fast_look, shadows };
        self.make_pipelines(device, key(shadows && !fast_look), true, true);
        // The fast look's shadows are capsules' footprints (no lookups), or
        // from the map where meshes cast.
        if fast_look && shadows {
            self.make_pipelines(device, key(true), true, true);
        }
    }

    /// Makes the pipelines for `key` if they are not made yet, the extras
    /// too when `extras` and the meshes' when `meshes`.
    fn make_pipelines(&mut self, device: &wgpu::Device, key: PipelineKey, extras: bool, meshes: bool) {
        let layouts = Layouts {
            frame: &self.frame_layout,
            shadow: &self.shadow_layout,
            skin: &self.meshes.skin_layout,
            joints: &self.skinned.layout,
            surface: &self.skinned.texture_layout,
        };
        match self.pipelines.iter_mut().find(|(k, _)| *k == key) {
            Some((_, made)) => {
                if extras && made.extras.is_none() {
                    made.extras = Some(ExtraPipelines::new(device, &layouts, self.format, key));
                }
                if meshes && made.meshes.is_none() {
                    made.meshes = Some(MeshPipelines::new(device, &layouts, self.format, key));
                }
            }
            None => {
                let pipelines = Pipelines::new(device, &layouts, self.format, key, extras, meshes);
                self.pipelines.push((key, pipelines));
            }
        }
    }

    /// The pipelines a frame into a target of `samples` samples draws with,
    /// with shadows or not (not looked up where they are footprints).
    fn key_for(&self, samples: u32, shadows: bool) -> PipelineKey {
        PipelineKey { samples, fast_look: self.fast_look, shadows: shadows && !self.footprints }
    }

    /// Records the draw of `scene` into `encoder`, targeting `target` (of any
    /// sample count).
    pub fn encode(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        target: &RenderTarget,
        scene: &Scene,
        camera: &Camera,
    ) {
        if self.fast_look && self.fast_shadow.is_none() {
            self.fast_shadow = Some(ShadowMap::small(device, &self.shadow_layout));
        }
        let (shadows, uniforms) = self.upload(device, queue, target, scene, camera);
        let key = self.key_for(target.sample_count(), shadows);
        self.draw_calls = 0;
        let [r, g, b, a] = crate::color::for_target(scene.background, self.format);
        let samples = target.sample_count();
        let floor =
            scene.grid.is_some().then(|| FloorKey::new(&uniforms, [r, g, b, a], target.size(), samples, self.format));
        let copy = self.floor_cache.plan(device, floor);
        self.floor_copied = copy.is_some();
        // A first frame of capsules alone does not wait for the pipelines of
        // spheres, lines and a copied floor's depth, nor of meshes.
        let extras = !scene.spheres.is_empty()
            || !scene.lines.is_empty()
            || !scene.overlay_lines.is_empty()
            || copy.as_ref().is_some_and(|c| !c.copy_depth);
        self.make_pipelines(device, key, extras, self.meshes.has_draws() || self.skinned.has_draws());
        // Only around the figures when the last frame's pixels are there to
        // start from (damage.rs): the same target, under the same floor.
        let casters = damage::Casters { capsules: &self.casters.0, boxes: &self.casters.1 };
        let figures =
            damage::figures_rect(scene, &uniforms, shadows.then_some(casters), self.pixels_per_point, target.size());
        let texture = target.attachment_texture().clone();
        let changed = match (&self.last_frame, &copy, figures) {
            (Some((last, Some(before))), Some(c), Some(now)) if !c.fill && *last == texture => {
                Some([damage::union(before[0], now[0]), damage::union(before[1], now[1])])
            }
            _ => None,
        };
        self.last_frame = Some((texture, figures));
        self.changed = changed;
        // The target is redrawn in one rect around both (cheap next to the
        // window's: the two rects matter where the frame is copied on).
        let redraw = changed.map(|[a, b]| damage::union(a, b));
        let background = wgpu::Color { r: r as f64, g: g as f64, b: b as f64, a: a as f64 };
        if let Some(copy) = &copy {
            if copy.fill {
                self.encode_floor_fill(encoder, copy, key, background);
            }
            if !copy.copy_into(encoder, target, redraw) {
                // Nothing moved: the target holds this frame already.
                return;
            }
        }
        // The shadow map after the copies: lavapipe copies textures on its
        // queue thread, and waits there for the work already submitted to
        // its rasteriser first, so a copy behind the shadow pass kept the
        // thread from setting up the scene's triangles while the map was
        // drawn (about 0.5 ms of a 64-character frame).
        if shadows && !self.footprints {
            self.encode_shadow_pass(encoder, key);
        }
        let depth_copied = copy.as_ref().is_some_and(|c| c.copy_depth);
        let (view, resolve_target) = target.color_attachment();
        let color = (view, resolve_target, load_or_clear(copy.is_some(), background));
        let mut pass = self.begin_lit_pass(
            encoder,
            "mocap scene",
            color,
            target.depth_view(),
            load_or_clear(depth_copied, 1.0),
            wgpu::StoreOp::Discard,
        );
        let whole = [0, 0, target.size()[0], target.size()[1]];
        let scissor = redraw.unwrap_or(whole);
        scissor_to(&mut pass, scissor);
        // Made by `prepare_pipelines` above.
        let Some(pipelines) = pipelines_for(&self.pipelines, key) else { return };
        if scene.grid.is_some() {
            let floor = match &copy {
                None => Some(&pipelines.floor),
                Some(_) if !depth_copied => pipelines.extras.as_ref().map(|e| &e.floor_depth),
                Some(_) => None,
            };
            if let Some(floor) = floor {
                pass.set_pipeline(floor);
                pass.draw(0..6, 0..1);
                self.draw_calls += 1;
            }
            // The floor's shadow only where it falls (see damage::shadow_area);
            // footprint frames have shadows (`upload`).
            let footprints = pipelines.footprints.as_ref().filter(|_| self.footprints);
            if let Some(footprints) = footprints {
                self.draw_calls += self.capsules.draw(&mut pass, &footprints.mark, self.caster_indices);
            }
            if let Some(area) = damage::shadow_area(shadows, figures, scissor) {
                scissor_to(&mut pass, area);
                pass.set_pipeline(footprints.map_or(&pipelines.floor_shadow, |f| &f.darken));
                pass.draw(0..6, 0..1);
                self.draw_calls += 1;
                scissor_to(&mut pass, scissor);
            }
        }
        self.draw_calls += self.capsules.draw(&mut pass, &pipelines.capsules, self.lit_indices);
        if let Some(meshes) = &pipelines.meshes {
            if self.meshes.has_draws() {
                pass.set_pipeline(&meshes.morph);
                self.draw_calls += self.meshes.draw(&mut pass, true);
            }
            if self.skinned.has_draws() {
                pass.set_pipeline(&meshes.skinned);
                self.draw_calls += self.skinned.draw(&mut pass, true);
            }
        }
        // Blended outlines: the lines first, so that a joint's fringe is
        // blended over the bones entering it (else a bone's line behind a
        // joint's fringe would be hidden by the fringe's depth).
        if let Some(extras) = &pipelines.extras {
            if key.blends_outlines() {
                self.draw_calls += self.lines.draw(&mut pass, &extras.lines);
                self.draw_calls += self.spheres.draw(&mut pass, &extras.spheres);
            } else {
                self.draw_calls += self.spheres.draw(&mut pass, &extras.spheres);
                self.draw_calls += self.lines.draw(&mut pass, &extras.lines);
            }
            self.draw_calls += self.overlay_lines.draw(&mut pass, &extras.overlay_lines);
        }
    }

    /// Draws `scene` into `target` and submits the work to `queue`.
    pub fn render(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        target: &RenderTarget,
        scene: &Scene,
        camera: &Camera,
    ) {
        let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("mocap scene") });
        self.encode(device, queue, &mut encoder, target, scene, camera);
        queue.submit([encoder.finish()]);
    }

    /// The shadow map this frame draws with (see [`SceneRenderer::fast_look`]).
    fn shadow_map(&self) -> &ShadowMap {
        match &self.fast_shadow {
            Some(map) if self.fast_look => map,
            _ => &self.shadow,
        }
    }

    /// Begins a pass into `color` (view, resolve target, load) and `depth`,
    /// with the frame's uniforms and shadow map bound (the lit pipelines' groups).
    fn begin_lit_pass<'a>(
        &self,
        encoder: &'a mut wgpu::CommandEncoder,
        label: &str,
        color: (&wgpu::TextureView, Option<&wgpu::TextureView>, wgpu::LoadOp<wgpu::Color>),
        depth: &wgpu::TextureView,
        depth_load: wgpu::LoadOp<f32>,
        depth_store: wgpu::StoreOp,
    ) -> wgpu::RenderPass<'a> {
        let (view, resolve_target, load) = color;
        let mut pass = encoder
            .begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some(label),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view,
                    depth_slice: None,
                    resolve_target,
                    ops: wgpu::Operations { load, store: wgpu::StoreOp::Store },
                })],
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: depth,
                    depth_ops: Some(wgpu::Operations { load: depth_load, store: depth_store }),
                    stencil_ops: None,
                }),
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            })
            .forget_lifetime();
        pass.set_bind_group(0, &self.frame_group, &[]);
        pass.set_bind_group(1, &self.shadow_map().bind_group, &[]);
        pass
    }

    /// Draws the floor over `background` into the floor cache's textures (of
    /// the target's size and sample count), with the pipelines for `key`.
    fn encode_floor_fill(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        cache: &FloorCopy,
        key: PipelineKey,
        background: wgpu::Color,
    ) {
        let view = cache.color.create_view(&Default::default());
        let depth = cache.depth.create_view(&Default::default());
        let color = (&view, None, wgpu::LoadOp::Clear(background));
        let mut pass = self.begin_lit_pass(
            encoder,
            "mocap floor cache",
            color,
            &depth,
            wgpu::LoadOp::Clear(1.0),
            wgpu::StoreOp::Store,
        );
        if let Some(pipelines) = pipelines_for(&self.pipelines, key) {
            pass.set_pipeline(&pipelines.floor);
            pass.draw(0..6, 0..1);
            self.draw_calls += 1;
        }
    }

    /// Draws every caster into the shadow map, with the pipelines for `key`.
    fn encode_shadow_pass(&mut self, encoder: &mut wgpu::CommandEncoder, key: PipelineKey) {
        let Some(pipelines) = pipelines_for(&self.pipelines, key) else { return };
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("mocap shadow map"),
            color_attachments: &[],
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: &self.shadow_map().view,
                depth_ops: Some(wgpu::Operations { load: wgpu::LoadOp::Clear(1.0), store: wgpu::StoreOp::Store }),
                stencil_ops: None,
            }),
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_bind_group(0, &self.frame_group, &[]);
        self.draw_calls += self.capsules.draw(&mut pass, &pipelines.shadow, self.caster_indices);
        if let Some(meshes) = &pipelines.meshes {
            if self.meshes.has_draws() {
                pass.set_pipeline(&meshes.morph_shadow);
                self.draw_calls += self.meshes.draw(&mut pass, false);
            }
            if self.skinned.has_draws() && !self.bodies_cast_as_capsules {
                pass.set_pipeline(&meshes.skinned_shadow);
                self.draw_calls += self.skinned.draw(&mut pass, false);
            }
        }
    }

    /// Uploads instances and uniforms; returns whether the shadow pass is
    /// needed, and the uniforms.
    fn upload(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        target: &RenderTarget,
        scene: &Scene,
        camera: &Camera,
    ) -> (bool, FrameUniforms) {
        let size = target.size();
        // The casters that are not drawn lit (the lit capsules cast too):
        // spheres (capsules of zero length) and capsules that only cast.
        let spheres = scene.spheres.iter().map(|s| (s.center, s.center, s.radius));
        // In the fast look the bodies' bones cast the bodies' shadows.
        self.bodies_cast_as_capsules = self.fast_look && !scene.body_casters.is_empty();
        let body_casters = scene.body_casters.iter().filter(|_| self.bodies_cast_as_capsules);
        let only_cast = spheres.chain(scene.shadow_casters.iter().chain(body_casters).map(|c| (c.a, c.b, c.radius)));
        let floor_y = scene.grid.as_ref().map(|g| g.center.y);
        self.meshes.prepare(device, queue, &scene.meshes);
        // The fast look draws bodies small on screen with their coarse meshes.
        let fast_look = self.fast_look;
        self.skinned.prepare(device, queue, &scene.skinned, |d| {
            fast_look && body_span_px(d, camera, size[1] as f32) < crate::skinned::COARSE_BODY_SPAN_PX
        });
        let skinned_bounds = scene.skinned.iter().filter_map(SkinnedDraw::world_bounds);
        let (caster_capsules, caster_boxes) = &mut self.casters;
        caster_capsules.clear();
        caster_boxes.clear();
        if scene.shadows {
            caster_capsules.extend(scene.capsules.iter().map(|c| (c.a, c.b, c.radius)).chain(only_cast.clone()));
            caster_boxes.extend(scene.meshes.iter().filter_map(|m| m.world_bounds()).chain(skinned_bounds));
        }
        let capsule_bounds = bounds::caster_bounds(caster_capsules.iter().copied());
        let bounds = caster_boxes.iter().copied().chain(capsule_bounds).reduce(|(a, b), (c, d)| (a.min(c), b.max(d)));
        // The look's map, fitted to the casters (see shadow.rs).
        let full =
            if self.fast_look { shadow::FAST_SIZE } else { shadow::SIZE }.min(device.limits().max_texture_dimension_2d);
        // Texels no smaller than the screen's pixels.
        let pixel = shadow::ScreenPixel::of(camera, size[1]);
        let view = bounds.and_then(|(min, max)| shadow::fit_light(min, max, floor_y, full, pixel));
        let map = match (&mut self.fast_shadow, self.fast_look) {
            (Some(map), true) => map,
            _ => &mut self.shadow,
        };
        // Capsules all that cast in the fast look: their footprints, no map.
        let mesh_casters = self.meshes.has_draws() || (self.skinned.has_draws() && !self.bodies_cast_as_capsules);
        self.footprints = self.fast_look && view.is_some() && scene.grid.is_some() && !mesh_casters;
        if let Some(view) = view.as_ref().filter(|_| !self.footprints) {
            map.fit(device, view.texels, &self.shadow_layout);
        }
        let light = view.map(|v| v.on_map(map.size));
        // The frame's pipelines, which set how outlines are drawn.
        let look = self.key_for(target.sample_count(), light.is_some());
        let uniforms =
            FrameUniforms::new(camera, size, look.outline(), self.format, scene.grid.as_ref(), light.as_ref());
        queue.write_buffer(&self.uniforms, 0, bytemuck::bytes_of(&uniforms));
        let capsules = &mut self.capsules;
        capsules.clear();
        // Each capsule's middle depth and span, once.
        let height = size[1] as f32;
        let placed = scene.capsules.iter().enumerate().map(|(i, c)| {
            let z = capsule::middle_depth(c, camera);
            (z, capsule::span_px_at(c, z, camera, height), i)
        });
        // The fast look leaves out capsules spanning under a couple of pixels.
        let min_span = if self.fast_look { capsule::FAST_LOOK_MIN_SPAN_PX } else { 0.0 };
        let order = &mut self.capsule_order;
        order.clear();
        order.extend(placed.filter(|&(_, span, _)| min_span <= 0.0 || span >= min_span));
        if look.blends_outlines() {
            sort_farthest_first(order, |&(z, _, _)| z);
        }
        let texel = light.as_ref().map(|l| l.texel);
        let forced = !self.four_corners_always;
        let in_order = order.iter().filter_map(|&(_, span, i)| Some((scene.capsules.get(i)?, span)));
        let with_shape = in_order
            .map(|(c, span)| (CapsuleInstance::new(c), forced && capsule::is_one_triangle(span, c.radius, texel)));
        capsule::expand(with_shape, &mut capsules.vertices, &mut capsules.indices);
        self.lit_indices = capsules.indices.len() as u32;
        if let Some(texel) = texel {
            // Drawn in the shadow pass alone: one triangle there is enough.
            let shadow_only = only_cast.map(|(a, b, radius)| {
                (CapsuleInstance::caster(a, b, radius), forced && capsule::is_one_triangle_in_map(radius, texel))
            });
            capsule::expand(shadow_only, &mut capsules.vertices, &mut capsules.indices);
            self.caster_indices = capsules.indices.len() as u32;
        } else {
            self.caster_indices = 0;
        }
        capsules.upload(device, queue);
        self.upload_lines_and_spheres(device, queue, scene, camera, look);
        (light.is_some(), uniforms)
    }
}

/// A rect as `[x, y, width, height]` from min x, min y, max x, max y.
fn size_form([x0, y0, x1, y1]: damage::PxRect) -> [u32; 4] {
    [x0, y0, x1.saturating_sub(x0), y1.saturating_sub(y0)]
}

/// Draws only within `rect` (min x, min y, max x, max y) from here on.
fn scissor_to(pass: &mut wgpu::RenderPass<'_>, rect: damage::PxRect) {
    let [x, y, w, h] = size_form(rect);
    pass.set_scissor_rect(x, y, w, h);
}

/// Keeps what an attachment holds (`load`), or else clears it to `clear`.
fn load_or_clear<T>(load: bool, clear: T) -> wgpu::LoadOp<T> {
    if load { wgpu::LoadOp::Load } else { wgpu::LoadOp::Clear(clear) }
}

/// How many pixels a body spans on screen at most (its bounding box's sphere,
/// [`capsule::span_px`]); infinite without a bound.
fn body_span_px(draw: &SkinnedDraw, camera: &Camera, height_px: f32) -> f32 {
    draw.world_bounds().map_or(f32::INFINITY, |(lo, hi)| {
        capsule::span_px(&crate::Capsule { a: lo, b: hi, radius: 0.0, color: [0; 4] }, camera, height_px)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn farthest_first_orders_by_view_depth_whatever_the_list_order() {
        let camera = Camera::look_at(Vec3::new(0.0, 0.0, 5.0), Vec3::ZERO, 0.8, 1.0);
        let z = |p: &Vec3| camera.view.transform_point3(*p).z;
        // Depths along the view: z = 2 is nearest the eye at z = 5; a NaN
        // sorts to one end without breaking the order of the rest.
        let mut points = vec![
            Vec3::new(0.0, 0.0, 2.0),
            Vec3::new(1.0, 0.0, -3.0),
            Vec3::new(0.0, 1.0, 0.0),
            Vec3::new(-1.0, 0.0, -1.0),
        ];
        sort_farthest_first(&mut points, z);
        let zs: Vec<f32> = points.iter().map(|p| p.z).collect();
        assert_eq!(zs, [-3.0, -1.0, 0.0, 2.0]);
        let mut with_nan = vec![Vec3::new(0.0, 0.0, 1.0), Vec3::NAN, Vec3::new(0.0, 0.0, -2.0)];
        sort_farthest_first(&mut with_nan, z);
        let finite: Vec<f32> = with_nan.iter().map(|p| p.z).filter(|z| z.is_finite()).collect();
        assert_eq!(finite, [-2.0, 1.0]);
    }
}
