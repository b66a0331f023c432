//! The 3D view: renders the scene offscreen with `mocap-render` and shows it as an egui image.

use crate::camera::OrbitCamera;
use crate::drag::{self, Handle, JointDrag, ViewGeometry};
use mocap_render::{RenderTarget, Scene, SceneRenderer};

/// Colour format of the offscreen image: egui composites in gamma space, so the
/// scene is drawn with sRGB-encoded colours into a plain unorm texture, like egui's own.
const FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;

/// GPU resources of the 3D view, created on first use.
struct Gpu {
    renderer: SceneRenderer,
    target: RenderTarget,
    texture: egui::TextureId,
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
}

impl Viewport {
    /// Lays out the view in `rect`, handles camera input and draws `scene`. A left
    /// press on one of `handles` (Edit mode) grabs that joint instead of orbiting;
    /// while it is held, the joint's target under the pointer is returned each frame.
    pub fn show(
        &mut self,
        ui: &mut egui::Ui,
        render_state: Option<&egui_wgpu::RenderState>,
        camera: &mut OrbitCamera,
        scene: &Scene,
        handles: &[Handle],
    ) -> (egui::Response, Option<JointDrag>) {
        let rect = ui.available_rect_before_wrap();
        let response = ui.allocate_rect(rect, egui::Sense::click_and_drag());
        let joint_drag = self.grab(&response, handles);
        if self.grabbed.is_none() {
            handle_camera_input(ui, &response, camera);
        }
        let aspect = (rect.width() / rect.height().max(1.0)).max(1e-3);
        self.geometry = Some(ViewGeometry { rect, camera: camera.to_camera(aspect) });
        let Some(rs) = render_state else {
            ui.painter().text(rect.center(), egui::Align2::CENTER_CENTER, "No GPU renderer", egui::FontId::proportional(16.0), egui::Color32::GRAY);
            return (response, joint_drag);
        };
        let ppp = ui.ctx().pixels_per_point();
        let size = [(rect.width() * ppp).round().max(1.0) as u32, (rect.height() * ppp).round().max(1.0) as u32];
        if self.backend.is_none() {
            self.backend = Some(format!("{:?}", rs.adapter.get_info().backend));
        }
        let gpu = self.gpu.get_or_insert_with(|| create_gpu(rs, size));
        if !gpu.target.matches(FORMAT, gpu.renderer.sample_count(), size) {
            gpu.target = RenderTarget::new(&rs.device, FORMAT, gpu.renderer.sample_count(), size);
            rs.renderer.write().update_egui_texture_from_wgpu_texture(&rs.device, &gpu.target.color_view, wgpu::FilterMode::Linear, gpu.texture);
        }
        gpu.renderer.pixels_per_point = ppp;
        let cam = camera.to_camera(size[0] as f32 / size[1] as f32);
        gpu.renderer.render(&rs.device, &rs.queue, &gpu.target, scene, &cam);
        self.frames_rendered += 1;
        let uv = egui::Rect::from_min_max(egui::pos2(0.0, 0.0), egui::pos2(1.0, 1.0));
        ui.painter().image(gpu.texture, rect, uv, egui::Color32::WHITE);
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
    let texture = rs.renderer.write().register_native_texture(&rs.device, &target.color_view, wgpu::FilterMode::Linear);
    Gpu { renderer, target, texture }
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
