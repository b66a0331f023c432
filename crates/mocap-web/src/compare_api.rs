//! `compare(i, j, align)`: two open characters measured against each other
//! ([`mocap::ops::compare`]), for scripts.

use crate::MocapViewer;
use js_sys::{Array, Object, Reflect};
use wasm_bindgen::prelude::*;

fn set(obj: &Object, key: &str, value: impl Into<JsValue>) {
    let _ = Reflect::set(obj, &JsValue::from_str(key), &value.into());
}

#[wasm_bindgen]
impl MocapViewer {
    /// Shows character `j` compared against character `i` in the view (Edit ▸
    /// Compare with): `j` as a ghost in `i`'s place, its bones coloured by
    /// error, the error curve under the timeline; with no arguments, stops.
    /// Returns the error message, or `undefined`.
    #[wasm_bindgen(js_name = showComparison)]
    pub fn show_comparison(&self, i: Option<u32>, j: Option<u32>) -> Option<String> {
        let pair = i.zip(j).map(|(i, j)| (i as usize, j as usize));
        let mut v = self.viewer.try_borrow_mut().ok()?;
        v.try_apply(mocap_viewer::Command::Compare(pair)).err()
    }

    /// Character `j` against character `i` (each as edited): `j` sampled at
    /// `i`'s frame times, both in metres with Y up. `align` is `"none"`
    /// (default), `"root"` or `"procrustes"`. Returns `{mpjpe, mpjpeM,
    /// worstFrame, joints: [{name, mean, max, angle}], frames}` (`mpjpe`, joint
    /// errors and `frames`, a Float32Array, in `i`'s file units; `angle` in
    /// degrees, `null` across different skeletons); throws the reason when
    /// they cannot be compared.
    pub fn compare(&self, i: u32, j: u32, align: Option<String>) -> Result<JsValue, JsError> {
        let align = align.as_deref().unwrap_or("none");
        let align = mocap::ops::compare::Align::from_name(align)
            .ok_or_else(|| JsError::new(&format!("align {align}: expected none, root, procrustes, root-once or procrustes-once")))?;
        let v = self.viewer.try_borrow().map_err(|_| JsError::new("viewer busy"))?;
        let clip = |k: u32| {
            v.state()
                .stage
                .actors
                .get(k as usize)
                .and_then(|c| c.clip())
                .ok_or_else(|| JsError::new(&format!("character {k}: no such clip (models have no skeleton)")))
        };
        let report = mocap::ops::compare::compare(clip(i)?, clip(j)?, align, &[]).map_err(|e| JsError::new(&e.to_string()))?;
        let o = Object::new();
        set(&o, "mpjpe", f64::from(report.mpjpe));
        set(&o, "mpjpeM", f64::from(report.mpjpe_m));
        set(&o, "worstFrame", report.worst_frame as f64);
        let joints: Array = report
            .joints
            .iter()
            .map(|e| {
                let item = Object::new();
                set(&item, "name", e.name.as_str());
                set(&item, "mean", f64::from(e.mean));
                set(&item, "max", f64::from(e.max));
                set(&item, "angle", e.angle.map_or(JsValue::NULL, |a| JsValue::from_f64(f64::from(a))));
                JsValue::from(item)
            })
            .collect();
        set(&o, "joints", joints);
        set(&o, "frames", js_sys::Float32Array::from(report.frames.as_slice()));
        Ok(o.into())
    }
}
