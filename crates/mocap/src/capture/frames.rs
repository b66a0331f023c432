//! The source's per-frame layout of a capture: for every frame its name, each
//! bone's translation and each bone's rotation in radians, as doubles.
//!
//! Binary, little-endian:
//!
//! | bytes | what |
//! |---|---|
//! | 8 | magic `MOCAPCF1` |
//! | 4 | bone count `B` (u32) |
//! | 4 | frame count `F` (u32) |
//! | `B` × 32 | bone names, NUL-padded (the joint names of the rig) |
//! | `F` × (16 + 48 `B`) | frames: the frame name (16 bytes, NUL-padded, as in MD2), then `B` translations (x, y, z: f64), then `B` rotations (x, y, z: f64) |
//!
//! Axes as in the source: X right, Y up, Z away from the viewer (so Z is the
//! negated Z of this crate's Y-up axes). A translation is the joint's position
//! in model units; a rotation is the joint's turn from the set-up pose, as angles
//! `(x, y, z)` in radians with the turn `Rx(x) · Ry(y) · Rz(z)` in those axes.
//!
//! [`parse`] checks the magic, the counts against the length (before any
//! allocation) and every name's terminator, and reports the byte offset of what
//! is wrong.

use crate::formats::md2::write::name_field;
use glam::{EulerRot, Mat3, Quat, Vec3};

/// The file's first eight bytes.
pub const MAGIC: &[u8; 8] = b"MOCAPCF1";
/// Bytes of a bone name.
pub const BONE_NAME: usize = 32;
/// Bytes of a frame name.
pub const FRAME_NAME: usize = 16;

/// One frame of the layout.
#[derive(Clone, Debug, PartialEq)]
pub struct FrameRecord {
    /// The frame's name.
    pub name: String,
    /// Per bone: its position (X right, Y up, Z away).
    pub translations: Vec<[f64; 3]>,
    /// Per bone: its rotation, radians (see the module documentation).
    pub rotations: Vec<[f64; 3]>,
}

/// A capture in the per-frame layout.
#[derive(Clone, Debug, PartialEq)]
pub struct CaptureFrames {
    /// Bone names.
    pub bones: Vec<String>,
    /// The frames.
    pub frames: Vec<FrameRecord>,
}

/// Why bytes are not a capture in this layout.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("byte {offset}: {message}")]
pub struct FramesError {
    /// Where.
    pub offset: usize,
    /// What.
    pub message: String,
}

/// Flips Z (Y-up right-handed ↔ the source's Z away from the viewer).
const FLIP: Mat3 = Mat3::from_cols(Vec3::X, Vec3::Y, Vec3::NEG_Z);

impl FrameRecord {
    /// A record from positions and rotations in this crate's Y-up axes.
    pub fn from_y_up(name: String, positions: &[Vec3], rotations: &[Quat]) -> FrameRecord {
        let translations = positions.iter().map(|p| [f64::from(p.x), f64::from(p.y), -f64::from(p.z)]).collect();
        let rotations = rotations
            .iter()
            .map(|q| {
                let m = FLIP * Mat3::from_quat(*q) * FLIP;
                let (x, y, z) = Quat::from_mat3(&m).to_euler(EulerRot::XYZ);
                [f64::from(x), f64::from(y), f64::from(z)]
            })
            .collect();
        FrameRecord { name, translations, rotations }
    }

    /// Bone `b`'s position and rotation back in Y-up axes.
    pub fn to_y_up(&self, b: usize) -> Option<(Vec3, Quat)> {
        let t = self.translations.get(b)?;
        let r = self.rotations.get(b)?;
        let q = Quat::from_euler(EulerRot::XYZ, r[0] as f32, r[1] as f32, r[2] as f32);
        let m = FLIP * Mat3::from_quat(q) * FLIP;
        Some((Vec3::new(t[0] as f32, t[1] as f32, -t[2] as f32), Quat::from_mat3(&m)))
    }
}

/// The bytes of `capture` (names longer than their field are cut).
pub fn write(capture: &CaptureFrames) -> Vec<u8> {
    let b = capture.bones.len();
    let mut out = Vec::with_capacity(16 + BONE_NAME * b + capture.frames.len() * (FRAME_NAME + 48 * b));
    out.extend_from_slice(MAGIC);
    out.extend_from_slice(&(b as u32).to_le_bytes());
    out.extend_from_slice(&(capture.frames.len() as u32).to_le_bytes());
    for name in &capture.bones {
        name_field(name, BONE_NAME, &mut out);
    }
    for f in &capture.frames {
        name_field(&f.name, FRAME_NAME, &mut out);
        for k in 0..b {
            for v in f.translations.get(k).copied().unwrap_or_default() {
                out.extend_from_slice(&v.to_le_bytes());
            }
        }
        for k in 0..b {
            for v in f.rotations.get(k).copied().unwrap_or_default() {
                out.extend_from_slice(&v.to_le_bytes());
            }
        }
    }
    out
}

fn fail<T>(offset: usize, message: impl Into<String>) -> Result<T, FramesError> {
    Err(FramesError { offset, message: message.into() })
}

fn name_at(bytes: &[u8], at: usize, size: usize, what: &str) -> Result<String, FramesError> {
    let field = &bytes[at..at + size];
    let end = field
        .iter()
        .position(|&c| c == 0)
        .map_or_else(|| fail(at, format!("{what} has no NUL within its {size} bytes")), Ok)?;
    Ok(String::from_utf8_lossy(&field[..end]).into_owned())
}

fn u32_at(bytes: &[u8], at: usize) -> u32 {
    u32::from_le_bytes([bytes[at], bytes[at + 1], bytes[at + 2], bytes[at + 3]])
}

fn f64_at(bytes: &[u8], at: usize) -> f64 {
    let mut b = [0u8; 8];
    b.copy_from_slice(&bytes[at..at + 8]);
    f64::from_le_bytes(b)
}

/// Reads a capture in this layout (see the module documentation).
pub fn parse(bytes: &[u8]) -> Result<CaptureFrames, FramesError> {
    if bytes.len() < 16 || &bytes[..8] != MAGIC {
        return fail(0, "not a capture in the per-frame layout (it does not start with MOCAPCF1 and two counts)");
    }
    let (b, f) = (u32_at(bytes, 8) as u64, u32_at(bytes, 12) as u64);
    let record = FRAME_NAME as u64 + 48 * b;
    let need = record.checked_mul(f).and_then(|r| r.checked_add(16 + BONE_NAME as u64 * b));
    if need != Some(bytes.len() as u64) {
        let need = need.map_or("more than 2^64".to_owned(), |n| n.to_string());
        return fail(8, format!("{b} bones and {f} frames need {need} bytes, the file has {}", bytes.len()));
    }
    let (b, f, record) = (b as usize, f as usize, record as usize);
    let mut bones = Vec::with_capacity(b);
    for k in 0..b {
        bones.push(name_at(bytes, 16 + BONE_NAME * k, BONE_NAME, &format!("bone {k}'s name"))?);
    }
    let first = 16 + BONE_NAME * b;
    let mut frames = Vec::with_capacity(f);
    for i in 0..f {
        let at = first + record * i;
        let name = name_at(bytes, at, FRAME_NAME, &format!("frame {i}'s name"))?;
        let triple = |o: usize| [f64_at(bytes, o), f64_at(bytes, o + 8), f64_at(bytes, o + 16)];
        let translations: Vec<[f64; 3]> = (0..b).map(|k| triple(at + FRAME_NAME + 24 * k)).collect();
        let rotations: Vec<[f64; 3]> = (0..b).map(|k| triple(at + FRAME_NAME + 24 * b + 24 * k)).collect();
        if let Some(k) = translations.iter().chain(&rotations).position(|t| !t.iter().all(|x| x.is_finite())) {
            return fail(at + FRAME_NAME + 24 * k, format!("frame {i} ({name:?}) has a value that is not finite"));
        }
        frames.push(FrameRecord { name, translations, rotations });
    }
    Ok(CaptureFrames { bones, frames })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_trips_and_converts_axes() {
        let q = Quat::from_euler(EulerRot::YXZ, 0.3, -0.4, 0.5);
        let rec = FrameRecord::from_y_up("run1".into(), &[Vec3::new(1.0, 2.0, 3.0)], &[q]);
        assert_eq!(rec.translations[0], [1.0, 2.0, -3.0]);
        let (p, back) = rec.to_y_up(0).unwrap();
        assert_eq!(p, Vec3::new(1.0, 2.0, 3.0));
        assert!(back.dot(q).abs() > 0.99999, "{back} vs {q}");
        let c = CaptureFrames {
            bones: vec!["Hips".into()],
            frames: vec![rec.clone(), FrameRecord { name: "run2".into(), ..rec }],
        };
        let bytes = write(&c);
        assert_eq!(bytes.len(), 16 + 32 + 2 * (16 + 48));
        assert_eq!(parse(&bytes).unwrap(), c);
        assert_eq!(parse(&bytes[..bytes.len() - 1]).unwrap_err().offset, 8);
        assert_eq!(
            parse(b"MOCAPCF1\xff\xff\xff\xff\xff\xff\xff\xff").unwrap_err().offset,
            8,
            "huge counts are refused before allocating"
        );
        assert_eq!(parse(b"nope").unwrap_err().offset, 0);
        let mut bad = bytes.clone();
        bad[16..48].fill(b'a');
        assert!(parse(&bad).unwrap_err().message.contains("bone 0's name"));
    }
}
