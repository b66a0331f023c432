//! `parseMotion(bytes, fileName)`: the core library from JavaScript, without the viewer.

use mocap::Clip;
use mocap::glam::Vec3;
use wasm_bindgen::prelude::*;

/// A parsed motion clip, for JavaScript (`parseMotion`'s result).
#[wasm_bindgen(js_name = MotionClip)]
pub struct MotionClip {
    clip: Clip,
    scratch: Vec<Vec3>,
    /// The generated body, built on first use (`Some(None)`: the skeleton gets none).
    body: Option<Option<mocap::runtime::skin::Skin>>,
}

/// Parses a motion file (BVH, BVA, or an Acclaim ASF alone: its rest pose; the
/// format comes from the content). For an Acclaim `.amc` motion pass its `.asf`
/// skeleton's bytes as `skeleton`. Throws an `Error` whose message is
/// `file:line:col: message`.
#[wasm_bindgen(js_name = parseMotion)]
pub fn parse_motion(bytes: &[u8], file_name: &str, skeleton: Option<Vec<u8>>) -> Result<MotionClip, JsError> {
    let mut files = Vec::new();
    if let Some(asf) = skeleton.as_deref() {
        files.push(mocap::Input { name: "skeleton.asf", bytes: asf });
    }
    files.push(mocap::Input { name: file_name, bytes });
    let last = mocap::load(&files).pop();
    let clip = match last {
        Some(Ok(loaded)) => match loaded.into_clip() {
            Some(clip) => clip,
            None => return Err(JsError::new(&format!("{file_name}: a model, not a motion: read it with parseModel"))),
        },
        Some(Err(e)) => return Err(JsError::new(&e.to_string())),
        None => return Err(JsError::new(&format!("{file_name}: no motion in this file"))),
    };
    Ok(MotionClip { clip, scratch: Vec::new(), body: None })
}

#[wasm_bindgen(js_class = MotionClip)]
impl MotionClip {
    /// Joint names in file order (End Sites included).
    #[wasm_bindgen(getter, js_name = jointNames)]
    pub fn joint_names(&self) -> Vec<String> {
        self.clip.skeleton().joints().iter().map(|j| j.name.clone()).collect()
    }

    /// Parent index of each joint; -1 for a root.
    #[wasm_bindgen(getter)]
    pub fn parents(&self) -> Vec<i32> {
        self.clip
            .skeleton()
            .joints()
            .iter()
            .map(|j| j.parent.and_then(|p| i32::try_from(p).ok()).unwrap_or(-1))
            .collect()
    }

    /// Whether each joint is an End Site.
    #[wasm_bindgen(getter, js_name = endSites)]
    pub fn end_sites(&self) -> Vec<u8> {
        self.clip.skeleton().joints().iter().map(|j| u8::from(j.is_end_site())).collect()
    }

    /// Number of frames.
    #[wasm_bindgen(getter, js_name = frameCount)]
    pub fn frame_count(&self) -> u32 {
        u32::try_from(self.clip.frame_count()).unwrap_or(u32::MAX)
    }

    /// Seconds per frame.
    #[wasm_bindgen(getter, js_name = frameTime)]
    pub fn frame_time(&self) -> f64 {
        self.clip.frame_time()
    }

    /// Which file axis points up, guessed from the motion: `'y'` (BVH's
    /// convention) or `'z'` (some tools' files; turn positions by it to stand the
    /// figure up, as the viewer does).
    #[wasm_bindgen(getter, js_name = upAxis)]
    pub fn up_axis(&self) -> String {
        self.clip.up_axis().name().to_owned()
    }

    /// World positions of every joint at `frame` (clamped), as `x, y, z` per joint in file units.
    #[wasm_bindgen(js_name = worldPositions)]
    pub fn world_positions(&mut self, frame: u32) -> Vec<f32> {
        let last = self.clip.frame_count().saturating_sub(1);
        if self.clip.frame_count() == 0 {
            return Vec::new();
        }
        self.clip.world_positions_into((frame as usize).min(last), &mut self.scratch);
        self.scratch.iter().flat_map(|p| p.to_array()).collect()
    }

    /// The generated body's triangles (three vertex indices each, counter-clockwise
    /// seen from outside), as body mode draws it; empty when the skeleton gets
    /// no body (too many bones).
    #[wasm_bindgen(js_name = bodyIndices)]
    pub fn body_indices(&mut self) -> Vec<u32> {
        self.body().map_or(Vec::new(), |b| b.indices().to_vec())
    }

    /// The generated body skinned at `frame` (clamped): `x, y, z` per vertex in
    /// file units, model space (the CPU reference of what body mode draws).
    #[wasm_bindgen(js_name = bodyVertices)]
    pub fn body_vertices(&mut self, frame: u32) -> Vec<f32> {
        let mut model = Vec::new();
        if self.clip.frame_count() > 0 {
            self.clip.world_transforms_into((frame as usize).min(self.clip.frame_count() - 1), &mut model);
        } else {
            model = self.clip.bind_pose();
        }
        let Some(body) = self.body() else { return Vec::new() };
        let (mut matrices, mut positions, mut normals) = (Vec::new(), Vec::new(), Vec::new());
        mocap::runtime::skin::skinning_matrices(&model, body.inverse_bind(), &mut matrices);
        mocap::runtime::skin::skin_vertices(body, &matrices, &mut positions, &mut normals);
        positions.iter().flat_map(|p| p.to_array()).collect()
    }

    /// The clip as standard BVH text.
    #[wasm_bindgen(js_name = toBvh)]
    pub fn to_bvh(&self) -> String {
        mocap::formats::bvh::write(&self.clip)
    }
}

impl MotionClip {
    /// The parsed clip.
    pub fn clip(&self) -> &Clip {
        &self.clip
    }

    /// The generated body, built once.
    fn body(&mut self) -> Option<&mocap::runtime::skin::Skin> {
        if self.body.is_none() {
            let extent = self.clip.pose_extent();
            self.body =
                Some(mocap_scene::body_skin(&self.clip, if extent > 0.0 && extent.is_finite() { extent } else { 1.0 }));
        }
        self.body.as_ref().and_then(Option::as_ref)
    }
}
