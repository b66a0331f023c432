//! The asset store: an [`Asset`] in a compact binary file, losslessly, for the
//! page's autosave. Everything the asset carries is kept: a clip's skeleton,
//! motion, warnings and metadata, its glTF character (the look: the skinned mesh
//! and its vertex colours; the takes; the summary) and which take it plays; a
//! model's mesh, skin image and chosen animation.
//!
//! Binary:
//!
//! | bytes | what |
//! |---|---|
//! | 8 | magic `MOCAPAS1` |
//! | 4 | version, 1, or 2 when the asset has morph targets or weights (u32, little-endian) |
//! | rest | the asset in [postcard](https://docs.rs/postcard) (below); version 2: then the morph section (see `morph.rs`) |
//!
//! Postcard writes serde's data model without names: integers (`usize` too) and
//! every length as LEB128 varints, `f32`/`f64` raw little-endian, a bool or an
//! `Option`'s tag as one byte 0/1, an enum as the varint index of its variant, a
//! string or sequence as its length then its bytes or elements, a struct, tuple
//! or array as its fields in order. The asset is variant 0 (a clip) or 1 (a
//! model):
//!
//! - a **clip**: the skeleton (per joint: name, parent, offset xyz, rest rotation
//!   xyzw, channels, limits, End Site flag; then the Euler convention), the motion
//!   (frame time f64, angle unit, channel count, then the rows: one sequence of
//!   f32 per frame), the warnings (line, message), the metadata (key, value), the
//!   character (the look: positions, normals, indices, joints and weights per
//!   vertex, one inverse bind matrix per joint, colours; the takes: name and
//!   motion; the summary), and the index of the take the motion is;
//! - a **model**: the mesh (positions and normals of every frame, texture
//!   coordinates, triangle indices, source vertices, frame names, animations,
//!   skin names, skin size, source counts), the skin (file name, width, height,
//!   RGBA pixels) and the chosen animation.
//!
//! A change of this layout is a new version; [`parse`] reads versions 1 and 2.
//!
//! **Guarantees.** `parse(&write(&a)) == a`, bit for bit (a NaN in a motion
//! comes back as the same NaN, though `==` never calls NaN equal). [`parse`]
//! never panics, and allocates nothing from a length in the bytes before the
//! elements are there: nothing is reserved for a sequence longer than the bytes
//! left, and never more than 1 MiB ahead (serde's cautious size hint); each
//! element takes at least one byte, a motion's frames included (rows are stored
//! one by one), so what is built is a small multiple of the input. What decodes
//! is then checked through the model's own constructors: [`Skeleton::new`]'s
//! rules (rest rotations must be unit already, and are kept exactly),
//! [`Motion::new`], [`Clip::new`], [`Skin::with_inverse_bind`]'s rules (weights
//! must sum to 1 already), a look's colour per vertex and inverse bind matrix per
//! joint, takes as wide as the skeleton, the take index, the mesh's array
//! lengths, indices and animation ranges, `width × height × 4` skin pixels and
//! the animation index. A store that decodes but does not hold together is an
//! error, never a broken model.
//!
//! **Errors.** A [`ParseError`] `byte N: …`: the magic, the version, where the
//! postcard body stopped decoding (cut, a bad varint, an unknown variant, bad
//! UTF-8), bytes after it, or (at byte 12, the body) the first check that fails,
//! with the path to it (`character: take 2 (`walk`): 57 channels for a skeleton
//! with 69`).
//!
//! ```
//! let bvh = b"HIERARCHY\nROOT Hips\n{\n OFFSET 0 0 0\n CHANNELS 3 Xposition Yposition Zposition\n End Site\n {\n  OFFSET 0 1 0\n }\n}\nMOTION\nFrames: 1\nFrame Time: 0.5\n1 2 3\n";
//! let asset = mocap::Asset::Clip(mocap::formats::bvh::parse(bvh).unwrap());
//! let stored = mocap::formats::store::write(&asset);
//! assert!(stored.starts_with(mocap::formats::store::MAGIC));
//! assert_eq!(mocap::formats::store::parse(&stored).unwrap(), asset);
//! let e = mocap::formats::store::parse(&stored[..stored.len() - 1]).unwrap_err();
//! assert!(e.message.starts_with("byte "), "{e}");
//! ```
//!
//! [`Skeleton::new`]: crate::Skeleton::new
//! [`Motion::new`]: crate::Motion::new
//! [`Clip::new`]: crate::Clip::new
//! [`Skin::with_inverse_bind`]: crate::runtime::skin::Skin::with_inverse_bind

mod morph;
mod parts;

use crate::error::ParseError;
use crate::model::asset::Asset;
use serde::Deserialize;

/// The file's first eight bytes.
pub const MAGIC: &[u8; 8] = b"MOCAPAS1";

/// The layout of an asset without morph targets nor weights.
const VERSION: u32 = 1;

/// The same followed by the morph section.
const VERSION_MORPH: u32 = 2;

/// Bytes before the postcard body: magic and version.
const HEADER: usize = 12;

/// Serialises an asset (a clip with everything it carries: skeleton, motion,
/// warnings, metadata, its glTF character (look = runtime::skin::Skin + vertex
/// colours, takes, summary) and take index; or an MD2 model: its MorphMesh,
/// skin image and chosen animation) losslessly: parse(write(a)) == a
/// (PartialEq), bit for bit.
pub fn write(asset: &Asset) -> Vec<u8> {
    let section = morph::MorphSection::of(asset);
    let version = if section.is_some() { VERSION_MORPH } else { VERSION };
    let mut out = Vec::with_capacity(HEADER + 64);
    out.extend_from_slice(MAGIC);
    out.extend_from_slice(&version.to_le_bytes());
    // Postcard refuses only sequences of unknown length, and every sequence of
    // the stored form has its length.
    let out = postcard::to_extend(asset, out).expect("every sequence of the stored form has a known length");
    match section {
        Some(section) => postcard::to_extend(&section, out).expect("every sequence of the section has a known length"),
        None => out,
    }
}

/// Reads what `write` wrote. Never panics, never allocates from a count in the
/// bytes beyond what the bytes can hold; every invariant of the model is checked
/// again through the model's own validating constructors (see the module
/// documentation): corrupt or hostile bytes are a [`ParseError`] (`byte N: …`)
/// with a clear message, never a broken model.
pub fn parse(bytes: &[u8]) -> Result<Asset, ParseError> {
    if bytes.get(..MAGIC.len()) != Some(MAGIC.as_slice()) {
        return Err(ParseError::at_byte(0, "not a stored asset (it does not start with MOCAPAS1)"));
    }
    let Some(version) = bytes.get(MAGIC.len()..HEADER) else {
        return Err(ParseError::at_byte(MAGIC.len(), "the file ends before its version (4 bytes)"));
    };
    let version = u32::from_le_bytes([version[0], version[1], version[2], version[3]]);
    if version != VERSION && version != VERSION_MORPH {
        return Err(ParseError::at_byte(
            MAGIC.len(),
            format!("version {version}: this reader reads versions {VERSION} and {VERSION_MORPH}"),
        ));
    }
    let body = bytes.get(HEADER..).unwrap_or(&[]);
    let mut de = postcard::Deserializer::from_flavor(Tracked { bytes: body, at: 0 });
    let parts = parts::AssetParts::deserialize(&mut de);
    let end = de.finalize().unwrap_or(0);
    let parts = parts
        .map_err(|e| ParseError::at_byte(HEADER + end, format!("the stored asset is cut or damaged here: {e}")))?;
    let (section, end) = if version == VERSION_MORPH {
        let mut de = postcard::Deserializer::from_flavor(Tracked { bytes: body, at: end });
        let section = morph::MorphSection::deserialize(&mut de);
        let after = de.finalize().unwrap_or(end);
        let section = section
            .map_err(|e| ParseError::at_byte(HEADER + after, format!("the stored morph targets are cut or damaged here: {e}")))?;
        (Some((section, end)), after)
    } else {
        (None, end)
    };
    if end != body.len() {
        return Err(ParseError::at_byte(
            HEADER + end,
            format!("{} bytes after the end of the stored asset", body.len() - end),
        ));
    }
    let mut asset =
        parts.build().map_err(|e| ParseError::at_byte(HEADER, format!("the stored asset does not hold together: {e}")))?;
    if let Some((section, at)) = section {
        section
            .apply(&mut asset)
            .map_err(|e| ParseError::at_byte(HEADER + at, format!("the stored morph targets do not hold together: {e}")))?;
    }
    Ok(asset)
}

/// Postcard's input: a slice and how far into it decoding has come (so an error
/// can say where). Its remainder is that position.
struct Tracked<'de> {
    bytes: &'de [u8],
    at: usize,
}

impl<'de> postcard::de_flavors::Flavor<'de> for Tracked<'de> {
    type Remainder = usize;
    type Source = &'de [u8];

    fn pop(&mut self) -> postcard::Result<u8> {
        let byte = *self.bytes.get(self.at).ok_or(postcard::Error::DeserializeUnexpectedEnd)?;
        self.at += 1;
        Ok(byte)
    }

    fn size_hint(&self) -> Option<usize> {
        Some(self.bytes.len() - self.at)
    }

    fn try_take_n(&mut self, ct: usize) -> postcard::Result<&'de [u8]> {
        let end = self.at.checked_add(ct).ok_or(postcard::Error::DeserializeUnexpectedEnd)?;
        let taken = self.bytes.get(self.at..end).ok_or(postcard::Error::DeserializeUnexpectedEnd)?;
        self.at = end;
        Ok(taken)
    }

    fn finalize(self) -> postcard::Result<usize> {
        Ok(self.at)
    }
}
