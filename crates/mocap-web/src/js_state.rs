//! Converts a viewer [`Snapshot`] to a plain JavaScript object.

use js_sys::{Array, Object, Reflect};
use mocap_viewer::Snapshot;
use wasm_bindgen::JsValue;

fn set(obj: &Object, key: &str, value: impl Into<JsValue>) {
    // Setting a property on a fresh plain object cannot fail.
    let _ = Reflect::set(obj, &JsValue::from_str(key), &value.into());
}

fn opt(s: &Option<String>) -> JsValue {
    s.as_deref().map_or(JsValue::NULL, JsValue::from_str)
}

fn strings(items: &[String]) -> Array {
    items.iter().map(|s| JsValue::from_str(s)).collect()
}

/// The snapshot as `{clips, frame, time, playing, speed, selectedJoint, selectedCharacter, layout, error, ...}`.
pub fn to_js(s: &Snapshot) -> JsValue {
    let clips: Array = s
        .clips
        .iter()
        .map(|c| {
            let o = Object::new();
            set(&o, "name", c.name.as_str());
            set(&o, "frames", c.frames as f64);
            set(&o, "frameTime", c.frame_time);
            set(&o, "joints", c.joints as f64);
            set(&o, "jointNames", strings(&c.joint_names));
            set(&o, "visible", c.visible);
            let [r, g, b, _] = c.color;
            set(&o, "color", format!("#{r:02x}{g:02x}{b:02x}"));
            let offset: Array = c.offset.iter().map(|x| JsValue::from_f64(f64::from(*x))).collect();
            set(&o, "offset", offset);
            set(&o, "animation", opt(&c.animation));
            set(&o, "animations", strings(&c.animations));
            set(&o, "modelFrame", c.model_frame.as_ref().map_or(JsValue::NULL, |(f, _)| JsValue::from_f64(*f as f64)));
            set(&o, "frameName", c.model_frame.as_ref().map_or(JsValue::NULL, |(_, n)| JsValue::from_str(n)));
            set(&o, "skin", opt(&c.skin));
            set(&o, "up", c.up);
            set(&o, "corrected", c.corrected);
            set(&o, "edited", c.edited);
            set(&o, "unsaved", c.unsaved);
            let keys: Array = c.keys.iter().map(|k| JsValue::from_f64(*k as f64)).collect();
            set(&o, "keys", keys);
            let contacts: Array = c.foot_contacts.iter().map(|n| JsValue::from_f64(*n as f64)).collect();
            set(&o, "footContacts", contacts);
            JsValue::from(o)
        })
        .collect();
    let o = Object::new();
    set(&o, "clips", clips);
    set(&o, "frame", s.frame as f64);
    set(&o, "time", s.time);
    set(&o, "playing", s.playing);
    set(&o, "speed", f64::from(s.speed));
    set(&o, "selectedJoint", opt(&s.selected_joint));
    set(&o, "selectedCharacter", s.selected_character.map_or(JsValue::NULL, |c| JsValue::from_f64(c as f64)));
    set(&o, "layout", s.layout);
    set(&o, "drawMode", s.draw_mode);
    set(&o, "shadows", s.shadows);
    set(&o, "poseMode", s.pose_mode);
    set(&o, "quality", s.quality);
    set(&o, "interpolation", s.interpolation);
    set(&o, "reduced", s.reduced);
    set(&o, "samples", f64::from(s.samples));
    let view_pixels: Array = s.view_pixels.iter().map(|&v| JsValue::from_f64(f64::from(v))).collect();
    set(&o, "viewPixels", view_pixels);
    set(&o, "floorCopied", s.floor_copied);
    set(&o, "error", opt(&s.error));
    set(&o, "errorNote", s.error_note.map_or(JsValue::NULL, JsValue::from_str));
    set(&o, "treeLabels", strings(&s.tree_labels));
    set(&o, "framesRendered", s.frames_rendered as f64);
    set(&o, "view", s.view.as_str());
    set(&o, "embed", s.embed);
    set(&o, "previousSession", s.previous_session);
    set(&o, "backend", opt(&s.backend));
    let demo = s.demo.as_ref().map_or(JsValue::NULL, |d| {
        let o = Object::new();
        set(&o, "bones", d.bones as f64);
        set(&o, "solver", d.solver);
        set(&o, "soft", d.soft);
        set(&o, "follow", d.follow);
        let v3 = |v: [f32; 3]| -> Array { v.iter().map(|x| JsValue::from_f64(f64::from(*x))).collect() };
        set(&o, "target", v3(d.target));
        set(&o, "tip", v3(d.tip));
        o.into()
    });
    set(&o, "demo", demo);
    set(&o, "undo", opt(&s.undo));
    set(&o, "redo", opt(&s.redo));
    o.into()
}
