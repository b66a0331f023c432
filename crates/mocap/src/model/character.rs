//! A character: what a clip carries besides its skeleton and motion when it was
//! read from a file that also holds a look and several animations (glTF): the
//! mesh skinned to the clip's skeleton, the file's animations ("takes") on that
//! skeleton, and a summary of what the file holds.
//!
//! The clip's own motion is always one of the takes ([`crate::Clip::set_take`]).
//! Lengths are metres and Y is up, as glTF says.

use crate::model::motion::Motion;
use crate::runtime::skin::Skin;
use serde::{Deserialize, Serialize};

/// One animation of the file, sampled on the clip's skeleton.
#[derive(Clone, Debug, PartialEq)]
pub struct Take {
    /// Its name in the file (or `animation N` when it has none).
    pub name: String,
    /// Its frames on the clip's skeleton.
    pub motion: Motion,
    /// The look's morph-target weights at the motion's frames: [`Morph::targets`]
    /// per frame, frame after frame; empty when the take sets none (the rest
    /// weights hold).
    pub weights: Vec<f32>,
}

impl Take {
    /// The weights of `targets` morph targets at `time` seconds (frame times
    /// `frame_time` apart, linear between frames, the ends held) into `out`;
    /// false when the take sets none.
    pub fn weights_at(&self, time: f64, targets: usize, out: &mut Vec<f32>) -> bool {
        let frames = self.motion.frame_count();
        if targets == 0 || frames == 0 || self.weights.len() != frames * targets {
            return false;
        }
        let at = if self.motion.frame_time() > 0.0 { time / self.motion.frame_time() } else { 0.0 };
        let at = if at.is_finite() { at.clamp(0.0, (frames - 1) as f64) } else { 0.0 };
        let (k, u) = (at.floor() as usize, (at - at.floor()) as f32);
        let next = (k + 1).min(frames - 1);
        out.clear();
        out.extend((0..targets).map(|i| {
            let a = self.weights.get(k * targets + i).copied().unwrap_or(0.0);
            let b = self.weights.get(next * targets + i).copied().unwrap_or(0.0);
            a + (b - a) * u
        }));
        true
    }
}

/// A look's morph targets (glTF blend shapes): offsets of its vertices in bind
/// space, blended by weights: position = bind position + Σ weightᵢ · offsetᵢ,
/// before skinning.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Morph {
    /// Per target, the vertices it moves and by how much (bind space, the
    /// look's units).
    pub targets: Vec<Vec<(u32, [f32; 3])>>,
    /// Each target's weight when no take sets it.
    pub rest: Vec<f32>,
}

impl Morph {
    /// The look's positions under `weights` (one per target; missing ones are
    /// the rest weights) into `out`, from its bind positions `base`.
    pub fn shape(&self, base: &[glam::Vec3], weights: &[f32], out: &mut Vec<glam::Vec3>) {
        out.clear();
        out.extend_from_slice(base);
        for (i, target) in self.targets.iter().enumerate() {
            let w = weights.get(i).or(self.rest.get(i)).copied().unwrap_or(0.0);
            if w == 0.0 || !w.is_finite() {
                continue;
            }
            for &(v, d) in target {
                if let Some(p) = out.get_mut(v as usize) {
                    *p += w * glam::Vec3::from_array(d);
                }
            }
        }
    }
}

/// A mesh bound to the clip's skeleton, with a colour per vertex.
#[derive(Clone, Debug, PartialEq)]
pub struct Look {
    /// Positions, normals, triangles, influences and inverse bind matrices, one
    /// inverse bind matrix per joint of the clip's skeleton.
    pub skin: Skin,
    /// One sRGB colour per vertex: the material's base colour times its
    /// base-colour texture sampled at the vertex (what a writer or a renderer
    /// without the texture uses).
    pub colors: Vec<[u8; 4]>,
    /// The base-colour texture to draw per pixel, when the look has one.
    pub surface: Option<Surface>,
    /// Its morph targets, when it has some.
    pub morph: Option<Morph>,
}

/// How a texture coordinate outside 0–1 is taken back into the image.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Wrap {
    /// The image repeats.
    #[default]
    Repeat,
    /// The image repeats, every other copy mirrored.
    Mirror,
    /// The edge texel.
    Clamp,
}

/// A texture image: sRGB RGBA, rows from the top.
#[derive(Clone, Debug, PartialEq)]
pub struct TextureImage {
    /// Width in texels.
    pub width: u32,
    /// Height in texels.
    pub height: u32,
    /// `width × height × 4` bytes.
    pub pixels: Vec<u8>,
    /// Wrap along u and v.
    pub wrap: [Wrap; 2],
}

/// A look's base-colour texture, drawn per pixel: the image most of the look's
/// textured vertices use, and per vertex its texture coordinate (glTF's, v down,
/// after `KHR_texture_transform`; `None` for a vertex of a part drawn without
/// this image, whose colour is [`Look::colors`]'s) and the colour the texture is
/// multiplied with (the base-colour factor times `COLOR_0`, sRGB).
#[derive(Clone, Debug, PartialEq)]
pub struct Surface {
    /// The image, shared by every copy of the look.
    pub image: std::sync::Arc<TextureImage>,
    /// One per vertex.
    pub uvs: Vec<Option<[f32; 2]>>,
    /// One per vertex.
    pub tints: Vec<[u8; 4]>,
}

/// A character's look, takes and summary.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Character {
    /// Its mesh, when the file has one (a bare skin shows as a skeleton).
    pub look: Option<Look>,
    /// Every animation of the file, in file order (may be empty: a posed character).
    pub takes: Vec<Take>,
    /// What the file holds, for `mocap info` and the inspector.
    pub summary: Summary,
}

/// Counts and names of what a glTF file holds.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Summary {
    /// Nodes in the file.
    pub nodes: usize,
    /// Scenes in the file.
    pub scenes: usize,
    /// Meshes: name, primitives and vertices.
    pub meshes: Vec<(String, usize, usize)>,
    /// Skins: name and joint count.
    pub skins: Vec<(String, usize)>,
    /// Animations: name, duration in seconds and channel count.
    pub animations: Vec<(String, f64, usize)>,
    /// Extensions the file uses.
    pub extensions_used: Vec<String>,
    /// Extensions the file requires.
    pub extensions_required: Vec<String>,
}

/// An sRGB byte (a [`Look`] colour) as a linear value in 0–1.
pub fn srgb_to_linear(c: u8) -> f32 {
    let c = c as f32 / 255.0;
    if c <= 0.04045 { c / 12.92 } else { ((c + 0.055) / 1.055).powf(2.4) }
}

/// A linear value (clamped to 0–1) as an sRGB byte.
pub fn linear_to_srgb(c: f32) -> u8 {
    let c = c.clamp(0.0, 1.0);
    let s = if c <= 0.003_130_8 { c * 12.92 } else { 1.055 * c.powf(1.0 / 2.4) - 0.055 };
    (s * 255.0).round() as u8
}
