//! The stored form of the model: one proxy per type that has private fields or
//! invariants, whose fields in order are the layout [`super`] writes. A proxy
//! borrows from the model when written (nothing is copied) and goes through the
//! model's own constructors when read, so what deserialises is a model that
//! holds together or an error that says what does not. Types without invariants
//! (channels, limits, warnings, the glTF summary, MD2 animations and counts) are
//! serde-derived where they are defined.
//!
//! The serde impls here are the model's only ones: JSON of a [`Clip`] goes
//! through the same checks.

use std::borrow::Cow;
use std::fmt;
use std::sync::Arc;

use glam::{Mat4, Quat, Vec3};
use serde::de::{self, DeserializeSeed, Deserializer, SeqAccess, Visitor};
use serde::ser::{SerializeSeq, Serializer};
use serde::{Deserialize, Serialize};

use crate::error::Warning;
use crate::model::asset::Asset;
use crate::model::channel::{AngleUnit, Channel};
use crate::model::character::{Character, Look, Summary, Surface, Take, TextureImage, Wrap};
use crate::model::clip::Clip;
use crate::model::mesh::{Animation, MeshParts, Model, MorphMesh, Rgba, Skin as ImageSkin, SourceCounts};
use crate::model::motion::Motion;
use crate::model::skeleton::{EulerConvention, Joint, Limit, Skeleton};
use crate::runtime::skin::{MAX_INFLUENCES, Skin};

/// `Serialize` through the proxy's `of` (borrowed), `Deserialize` through its
/// `build` (checked).
macro_rules! stored {
    ($($ty:ty => $parts:ident,)*) => {$(
        impl Serialize for $ty {
            fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
                $parts::of(self).serialize(serializer)
            }
        }

        impl<'de> Deserialize<'de> for $ty {
            fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
                $parts::deserialize(deserializer)?.build().map_err(de::Error::custom)
            }
        }
    )*};
}

stored! {
    Joint => JointParts,
    Skeleton => SkeletonParts,
    Motion => MotionParts,
    Take => TakeParts,
    Skin => SkinParts,
    Look => LookParts,
    Character => CharacterParts,
    Clip => ClipParts,
    Rgba => RgbaParts,
    ImageSkin => ImageSkinParts,
    MorphMesh => MeshStored,
    Model => ModelParts,
}

/// Prefixes an error with where it is (`skeleton: joint 3 …`).
fn within<E: fmt::Display>(what: impl fmt::Display) -> impl FnOnce(E) -> String {
    move |e| format!("{what}: {e}")
}

/// An [`Asset`] as stored: read by [`super::parse`] (the model's own
/// `Deserialize` would lose the checks' messages in postcard, which keeps no
/// custom error text). Same variants, in the same order, as [`Asset`].
#[derive(Deserialize)]
#[allow(clippy::large_enum_variant, reason = "one value per parse, unpacked at once")]
pub(super) enum AssetParts<'a> {
    /// [`Asset::Clip`].
    Clip(ClipParts<'a>),
    /// [`Asset::Model`].
    Model(ModelParts<'a>),
}

impl AssetParts<'_> {
    /// The asset, every part checked.
    pub(super) fn build(self) -> Result<Asset, String> {
        Ok(match self {
            AssetParts::Clip(c) => Asset::Clip(c.build()?),
            AssetParts::Model(m) => Asset::Model(m.build()?),
        })
    }
}

/// A [`Joint`]: its fields and whether it is an End Site (the motion columns
/// are the skeleton's to assign).
#[derive(Serialize, Deserialize)]
struct JointParts<'a> {
    name: Cow<'a, str>,
    parent: Option<usize>,
    offset: Vec3,
    rest_rotation: Quat,
    channels: Cow<'a, [Channel]>,
    limits: Cow<'a, [Limit]>,
    end_site: bool,
}

impl<'a> JointParts<'a> {
    fn of(j: &'a Joint) -> Self {
        JointParts {
            name: Cow::Borrowed(&j.name),
            parent: j.parent,
            offset: j.offset,
            rest_rotation: j.rest_rotation,
            channels: Cow::Borrowed(&j.channels),
            limits: Cow::Borrowed(&j.limits),
            end_site: j.is_end_site(),
        }
    }

    /// The joint as stored (an End Site with channels is the skeleton's to refuse).
    fn build(self) -> Result<Joint, String> {
        let mut joint = if self.end_site {
            Joint::end_site(self.name, self.parent, self.offset)
        } else {
            Joint::new(self.name, self.parent, self.offset, Vec::new())
        };
        joint.channels = self.channels.into_owned();
        Ok(joint.with_rest_rotation(self.rest_rotation).with_limits(self.limits.into_owned()))
    }
}

/// A [`Skeleton`]: its joints and Euler convention, checked by
/// [`Skeleton::new`]'s rules (rest rotations kept exactly).
#[derive(Serialize, Deserialize)]
struct SkeletonParts<'a> {
    joints: Vec<JointParts<'a>>,
    euler: EulerConvention,
}

impl<'a> SkeletonParts<'a> {
    fn of(s: &'a Skeleton) -> Self {
        SkeletonParts { joints: s.joints().iter().map(JointParts::of).collect(), euler: s.euler() }
    }

    fn build(self) -> Result<Skeleton, String> {
        let joints = self.joints.into_iter().map(JointParts::build).collect::<Result<Vec<_>, _>>()?;
        Skeleton::with_unit_rotations(joints, self.euler).map_err(|e| e.to_string())
    }
}

/// A [`Motion`]: frame time, angle unit, channel count and the rows.
#[derive(Serialize, Deserialize)]
struct MotionParts<'a> {
    frame_time: f64,
    angle_unit: AngleUnit,
    channel_count: usize,
    rows: Rows<'a>,
}

impl<'a> MotionParts<'a> {
    fn of(m: &'a Motion) -> Self {
        MotionParts {
            frame_time: m.frame_time(),
            angle_unit: m.angle_unit(),
            channel_count: m.channel_count(),
            rows: Rows {
                data: Cow::Borrowed(m.data()),
                width: m.channel_count(),
                frames: m.frame_count(),
                uneven: None,
            },
        }
    }

    fn build(self) -> Result<Motion, String> {
        let Rows { data, width, frames, uneven } = self.rows;
        if let Some((row, n)) = uneven {
            return Err(format!("row {row} has {n} values, row 0 has {width}"));
        }
        if frames > 0 && width != self.channel_count {
            return Err(format!("rows of {width} values for {} channels", self.channel_count));
        }
        Motion::new(self.frame_time, self.channel_count, frames, data.into_owned())
            .map(|m| m.with_angle_unit(self.angle_unit))
            .ok_or_else(|| format!("frame time {} s is not a positive duration", self.frame_time))
    }
}

/// A motion's matrix, stored row by row (a sequence of sequences of f32): every
/// frame takes at least its length byte, so a frame count is paid for in bytes
/// even when there are no channels. Read into one flat matrix, noting the width
/// of the first row and the first row of another width.
struct Rows<'a> {
    data: Cow<'a, [f32]>,
    width: usize,
    frames: usize,
    /// The first row whose length differs from row 0's, and its length.
    uneven: Option<(usize, usize)>,
}

impl Serialize for Rows<'_> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut seq = serializer.serialize_seq(Some(self.frames))?;
        for frame in 0..self.frames {
            let start = frame.saturating_mul(self.width);
            seq.serialize_element(self.data.get(start..start.saturating_add(self.width)).unwrap_or(&[]))?;
        }
        seq.end()
    }
}

impl<'de> Deserialize<'de> for Rows<'_> {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        deserializer.deserialize_seq(RowsVisitor)
    }
}

struct RowsVisitor;

impl<'de> Visitor<'de> for RowsVisitor {
    type Value = Rows<'static>;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("a sequence of motion rows")
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Rows<'static>, A::Error> {
        // Grown as values arrive, never reserved from a length in the input.
        let mut data = Vec::new();
        let (mut frames, mut width, mut uneven) = (0usize, 0usize, None);
        while let Some(n) = seq.next_element_seed(RowSeed(&mut data))? {
            if frames == 0 {
                width = n;
            } else if n != width && uneven.is_none() {
                uneven = Some((frames, n));
            }
            frames += 1;
        }
        Ok(Rows { data: Cow::Owned(data), width, frames, uneven })
    }
}

/// One row, appended to the matrix; its value is the row's length.
struct RowSeed<'v>(&'v mut Vec<f32>);

impl<'de> DeserializeSeed<'de> for RowSeed<'_> {
    type Value = usize;

    fn deserialize<D: Deserializer<'de>>(self, deserializer: D) -> Result<usize, D::Error> {
        deserializer.deserialize_seq(self)
    }
}

impl<'de> Visitor<'de> for RowSeed<'_> {
    type Value = usize;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("a motion row (a sequence of numbers)")
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<usize, A::Error> {
        let start = self.0.len();
        while let Some(v) = seq.next_element::<f32>()? {
            self.0.push(v);
        }
        Ok(self.0.len() - start)
    }
}

/// A [`Take`]: its name and motion.
#[derive(Serialize, Deserialize)]
struct TakeParts<'a> {
    name: Cow<'a, str>,
    motion: MotionParts<'a>,
}

impl<'a> TakeParts<'a> {
    fn of(t: &'a Take) -> Self {
        TakeParts { name: Cow::Borrowed(&t.name), motion: MotionParts::of(&t.motion) }
    }

    fn build(self) -> Result<Take, String> {
        let motion = self.motion.build().map_err(within(format_args!("`{}`: motion", self.name)))?;
        Ok(Take { name: self.name.into_owned(), motion, weights: Vec::new() })
    }
}

/// A skinned mesh ([`Skin`]): its arrays, checked by
/// [`Skin::with_inverse_bind`]'s rules (weights kept exactly).
#[derive(Serialize, Deserialize)]
struct SkinParts<'a> {
    positions: Cow<'a, [Vec3]>,
    normals: Cow<'a, [Vec3]>,
    indices: Cow<'a, [u32]>,
    joints: Cow<'a, [[u32; MAX_INFLUENCES]]>,
    weights: Cow<'a, [[f32; MAX_INFLUENCES]]>,
    inverse_bind: Cow<'a, [Mat4]>,
}

impl<'a> SkinParts<'a> {
    fn of(s: &'a Skin) -> Self {
        SkinParts {
            positions: Cow::Borrowed(s.positions()),
            normals: Cow::Borrowed(s.normals()),
            indices: Cow::Borrowed(s.indices()),
            joints: Cow::Borrowed(s.joints()),
            weights: Cow::Borrowed(s.weights()),
            inverse_bind: Cow::Borrowed(s.inverse_bind()),
        }
    }

    fn build(self) -> Result<Skin, String> {
        Skin::with_unit_weights(
            self.positions.into_owned(),
            self.normals.into_owned(),
            self.indices.into_owned(),
            self.joints.into_owned(),
            self.weights.into_owned(),
            self.inverse_bind.into_owned(),
        )
        .map_err(|e| e.to_string())
    }
}

/// A character's [`Look`]: the skin, one colour per vertex and the texture.
#[derive(Serialize, Deserialize)]
struct LookParts<'a> {
    skin: SkinParts<'a>,
    colors: Cow<'a, [[u8; 4]]>,
    surface: Option<SurfaceParts<'a>>,
}

impl<'a> LookParts<'a> {
    fn of(l: &'a Look) -> Self {
        LookParts {
            skin: SkinParts::of(&l.skin),
            colors: Cow::Borrowed(&l.colors),
            surface: l.surface.as_ref().map(SurfaceParts::of),
        }
    }

    fn build(self) -> Result<Look, String> {
        let skin = self.skin.build().map_err(within("skin"))?;
        let n = skin.positions().len();
        if self.colors.len() != n {
            return Err(format!("{} colours for {n} vertices", self.colors.len()));
        }
        let surface = self.surface.map(|s| s.build(n).map_err(within("texture"))).transpose()?;
        Ok(Look { skin, colors: self.colors.into_owned(), surface, morph: None })
    }
}

/// A look's [`Surface`]: the image (wrap modes as 0 repeat, 1 mirror, 2 clamp),
/// a coordinate and a colour per vertex.
#[derive(Serialize, Deserialize)]
struct SurfaceParts<'a> {
    width: u32,
    height: u32,
    pixels: Cow<'a, [u8]>,
    wrap: [u8; 2],
    uvs: Cow<'a, [Option<[f32; 2]>]>,
    tints: Cow<'a, [[u8; 4]]>,
}

impl<'a> SurfaceParts<'a> {
    fn of(s: &'a Surface) -> Self {
        let code = |w: Wrap| match w {
            Wrap::Repeat => 0,
            Wrap::Mirror => 1,
            Wrap::Clamp => 2,
        };
        SurfaceParts {
            width: s.image.width,
            height: s.image.height,
            pixels: Cow::Borrowed(&s.image.pixels),
            wrap: s.image.wrap.map(code),
            uvs: Cow::Borrowed(&s.uvs),
            tints: Cow::Borrowed(&s.tints),
        }
    }

    fn build(self, vertices: usize) -> Result<Surface, String> {
        let texels = u64::from(self.width) * u64::from(self.height);
        if self.width == 0 || self.height == 0 || texels.checked_mul(4) != Some(self.pixels.len() as u64) {
            return Err(format!("{} bytes for a {}×{} image", self.pixels.len(), self.width, self.height));
        }
        if self.uvs.len() != vertices || self.tints.len() != vertices {
            return Err(format!(
                "{} coordinates and {} colours for {vertices} vertices",
                self.uvs.len(),
                self.tints.len()
            ));
        }
        if self.uvs.iter().flatten().flatten().any(|x| !x.is_finite()) {
            return Err("a texture coordinate is not finite".into());
        }
        let wrap = |c: u8| match c {
            0 => Ok(Wrap::Repeat),
            1 => Ok(Wrap::Mirror),
            2 => Ok(Wrap::Clamp),
            other => Err(format!("wrap mode {other} (0, 1 or 2)")),
        };
        let image = TextureImage {
            width: self.width,
            height: self.height,
            pixels: self.pixels.into_owned(),
            wrap: [wrap(self.wrap[0])?, wrap(self.wrap[1])?],
        };
        Ok(Surface { image: std::sync::Arc::new(image), uvs: self.uvs.into_owned(), tints: self.tints.into_owned() })
    }
}

/// A [`Character`]: look, takes and summary (that they fit the clip's skeleton
/// is the clip's to check).
#[derive(Serialize, Deserialize)]
struct CharacterParts<'a> {
    look: Option<LookParts<'a>>,
    takes: Vec<TakeParts<'a>>,
    summary: Cow<'a, Summary>,
}

impl<'a> CharacterParts<'a> {
    fn of(c: &'a Character) -> Self {
        CharacterParts {
            look: c.look.as_ref().map(LookParts::of),
            takes: c.takes.iter().map(TakeParts::of).collect(),
            summary: Cow::Borrowed(&c.summary),
        }
    }

    fn build(self) -> Result<Character, String> {
        let look = self.look.map(|l| l.build().map_err(within("look"))).transpose()?;
        let takes = self
            .takes
            .into_iter()
            .enumerate()
            .map(|(i, t)| t.build().map_err(within(format_args!("take {i}"))))
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Character { look, takes, summary: self.summary.into_owned() })
    }
}

/// A [`Clip`]: skeleton, motion, warnings, metadata, character and which take
/// the motion is.
#[derive(Serialize, Deserialize)]
pub(super) struct ClipParts<'a> {
    skeleton: SkeletonParts<'a>,
    motion: MotionParts<'a>,
    warnings: Cow<'a, [Warning]>,
    metadata: Cow<'a, [(String, String)]>,
    character: Option<CharacterParts<'a>>,
    take: usize,
}

impl<'a> ClipParts<'a> {
    fn of(c: &'a Clip) -> Self {
        ClipParts {
            skeleton: SkeletonParts::of(c.skeleton()),
            motion: MotionParts::of(c.motion()),
            warnings: Cow::Borrowed(&c.warnings),
            metadata: Cow::Borrowed(&c.metadata),
            character: c.character.as_deref().map(CharacterParts::of),
            take: c.take_index(),
        }
    }

    /// The clip: the motion must fit the skeleton ([`Clip::new`]), and a
    /// character's look have one inverse bind matrix per joint and its takes the
    /// skeleton's channels; the take index must name a take (or be 0).
    fn build(self) -> Result<Clip, String> {
        let skeleton = self.skeleton.build().map_err(within("skeleton"))?;
        let motion = self.motion.build().map_err(within("motion"))?;
        let mut clip = Clip::new(skeleton, motion).map_err(|e| e.to_string())?;
        clip.warnings = self.warnings.into_owned();
        clip.metadata = self.metadata.into_owned();
        if let Some(character) = self.character {
            let character = character.build().map_err(within("character"))?;
            let (joints, width) = (clip.skeleton().len(), clip.skeleton().channel_count());
            if let Some(look) = &character.look
                && look.skin.inverse_bind().len() != joints
            {
                let n = look.skin.inverse_bind().len();
                return Err(format!("character: look: {n} inverse bind matrices for {joints} joints"));
            }
            if let Some((i, t)) = character.takes.iter().enumerate().find(|(_, t)| t.motion.channel_count() != width) {
                let n = t.motion.channel_count();
                return Err(format!("character: take {i} (`{}`): {n} channels for a skeleton with {width}", t.name));
            }
            clip = clip.with_character(Arc::new(character));
        }
        if !clip.set_take_index(self.take) {
            return Err(format!("the motion is take {} but the clip has {} takes", self.take, clip.takes().len()));
        }
        Ok(clip)
    }
}

/// An [`Rgba`] image: size and pixels (`width × height × 4` bytes).
#[derive(Serialize, Deserialize)]
struct RgbaParts<'a> {
    width: u32,
    height: u32,
    pixels: Cow<'a, [u8]>,
}

impl<'a> RgbaParts<'a> {
    fn of(r: &'a Rgba) -> Self {
        RgbaParts { width: r.width, height: r.height, pixels: Cow::Borrowed(&r.pixels) }
    }

    fn build(self) -> Result<Rgba, String> {
        let (w, h) = (self.width, self.height);
        let expected = u64::from(w).checked_mul(u64::from(h)).and_then(|n| n.checked_mul(4));
        if expected != Some(self.pixels.len() as u64) {
            return Err(format!(
                "{} bytes of pixels for a {w} × {h} image ({w} × {h} × 4 expected)",
                self.pixels.len()
            ));
        }
        Ok(Rgba { width: w, height: h, pixels: self.pixels.into_owned() })
    }
}

/// A model's skin ([`ImageSkin`]): its file name and image.
#[derive(Serialize, Deserialize)]
struct ImageSkinParts<'a> {
    name: Cow<'a, str>,
    image: RgbaParts<'a>,
}

impl<'a> ImageSkinParts<'a> {
    fn of(s: &'a ImageSkin) -> Self {
        ImageSkinParts { name: Cow::Borrowed(&s.name), image: RgbaParts::of(&s.image) }
    }

    fn build(self) -> Result<ImageSkin, String> {
        let image = self.image.build().map_err(within(format_args!("`{}`", self.name)))?;
        Ok(ImageSkin { name: self.name.into_owned(), image: Arc::new(image) })
    }
}

/// A [`MorphMesh`]: the fields a reader gives ([`MeshParts`]; the bounds are
/// computed again), checked by [`MorphMesh::checked_from_parts`].
#[derive(Serialize, Deserialize)]
struct MeshStored<'a> {
    positions: Cow<'a, [[f32; 3]]>,
    normals: Cow<'a, [[f32; 3]]>,
    tex_coords: Cow<'a, [[f32; 2]]>,
    indices: Cow<'a, [u32]>,
    sources: Cow<'a, [u32]>,
    frame_names: Cow<'a, [String]>,
    animations: Cow<'a, [Animation]>,
    skins: Cow<'a, [String]>,
    skin_size: [u32; 2],
    source_counts: SourceCounts,
}

impl<'a> MeshStored<'a> {
    fn of(m: &'a MorphMesh) -> Self {
        MeshStored {
            positions: Cow::Borrowed(m.positions()),
            normals: Cow::Borrowed(m.normals()),
            tex_coords: Cow::Borrowed(m.tex_coords()),
            indices: Cow::Borrowed(m.indices()),
            sources: Cow::Borrowed(m.sources()),
            frame_names: Cow::Borrowed(m.frame_names()),
            animations: Cow::Borrowed(m.animations()),
            skins: Cow::Borrowed(&m.skins),
            skin_size: m.skin_size,
            source_counts: m.source_counts,
        }
    }

    fn build(self) -> Result<MorphMesh, String> {
        MorphMesh::checked_from_parts(MeshParts {
            positions: self.positions.into_owned(),
            normals: self.normals.into_owned(),
            tex_coords: self.tex_coords.into_owned(),
            indices: self.indices.into_owned(),
            sources: self.sources.into_owned(),
            frame_names: self.frame_names.into_owned(),
            animations: self.animations.into_owned(),
            skins: self.skins.into_owned(),
            skin_size: self.skin_size,
            source_counts: self.source_counts,
        })
    }
}

/// A [`Model`]: mesh, skin and the animation chosen.
#[derive(Serialize, Deserialize)]
pub(super) struct ModelParts<'a> {
    mesh: MeshStored<'a>,
    skin: Option<ImageSkinParts<'a>>,
    animation: Option<usize>,
}

impl<'a> ModelParts<'a> {
    fn of(m: &'a Model) -> Self {
        ModelParts {
            mesh: MeshStored::of(&m.mesh),
            skin: m.skin.as_ref().map(ImageSkinParts::of),
            animation: m.animation(),
        }
    }

    fn build(self) -> Result<Model, String> {
        let mesh = self.mesh.build().map_err(within("mesh"))?;
        let skin = self.skin.map(|s| s.build().map_err(within("skin"))).transpose()?;
        let mut model = Model::new(mesh, skin);
        if !model.set_animation(self.animation) {
            let (i, n) = (self.animation.unwrap_or(0), model.mesh.animations().len());
            return Err(format!("animation {i} chosen but the mesh has {n}"));
        }
        Ok(model)
    }
}
