//! What an actor is drawn with: a clip's figure (bones and joints, sized once in
//! its bind pose) and its generated body (built on first use), or a model's mesh.

use mocap::glam::{Mat4, Vec3};
use mocap::{Asset, Clip, Model};
use mocap_render::wgpu::AddressMode;
use mocap_render::{FigureJoint, MorphMeshData, SkinImage, SkinnedMeshData, SkinnedTexture};
use std::sync::Arc;

/// A clip's generated body as the renderer draws it.
#[derive(Clone, Debug)]
pub struct Body {
    /// The bind-pose mesh with its weights.
    pub mesh: Arc<SkinnedMeshData>,
    /// The same body cut coarser ([`mocap::build::body::Detail::COARSE`]), for the
    /// fast look when it is small on screen ([`mocap_render::SkinnedDraw::coarse`]).
    pub coarse: Option<Arc<SkinnedMeshData>>,
    /// One inverse bind matrix per joint (file units).
    pub inverse_bind: Vec<Mat4>,
    /// The character's own look (a glTF mesh, coloured per vertex), not a
    /// generated body: drawn untinted, in every mode but sticks.
    pub own: bool,
}

/// What one actor is drawn with.
#[derive(Clone, Debug, Default)]
pub struct Drawable {
    /// Parents, joint markers and bone radii of a clip's figure (empty for a model).
    pub figure: Vec<FigureJoint>,
    /// A model's mesh on the GPU side (`None` for a clip, or a model that cannot be drawn).
    pub mesh: Option<Arc<MorphMeshData>>,
    /// The generated body of a clip, built on first use ([`Drawable::ensure_body`]):
    /// `None` not tried yet, `Some(None)` when the skeleton gets none (too many bones).
    pub body: Option<Option<Body>>,
}

impl Drawable {
    /// What `asset` is drawn with: a clip's figure with bone radii for a figure
    /// `extent` file units across ([`mocap_render::size_figure`], in the pose the
    /// body is built around), or a model's mesh. No body yet.
    pub fn of(asset: &Asset, extent: f32) -> Drawable {
        match asset {
            Asset::Clip(clip) => {
                let joints = clip.skeleton().joints();
                let mut figure = mocap_render::figure(joints.iter().map(|j| (j.parent, !j.is_end_site())));
                let bind: Vec<Vec3> = clip.bind_pose().iter().map(|t| t.translation).collect();
                mocap_render::size_figure(&mut figure, &bind, extent);
                let look = clip.character.as_ref().and_then(|c| c.look.as_ref());
                let body = look.map(|look| Body::from_look(look, clip.skeleton().len()));
                Drawable { figure, body, ..Drawable::default() }
            }
            Asset::Model(model) => Drawable { mesh: mesh_data(model), ..Drawable::default() },
        }
    }

    /// Builds the body of `clip` (an actor `extent` file units across) once; later
    /// calls do nothing. See [`body_skin`].
    pub fn ensure_body(&mut self, clip: Option<&Clip>, extent: f32) {
        if self.body.is_none() {
            self.body = Some(clip.and_then(|clip| build_body(clip, extent)));
        }
    }

    /// The body, if built and the skeleton has one.
    pub fn built_body(&self) -> Option<&Body> {
        self.body.as_ref().and_then(Option::as_ref)
    }
}

/// The generated body of a clip whose first pose is `extent` file units across:
/// [`mocap::build::body::build`] around [`mocap::Clip::bind_pose`], tube radii by
/// [`mocap_render::body_radii`] (the capsule mode's radii in that pose, thicker).
/// `None` when the skeleton gets none (too many bones).
pub fn body_skin(clip: &Clip, extent: f32) -> Option<mocap::runtime::skin::Skin> {
    body_skin_with(clip, extent, mocap::build::body::Detail::FULL)
}

/// [`body_skin`] with tubes cut as `detail` says.
fn body_skin_with(clip: &Clip, extent: f32, detail: mocap::build::body::Detail) -> Option<mocap::runtime::skin::Skin> {
    let bind = clip.bind_pose();
    let joints = clip.skeleton().joints();
    let radii =
        mocap_render::body_radii(joints.len(), |j| joints.get(j)?.parent, |j| Some(bind.get(j)?.translation), extent);
    mocap::build::body::build_with(clip.skeleton(), &bind, |j, _| radii.get(j).copied().unwrap_or(0.0), detail).ok()
}

/// The body at full detail and its coarse cut, as the renderer draws them.
fn build_body(clip: &Clip, extent: f32) -> Option<Body> {
    let skin = body_skin(clip, extent)?;
    let coarse = body_skin_with(clip, extent, mocap::build::body::Detail::COARSE);
    Body::from_skin(&skin, coarse.as_ref(), clip.skeleton().len())
}

impl Body {
    /// The renderer's copy of `skin` (and of its coarse cut, if any) for a
    /// skeleton of `joints` joints; `None` when the renderer cannot take it.
    pub fn from_skin(
        skin: &mocap::runtime::skin::Skin,
        coarse: Option<&mocap::runtime::skin::Skin>,
        joints: usize,
    ) -> Option<Body> {
        let mesh_of = |skin: &mocap::runtime::skin::Skin| {
            SkinnedMeshData::new(
                skin.positions(),
                skin.normals(),
                skin.joints(),
                skin.weights(),
                skin.indices().to_vec(),
                joints,
            )
            .ok()
        };
        let mesh = mesh_of(skin)?;
        let coarse = coarse.and_then(mesh_of).map(Arc::new);
        Some(Body { mesh: Arc::new(mesh), coarse, inverse_bind: skin.inverse_bind().to_vec(), own: false })
    }

    /// The renderer's copy of a character's own look: its vertex colours, and its
    /// base-colour texture drawn per pixel where it has one (else the colours
    /// baked from it); `None` when the renderer cannot take it.
    pub fn from_look(look: &mocap::model::character::Look, joints: usize) -> Option<Body> {
        let mut body = Body::from_skin(&look.skin, None, joints)?;
        let mut mesh = Arc::try_unwrap(body.mesh).ok()?.with_colors(&look.colors).ok()?;
        if let Some(surface) = &look.surface {
            // A texture the renderer refuses leaves the baked colours.
            let _ = mesh.set_texture(texture_of(&surface.image), &surface.uvs, &surface.tints);
        }
        body.mesh = Arc::new(mesh);
        body.own = true;
        Some(body)
    }
}

/// The renderer's copy of a look's texture image and wrap modes.
fn texture_of(image: &mocap::model::character::TextureImage) -> SkinnedTexture {
    use mocap::model::character::Wrap;
    let mode = |w: Wrap| match w {
        Wrap::Repeat => AddressMode::Repeat,
        Wrap::Mirror => AddressMode::MirrorRepeat,
        Wrap::Clamp => AddressMode::ClampToEdge,
    };
    SkinnedTexture {
        image: SkinImage { width: image.width, height: image.height, pixels: image.pixels.clone() },
        wrap: image.wrap.map(mode),
    }
}

/// The renderer's copy of a model's key frames and skin ([`MorphMeshData::from_frames`]).
pub fn mesh_data(model: &Model) -> Option<Arc<MorphMeshData>> {
    let m = &model.mesh;
    let skin = model.skin.as_ref().map(|s| SkinImage {
        width: s.image.width,
        height: s.image.height,
        pixels: s.image.pixels.clone(),
    });
    MorphMeshData::from_frames(m.vertex_count(), m.positions(), m.normals(), m.tex_coords(), m.indices(), skin)
        .ok()
        .map(Arc::new)
}
