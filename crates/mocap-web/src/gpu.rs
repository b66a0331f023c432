//! Surviving a lost graphics device: the page stops drawing, then starts the
//! viewer again on a new device. Every piece of state (clips, edits, frame,
//! camera, panels) lives on the CPU side in the viewer, so nothing is lost; the
//! 3D view's GPU resources are made again on the new device
//! (`mocap_viewer::viewport`). The page (`web/gpu-loss.js`) listens for the losses
//! (`webglcontextlost` on the canvas, the `mocap-gpu-lost` event for WebGPU),
//! shows the notice and calls these.

use crate::MocapViewer;
use crate::start::{run_on, stop};
use wasm_bindgen::prelude::*;

#[wasm_bindgen]
impl MocapViewer {
    /// Stops drawing (the device is lost): no frame runs on it again. What is open
    /// stays, and `state()`, `saveBvh()`, `saveGltf()` and the rest keep working.
    #[wasm_bindgen(js_name = stopGraphics)]
    pub fn stop_graphics(&self) {
        stop(&self.shared);
    }

    /// True while a runner draws (false after `stopGraphics` until `restartGraphics` succeeds).
    #[wasm_bindgen(js_name = graphicsRunning)]
    pub fn graphics_running(&self) -> bool {
        self.shared.runner.try_borrow().map(|r| r.is_some()).unwrap_or(true)
    }

    /// Starts drawing again on `canvas` (a fresh one, or the old one once its
    /// context is restored) with a new device, on the same state. The promise
    /// rejects with a message when no device can be had; try again later.
    #[wasm_bindgen(js_name = restartGraphics)]
    pub fn restart_graphics(&self, canvas: web_sys::HtmlCanvasElement) -> js_sys::Promise {
        let shared = self.shared.clone();
        wasm_bindgen_futures::future_to_promise(async move {
            run_on(canvas, &shared).await?;
            Ok(JsValue::TRUE)
        })
    }
}
