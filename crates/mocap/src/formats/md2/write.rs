//! Writing MD2: [`write`] turns an [`Md2`] into the bytes [`super::parse`] reads
//! back as the same model, and [`build`] packs float vertex frames (Y-up, file
//! units) into one: each frame gets its own scale and translation (its bounds over
//! 255 steps per axis), each vertex the nearest of the 162 Quake normals.
//!
//! ```
//! use mocap::glam::Vec3;
//! let frame = vec![Vec3::ZERO, Vec3::new(10.0, 0.0, 0.0), Vec3::new(0.0, 20.0, 0.0)];
//! let md2 = mocap::formats::md2::build(&[("stand1".to_owned(), frame)], &[[0, 1, 2]]).unwrap();
//! let again = mocap::formats::md2::parse(&mocap::formats::md2::write(&md2)).unwrap();
//! assert_eq!(again, md2);
//! ```

use super::{
    Animation, FRAME_HEADER_SIZE, FRAME_NAME_SIZE, Frame, HEADER_SIZE, IDENT, Md2, NORMALS, SKIN_NAME_SIZE, Triangle,
    VERSION,
};
use glam::Vec3;

/// Why frames cannot be packed into an MD2.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{0}")]
pub struct WriteError(pub String);

/// Quake axes of a Y-up position (the inverse of [`to_y_up`]).
pub fn from_y_up(v: [f32; 3]) -> [f32; 3] {
    [v[0], -v[2], v[1]]
}

/// The model's bytes: header, skin names, texture coordinates, triangles, frames
/// and an empty OpenGL command list (one terminating zero), in that order.
pub fn write(md2: &Md2) -> Vec<u8> {
    let n = md2.vertex_count;
    let frame_size = FRAME_HEADER_SIZE + 4 * n;
    let ofs_skins = HEADER_SIZE;
    let ofs_st = ofs_skins + SKIN_NAME_SIZE * md2.skins.len();
    let ofs_tris = ofs_st + 4 * md2.tex_coords.len();
    let ofs_frames = ofs_tris + 12 * md2.triangles.len();
    let ofs_glcmds = ofs_frames + frame_size * md2.frames.len();
    let ofs_end = ofs_glcmds + 4;
    let mut out = Vec::with_capacity(ofs_end);
    out.extend_from_slice(IDENT);
    let header = [
        VERSION as usize,
        md2.skin_width as usize,
        md2.skin_height as usize,
        frame_size,
        md2.skins.len(),
        n,
        md2.tex_coords.len(),
        md2.triangles.len(),
        1,
        md2.frames.len(),
        ofs_skins,
        ofs_st,
        ofs_tris,
        ofs_frames,
        ofs_glcmds,
        ofs_end,
    ];
    for v in header {
        out.extend_from_slice(&(v as i32).to_le_bytes());
    }
    for skin in &md2.skins {
        name_field(skin, SKIN_NAME_SIZE, &mut out);
    }
    for st in &md2.tex_coords {
        out.extend_from_slice(&st[0].to_le_bytes());
        out.extend_from_slice(&st[1].to_le_bytes());
    }
    for t in &md2.triangles {
        for i in t.vertices.iter().chain(&t.tex_coords) {
            out.extend_from_slice(&i.to_le_bytes());
        }
    }
    for f in &md2.frames {
        for v in f.scale.iter().chain(&f.translate) {
            out.extend_from_slice(&v.to_le_bytes());
        }
        name_field(&f.name, FRAME_NAME_SIZE, &mut out);
        for v in &f.vertices {
            out.extend_from_slice(v);
        }
    }
    out.extend_from_slice(&0i32.to_le_bytes());
    out
}

/// `name` in a NUL-padded field of `size` bytes (cut to leave room for the NUL).
pub(crate) fn name_field(name: &str, size: usize, out: &mut Vec<u8>) {
    let bytes = name.as_bytes();
    let keep = bytes.len().min(size - 1);
    out.extend_from_slice(&bytes[..keep]);
    out.resize(out.len() + size - keep, 0);
}

/// One packed frame from Y-up positions (file units): the frame's bounds over
/// 255 steps per axis, each vertex's normal the Quake normal nearest to the
/// area-weighted normal of the triangles around it.
pub fn pack_frame(name: &str, positions: &[Vec3], triangles: &[[u32; 3]]) -> Frame {
    let quake: Vec<[f32; 3]> = positions.iter().map(|p| from_y_up(p.to_array())).collect();
    let mut lo = [f32::INFINITY; 3];
    let mut hi = [f32::NEG_INFINITY; 3];
    for p in &quake {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let scale = [0, 1, 2].map(|k| if hi[k] > lo[k] { (hi[k] - lo[k]) / 255.0 } else { 1.0 });
    let translate = [0, 1, 2].map(|k| if lo[k].is_finite() { lo[k] } else { 0.0 });
    let mut normals = vec![Vec3::ZERO; positions.len()];
    for t in triangles {
        let [a, b, c] = t.map(|i| quake.get(i as usize).map_or(Vec3::ZERO, |p| Vec3::from_array(*p)));
        let n = (b - a).cross(c - a);
        for i in t {
            if let Some(x) = normals.get_mut(*i as usize) {
                *x += n;
            }
        }
    }
    let vertices = quake
        .iter()
        .zip(&normals)
        .map(|(p, n)| {
            let q = [0, 1, 2].map(|k| ((p[k] - translate[k]) / scale[k]).round().clamp(0.0, 255.0) as u8);
            [q[0], q[1], q[2], nearest_normal(n.normalize_or_zero())]
        })
        .collect();
    Frame { name: name.chars().take(FRAME_NAME_SIZE - 1).collect(), scale, translate, vertices }
}

/// Index of the Quake normal nearest to `n` (Quake axes).
fn nearest_normal(n: Vec3) -> u8 {
    let mut best = (0usize, f32::NEG_INFINITY);
    for (i, m) in NORMALS.iter().enumerate() {
        let d = n.dot(Vec3::from_array(*m));
        if d > best.1 {
            best = (i, d);
        }
    }
    best.0 as u8
}

/// A model from named vertex frames (Y-up, file units, every frame the same
/// vertex count) and triangles (vertex indices), with one texture coordinate and
/// no skin name: the frames are packed by [`pack_frame`], the animations grouped
/// from the names.
pub fn build(frames: &[(String, Vec<Vec3>)], triangles: &[[u32; 3]]) -> Result<Md2, WriteError> {
    let n = frames.first().map_or(0, |f| f.1.len());
    if n == 0 || frames.iter().any(|f| f.1.len() != n) {
        return Err(WriteError("every frame needs the same, non-zero number of vertices".into()));
    }
    if n > usize::from(u16::MAX) {
        return Err(WriteError(format!("{n} vertices: an MD2 holds at most {}", u16::MAX)));
    }
    if let Some(t) = triangles.iter().find(|t| t.iter().any(|&i| i as usize >= n)) {
        return Err(WriteError(format!("triangle {t:?} uses a vertex past the last ({})", n - 1)));
    }
    if frames.iter().any(|f| f.1.iter().any(|p| !p.is_finite())) {
        return Err(WriteError("a vertex position is not finite".into()));
    }
    let packed: Vec<Frame> = frames.iter().map(|(name, p)| pack_frame(name, p, triangles)).collect();
    let animations: Vec<Animation> = super::group_animations(packed.iter().map(|f| f.name.as_str()));
    Ok(Md2 {
        skin_width: 8,
        skin_height: 8,
        skins: Vec::new(),
        tex_coords: vec![[0, 0]],
        triangles: triangles
            .iter()
            .map(|t| Triangle { vertices: t.map(|i| i as u16), tex_coords: [0, 0, 0] })
            .collect(),
        frames: packed,
        animations,
        vertex_count: n,
    })
}

#[cfg(test)]
mod tests {
    use super::super::to_y_up;
    use super::*;

    #[test]
    fn y_up_round_trips() {
        let v = [1.0, 2.0, 3.0];
        assert_eq!(to_y_up(from_y_up(v)), v);
    }

    #[test]
    fn packed_positions_are_within_half_a_step() {
        let frame: Vec<Vec3> = (0..50)
            .map(|i| Vec3::new((i as f32 * 0.37).sin() * 20.0, i as f32, (i as f32 * 0.11).cos() * 5.0))
            .collect();
        let tris: Vec<[u32; 3]> = (0..48).map(|i| [i, i + 1, i + 2]).collect();
        let md2 = build(&[("a1".into(), frame.clone()), ("a2".into(), frame.clone())], &tris).unwrap();
        let back = super::super::parse(&write(&md2)).unwrap();
        assert_eq!(back, md2);
        assert_eq!(back.animations.len(), 1);
        let mut out = Vec::new();
        back.frame_positions(1, &mut out);
        let f = &back.frames[1];
        for (p, q) in frame.iter().zip(&out) {
            for k in 0..3 {
                assert!(
                    (p[k] - q[k]).abs() <= 0.5 * f.scale.iter().cloned().fold(0.0, f32::max) + 1e-4,
                    "{p} vs {q:?}"
                );
            }
        }
        assert!(build(&[], &tris).is_err());
        assert!(build(&[("a".into(), vec![Vec3::ZERO])], &[[0, 0, 1]]).is_err());
    }
}
