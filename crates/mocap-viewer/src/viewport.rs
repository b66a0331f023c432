//! The 3D view: renders the scene offscreen with `mocap-render` and shows it as an egui image.

use crate::drag::{self, Handle, JointDrag, ViewGeometry};
use crate::quality::{Adaptive, Quality};
use mocap_render::{Blit, BlitSource, RenderTarget, Scene, SceneRenderer};
use mocap_scene::OrbitCamera;

/// Colour format of the offscreen image: egui composites in gamma space, so the
/// scene is drawn with sRGB-encoded colours into a plain unorm texture, like egui's own.
const FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;

/// GPU resources of the 3D view, created on first use. The frame reaches the
/// window through [`ShowFrame`], a copy inside egui's own pass.
struct Gpu {
    /// The egui renderer of the device these resources belong to: when the page
    /// starts again on a new device (after the old one was lost), it differs and
    /// everything here is made again on the new one.
    owner: std::sync::Weak<egui::mutex::RwLock<egui_wgpu::Renderer>>,
    renderer: SceneRenderer,
    /// Multisampled when the adapter can: full quality for scenes that need
    /// it (meshes and bodies).
    target: RenderTarget,
    /// One sample, made when first needed beside a multisampled `target`:
    /// full quality for scenes smooth on one sample
    /// (`SceneRenderer::samples_for`).
    single: Option<RenderTarget>,
    /// One sample at [`FAST_SCALE`] of the view's pixels per axis, made when
    /// first needed: the fast look.
    scaled: Option<RenderTarget>,
}

/// The fast look's resolution per axis, as a part of the view's pixels: a
/// frame drawn while the view moves on a slow device (see [`crate::quality`])
/// has a quarter of the pixels to fill, and is shown on the view's rect
/// filtered bilinearly. The panels around the view are not touched by it.
const FAST_SCALE: f32 = 0.5;

/// Which of the view's targets a frame is drawn into and shown from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Which {
    /// `Gpu::target`.
    Full,
    /// `Gpu::single`.
    Single,
    /// `Gpu::scaled`.
    Scaled,
}

/// What [`ShowFrame`] draws with: kept in egui-wgpu's callback resources.
struct FrameCopy {
    blit: Blit,
    /// What changed in the shown frame since the painter last asked
    /// ([`ShowFrame::copy_changed`]).
    changed: egui::mutex::Mutex<egui_wgpu::CopyChange>,
    /// The (multisampled) `target`'s frame.
    full: Shown,
    /// The single-sampled target's frame.
    single: Option<Shown>,
    /// The fast look's smaller target's frame.
    scaled: Option<Shown>,
}

/// A target's finished frame (single-sampled), as drawn and as copied.
struct Shown {
    source: BlitSource,
    texture: wgpu::Texture,
}

/// The paint callback that shows the 3D view's finished frame on its rect of
/// the window (instead of an egui image: egui's image shader and blending cost
/// several times more per pixel on software rasterisers). The web page's
/// painter copies the frame's texture into the window's (`copy_source`),
/// which costs a small part of even a plain draw there; elsewhere, and for the
/// fast look's smaller frame, it is drawn.
struct ShowFrame {
    /// The target whose frame is shown.
    which: Which,
}

impl ShowFrame {
    fn shown<'a>(&self, resources: &'a egui_wgpu::CallbackResources) -> Option<(&'a Blit, &'a Shown)> {
        let copy = resources.get::<FrameCopy>()?;
        let shown = match self.which {
            Which::Full => &copy.full,
            Which::Single => copy.single.as_ref()?,
            Which::Scaled => copy.scaled.as_ref()?,
        };
        Some((&copy.blit, shown))
    }
}

impl egui_wgpu::CallbackTrait for ShowFrame {
    fn paint(
        &self,
        _info: egui::PaintCallbackInfo,
        pass: &mut wgpu::RenderPass<'static>,
        resources: &egui_wgpu::CallbackResources,
    ) {
        if let Some((blit, shown)) = self.shown(resources) {
            blit.draw(pass, &shown.source);
        }
    }

    fn copy_source<'a>(&self, resources: &'a egui_wgpu::CallbackResources) -> Option<&'a wgpu::Texture> {
        // A copy is texel for pixel: the smaller frame is drawn, stretched.
        if self.which == Which::Scaled {
            return None;
        }
        self.shown(resources).map(|(_, shown)| &shown.texture)
    }

    fn covers(&self, resources: &egui_wgpu::CallbackResources) -> bool {
        // `paint` draws the frame over the whole rect, without blending.
        self.shown(resources).is_some()
    }

    fn copy_changed(&self, resources: &egui_wgpu::CallbackResources) -> egui_wgpu::CopyChange {
        resources.get::<FrameCopy>().map_or(egui_wgpu::CopyChange::All, |copy| {
            std::mem::replace(&mut *copy.changed.lock(), egui_wgpu::CopyChange::Nothing)
        })
    }
}

/// The 3D view widget's non-plain state (GPU objects).
#[derive(Default)]
pub struct Viewport {
    gpu: Option<Gpu>,
    /// Frames rendered so far (observable progress for tests and benchmarks).
    pub frames_rendered: u64,
    /// The wgpu backend in use ("BrowserWebGpu", "Gl", "Vulkan", ...), once known.
    pub backend: Option<String>,
    /// Where the view was last drawn and with which camera.
    pub geometry: Option<ViewGeometry>,
    /// The joint held by the pointer (Edit mode), from the press to the release,
    /// and where the press was.
    grabbed: Option<(Handle, egui::Pos2)>,
    /// The automatic quality rule's memory.
    adaptive: Adaptive,
    /// Whether the last frame was drawn in the fast look.
    pub reduced: bool,
    /// Samples per pixel of the last frame (1: the fast look, or a scene
    /// smooth on one sample; see `SceneRenderer::samples_for`); 0 before the
    /// first.
    pub samples: u32,
    /// The last frame's size as drawn, in pixels (see [`FAST_SCALE`]); zero
    /// before the first.
    pub drawn_pixels: [u32; 2],
    /// Whether the last frame started from the floor drawn for an earlier one
    /// (a still camera; see `mocap_render::SceneRenderer::floor_copied`).
    pub floor_copied: bool,
    /// egui's number of the first painted frame that showed the view.
    first_frame: Option<u64>,
    /// Pipeline sets made ahead so far (the fast look's, then the
    /// multisampled one), a painted frame apart after the first.
    prepared: u8,
}

impl Viewport {
    /// Lays out the view in `rect`, handles camera input and draws `scene`. A left
    /// press on one of `handles` (Edit mode) grabs that joint instead of orbiting;
    /// while it is held, the joint's target under the pointer is returned each frame.
    /// `quality` and `playing` (with a drag in the view) choose the look
    /// ([`crate::quality`]).
    #[allow(clippy::too_many_arguments)]
    pub fn show(
        &mut self,
        ui: &mut egui::Ui,
        render_state: Option<&egui_wgpu::RenderState>,
        camera: &mut OrbitCamera,
        scene: &Scene,
        handles: &[Handle],
        quality: Quality,
        playing: bool,
    ) -> (egui::Response, Option<JointDrag>) {
        let rect = ui.available_rect_before_wrap();
        let response = ui.allocate_rect(rect, egui::Sense::click_and_drag());
        let joint_drag = self.grab(&response, handles);
        if self.grabbed.is_none() {
            handle_camera_input(ui, &response, camera);
        }
        let aspect = (rect.width() / rect.height().max(1.0)).max(1e-3);
        // Framing (OrbitCamera::frame) fits the view's narrower field of view.
        camera.aspect = aspect;
        self.geometry = Some(ViewGeometry { rect, camera: camera.to_camera(aspect) });
        let Some(rs) = render_state else {
            ui.painter().text(
                rect.center(),
                egui::Align2::CENTER_CENTER,
                "No GPU renderer",
                egui::FontId::proportional(16.0),
                egui::Color32::GRAY,
            );
            return (response, joint_drag);
        };
        let ppp = ui.ctx().pixels_per_point();
        // The rect's size in pixels as egui's painters round it (each edge
        // rounded), so that the frame is copied texel for pixel.
        let px = |a: f32, b: f32| ((b * ppp).round() - (a * ppp).round()).max(1.0) as u32;
        let size = [px(rect.min.x, rect.max.x), px(rect.min.y, rect.max.y)];
        if self.backend.is_none() {
            self.backend = Some(format!("{:?}", rs.adapter.get_info().backend));
        }
        let moving = playing || response.dragged() || joint_drag.is_some();
        let dt = ui.input(|i| i.unstable_dt);
        if self.gpu.as_ref().is_some_and(|g| !std::ptr::eq(g.owner.as_ptr(), std::sync::Arc::as_ptr(&rs.renderer))) {
            self.gpu = None;
        }
        if self.gpu.is_none() {
            // A new device (the first, or one after a loss): its pipelines
            // are made ahead again, counting from its first frame.
            self.first_frame = None;
            self.prepared = 0;
        }
        let gpu = self.gpu.get_or_insert_with(|| create_gpu(rs, size));
        self.reduced = self.adaptive.decide(quality, moving, dt);
        gpu.renderer.fast_look = self.reduced;
        // One sample has its own target only when `target` is multisampled.
        let single = gpu.renderer.sample_count() > 1 && gpu.renderer.samples_for(scene) == 1;
        if !gpu.target.matches(FORMAT, gpu.renderer.sample_count(), size) {
            gpu.target = RenderTarget::new(&rs.device, FORMAT, gpu.renderer.sample_count(), size);
            bind_frame(rs, &gpu.target, Which::Full);
        }
        let which = if self.reduced {
            Which::Scaled
        } else if single {
            Which::Single
        } else {
            Which::Full
        };
        let drawn_size = match which {
            Which::Scaled => scaled_size(size),
            _ => size,
        };
        let made = match which {
            Which::Full => None,
            Which::Single => Some(&mut gpu.single),
            Which::Scaled => Some(&mut gpu.scaled),
        };
        if let Some(slot) = made {
            if !slot.as_ref().is_some_and(|t| t.matches(FORMAT, 1, drawn_size)) {
                let target = RenderTarget::new(&rs.device, FORMAT, 1, drawn_size);
                bind_frame(rs, &target, which);
                *slot = Some(target);
            }
        }
        let target = match (which, &gpu.single, &gpu.scaled) {
            (Which::Single, Some(t), _) | (Which::Scaled, _, Some(t)) => t,
            _ => &gpu.target,
        };
        self.samples = target.sample_count();
        self.drawn_pixels = target.size();
        // Line widths and edges in the target's pixels.
        gpu.renderer.pixels_per_point = ppp * drawn_size[0] as f32 / size[0] as f32;
        let cam = camera.to_camera(size[0] as f32 / size[1] as f32);
        gpu.renderer.render(&rs.device, &rs.queue, target, scene, &cam);
        // What the copy of the frame into the window has to carry: the
        // renderer's changed rects around the figures and their shadow (all
        // of it for another target than the last frame's), in the view's
        // pixels.
        let change = gpu.renderer.changed_rects().map_or(egui_wgpu::CopyChange::All, |rects| {
            egui_wgpu::CopyChange::Rects(rects.map(|rect| shown_rect(rect, drawn_size, size)))
        });
        mark_changed(rs, change);
        self.floor_copied = gpu.renderer.floor_copied();
        // Painted frames since the first (egui may lay a frame out twice,
        // drawing the view each time, before it paints it).
        let frame = ui.ctx().cumulative_frame_nr();
        let since_first = frame - *self.first_frame.get_or_insert(frame);
        if since_first >= 1 && self.prepared == 0 {
            // The fast look's pipelines, after the first frame is out: compiled
            // then, not in the middle of playback when frames are already slow.
            gpu.renderer.prepare_pipelines(&rs.device, 1, true, scene.shadows);
            self.prepared = 1;
        } else if since_first >= 2 && self.prepared == 1 {
            // And the multisampled ones that bodies and models are drawn with
            // (capsules alone take one sample): a frame later, so that the
            // first file dropped with a mesh does not wait for its shaders
            // (some 100 ms on a software rasteriser).
            let samples = gpu.renderer.sample_count();
            gpu.renderer.prepare_pipelines(&rs.device, samples, false, scene.shadows);
            self.prepared = 2;
        }
        if self.prepared < 2 {
            // The frames that make the next sets, even where nothing else
            // changes (a paused view draws nothing otherwise).
            ui.ctx().request_repaint();
        }
        self.frames_rendered += 1;
        ui.painter().add(egui_wgpu::Callback::new_paint_callback(rect, ShowFrame { which }));
        (response, joint_drag)
    }

    /// Grabs a joint on a left press over it, follows the pointer while held (in the
    /// plane through the joint facing the camera of the last frame) and lets go on
    /// release.
    fn grab(&mut self, response: &egui::Response, handles: &[Handle]) -> Option<JointDrag> {
        let view = self.geometry?;
        let pointer = response.interact_pointer_pos();
        if response.drag_started_by(egui::PointerButton::Primary) {
            // The press position, not where the pointer is after the drag threshold.
            let press = response.ctx.input(|i| i.pointer.press_origin()).or(pointer);
            self.grabbed = press.and_then(|p| Some((drag::pick(handles, &view, p)?, p)));
        }
        let (handle, press) = self.grabbed?;
        if !response.dragged_by(egui::PointerButton::Primary) || response.drag_stopped() {
            self.grabbed = None;
        }
        let pointer = pointer?;
        let target = view.on_plane(pointer, handle.world)?;
        Some(JointDrag { handle, target, pointer, press })
    }
}

fn create_gpu(rs: &egui_wgpu::RenderState, size: [u32; 2]) -> Gpu {
    let samples = if rs.adapter.get_texture_format_features(FORMAT).flags.sample_count_supported(4) { 4 } else { 1 };
    let renderer = SceneRenderer::new(&rs.device, FORMAT, samples);
    let target = RenderTarget::new(&rs.device, FORMAT, samples, size);
    bind_frame(rs, &target, Which::Full);
    Gpu { owner: std::sync::Arc::downgrade(&rs.renderer), renderer, target, single: None, scaled: None }
}

/// The fast look's target size for a view of `size` pixels ([`FAST_SCALE`]
/// per axis, rounded up).
fn scaled_size(size: [u32; 2]) -> [u32; 2] {
    size.map(|v| ((v as f32 * FAST_SCALE).ceil() as u32).max(1))
}

/// Texels a bilinear lookup reaches beyond the texel a pixel falls in.
const FILTER_REACH: u32 = 1;

/// `rect` (`[x, y, width, height]` of a target of `drawn` pixels) as the
/// pixels of a view of `shown` pixels it reaches when the target is stretched
/// over the view, bilinearly filtered: grown by the filter's reach, within the
/// view. The identity where the sizes are the same.
fn shown_rect(rect: [u32; 4], drawn: [u32; 2], shown: [u32; 2]) -> [u32; 4] {
    if drawn == shown || rect[2] == 0 || rect[3] == 0 {
        return rect;
    }
    let axis = |start: u32, len: u32, from: u32, to: u32| {
        let k = to as f64 / from.max(1) as f64;
        let lo = start.saturating_sub(FILTER_REACH);
        let hi = start.saturating_add(len).saturating_add(FILTER_REACH).min(from);
        let a = ((lo as f64 * k).floor() as u32).min(to);
        let b = ((hi as f64 * k).ceil() as u32).min(to);
        (a, b.saturating_sub(a))
    };
    let (x, w) = axis(rect[0], rect[2], drawn[0], shown[0]);
    let (y, h) = axis(rect[1], rect[3], drawn[1], shown[1]);
    [x, y, w, h]
}

/// Points [`ShowFrame`] at `target` as the frame of `which` (the first time,
/// makes the copy pipeline for the window's format).
fn bind_frame(rs: &egui_wgpu::RenderState, target: &RenderTarget, which: Which) {
    let mut renderer = rs.renderer.write();
    let resources = &mut renderer.callback_resources;
    match resources.get_mut::<FrameCopy>() {
        Some(copy) => {
            let source = match which {
                Which::Scaled => copy.blit.scaled_source(&rs.device, target),
                _ => copy.blit.source(&rs.device, target),
            };
            let shown = Shown { source, texture: target.color.clone() };
            match which {
                Which::Full => copy.full = shown,
                Which::Single => copy.single = Some(shown),
                Which::Scaled => copy.scaled = Some(shown),
            }
        }
        // The first target bound is the multisampled one (see `create_gpu`).
        None => {
            let blit = Blit::new(&rs.device, rs.target_format);
            let full = Shown { source: blit.source(&rs.device, target), texture: target.color.clone() };
            let changed = egui::mutex::Mutex::new(egui_wgpu::CopyChange::All);
            resources.insert(FrameCopy { blit, full, single: None, scaled: None, changed });
        }
    }
}

/// Adds `change` to what changed in the shown frame since the painter last
/// asked (see [`ShowFrame::copy_changed`]).
fn mark_changed(rs: &egui_wgpu::RenderState, change: egui_wgpu::CopyChange) {
    if let Some(copy) = rs.renderer.read().callback_resources.get::<FrameCopy>() {
        let mut changed = copy.changed.lock();
        *changed = changed.union(change);
    }
}

/// Orbit (left drag), pan (right/middle drag), zoom (wheel / pinch) when over the view.
fn handle_camera_input(ui: &egui::Ui, response: &egui::Response, camera: &mut OrbitCamera) {
    if response.dragged_by(egui::PointerButton::Primary) {
        let d = response.drag_delta();
        camera.orbit(d.x, d.y);
    } else if response.dragged_by(egui::PointerButton::Secondary) || response.dragged_by(egui::PointerButton::Middle) {
        let d = response.drag_delta();
        camera.pan(d.x, d.y, response.rect.height());
    }
    if response.hovered() {
        let (scroll, zoom) = ui.input(|i| (i.smooth_scroll_delta().y, i.zoom_delta()));
        if scroll != 0.0 {
            camera.zoom((-scroll * 0.002).exp());
        }
        if zoom != 1.0 {
            camera.zoom(1.0 / zoom);
        }
    }
}
