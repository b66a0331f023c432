//! Quake 2 MD2 models: a pure [`parse`] from bytes to an [`Md2`] (vertex-animated
//! triangle mesh: skins, texture coordinates, triangles and key frames).
//!
//! The reader validates the whole 68-byte header before it reads anything else:
//! ident `IDP2`, version 8, no negative count or offset, at least one vertex and one
//! frame, `framesize == 40 + 4 · num_xyz`, and every section (`offset + count · size`,
//! in checked arithmetic) inside the file. Nothing is allocated from a count in the
//! file before that count is known to fit in the bytes, so a header that claims a
//! million frames in a 10 KB file fails at once. Then every triangle's vertex and
//! texture-coordinate index is checked against its count, every normal index against
//! the 162-entry [`NORMALS`] table, every name for its NUL terminator, and every frame's
//! scale and translation for being finite. The OpenGL command list is not decoded,
//! but its offset and size must still lie inside the file. Bytes past the sections
//! (and past `ofs_end`) are ignored.
//!
//! **Errors.** A malformed file gives a [`ParseError`] whose message starts with the
//! 0-based byte offset of the offending field (`byte 56: ofs_frames 9999 + 1 frames ×
//! 1240 bytes (num_frames) runs past the end of the file (256 bytes)`). Binary files have no lines:
//! the error's `line` is always 1 and its `column` the same offset, 1-based. The
//! caller adds the file name.
//!
//! **Axes.** Quake is Z-up; this crate is Y-up. Decoded positions and normals
//! ([`Md2::frame_positions`], [`Md2::frame_normals`], [`to_y_up`]) are rotated by −90°
//! about X: `(x, y, z)` in Quake becomes `(x, z, −y)`. That is a proper rotation (it
//! keeps handedness), so Quake's up (+Z) becomes +Y and a model that faces +X in Quake
//! (the convention for players and monsters) still faces +X. The raw packed vertices in
//! [`Frame::vertices`] stay in Quake's axes. Units are the file's (Quake units, a
//! player is about 56 tall).
//!
//! **Animations.** MD2 has no animation list: frames are named, and consecutive frames
//! that share a base name ([`animation_base_name`]) form one [`Animation`]
//! ([`group_animations`]).
//!
//! ```
//! // Not an MD2 file at all:
//! assert!(!mocap::formats::md2::sniff(b"HIERARCHY"));
//! let e = mocap::formats::md2::parse(b"IDP2\x07\0\0\0").unwrap_err();
//! assert!(e.message.starts_with("byte 4:"), "{e}");
//! ```

mod mesh;
mod normals;
#[cfg(test)]
mod tests;
pub(crate) mod write;

/// A named run of frames: the model's own type, which frame names group into
/// ([`group_animations`]: the base name is [`animation_base_name`]).
pub use crate::model::mesh::Animation;
pub use normals::NORMALS;
pub use write::{WriteError, build, from_y_up, pack_frame, write};

use crate::error::ParseError;

/// The four bytes every MD2 file starts with.
pub const IDENT: &[u8; 4] = b"IDP2";

/// The only MD2 version there is.
pub const VERSION: i32 = 8;

/// Size of the MD2 header in bytes.
pub const HEADER_SIZE: usize = 68;

/// Bytes of a skin name record (NUL-terminated within it).
pub const SKIN_NAME_SIZE: usize = 64;

/// Bytes of a frame name (NUL-terminated within it).
pub const FRAME_NAME_SIZE: usize = 16;

/// Bytes of a frame before its vertices: scale, translate (3 × f32 each) and the name.
pub const FRAME_HEADER_SIZE: usize = 24 + FRAME_NAME_SIZE;

/// A triangle: indices into the frame vertices and into the texture coordinates.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Triangle {
    /// Indices into every frame's [`Frame::vertices`] (all `< Md2::vertex_count`).
    pub vertices: [u16; 3],
    /// Indices into [`Md2::tex_coords`] (all in range).
    pub tex_coords: [u16; 3],
}

/// One key frame: packed vertex positions and normal indices.
#[derive(Clone, Debug, PartialEq)]
pub struct Frame {
    /// The frame's name (`stand01`, `run3`, …), up to its NUL terminator.
    pub name: String,
    /// Per-axis scale of the packed coordinates (Quake axes, finite).
    pub scale: [f32; 3],
    /// Per-axis offset added after scaling (Quake axes, finite).
    pub translate: [f32; 3],
    /// Packed vertices `[x, y, z, normal index]`: position `translate + scale · xyz` in
    /// Quake axes, and an index into [`NORMALS`] (always `< 162`).
    pub vertices: Vec<[u8; 4]>,
}

/// A parsed MD2 model.
#[derive(Clone, Debug, PartialEq)]
pub struct Md2 {
    /// Skin width in pixels, as the header gives it (texture coordinates are in pixels).
    pub skin_width: u32,
    /// Skin height in pixels, as the header gives it.
    pub skin_height: u32,
    /// Skin file names (often Quake paths such as `models/monsters/x/skin.pcx`); may be
    /// empty.
    pub skins: Vec<String>,
    /// Texture coordinates `[s, t]` in skin pixels.
    pub tex_coords: Vec<[i16; 2]>,
    /// The triangles (every index checked).
    pub triangles: Vec<Triangle>,
    /// The key frames (at least one), each with [`Md2::vertex_count`] vertices.
    pub frames: Vec<Frame>,
    /// Named animations from the frame names, in file order (at least one).
    pub animations: Vec<Animation>,
    /// Vertices per frame (at least one).
    pub vertex_count: usize,
}

/// Whether `bytes` look like an MD2 file (they start with `IDP2`).
pub fn sniff(bytes: &[u8]) -> bool {
    bytes.starts_with(IDENT)
}

/// Converts a vector from Quake's Z-up axes to this crate's Y-up axes: `(x, y, z)` →
/// `(x, z, −y)`, a rotation of −90° about X.
pub fn to_y_up(v: [f32; 3]) -> [f32; 3] {
    [v[0], v[2], -v[1]]
}

/// The animation a frame name belongs to: the name without its trailing digits, except
/// that when three or more digits end the name the first of them is kept (Quake's
/// `pain101`…`pain104`, `pain201`… are the animations `pain1`, `pain2`). So `run1` →
/// `run`, `stand01` → `stand`, `crattak1` → `crattak`, `pain101` → `pain1`, `jump` →
/// `jump`. A name that is all digits (or empty) is its own base.
pub fn animation_base_name(name: &str) -> &str {
    let stem = name.trim_end_matches(|c: char| c.is_ascii_digit());
    let digits = name.len() - stem.len();
    let base = if digits >= 3 { &name[..stem.len() + 1] } else { stem };
    if base.is_empty() { name } else { base }
}

/// Groups frame names into animations: consecutive frames with the same
/// [`animation_base_name`] form one entry (first and last frame index, in file order);
/// a base name that reappears after another one starts a new entry.
///
/// ```
/// use mocap::formats::md2::{group_animations, Animation};
/// let names = ["stand01", "stand02", "run1", "run2", "pain101", "pain201", "run3"];
/// let a = group_animations(names);
/// let got: Vec<_> = a.iter().map(|a| (a.name.as_str(), a.first, a.last)).collect();
/// assert_eq!(got, [("stand", 0, 1), ("run", 2, 3), ("pain1", 4, 4), ("pain2", 5, 5), ("run", 6, 6)]);
/// ```
pub fn group_animations<'a>(names: impl IntoIterator<Item = &'a str>) -> Vec<Animation> {
    let mut out: Vec<Animation> = Vec::new();
    for (i, name) in names.into_iter().enumerate() {
        let base = animation_base_name(name);
        match out.last_mut() {
            Some(last) if last.name == base && last.last + 1 == i => last.last = i,
            _ => out.push(Animation { name: base.to_string(), first: i, last: i }),
        }
    }
    out
}

fn err(offset: usize, message: impl std::fmt::Display) -> ParseError {
    ParseError::at_byte(offset, message)
}

fn i32_at(bytes: &[u8], offset: usize) -> i32 {
    i32::from_le_bytes(bytes[offset..offset + 4].try_into().expect("4 bytes"))
}

fn u16_at(bytes: &[u8], offset: usize) -> u16 {
    u16::from_le_bytes(bytes[offset..offset + 2].try_into().expect("2 bytes"))
}

fn f32_at(bytes: &[u8], offset: usize) -> f32 {
    f32::from_le_bytes(bytes[offset..offset + 4].try_into().expect("4 bytes"))
}

/// The NUL-terminated string at the start of `field`, or `None` without a NUL.
fn c_string(field: &[u8]) -> Option<String> {
    let end = field.iter().position(|&b| b == 0)?;
    Some(String::from_utf8_lossy(&field[..end]).into_owned())
}

/// The header fields, in file order, with their names for messages.
const FIELDS: [&str; 16] = [
    "version",
    "skinwidth",
    "skinheight",
    "framesize",
    "num_skins",
    "num_xyz",
    "num_st",
    "num_tris",
    "num_glcmds",
    "num_frames",
    "ofs_skins",
    "ofs_st",
    "ofs_tris",
    "ofs_frames",
    "ofs_glcmds",
    "ofs_end",
];

/// Byte offset of header field `i` (of [`FIELDS`]).
const fn field_offset(i: usize) -> usize {
    4 + 4 * i
}

struct Header {
    skin_width: usize,
    skin_height: usize,
    frame_size: usize,
    num_skins: usize,
    num_xyz: usize,
    num_st: usize,
    num_tris: usize,
    num_frames: usize,
    ofs_skins: usize,
    ofs_st: usize,
    ofs_tris: usize,
    ofs_frames: usize,
}

fn header(bytes: &[u8]) -> Result<Header, ParseError> {
    let len = bytes.len();
    if len < 4 || !sniff(bytes) {
        let got = &bytes[..len.min(4)];
        return Err(err(
            0,
            format!("not an MD2 file: it starts with {:?}, not \"IDP2\"", String::from_utf8_lossy(got)),
        ));
    }
    if len >= 8 {
        let version = i32_at(bytes, 4);
        if version != VERSION {
            return Err(err(4, format!("MD2 version {version}, expected {VERSION}")));
        }
    }
    if len < HEADER_SIZE {
        return Err(err(len, format!("the file ends inside the {HEADER_SIZE}-byte MD2 header (it has {len} bytes)")));
    }
    let mut v = [0usize; 16];
    for (i, name) in FIELDS.iter().enumerate().skip(1) {
        let value = i32_at(bytes, field_offset(i));
        v[i] = usize::try_from(value)
            .map_err(|_| err(field_offset(i), format!("{name} is {value}, which is negative")))?;
    }
    let h = Header {
        skin_width: v[1],
        skin_height: v[2],
        frame_size: v[3],
        num_skins: v[4],
        num_xyz: v[5],
        num_st: v[6],
        num_tris: v[7],
        num_frames: v[9],
        ofs_skins: v[10],
        ofs_st: v[11],
        ofs_tris: v[12],
        ofs_frames: v[13],
    };
    let (num_glcmds, ofs_glcmds, ofs_end) = (v[8], v[14], v[15]);
    if h.num_xyz == 0 {
        return Err(err(field_offset(5), "num_xyz is 0: the model has zero vertices"));
    }
    if h.num_frames == 0 {
        return Err(err(field_offset(9), "num_frames is 0: the model has no frames"));
    }
    let expected = (h.num_xyz as u64).checked_mul(4).and_then(|n| n.checked_add(FRAME_HEADER_SIZE as u64));
    if expected != Some(h.frame_size as u64) {
        return Err(err(
            field_offset(3),
            format!(
                "framesize is {} bytes but {} vertices need {} (40 + 4 × num_xyz)",
                h.frame_size,
                h.num_xyz,
                expected.map_or("more than 2^64".to_string(), |n| n.to_string())
            ),
        ));
    }
    if ofs_end > len {
        return Err(err(
            field_offset(15),
            format!("ofs_end is {ofs_end} but the file has only {len} bytes: it is truncated"),
        ));
    }
    let sections = [
        (10, 4, h.ofs_skins, h.num_skins, SKIN_NAME_SIZE, "skins"),
        (11, 6, h.ofs_st, h.num_st, 4, "texture coordinates"),
        (12, 7, h.ofs_tris, h.num_tris, 12, "triangles"),
        (13, 9, h.ofs_frames, h.num_frames, h.frame_size, "frames"),
        (14, 8, ofs_glcmds, num_glcmds, 4, "GL command words"),
    ];
    for (ofs_field, count_field, ofs, count, size, what) in sections {
        let end = (count as u64).checked_mul(size as u64).and_then(|n| n.checked_add(ofs as u64));
        if end.is_none_or(|end| end > len as u64) {
            return Err(err(
                field_offset(ofs_field),
                format!(
                    "{} {ofs} + {count} {what} × {size} bytes ({}) runs past the end of the file ({len} bytes)",
                    FIELDS[ofs_field], FIELDS[count_field],
                ),
            ));
        }
    }
    Ok(h)
}

/// Reads an MD2 model from its bytes. See the [module documentation](self) for what is
/// checked and how errors are reported.
pub fn parse(bytes: &[u8]) -> Result<Md2, ParseError> {
    let h = header(bytes)?;

    let mut skins = Vec::with_capacity(h.num_skins);
    for i in 0..h.num_skins {
        let at = h.ofs_skins + i * SKIN_NAME_SIZE;
        let name = c_string(&bytes[at..at + SKIN_NAME_SIZE]).ok_or_else(|| {
            err(at, format!("skin {i}'s name has no NUL terminator within its {SKIN_NAME_SIZE} bytes"))
        })?;
        skins.push(name);
    }

    let tex_coords = (0..h.num_st)
        .map(|i| {
            let at = h.ofs_st + 4 * i;
            [u16_at(bytes, at) as i16, u16_at(bytes, at + 2) as i16]
        })
        .collect();

    let mut triangles = Vec::with_capacity(h.num_tris);
    for i in 0..h.num_tris {
        let at = h.ofs_tris + 12 * i;
        let index = |k: usize| u16_at(bytes, at + 2 * k);
        let tri = Triangle { vertices: [index(0), index(1), index(2)], tex_coords: [index(3), index(4), index(5)] };
        for k in 0..3 {
            if usize::from(tri.vertices[k]) >= h.num_xyz {
                return Err(err(
                    at + 2 * k,
                    format!("triangle {i} uses vertex {} but the model has {} vertices", tri.vertices[k], h.num_xyz),
                ));
            }
            if usize::from(tri.tex_coords[k]) >= h.num_st {
                return Err(err(
                    at + 6 + 2 * k,
                    format!(
                        "triangle {i} uses texture coordinate {} but the model has {} texture coordinates",
                        tri.tex_coords[k], h.num_st
                    ),
                ));
            }
        }
        triangles.push(tri);
    }

    let mut frames = Vec::with_capacity(h.num_frames);
    for i in 0..h.num_frames {
        let at = h.ofs_frames + i * h.frame_size;
        let name_at = at + 24;
        let name = c_string(&bytes[name_at..name_at + FRAME_NAME_SIZE]).ok_or_else(|| {
            err(name_at, format!("frame {i}'s name has no NUL terminator within its {FRAME_NAME_SIZE} bytes"))
        })?;
        let vec3 = |o: usize| [f32_at(bytes, o), f32_at(bytes, o + 4), f32_at(bytes, o + 8)];
        let (scale, translate) = (vec3(at), vec3(at + 12));
        for (what, value, o) in [("scale", scale, at), ("translate", translate, at + 12)] {
            if !value.iter().all(|c| c.is_finite()) {
                return Err(err(o, format!("frame {i} ({name:?}) has a non-finite {what} {value:?}")));
            }
        }
        let first = at + FRAME_HEADER_SIZE;
        let vertices: Vec<[u8; 4]> =
            bytes[first..first + 4 * h.num_xyz].chunks_exact(4).map(|c| [c[0], c[1], c[2], c[3]]).collect();
        if let Some(v) = vertices.iter().position(|v| usize::from(v[3]) >= NORMALS.len()) {
            return Err(err(
                first + 4 * v + 3,
                format!(
                    "frame {i} ({name:?}) vertex {v} has normal index {}, past the last entry (161) of the Quake 2 normal table",
                    vertices[v][3]
                ),
            ));
        }
        frames.push(Frame { name, scale, translate, vertices });
    }

    let animations = group_animations(frames.iter().map(|f| f.name.as_str()));
    Ok(Md2 {
        skin_width: h.skin_width as u32,
        skin_height: h.skin_height as u32,
        skins,
        tex_coords,
        triangles,
        frames,
        animations,
        vertex_count: h.num_xyz,
    })
}

impl Frame {
    /// Position of vertex `v` in Quake's axes (file units): `translate + scale · xyz`.
    ///
    /// Panics if `v` is out of range.
    pub fn quake_position(&self, v: usize) -> [f32; 3] {
        let p = self.vertices[v];
        [0, 1, 2].map(|k| self.translate[k] + self.scale[k] * f32::from(p[k]))
    }
}

impl Md2 {
    /// Decoded positions of frame `frame` (Y-up, see [`to_y_up`]; file units), one per
    /// vertex, into `out` (cleared first).
    ///
    /// Panics if `frame >= self.frames.len()`.
    pub fn frame_positions(&self, frame: usize, out: &mut Vec<[f32; 3]>) {
        let f = &self.frames[frame];
        out.clear();
        out.extend((0..f.vertices.len()).map(|v| to_y_up(f.quake_position(v))));
    }

    /// Positions between frames `a` and `b` (Y-up, file units): `pa + (pb − pa) · t`, per
    /// vertex, into `out` (cleared first). `t` is normally in `[0, 1]` and is not clamped.
    ///
    /// Panics if `a` or `b` is out of range, or if a frame has fewer than
    /// [`Md2::vertex_count`] vertices (never the case for a parsed model).
    pub fn interpolated_positions(&self, a: usize, b: usize, t: f32, out: &mut Vec<[f32; 3]>) {
        let (fa, fb) = (&self.frames[a], &self.frames[b]);
        out.clear();
        out.extend((0..self.vertex_count).map(|v| {
            let (pa, pb) = (fa.quake_position(v), fb.quake_position(v));
            to_y_up([0, 1, 2].map(|k| pa[k] + (pb[k] - pa[k]) * t))
        }));
    }

    /// Per-vertex unit normals of frame `frame` from the [`NORMALS`] table (Y-up), into
    /// `out` (cleared first).
    ///
    /// Panics if `frame >= self.frames.len()`.
    pub fn frame_normals(&self, frame: usize, out: &mut Vec<[f32; 3]>) {
        out.clear();
        out.extend(self.frames[frame].vertices.iter().map(|v| to_y_up(NORMALS[usize::from(v[3])])));
    }

    /// Height of frame 0 in file units: the extent of its vertices along Y (Quake's Z),
    /// for guessing the unit (a Quake 2 player is about 56 units tall).
    ///
    /// Panics if there are no frames (never the case for a parsed model).
    pub fn height(&self) -> f32 {
        let f = &self.frames[0];
        let (lo, hi) = (0..f.vertices.len())
            .map(|v| f.quake_position(v)[2])
            .fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), z| (lo.min(z), hi.max(z)));
        if hi >= lo { hi - lo } else { 0.0 }
    }

    /// The animation that contains frame `frame`, if any.
    pub fn animation_of(&self, frame: usize) -> Option<&Animation> {
        self.animations.iter().find(|a| a.first <= frame && frame <= a.last)
    }
}
