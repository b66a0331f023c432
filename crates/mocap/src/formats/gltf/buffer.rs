//! The binary side of the glTF writers: one buffer of 4-byte aligned views,
//! accessors over them, and the `.glb` container or an inline `data:` URI.

use super::write::WriteError;
use base64::Engine as _;
use glam::Vec3;
use serde_json::{Value, json};

/// A buffer view of vertex attributes.
pub(super) const ARRAY_BUFFER: u32 = 34962;
/// A buffer view of vertex indices.
pub(super) const ELEMENT_ARRAY_BUFFER: u32 = 34963;

/// The binary buffer and its views, each 4-byte aligned.
#[derive(Default)]
pub(super) struct Binary {
    data: Vec<u8>,
    views: Vec<Value>,
}

impl Binary {
    /// Puts `bufferViews` and `buffers` into `document` (the data inline as a
    /// `data:` URI with `inline`); the data, for a `.glb`'s binary chunk.
    pub(super) fn finish(self, document: &mut Value, inline: bool) -> Result<Vec<u8>, WriteError> {
        document["bufferViews"] = Value::Array(self.views);
        let length = self.data.len();
        u32::try_from(length).map_err(|_| WriteError::TooLarge(length))?;
        document["buffers"] = if inline {
            let coded = base64::engine::general_purpose::STANDARD.encode(&self.data);
            json!([{ "byteLength": length, "uri": format!("data:application/octet-stream;base64,{coded}") }])
        } else {
            json!([{ "byteLength": length }])
        };
        Ok(self.data)
    }

    /// Appends bytes as one buffer view; its index.
    pub(super) fn view(&mut self, bytes: &[u8], target: Option<u32>) -> usize {
        while self.data.len() % 4 != 0 {
            self.data.push(0);
        }
        let mut view = json!({ "buffer": 0, "byteOffset": self.data.len(), "byteLength": bytes.len() });
        if let Some(target) = target {
            view["target"] = json!(target);
        }
        self.views.push(view);
        self.data.extend_from_slice(bytes);
        self.views.len() - 1
    }

    pub(super) fn f32s(&mut self, values: &[f32], target: Option<u32>) -> usize {
        let bytes: Vec<u8> = values.iter().flat_map(|v| v.to_le_bytes()).collect();
        self.view(&bytes, target)
    }

    pub(super) fn u16s(&mut self, values: &[u16]) -> usize {
        let bytes: Vec<u8> = values.iter().flat_map(|v| v.to_le_bytes()).collect();
        self.view(&bytes, Some(ARRAY_BUFFER))
    }

    pub(super) fn u32s(&mut self, values: &[u32]) -> usize {
        let bytes: Vec<u8> = values.iter().flat_map(|v| v.to_le_bytes()).collect();
        self.view(&bytes, Some(ELEMENT_ARRAY_BUFFER))
    }
}

/// A float accessor over new data; its index.
pub(super) fn accessor(
    accessors: &mut Vec<Value>,
    bin: &mut Binary,
    values: &[f32],
    kind: &str,
    component: u32,
    count: usize,
    min_max: Option<(Vec<f32>, Vec<f32>)>,
) -> usize {
    let view = bin.f32s(values, None);
    push_accessor(accessors, view, kind, component, count, min_max)
}

/// A float vertex-attribute accessor over new data; its index.
pub(super) fn vertex_accessor(
    accessors: &mut Vec<Value>,
    bin: &mut Binary,
    values: &[f32],
    kind: &str,
    count: usize,
    min_max: Option<(Vec<f32>, Vec<f32>)>,
) -> usize {
    let view = bin.f32s(values, Some(ARRAY_BUFFER));
    push_accessor(accessors, view, kind, 5126, count, min_max)
}

/// An accessor over buffer view `view`; its index.
pub(super) fn push_accessor(
    accessors: &mut Vec<Value>,
    view: usize,
    kind: &str,
    component: u32,
    count: usize,
    min_max: Option<(Vec<f32>, Vec<f32>)>,
) -> usize {
    let mut a = json!({ "bufferView": view, "componentType": component, "count": count, "type": kind });
    if let Some((min, max)) = min_max {
        a["min"] = json!(min);
        a["max"] = json!(max);
    }
    accessors.push(a);
    accessors.len() - 1
}

/// Per-component minimum and maximum of `points`.
pub(super) fn bounds(points: &[Vec3]) -> (Vec<f32>, Vec<f32>) {
    let min = points.iter().fold(Vec3::splat(f32::INFINITY), |a, p| a.min(*p));
    let max = points.iter().fold(Vec3::splat(f32::NEG_INFINITY), |a, p| a.max(*p));
    (min.to_array().to_vec(), max.to_array().to_vec())
}

/// The `.glb` container: a JSON chunk and a binary chunk, each padded to 4 bytes.
pub(super) fn glb(json: &Value, mut bin: Vec<u8>) -> Result<Vec<u8>, WriteError> {
    let mut text = serde_json::to_vec(json).unwrap_or_default();
    while text.len() % 4 != 0 {
        text.push(b' ');
    }
    while bin.len() % 4 != 0 {
        bin.push(0);
    }
    let total = 12 + 8 + text.len() + 8 + bin.len();
    let length = u32::try_from(total).map_err(|_| WriteError::TooLarge(total))?;
    let mut out = Vec::with_capacity(total);
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&length.to_le_bytes());
    out.extend_from_slice(&(text.len() as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(&text);
    out.extend_from_slice(&(bin.len() as u32).to_le_bytes());
    out.extend_from_slice(b"BIN\0");
    out.extend_from_slice(&bin);
    Ok(out)
}
