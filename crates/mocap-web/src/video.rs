//! Video frames for the page's exporter (`web/video-export.js`): the picture
//! at an exact time, drawn offscreen at the size asked for by the same renderer
//! as the view, read back as RGBA. The page encodes them (WebCodecs or GIF) and
//! never captures the canvas in real time, so a slow GPU gives a smooth video.

use crate::MocapViewer;
use mocap_render::{Readback, RenderTarget, SceneRenderer};
use std::sync::{Arc, Mutex};
use wasm_bindgen::prelude::*;
use wasm_bindgen_futures::JsFuture;

/// The view's colour format (sRGB-encoded colours in a plain unorm texture).
const FORMAT: eframe::wgpu::TextureFormat = eframe::wgpu::TextureFormat::Rgba8Unorm;

/// The exporter's GPU objects, on one device and for one frame size.
pub(crate) struct VideoGpu {
    device: eframe::wgpu::Device,
    renderer: SceneRenderer,
    /// Multisampled where the adapter can (bodies and meshes need it).
    target: RenderTarget,
    /// One sample, for scenes smooth on one (`SceneRenderer::samples_for`).
    single: RenderTarget,
    readback: Readback,
}

impl VideoGpu {
    fn new(rs: &eframe::egui_wgpu::RenderState, size: [u32; 2]) -> VideoGpu {
        let samples = if rs.adapter.get_texture_format_features(FORMAT).flags.sample_count_supported(4) { 4 } else { 1 };
        VideoGpu {
            device: rs.device.clone(),
            renderer: SceneRenderer::new(&rs.device, FORMAT, samples),
            target: RenderTarget::new(&rs.device, FORMAT, samples, size),
            single: RenderTarget::new(&rs.device, FORMAT, 1, size),
            readback: Readback::new(&rs.device, size),
        }
    }
}

/// Where a frame's mapping result arrives (wgpu's callback must be `Send`).
type Mapped = Arc<Mutex<Option<Result<(), eframe::wgpu::BufferAsyncError>>>>;

/// Resolves after `ms` milliseconds (lets the browser run the GPU's callbacks).
async fn sleep(ms: i32) {
    let promise = js_sys::Promise::new(&mut |resolve, _| {
        if let Some(window) = web_sys::window() {
            let _ = window.set_timeout_with_callback_and_timeout_and_arguments_0(&resolve, ms);
        }
    });
    let _ = JsFuture::from(promise).await;
}

#[wasm_bindgen]
impl MocapViewer {
    /// The picture at `time` seconds as `width`x`height` RGBA pixels (rows top
    /// to bottom, a `Uint8Array`): every visible character posed at that time,
    /// the floor and the view's draw settings, without selection overlays, seen
    /// from the view's camera (its target on the current character's root when
    /// `follow`). What the view shows is not changed. Rejects with a message
    /// when there is no graphics device or the size is outside 16 to the
    /// device's largest texture.
    #[wasm_bindgen(js_name = renderVideoFrame)]
    pub fn render_video_frame(&self, time: f64, width: u32, height: u32, follow: bool) -> js_sys::Promise {
        let started = self.submit_video_frame(time, [width, height], follow);
        let shared = self.shared.clone();
        wasm_bindgen_futures::future_to_promise(async move {
            let mapped = started.map_err(|e| JsValue::from_str(&e))?;
            let result = loop {
                if let Some(result) = mapped.lock().ok().and_then(|mut m| m.take()) {
                    break result;
                }
                let device = shared.video.borrow().as_ref().map(|v| v.device.clone());
                let Some(device) = device else { return Err("the graphics device was reset".into()) };
                let _ = device.poll(eframe::wgpu::PollType::Poll);
                sleep(0).await;
            };
            result.map_err(|e| JsValue::from_str(&format!("GPU readback failed: {e}")))?;
            let video = shared.video.borrow();
            let video = video.as_ref().ok_or("the graphics device was reset")?;
            let pixels = video.readback.read().map_err(|e| JsValue::from_str(&e))?;
            Ok(js_sys::Uint8Array::from(pixels.as_slice()).into())
        })
    }

    /// `{fps, duration, loopFrom, loopTo, viewWidth, viewHeight}`: the current
    /// character's frame rate, the stage's length in seconds, the loop range in
    /// seconds (`null` when none is set) and the 3D view's size in CSS pixels
    /// (`null` before it is drawn): what the export dialog starts from.
    #[wasm_bindgen(js_name = videoDefaults)]
    pub fn video_defaults(&self) -> JsValue {
        let Ok(v) = self.viewer.try_borrow() else { return JsValue::NULL };
        let d = v.video_defaults();
        let o = js_sys::Object::new();
        let set = |k: &str, value: JsValue| {
            let _ = js_sys::Reflect::set(&o, &k.into(), &value);
        };
        let num = |x: Option<f64>| x.map_or(JsValue::NULL, JsValue::from_f64);
        set("fps", d.fps.into());
        set("duration", d.duration.into());
        set("loopFrom", num(d.range.map(|r| r.0)));
        set("loopTo", num(d.range.map(|r| r.1)));
        set("viewWidth", num(d.view.map(|s| f64::from(s[0]))));
        set("viewHeight", num(d.view.map(|s| f64::from(s[1]))));
        o.into()
    }
}

impl MocapViewer {
    /// Draws the frame and starts mapping its pixels; the cell gets the
    /// mapping's result.
    fn submit_video_frame(
        &self,
        time: f64,
        size: [u32; 2],
        follow: bool,
    ) -> Result<Mapped, String> {
        let rs = self.shared.render_state.borrow().clone().ok_or("no graphics device")?;
        let largest = rs.device.limits().max_texture_dimension_2d;
        if !(16..=largest).contains(&size[0]) || !(16..=largest).contains(&size[1]) || !time.is_finite() {
            return Err(format!("a video frame is 16 to {largest} pixels a side, at a finite time"));
        }
        let (scene, camera) = {
            let mut v = self.viewer.try_borrow_mut().map_err(|_| "the viewer is busy".to_string())?;
            v.video_frame(time, size[0] as f32 / size[1] as f32, follow)
        };
        let mut slot = self.shared.video.borrow_mut();
        let stale = slot.as_ref().is_none_or(|v| v.device != rs.device || v.readback.size() != size);
        if stale {
            *slot = Some(VideoGpu::new(&rs, size));
        }
        let video = slot.as_mut().ok_or("no graphics device")?;
        let single = video.renderer.sample_count() > 1 && video.renderer.samples_for(&scene) == 1;
        let target = if single { &video.single } else { &video.target };
        let mut encoder = rs.device.create_command_encoder(&eframe::wgpu::CommandEncoderDescriptor {
            label: Some("mocap video frame"),
        });
        video.renderer.encode(&rs.device, &rs.queue, &mut encoder, target, &scene, &camera);
        video.readback.copy(&mut encoder, &target.color);
        rs.queue.submit([encoder.finish()]);
        let mapped: Mapped = Arc::default();
        let done = mapped.clone();
        video.readback.buffer().slice(..).map_async(eframe::wgpu::MapMode::Read, move |result| {
            if let Ok(mut slot) = done.lock() {
                *slot = Some(result);
            }
        });
        Ok(mapped)
    }
}
