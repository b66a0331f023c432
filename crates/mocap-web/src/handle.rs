//! The object JavaScript holds: `state()`, `load()`, `seek()`, `play()`, `pause()`.

use eframe::egui;
use mocap_viewer::Viewer;
use std::cell::RefCell;
use std::rc::Rc;
use wasm_bindgen::prelude::*;

/// Handle to the running viewer, exported to JavaScript.
#[wasm_bindgen]
pub struct MocapViewer {
    pub(crate) viewer: Rc<RefCell<Viewer>>,
    pub(crate) ctx: Rc<RefCell<Option<egui::Context>>>,
    pub(crate) _runner: eframe::WebRunner,
}

#[wasm_bindgen]
impl MocapViewer {
    /// `{clips:[{name, frames, frameTime, joints, jointNames}], frame, time, playing, speed,
    /// selectedJoint, error, treeLabels, framesRendered, view, embed, backend}`.
    pub fn state(&self) -> JsValue {
        match self.viewer.try_borrow() {
            Ok(v) => crate::js_state::to_js(&v.snapshot()),
            Err(_) => JsValue::NULL,
        }
    }

    /// Parses and opens a file; returns the error text (and shows it) when it cannot,
    /// keeping the clip that was open. Returns `undefined` on success.
    pub fn load(&self, file_name: &str, bytes: &[u8]) -> Option<String> {
        let result = self.with_viewer(|v| v.load(file_name, bytes));
        match result {
            Some(Ok(())) => None,
            Some(Err(e)) => Some(e),
            None => Some("viewer busy".to_owned()),
        }
    }

    /// Opens a clip from `parseMotion` (copying it; `clip` stays usable) under `file_name`.
    #[wasm_bindgen(js_name = loadClip)]
    pub fn load_clip(&self, clip: &crate::MotionClip, file_name: &str) {
        let doc = mocap_viewer::Document::new(file_name, clip.clip().clone());
        self.with_viewer(|v| v.open(doc));
    }

    /// Moves to a frame (clamped).
    pub fn seek(&self, frame: u32) {
        self.with_viewer(|v| v.seek(frame as usize));
    }

    /// Starts playback.
    pub fn play(&self) {
        self.with_viewer(|v| v.set_playing(true));
    }

    /// Pauses playback (on an exact frame).
    pub fn pause(&self) {
        self.with_viewer(|v| v.set_playing(false));
    }

    /// The view state as a URL fragment (no leading `#`): time, play state, speed,
    /// loop range, camera, selection, draw flags and panels.
    #[wasm_bindgen(js_name = viewState)]
    pub fn view_state(&self) -> String {
        self.viewer.try_borrow().map(|v| v.view_fragment()).unwrap_or_default()
    }

    /// Restores a view state written by [`MocapViewer::view_state`] (a `#` is optional).
    #[wasm_bindgen(js_name = applyViewState)]
    pub fn apply_view_state(&self, fragment: &str) {
        self.with_viewer(|v| v.apply_fragment(fragment));
    }

    /// Shows a message in the viewer's error banner (the open clip, if any, stays).
    #[wasm_bindgen(js_name = showError)]
    pub fn show_error(&self, message: &str) {
        self.with_viewer(|v| v.error = Some(message.to_owned()));
    }

    /// Switches the embed layout (3D view and a minimal timeline) on or off.
    #[wasm_bindgen(js_name = setEmbed)]
    pub fn set_embed(&self, embed: bool) {
        self.with_viewer(|v| v.panels.embed = embed);
    }

    /// Closes the open clip (the view shows a drop hint).
    pub fn clear(&self) {
        self.with_viewer(|v| {
            v.document = None;
            v.selected = None;
        });
    }

    /// Selects a joint by name; returns whether it exists.
    #[wasm_bindgen(js_name = selectJoint)]
    pub fn select_joint(&self, name: &str) -> bool {
        self.with_viewer(|v| {
            let index = v.document.as_ref().and_then(|d| d.clip.skeleton.joints.iter().position(|j| j.name == name));
            v.select(index);
            index.is_some()
        })
        .unwrap_or(false)
    }

    /// Runs `f` on the viewer and asks for a repaint.
    fn with_viewer<R>(&self, f: impl FnOnce(&mut Viewer) -> R) -> Option<R> {
        let result = self.viewer.try_borrow_mut().ok().map(|mut v| f(&mut v));
        if let Some(ctx) = self.ctx.borrow().as_ref() {
            ctx.request_repaint();
        }
        result
    }
}
