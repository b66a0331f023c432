//! Autosave's JavaScript side (`web/autosave.js` stores and reads the session in
//! the browser's storage): the session as the viewer gives it, and restoring one.

use crate::MocapViewer;
use js_sys::{Array, Object, Reflect, Uint8Array};
use mocap_viewer::Command;
use wasm_bindgen::prelude::*;

fn set(obj: &Object, key: &str, value: impl Into<JsValue>) {
    // Setting a property on a fresh plain object cannot fail.
    let _ = Reflect::set(obj, &JsValue::from_str(key), &value.into());
}

#[wasm_bindgen]
impl MocapViewer {
    /// A string that changes whenever the stored session would (the characters,
    /// how they are shown, the edits and what is saved), but not with the view:
    /// the page calls `storeSession` only when it changed.
    #[wasm_bindgen(js_name = sessionStamp)]
    pub fn session_stamp(&self) -> String {
        self.viewer.try_borrow().map(|v| v.session_stamp()).unwrap_or_default()
    }

    /// The session to store: `{manifest, view, unsaved, worth, keys, fresh}`:
    /// the manifest (JSON), the view (URL fragment), whether some edit is unsaved,
    /// whether it is worth keeping (anything but the untouched default clip),
    /// the keys of every asset it names, and `[key, bytes]` for each of those not
    /// in `known` (the keys the page has stored already: not copied again).
    #[wasm_bindgen(js_name = storeSession)]
    pub fn store_session(&self, known: Vec<String>) -> JsValue {
        let Ok(v) = self.viewer.try_borrow() else { return JsValue::NULL };
        let stored = v.store_session();
        let actors = &v.state().stage.actors;
        let (done, undone) = v.state().history.changes();
        let pristine = actors.len() == 1
            && actors.first().is_some_and(|c| c.name == crate::DEFAULT_CLIP_NAME)
            && done.is_empty()
            && undone.is_empty();
        let keys: Array = stored.assets.iter().map(|(k, _)| JsValue::from_str(k)).collect();
        let fresh: Array = stored
            .assets
            .iter()
            .filter(|(k, _)| !known.contains(k))
            .map(|(k, bytes)| Array::of2(&JsValue::from_str(k), &Uint8Array::from(bytes.as_slice())))
            .collect();
        let o = Object::new();
        set(&o, "manifest", stored.manifest.as_str());
        set(&o, "view", v.state().view_fragment());
        set(&o, "unsaved", stored.unsaved);
        set(&o, "worth", !pristine);
        set(&o, "keys", keys);
        set(&o, "fresh", fresh);
        o.into()
    }

    /// Opens a stored session in place of what is open: `manifest` as
    /// `storeSession` gave it, `view` the latest view (or `undefined` for the
    /// manifest's), and the assets it names (`keys[i]` holds `assets[i]`). Checks
    /// everything first: the error message (nothing changed), or `undefined`.
    #[wasm_bindgen(js_name = restoreSession)]
    pub fn restore_session(
        &self,
        manifest: &str,
        view: Option<String>,
        keys: Vec<String>,
        assets: Vec<Uint8Array>,
    ) -> Option<String> {
        let find = |key: &str| keys.iter().position(|k| k == key).and_then(|i| assets.get(i)).map(|a| a.to_vec());
        let mut restored = match mocap_viewer::session::parse(manifest, &find) {
            Ok(r) => r,
            Err(e) => return Some(e),
        };
        if let Some(view) = view {
            restored.view = view;
        }
        self.with_viewer(|v| v.apply(Command::Restore(Box::new(restored)))).and_then(Result::err)
    }

    /// Tells the viewer whether the page holds an earlier session (its "Restore
    /// previous session" button shows while it does).
    #[wasm_bindgen(js_name = setPreviousSession)]
    pub fn set_previous_session(&self, held: bool) {
        self.with_viewer(|v| v.apply(Command::SetPreviousSession(held)));
    }

    /// What "Restore previous session" does: asks the page (a
    /// `mocap-restore-previous` event on `window`) to restore the earlier session.
    #[wasm_bindgen(js_name = restorePreviousSession)]
    pub fn restore_previous_session(&self) {
        self.with_viewer(|v| v.apply(Command::RestorePrevious));
    }

    /// Opens the built-in walk cycle in place of everything open (Discard after a restore).
    #[wasm_bindgen(js_name = openDefault)]
    pub fn open_default(&self) -> Option<String> {
        self.with_viewer(|v| v.load(crate::DEFAULT_CLIP_NAME, crate::DEFAULT_CLIP)).and_then(Result::err)
    }
}
