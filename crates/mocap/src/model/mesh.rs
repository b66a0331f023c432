//! Vertex-animated meshes: the asset a Quake 2 MD2 model becomes (mesh + vertex
//! frames), independent of the file it came from.
//!
//! A [`MorphMesh`] holds one triangle list over *drawing vertices* (a file vertex
//! paired with one texture coordinate: MD2 triangles index positions and texture
//! coordinates separately, a GPU draws one index per corner), and for every key
//! frame the position and unit normal of each drawing vertex, Y-up, in file units.
//! A [`Model`] is a mesh on the stage: the mesh, the skin it is drawn with, and the
//! animation it plays. Time maps to frames by the one rule of [`crate::model::time`], at
//! [`FRAME_TIME`] (Quake 2 animates models at 10 frames per second):
//! [`Model::frames_at`] gives the two key frames to blend and the blend weight,
//! which the renderer interpolates on the GPU.

use crate::model::clip::{Aabb, Units};
use crate::model::time::{FramePosition, Timeline};
use crate::runtime::sample::Interpolation;
use glam::Vec3;
use serde::{Deserialize, Serialize};
use std::sync::Arc;

/// Seconds between key frames: Quake 2 runs model animations at 10 Hz.
pub const FRAME_TIME: f64 = 0.1;

/// Height of a Quake 2 player model in Quake units: the size the unit of every
/// MD2 model is guessed from.
pub const QUAKE_PLAYER_HEIGHT: f32 = 56.0;

/// A triangle mesh whose vertices move from key frame to key frame.
#[derive(Clone, Debug, PartialEq)]
pub struct MorphMesh {
    vertex_count: usize,
    positions: Vec<[f32; 3]>,
    normals: Vec<[f32; 3]>,
    tex_coords: Vec<[f32; 2]>,
    indices: Vec<u32>,
    /// The file vertex each drawing vertex was split from.
    sources: Vec<u32>,
    frame_names: Vec<String>,
    animations: Vec<Animation>,
    /// Skin file names the model names (may be empty).
    pub skins: Vec<String>,
    /// Skin size in pixels the texture coordinates were made for (the file's header).
    pub skin_size: [u32; 2],
    /// Counts in the source file: vertices, triangles, texture coordinates.
    pub source_counts: SourceCounts,
    bounds: Aabb,
    first_bounds: Aabb,
}

/// Counts as the source file gives them (before vertices are split per texture
/// coordinate for drawing).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct SourceCounts {
    /// Vertices per frame.
    pub vertices: usize,
    /// Triangles.
    pub triangles: usize,
    /// Texture coordinates.
    pub tex_coords: usize,
}

/// What a reader gives to make a [`MorphMesh`] ([`MorphMesh::from_parts`]): the
/// fields of the mesh, laid out as its accessors describe them.
pub(crate) struct MeshParts {
    /// Every frame's positions per drawing vertex, frame after frame (Y-up, file units).
    pub positions: Vec<[f32; 3]>,
    /// Unit normals, laid out as `positions`.
    pub normals: Vec<[f32; 3]>,
    /// Texture coordinates per drawing vertex (0–1 across the skin).
    pub tex_coords: Vec<[f32; 2]>,
    /// Three indices per triangle into the drawing vertices.
    pub indices: Vec<u32>,
    /// The file vertex each drawing vertex was split from (one per drawing vertex).
    pub sources: Vec<u32>,
    /// Frame names in file order.
    pub frame_names: Vec<String>,
    /// Named animations in file order.
    pub animations: Vec<Animation>,
    /// Skin file names the model names.
    pub skins: Vec<String>,
    /// Skin size the texture coordinates were made for.
    pub skin_size: [u32; 2],
    /// Counts in the source file.
    pub source_counts: SourceCounts,
}

/// A named run of consecutive frames (`stand`: frames 0 to 39).
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Animation {
    /// Base name shared by the frames (for MD2, the frame names without their
    /// trailing digits).
    pub name: String,
    /// Index of the first frame.
    pub first: usize,
    /// Index of the last frame (inclusive, `>= first`).
    pub last: usize,
}

impl MorphMesh {
    /// The mesh from its parts (a reader's work: [`MorphMesh::from_md2`] for MD2);
    /// the vertex count is that of `parts.sources`, the bounds are computed here.
    pub(crate) fn from_parts(parts: MeshParts) -> MorphMesh {
        let MeshParts {
            positions,
            normals,
            tex_coords,
            indices,
            sources,
            frame_names,
            animations,
            skins,
            skin_size,
            source_counts,
        } = parts;
        let mut mesh = MorphMesh {
            vertex_count: sources.len(),
            positions,
            normals,
            tex_coords,
            indices,
            sources,
            frame_names,
            animations,
            skins,
            skin_size,
            source_counts,
            bounds: Aabb::EMPTY,
            first_bounds: Aabb::EMPTY,
        };
        mesh.bounds = bounds_of(&mesh.positions);
        mesh.first_bounds = bounds_of(mesh.frame_positions(0));
        mesh
    }

    /// The mesh from parts whose every invariant is checked first (a stored mesh,
    /// [`crate::formats::store`]; a reader's parts hold by construction): at
    /// least one key frame; positions and normals for every drawing vertex of
    /// every frame; one texture coordinate and one file vertex (below the source
    /// count, at most 65,536: MD2 triangles index vertices with 16 bits) per
    /// drawing vertex; whole triangles of drawing vertices, as many as the source
    /// says; animations over existing frames, `first <= last`.
    pub(crate) fn checked_from_parts(parts: MeshParts) -> Result<MorphMesh, String> {
        let vertices = parts.sources.len();
        let frames = parts.frame_names.len();
        if frames == 0 {
            return Err("the mesh has no key frames".into());
        }
        let expected = vertices.checked_mul(frames);
        if expected != Some(parts.positions.len()) || expected != Some(parts.normals.len()) {
            return Err(format!(
                "{} positions and {} normals for {vertices} vertices × {frames} frames",
                parts.positions.len(),
                parts.normals.len()
            ));
        }
        if parts.tex_coords.len() != vertices {
            return Err(format!("{} texture coordinates for {vertices} vertices", parts.tex_coords.len()));
        }
        let sources = parts.source_counts.vertices;
        if sources > 1 << 16 {
            return Err(format!("{sources} source vertices: MD2 triangles reach 65536"));
        }
        if let Some((i, v)) = parts.sources.iter().enumerate().find(|(_, v)| **v as usize >= sources) {
            return Err(format!("vertex {i} comes from source vertex {v}, but there are {sources}"));
        }
        if !parts.indices.len().is_multiple_of(3) || parts.indices.len() / 3 != parts.source_counts.triangles {
            return Err(format!(
                "{} triangle corners for {} triangles",
                parts.indices.len(),
                parts.source_counts.triangles
            ));
        }
        if let Some((corner, v)) = parts.indices.iter().enumerate().find(|(_, v)| **v as usize >= vertices) {
            return Err(format!("triangle corner {corner} uses vertex {v}, but there are {vertices}"));
        }
        if let Some(a) = parts.animations.iter().find(|a| a.first > a.last || a.last >= frames) {
            return Err(format!("animation `{}` runs over frames {} to {} of {frames}", a.name, a.first, a.last));
        }
        Ok(MorphMesh::from_parts(parts))
    }

    /// The file vertex each drawing vertex was split from.
    pub(crate) fn sources(&self) -> &[u32] {
        &self.sources
    }

    /// Every frame's positions per file vertex (before the split per texture
    /// coordinate; Y-up, file units): what a capture tracks. A file vertex no
    /// triangle uses stays at the origin.
    pub fn source_frames(&self) -> Vec<Vec<Vec3>> {
        (0..self.frame_count())
            .map(|f| {
                let mut out = vec![Vec3::ZERO; self.source_counts.vertices];
                for (p, &v) in self.frame_positions(f).iter().zip(&self.sources) {
                    if let Some(o) = out.get_mut(v as usize) {
                        *o = Vec3::from(*p);
                    }
                }
                out
            })
            .collect()
    }

    /// The triangles as file vertex indices.
    pub fn source_triangles(&self) -> Vec<[usize; 3]> {
        let at = |i: u32| self.sources.get(i as usize).map_or(0, |&v| v as usize);
        self.indices.chunks_exact(3).map(|t| [at(t[0]), at(t[1]), at(t[2])]).collect()
    }

    /// Drawing vertices per frame.
    pub fn vertex_count(&self) -> usize {
        self.vertex_count
    }

    /// Key frames.
    pub fn frame_count(&self) -> usize {
        self.frame_names.len()
    }

    /// Triangle corners: three indices per triangle into the drawing vertices.
    pub fn indices(&self) -> &[u32] {
        &self.indices
    }

    /// Texture coordinates per drawing vertex (0–1 across the skin, rows down).
    pub fn tex_coords(&self) -> &[[f32; 2]] {
        &self.tex_coords
    }

    /// Positions of every frame, frame after frame (Y-up, file units).
    pub fn positions(&self) -> &[[f32; 3]] {
        &self.positions
    }

    /// Unit normals of every frame, laid out as [`MorphMesh::positions`].
    pub fn normals(&self) -> &[[f32; 3]] {
        &self.normals
    }

    /// Positions of one frame (empty when out of range).
    pub fn frame_positions(&self, frame: usize) -> &[[f32; 3]] {
        let start = frame.saturating_mul(self.vertex_count);
        self.positions.get(start..start.saturating_add(self.vertex_count)).unwrap_or(&[])
    }

    /// Frame names in file order.
    pub fn frame_names(&self) -> &[String] {
        &self.frame_names
    }

    /// Named animations in file order (at least one for a parsed model).
    pub fn animations(&self) -> &[Animation] {
        &self.animations
    }

    /// Bounds of every vertex over every frame (file units).
    pub fn bounds(&self) -> Aabb {
        self.bounds
    }

    /// Bounds of the first key frame (file units): the pose a model stands in
    /// (MD2 models are centred on their origin; their feet are this box's
    /// bottom, and frames such as deaths reach lower).
    pub fn first_bounds(&self) -> Aabb {
        self.first_bounds
    }

    /// Height of the first frame (file units): the size a unit guess reads.
    pub fn height(&self) -> f32 {
        self.first_bounds.size().y
    }

    /// Largest edge of the first frame's bounds (file units).
    pub fn extent(&self) -> f32 {
        self.first_bounds.size().max_element()
    }

    /// The length unit: MD2 models are all in Quake units, so one guess holds for
    /// every model (weapons and monsters too), made by the rule every asset uses
    /// ([`Units::guess`]) on a Quake 2 player's height ([`QUAKE_PLAYER_HEIGHT`]):
    /// inches. A player then stands 1.42 m tall beside a BVH actor.
    pub fn units(&self) -> Units {
        Units::guess(QUAKE_PLAYER_HEIGHT)
    }
}

fn bounds_of(points: &[[f32; 3]]) -> Aabb {
    let mut b = Aabb::EMPTY;
    points.iter().for_each(|&p| b.include(Vec3::from(p)));
    b
}

/// An RGBA8 image, rows top to bottom.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Rgba {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// `width × height × 4` bytes: red, green, blue, alpha per pixel.
    pub pixels: Vec<u8>,
}

impl Rgba {
    /// The pixel at `(x, y)` as `[r, g, b, a]`; `None` outside the image.
    pub fn pixel(&self, x: u32, y: u32) -> Option<[u8; 4]> {
        if x >= self.width || y >= self.height {
            return None;
        }
        let i = (y as usize * self.width as usize + x as usize) * 4;
        let p = self.pixels.get(i..i + 4)?;
        Some([p[0], p[1], p[2], p[3]])
    }
}

/// A decoded skin and the file it came from.
#[derive(Clone, Debug, PartialEq)]
pub struct Skin {
    /// The image file's name.
    pub name: String,
    /// Its pixels.
    pub image: Arc<Rgba>,
}

/// Two key frames and the weight of the second: what one draw of a morph mesh needs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MorphSample {
    /// First key frame (absolute index in the file).
    pub frame0: usize,
    /// Second key frame.
    pub frame1: usize,
    /// Weight of `frame1`, in `[0, 1)`; 0 when not interpolating.
    pub blend: f32,
}

/// A morph mesh on the stage: its skin and the animation it plays.
#[derive(Clone, Debug, PartialEq)]
pub struct Model {
    /// The mesh (shared: the renderer keeps its GPU copy by this).
    pub mesh: Arc<MorphMesh>,
    /// The skin it is drawn with; `None` draws a neutral lit material.
    pub skin: Option<Skin>,
    animation: Option<usize>,
}

impl Model {
    /// A model playing all its frames in file order.
    pub fn new(mesh: MorphMesh, skin: Option<Skin>) -> Model {
        Model { mesh: Arc::new(mesh), skin, animation: None }
    }

    /// The animation playing: an index into [`MorphMesh::animations`], or `None` for
    /// all frames in file order.
    pub fn animation(&self) -> Option<usize> {
        self.animation
    }

    /// The name of the animation playing, `"all"` for every frame.
    pub fn animation_name(&self) -> &str {
        self.animation.and_then(|a| self.mesh.animations.get(a)).map_or("all", |a| a.name.as_str())
    }

    /// Plays animation `index` (`None`: all frames); false (and no change) when out of range.
    pub fn set_animation(&mut self, index: Option<usize>) -> bool {
        if index.is_some_and(|i| i >= self.mesh.animations.len()) {
            return false;
        }
        self.animation = index;
        true
    }

    /// Plays the animation named `name` (`"all"` for every frame); false when there is none.
    pub fn set_animation_by_name(&mut self, name: &str) -> bool {
        if name == "all" {
            return self.set_animation(None);
        }
        let found = self.mesh.animations.iter().position(|a| a.name == name);
        found.is_some_and(|i| self.set_animation(Some(i)))
    }

    /// First and last key frame played (inclusive).
    pub fn range(&self) -> (usize, usize) {
        match self.animation.and_then(|a| self.mesh.animations.get(a)) {
            Some(a) => (a.first, a.last),
            None => (0, self.mesh.frame_count().saturating_sub(1)),
        }
    }

    /// The frames played, [`FRAME_TIME`] apart.
    pub fn timeline(&self) -> Timeline {
        let (first, last) = self.range();
        Timeline::new(FRAME_TIME, last - first + 1)
    }

    /// The key frames to draw at `time` (seconds into the animation) and the blend
    /// between them: linear between neighbours, or the frame shown
    /// ([`Interpolation::Step`], "switch at the frame") or the nearest one
    /// ([`Interpolation::Nearest`], "switch at the halfway point"). The animation
    /// loops: past its last frame it blends back into its first and starts again
    /// (so beside a longer clip it keeps playing, as in the game).
    pub fn frames_at(&self, time: f64, interpolation: Interpolation) -> MorphSample {
        let (first, last) = self.range();
        let n = last - first + 1;
        // One lap of the loop: the n frames and the way back to the first.
        let lap = Timeline::new(FRAME_TIME, n + 1);
        let period = lap.duration();
        let time =
            if time > self.timeline().duration() && n > 1 && time.is_finite() { time.rem_euclid(period) } else { time };
        let wrap = |f: usize| f % n;
        let FramePosition { frame0, frame1, alpha } = lap.position(time);
        let (frame0, frame1, blend) = match interpolation {
            // Vertex animation blends two key frames on the GPU: cubic is linear here.
            Interpolation::Linear | Interpolation::Cubic => (frame0, frame1, alpha),
            Interpolation::Step => (frame0, frame0, 0.0),
            Interpolation::Nearest => {
                let f = lap.nearest(time);
                (f, f, 0.0)
            }
        };
        MorphSample { frame0: first + wrap(frame0), frame1: first + wrap(frame1), blend }
    }

    /// Bounds of every vertex over the frames played (file units): the floor and
    /// the camera follow the animation chosen, not the model's whole file.
    pub fn bounds(&self) -> Aabb {
        let (first, last) = self.range();
        let start = first.saturating_mul(self.mesh.vertex_count);
        let end = (last + 1).saturating_mul(self.mesh.vertex_count);
        self.mesh.positions.get(start..end).map_or(self.mesh.bounds, bounds_of)
    }

    /// The name of key frame `frame` (empty when out of range).
    pub fn frame_name(&self, frame: usize) -> &str {
        self.mesh.frame_names.get(frame).map_or("", String::as_str)
    }
}

/// The last path component of a name, lower-cased (`models/x/Skin.PCX` → `skin.pcx`).
pub fn file_key(name: &str) -> String {
    name.rsplit(['/', '\\']).next().unwrap_or(name).to_ascii_lowercase()
}

/// Which of `images` (file names) belongs to a model named `model_name` with
/// embedded skin names `skins`: the first image whose file name matches an embedded
/// skin name (case-insensitive, any folder prefix), else one that matches a skin
/// name but for its extension (`skin.tga` for `skin.pcx`), else the first whose
/// name without extension is the model's. `None` when none matches.
pub fn match_skin(model_name: &str, skins: &[String], images: &[&str]) -> Option<usize> {
    let wanted: Vec<String> = skins.iter().map(|s| file_key(s)).collect();
    if let Some(i) = images.iter().position(|name| wanted.contains(&file_key(name))) {
        return Some(i);
    }
    let stem = |n: &str| {
        let key = file_key(n);
        key.rsplit_once('.').map_or(key.clone(), |(s, _)| s.to_owned())
    };
    // A skin named `skin.pcx` shipped as `skin.tga` (what Quake 2 engines fall back to).
    let wanted_stems: Vec<String> = skins.iter().map(|s| stem(s)).collect();
    if let Some(i) = images.iter().position(|name| wanted_stems.contains(&stem(name))) {
        return Some(i);
    }
    let model = stem(model_name);
    images.iter().position(|name| stem(name) == model)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Three frames of one triangle (file vertices 0, 1, 2), 2 units higher each
    /// frame; frames `run1`, `run2` and `jump1`.
    fn mesh() -> MorphMesh {
        let frame = |y: f32| [[0.0, y, 0.0], [10.0, y, 0.0], [0.0, 20.0 + y, 0.0]];
        let animation = |name: &str, first, last| Animation { name: name.into(), first, last };
        MorphMesh::from_parts(MeshParts {
            positions: [0.0, 2.0, 4.0].into_iter().flat_map(frame).collect(),
            normals: vec![[0.0, 1.0, 0.0]; 9],
            tex_coords: vec![[0.0; 2]; 3],
            indices: vec![0, 1, 2],
            sources: vec![0, 1, 2],
            frame_names: vec!["run1".into(), "run2".into(), "jump1".into()],
            animations: vec![animation("run", 0, 1), animation("jump", 2, 2)],
            skins: Vec::new(),
            skin_size: [64, 32],
            source_counts: SourceCounts { vertices: 3, triangles: 1, tex_coords: 3 },
        })
    }

    #[test]
    fn a_mesh_from_its_parts_has_its_frames_and_bounds() {
        let mesh = mesh();
        assert_eq!((mesh.vertex_count(), mesh.frame_count()), (3, 3));
        assert_eq!(mesh.frame_positions(1)[2], [0.0, 22.0, 0.0]);
        assert!(mesh.frame_positions(3).is_empty());
        assert_eq!(mesh.height(), 20.0);
        assert_eq!(mesh.bounds().max.y, 24.0);
        assert_eq!(mesh.source_triangles(), [[0, 1, 2]]);
    }

    #[test]
    fn animations_choose_the_frames_and_time_maps_at_ten_per_second() {
        let mut m = Model::new(mesh(), None);
        assert_eq!(m.animation_name(), "all");
        assert_eq!(m.timeline().frames(), 3);
        assert_eq!(m.frames_at(0.15, Interpolation::Linear), MorphSample { frame0: 1, frame1: 2, blend: 0.5 });
        assert!(m.set_animation_by_name("jump"));
        assert_eq!(m.range(), (2, 2));
        assert_eq!(m.frames_at(5.0, Interpolation::Linear), MorphSample { frame0: 2, frame1: 2, blend: 0.0 });
        assert!(m.set_animation_by_name("run"));
        assert_eq!(m.frames_at(0.05, Interpolation::Linear), MorphSample { frame0: 0, frame1: 1, blend: 0.5 });
        // Past its end the animation loops: back into its first frame, then again.
        assert_eq!(m.frames_at(0.1, Interpolation::Linear), MorphSample { frame0: 1, frame1: 1, blend: 0.0 });
        assert_eq!(m.frames_at(0.15, Interpolation::Linear), MorphSample { frame0: 1, frame1: 0, blend: 0.5 });
        assert_eq!(m.frames_at(0.25, Interpolation::Linear), MorphSample { frame0: 0, frame1: 1, blend: 0.5 });
        assert_eq!(m.frames_at(0.16, Interpolation::Nearest), MorphSample { frame0: 0, frame1: 0, blend: 0.0 });
        assert_eq!(m.frames_at(0.06, Interpolation::Step), MorphSample { frame0: 0, frame1: 0, blend: 0.0 });
        assert_eq!(m.frames_at(0.06, Interpolation::Nearest), MorphSample { frame0: 1, frame1: 1, blend: 0.0 });
        assert_eq!(m.frame_name(1), "run2");
        assert_eq!((m.bounds().min.y, m.bounds().max.y), (0.0, 22.0), "run's frames only");
        assert!(!m.set_animation(Some(9)) && !m.set_animation_by_name("walk"));
        assert_eq!(m.animation_name(), "run");
    }

    #[test]
    fn skins_match_by_embedded_name_then_model_name() {
        let skins = vec!["players/waste/weapon.pcx".to_owned()];
        assert_eq!(match_skin("weapon.md2", &skins, &["waste.pcx", "dir/WEAPON.PCX"]), Some(1));
        assert_eq!(match_skin("a/tris.md2", &[], &["waste.pcx", "tris.bmp"]), Some(1));
        assert_eq!(match_skin("tris.md2", &[], &["waste.pcx"]), None);
        assert_eq!(match_skin("tris.md2", &skins, &[]), None);
    }
}
