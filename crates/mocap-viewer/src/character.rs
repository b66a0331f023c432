//! One character on the stage: a clip or a model placed in the shared world by the
//! core's [`mocap::stage`], with what only the viewer keeps ([`Look`]): its colour,
//! the figure or mesh the renderer draws, children lists for the joint tree, and
//! its current pose (joint transforms, or the model's two key frames).

use mocap::morph::MorphSample;
use mocap::stage::{Actor, PoseScratch};
use mocap::{Asset, Interpolation, Model, Transform};
use mocap::glam::Mat4;
use mocap_render::{FigureJoint, MorphMeshData, SkinImage, SkinnedMeshData};
use std::sync::Arc;

/// Bone colours given to characters in turn (the renderer's palette).
pub use mocap_render::PALETTE;

/// What the viewer keeps per character.
#[derive(Clone, Debug, Default)]
pub struct Look {
    /// Bone colour (sRGB, 0-255).
    pub color: [u8; 4],
    /// Parents and joint markers, as the renderer draws them.
    pub figure: Vec<FigureJoint>,
    /// Children of each joint, in joint order (for the joint tree).
    pub children: Vec<Vec<usize>>,
    /// World transforms of the last [`pose_at`] (metres, placed), in joint order
    /// (empty for a model).
    pub pose: Vec<Transform>,
    /// A model's mesh as the renderer draws it (`None` for a clip).
    pub mesh: Option<Arc<MorphMeshData>>,
    /// A model's key frames at the last [`pose_at`].
    pub morph: Option<MorphSample>,
    /// The generated body of a clip (body mode), built on first use: `None` not
    /// tried yet, `Some(None)` when the skeleton gets none (too many bones).
    pub body: Option<Option<Body>>,
}

/// A clip's generated body as the renderer draws it.
#[derive(Clone, Debug)]
pub struct Body {
    /// The bind-pose mesh with its weights.
    pub mesh: Arc<SkinnedMeshData>,
    /// One inverse bind matrix per joint (file units).
    pub inverse_bind: Vec<Mat4>,
}

/// Builds the body of a clip character ([`mocap::body::build`] around
/// [`mocap::Clip::bind_pose`], tube radii by the capsule mode's
/// [`mocap_render::bone_radius`]) once; later calls do nothing.
pub fn ensure_body(c: &mut Character) {
    if c.extra.body.is_some() {
        return;
    }
    let extent = c.extent;
    let body = c.clip().and_then(|clip| {
        let skin = mocap::body::build(clip.skeleton(), &clip.bind_pose(), |length| mocap_render::body_radius(length, extent)).ok()?;
        let mesh = SkinnedMeshData::new(skin.positions(), skin.normals(), skin.joints(), skin.weights(), skin.indices().to_vec(), clip.skeleton().len()).ok()?;
        Some(Body { mesh: Arc::new(mesh), inverse_bind: skin.inverse_bind().to_vec() })
    });
    c.extra.body = Some(body);
}

/// A clip or model on the viewer's stage.
pub type Character = Actor<Look>;

/// A visible character named `name`, in the first palette colour no character in
/// `open` uses.
pub fn new_character(name: &str, asset: Asset, open: &[Character]) -> Character {
    let mut look = Look { color: next_color(open), ..Look::default() };
    match &asset {
        Asset::Clip(clip) => {
            look.figure = mocap_render::figure(clip.skeleton().joints().iter().map(|j| (j.parent, !j.is_end_site())));
            look.children = clip.skeleton().children();
        }
        Asset::Model(model) => look.mesh = mesh_data(model),
    }
    Actor::new(name, asset, look)
}

/// The renderer's copy of a model's key frames and skin.
fn mesh_data(model: &Model) -> Option<Arc<MorphMeshData>> {
    let m = &model.mesh;
    let skin = model.skin.as_ref().map(|s| SkinImage { width: s.image.width, height: s.image.height, pixels: s.image.pixels.clone() });
    MorphMeshData::from_frames(m.vertex_count(), m.positions(), m.normals(), m.tex_coords(), m.indices(), skin).ok().map(Arc::new)
}

/// Poses the character at `time`: interpolated when `smooth`, else the frame shown
/// at that time in its own frame time (the one rule of [`mocap::time`]); a model
/// not interpolating switches frames at the halfway point (Quake's nearest frame).
/// Past its end a clip holds its last pose. The transforms are in metres and placed.
pub fn pose_at(c: &mut Character, time: f64, smooth: bool, scratch: &mut PoseScratch) {
    let interpolation = match (smooth, c.model().is_some()) {
        (true, _) => Interpolation::Linear,
        (false, false) => Interpolation::Step,
        (false, true) => Interpolation::Nearest,
    };
    let mut pose = std::mem::take(&mut c.extra.pose);
    c.pose_at(time, interpolation, scratch, &mut pose);
    c.extra.pose = pose;
    c.extra.morph = c.morph_at(time, interpolation);
}

/// The first palette colour no open character uses, or the palette cycled by count.
pub fn next_color(open: &[Character]) -> [u8; 4] {
    let unused = PALETTE.iter().find(|c| !open.iter().any(|o| o.extra.color == **c));
    unused.copied().unwrap_or(PALETTE[open.len() % PALETTE.len()])
}
