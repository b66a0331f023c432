//! `parseModel(bytes, fileName)`: the core's Quake 2 MD2 reader from JavaScript.

use mocap::formats::md2::Md2;
use wasm_bindgen::prelude::*;

/// A parsed MD2 model, for JavaScript (`parseModel`'s result).
#[wasm_bindgen(js_name = ModelMesh)]
pub struct ModelMesh {
    model: Md2,
    scratch: Vec<[f32; 3]>,
}

/// Parses a Quake 2 MD2 model; throws an `Error` whose message is
/// `file:byte N: message` when the file is malformed.
#[wasm_bindgen(js_name = parseModel)]
pub fn parse_model(bytes: &[u8], file_name: &str) -> Result<ModelMesh, JsError> {
    let model = mocap::formats::md2::parse(bytes).map_err(|e| JsError::new(&format!("{file_name}:{e}")))?;
    Ok(ModelMesh { model, scratch: Vec::new() })
}

fn count(n: usize) -> u32 {
    u32::try_from(n).unwrap_or(u32::MAX)
}

#[wasm_bindgen(js_class = ModelMesh)]
impl ModelMesh {
    /// Vertices per frame.
    #[wasm_bindgen(getter, js_name = vertexCount)]
    pub fn vertex_count(&self) -> u32 {
        count(self.model.vertex_count)
    }

    /// Number of key frames.
    #[wasm_bindgen(getter, js_name = frameCount)]
    pub fn frame_count(&self) -> u32 {
        count(self.model.frames.len())
    }

    /// Number of triangles.
    #[wasm_bindgen(getter, js_name = triangleCount)]
    pub fn triangle_count(&self) -> u32 {
        count(self.model.triangles.len())
    }

    /// Frame names in file order.
    #[wasm_bindgen(getter, js_name = frameNames)]
    pub fn frame_names(&self) -> Vec<String> {
        self.model.frames.iter().map(|f| f.name.clone()).collect()
    }

    /// Skin file names the model embeds (often none).
    #[wasm_bindgen(getter)]
    pub fn skins(&self) -> Vec<String> {
        self.model.skins.clone()
    }

    /// Animation names, in file order (see `animationFirst`/`animationLast`).
    #[wasm_bindgen(getter, js_name = animationNames)]
    pub fn animation_names(&self) -> Vec<String> {
        self.model.animations.iter().map(|a| a.name.clone()).collect()
    }

    /// First frame of each animation, in the order of `animationNames`.
    #[wasm_bindgen(getter, js_name = animationFirst)]
    pub fn animation_first(&self) -> Vec<u32> {
        self.model.animations.iter().map(|a| count(a.first)).collect()
    }

    /// Last frame of each animation, in the order of `animationNames`.
    #[wasm_bindgen(getter, js_name = animationLast)]
    pub fn animation_last(&self) -> Vec<u32> {
        self.model.animations.iter().map(|a| count(a.last)).collect()
    }

    /// Vertex positions between frame `frame` and the next (both clamped to the
    /// model) at `t` in [0, 1] (clamped): `x, y, z` per vertex, Y up, file units.
    pub fn positions(&mut self, frame: u32, t: f32) -> Vec<f32> {
        let last = self.model.frames.len().saturating_sub(1);
        let a = (frame as usize).min(last);
        let b = (a + 1).min(last);
        let t = if t.is_finite() { t.clamp(0.0, 1.0) } else { 0.0 };
        self.model.interpolated_positions(a, b, t, &mut self.scratch);
        self.scratch.iter().flatten().copied().collect()
    }
}
