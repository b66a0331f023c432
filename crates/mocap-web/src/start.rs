//! Starts eframe on a canvas with the default clip open.

use crate::MocapViewer;
use eframe::egui;
use mocap_viewer::app::ViewerApp;
use mocap_viewer::{OpenMode, Viewer};
use std::cell::RefCell;
use std::rc::Rc;
use std::sync::atomic::{AtomicU32, Ordering};
use wasm_bindgen::JsCast;
use wasm_bindgen::prelude::*;

/// Starts the viewer on the canvas with id `canvas_id`. `file_input_id` names an
/// `<input type=file>` that the "Open…" and "Add…" buttons click, after setting its
/// `data-mode` attribute to `replace` or `add` (the page reads it). With `default_clip` the
/// generated walk cycle is open at once. The "Share" button dispatches a
/// `mocap-share` event on `window`. `webgpu_adapter` (optional) is a
/// `navigator.gpu.requestAdapter()` the page made early, while the module
/// compiled (see [`ViewerOptions`]'s `webgpuAdapter`). Fails (with a message)
/// when the browser has neither WebGPU nor WebGL2.
#[wasm_bindgen]
pub async fn start(
    canvas_id: &str,
    file_input_id: &str,
    default_clip: bool,
    webgpu_adapter: Option<js_sys::Promise>,
) -> Result<MocapViewer, JsValue> {
    let document = web_sys::window().and_then(|w| w.document()).ok_or("no document")?;
    let canvas = document
        .get_element_by_id(canvas_id)
        .ok_or_else(|| format!("no element #{canvas_id}"))?
        .dyn_into::<web_sys::HtmlCanvasElement>()
        .map_err(|_| format!("#{canvas_id} is not a canvas"))?;
    start_on(canvas, Some(file_input_id.to_owned()), default_clip, false, webgpu_adapter).await
}

#[wasm_bindgen(typescript_custom_section)]
const VIEWER_OPTIONS: &str = r#"
/** Options for `startViewer`. */
export interface ViewerOptions {
  /** Open the built-in walk cycle at once (default false). */
  defaultClip?: boolean;
  /** Embed layout: the 3D view and a minimal timeline only (default false). */
  embed?: boolean;
  /** Id of an `<input type=file>` that the "Open…" button clicks. */
  fileInput?: string;
  /**
   * A `navigator.gpu.requestAdapter()` made early (before the module was
   * loaded): where it resolves to `null` the viewer goes straight to WebGL2
   * without asking for a WebGPU adapter again. Browsers without a GPU answer
   * that request late in the page's start; asked early, the wait overlaps the
   * download and compilation.
   */
  webgpuAdapter?: Promise<unknown>;
}
"#;

/// Starts the viewer on `canvas` and returns its handle (`load`, `add`, `loadClip`,
/// `addClip`, `seek`, `play`, `pause`, `state`, ...). Options (optional):
/// `{defaultClip, embed, fileInput, webgpuAdapter}`.
#[wasm_bindgen(js_name = startViewer)]
pub async fn start_viewer(
    canvas: web_sys::HtmlCanvasElement,
    #[wasm_bindgen(unchecked_optional_param_type = "ViewerOptions")] options: JsValue,
) -> Result<MocapViewer, JsValue> {
    let get = |key: &str| {
        if options.is_object() { js_sys::Reflect::get(&options, &JsValue::from_str(key)).ok() } else { None }
    };
    let default_clip = get("defaultClip").is_some_and(|v| v.is_truthy());
    let embed = get("embed").is_some_and(|v| v.is_truthy());
    let file_input = get("fileInput").and_then(|v| v.as_string());
    let webgpu_adapter = get("webgpuAdapter").and_then(|v| v.dyn_into::<js_sys::Promise>().ok());
    start_on(canvas, file_input, default_clip, embed, webgpu_adapter).await
}

async fn start_on(
    canvas: web_sys::HtmlCanvasElement,
    file_input_id: Option<String>,
    default_clip: bool,
    embed: bool,
    webgpu_adapter: Option<js_sys::Promise>,
) -> Result<MocapViewer, JsValue> {
    let mut viewer = Viewer::default();
    let _ = viewer.apply(mocap_viewer::Command::SetPanels(mocap_viewer::Panels { embed, ..Default::default() }));
    if default_clip && let Err(e) = viewer.load(crate::DEFAULT_CLIP_NAME, crate::DEFAULT_CLIP) {
        web_sys::console::error_1(&format!("default clip: {e}").into());
    }
    let shared = Shared {
        viewer: Rc::new(RefCell::new(viewer)),
        saved: Rc::default(),
        ctx: Rc::default(),
        file_input_id,
        runner: Rc::default(),
        render_state: Rc::default(),
        video: Rc::default(),
        webgpu_adapter,
    };
    run_on(canvas, &shared).await?;
    Ok(MocapViewer { viewer: shared.viewer.clone(), saved: shared.saved.clone(), ctx: shared.ctx.clone(), shared })
}

/// What the viewer's runner is started with, kept so that a new runner on a new
/// graphics device (after the old one was lost) starts on the same state.
#[derive(Clone)]
pub(crate) struct Shared {
    pub viewer: Rc<RefCell<Viewer>>,
    pub saved: Rc<RefCell<Option<(String, Vec<u8>)>>>,
    pub ctx: Rc<RefCell<Option<egui::Context>>>,
    pub file_input_id: Option<String>,
    /// The running eframe runner; `None` while the graphics device is lost.
    pub runner: Rc<RefCell<Option<eframe::WebRunner>>>,
    /// The running runner's device and queue (video frames are drawn on them).
    pub render_state: Rc<RefCell<Option<eframe::egui_wgpu::RenderState>>>,
    /// The video exporter's GPU objects (`crate::video`), made on first use.
    pub video: Rc<RefCell<Option<crate::video::VideoGpu>>>,
    /// The page's early WebGPU adapter request, if it made one (see
    /// `eframe::WebOptions::webgpu_probe`, a vendored change).
    pub webgpu_adapter: Option<js_sys::Promise>,
}

/// Which runner is current: a device-lost callback of an earlier one (its device
/// dropped when it was stopped) is not a loss of the current device.
static GENERATION: AtomicU32 = AtomicU32::new(0);

/// Stops the running runner, if any: no more frames on its device.
pub(crate) fn stop(shared: &Shared) {
    GENERATION.fetch_add(1, Ordering::Relaxed);
    if let Ok(mut slot) = shared.render_state.try_borrow_mut() {
        *slot = None;
    }
    if let Ok(mut slot) = shared.video.try_borrow_mut() {
        *slot = None;
    }
    if let Ok(mut slot) = shared.runner.try_borrow_mut()
        && let Some(runner) = slot.take()
    {
        runner.destroy();
    }
}

/// Starts a runner on `canvas` drawing `shared`'s viewer (stopping any running
/// one first). Fails with a message when no graphics device can be had.
pub(crate) async fn run_on(canvas: web_sys::HtmlCanvasElement, shared: &Shared) -> Result<(), JsValue> {
    stop(shared);
    let generation = GENERATION.load(Ordering::Relaxed);
    let saved = shared.saved.clone();
    let save = move |name: String, bytes: Vec<u8>| {
        if let Ok(mut slot) = saved.try_borrow_mut() {
            *slot = Some((name, bytes));
        }
        save_event();
    };
    let file_input_id = shared.file_input_id.clone();
    let open_picker = move |mode: OpenMode| {
        let input = web_sys::window()
            .and_then(|w| w.document())
            .zip(file_input_id.as_deref())
            .and_then(|(d, id)| d.get_element_by_id(id))
            .and_then(|e| e.dyn_into::<web_sys::HtmlElement>().ok());
        if let Some(input) = input {
            let mode = if mode == OpenMode::Add { "add" } else { "replace" };
            // Plain attributes on an element the page owns: cannot fail in practice.
            let _ = input.set_attribute("data-mode", mode);
            let _ = input.set_attribute("multiple", "");
            input.click();
        }
    };
    // egui's memory (panel sizes, open windows, scroll places) carries over to the new context.
    let memory = shared.ctx.borrow().as_ref().map(|c| c.memory(|m| m.clone()));
    let runner = eframe::WebRunner::new();
    let (app_viewer, app_ctx) = (shared.viewer.clone(), shared.ctx.clone());
    runner
        .start(
            canvas,
            eframe::WebOptions {
                webgpu_probe: shared.webgpu_adapter.clone(),
                wgpu_options: wgpu_options(),
                ..Default::default()
            },
            // The app is made before the graphics device is ready (eframe lays
            // its first pass out meanwhile; see vendor/eframe/VENDORED.md): the
            // device is watched once `start` has it.
            Box::new(move |cc| {
                if let Some(memory) = memory {
                    cc.egui_ctx.memory_mut(|m| *m = memory);
                }
                *app_ctx.borrow_mut() = Some(cc.egui_ctx.clone());
                let app = ViewerApp::new(&cc.egui_ctx, app_viewer, Box::new(open_picker))
                    .on_share(Box::new(share_event))
                    .on_export_video(Box::new(export_video_event))
                    .on_restore_previous(Box::new(restore_previous_event))
                    .on_save(Box::new(save))
                    .on_view_change(Box::new(view_event));
                Ok(Box::new(app))
            }),
        )
        .await?;
    let Some(rs) = runner.wgpu_render_state() else {
        runner.destroy();
        return Err("no wgpu renderer".into());
    };
    watch_device(&rs.device, generation);
    *shared.render_state.borrow_mut() = Some(rs);
    *shared.runner.borrow_mut() = Some(runner);
    Ok(())
}

/// Tells the page when `device` is lost (a `mocap-gpu-lost` event on `window`,
/// with the reason as `detail`), unless a newer runner has started since; and
/// keeps wgpu's errors from aborting the page (wgpu's default handler panics:
/// after a loss every call may fail until the page starts again on a new device).
/// eframe's wgpu set-up, with pass-through shaders asked for where the
/// adapter has them (wgpu's GL back end, WebGL2 here): the renderer makes a
/// first frame's pipelines from GLSL written at build time
/// (`mocap_render`'s `shader_source::written_modules`).
fn wgpu_options() -> eframe::egui_wgpu::WgpuConfiguration {
    use eframe::egui_wgpu::{WgpuConfiguration, WgpuSetup, WgpuSetupCreateNew};
    use eframe::wgpu::Features;
    let mut setup = WgpuSetupCreateNew::without_display_handle();
    let device_descriptor = setup.device_descriptor.clone();
    setup.device_descriptor = std::sync::Arc::new(move |adapter| {
        let mut descriptor = device_descriptor(adapter);
        descriptor.required_features |= adapter.features() & Features::PASSTHROUGH_SHADERS;
        descriptor
    });
    WgpuConfiguration { wgpu_setup: WgpuSetup::CreateNew(setup), ..Default::default() }
}

fn watch_device(device: &eframe::wgpu::Device, generation: u32) {
    device.set_device_lost_callback(move |reason, message| {
        if GENERATION.load(Ordering::Relaxed) == generation {
            gpu_lost_event(&format!("{reason:?}: {message}"));
        }
    });
    device.on_uncaptured_error(std::sync::Arc::new(|error| {
        web_sys::console::warn_1(&format!("graphics error: {error}").into());
    }));
}

/// A `mocap-gpu-lost` event on `window` whose `detail` is `reason`.
fn gpu_lost_event(reason: &str) {
    let init = web_sys::CustomEventInit::new();
    init.set_detail(&JsValue::from_str(reason));
    let event = web_sys::CustomEvent::new_with_event_init_dict("mocap-gpu-lost", &init);
    if let (Some(window), Ok(event)) = (web_sys::window(), event) {
        let _ = window.dispatch_event(&event);
    }
}

/// Tells the page that the viewer asked to save a file (a `mocap-save` event on
/// `window`; the page takes it with `takeDownload()` and downloads it).
fn save_event() {
    let event = web_sys::Event::new("mocap-save");
    if let (Some(window), Ok(event)) = (web_sys::window(), event) {
        let _ = window.dispatch_event(&event);
    }
}

/// Tells the page that the view state changed (a `mocap-view` event on
/// `window`, after the frame that changed it; the page updates the URL fragment).
fn view_event() {
    let event = web_sys::Event::new("mocap-view");
    if let (Some(window), Ok(event)) = (web_sys::window(), event) {
        let _ = window.dispatch_event(&event);
    }
}

/// Tells the page that the user asked for the previous session (a
/// `mocap-restore-previous` event on `window`).
fn restore_previous_event() {
    let event = web_sys::Event::new("mocap-restore-previous");
    if let (Some(window), Ok(event)) = (web_sys::window(), event) {
        let _ = window.dispatch_event(&event);
    }
}

/// Tells the page that the user asked to export a video (a `mocap-export-video`
/// event on `window`; the page shows its dialog).
fn export_video_event() {
    let event = web_sys::Event::new("mocap-export-video");
    if let (Some(window), Ok(event)) = (web_sys::window(), event) {
        let _ = window.dispatch_event(&event);
    }
}

/// Tells the page that the user pressed "Share" (a `mocap-share` event on `window`).
fn share_event() {
    let event = web_sys::Event::new("mocap-share");
    if let (Some(window), Ok(event)) = (web_sys::window(), event) {
        let _ = window.dispatch_event(&event);
    }
}
