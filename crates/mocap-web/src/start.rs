//! Starts eframe on a canvas with the default clip open.

use crate::MocapViewer;
use eframe::egui;
use mocap_viewer::Viewer;
use mocap_viewer::app::ViewerApp;
use std::cell::RefCell;
use std::rc::Rc;
use wasm_bindgen::JsCast;
use wasm_bindgen::prelude::*;

/// Starts the viewer on the canvas with id `canvas_id`. `file_input_id` names an
/// `<input type=file>` that the "Open…" button clicks. Fails (with a message) when
/// the browser has neither WebGPU nor WebGL2.
#[wasm_bindgen]
pub async fn start(canvas_id: &str, file_input_id: &str) -> Result<MocapViewer, JsValue> {
    let document = web_sys::window().and_then(|w| w.document()).ok_or("no document")?;
    let canvas = document
        .get_element_by_id(canvas_id)
        .ok_or_else(|| format!("no element #{canvas_id}"))?
        .dyn_into::<web_sys::HtmlCanvasElement>()
        .map_err(|_| format!("#{canvas_id} is not a canvas"))?;

    let mut viewer = Viewer::default();
    if let Err(e) = viewer.load(crate::DEFAULT_CLIP_NAME, crate::DEFAULT_CLIP) {
        web_sys::console::error_1(&format!("default clip: {e}").into());
    }
    let viewer = Rc::new(RefCell::new(viewer));
    let ctx: Rc<RefCell<Option<egui::Context>>> = Rc::default();

    let input_id = file_input_id.to_owned();
    let open_picker = move || {
        let input = web_sys::window()
            .and_then(|w| w.document())
            .and_then(|d| d.get_element_by_id(&input_id))
            .and_then(|e| e.dyn_into::<web_sys::HtmlElement>().ok());
        if let Some(input) = input {
            input.click();
        }
    };

    let runner = eframe::WebRunner::new();
    let (app_viewer, app_ctx) = (viewer.clone(), ctx.clone());
    runner
        .start(
            canvas,
            eframe::WebOptions::default(),
            Box::new(move |cc| {
                *app_ctx.borrow_mut() = Some(cc.egui_ctx.clone());
                if cc.wgpu_render_state.is_none() {
                    return Err("no wgpu renderer".into());
                }
                Ok(Box::new(ViewerApp::new(&cc.egui_ctx, app_viewer, Box::new(open_picker))))
            }),
        )
        .await?;
    Ok(MocapViewer { viewer, ctx, _runner: runner })
}
