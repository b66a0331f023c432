//! Capsules on the GPU: the shared unit-capsule mesh and the per-capsule instance layout.

use crate::Capsule;
use bytemuck::{Pod, Zeroable};
use glam::Vec3;
use std::f32::consts::{FRAC_PI_2, TAU};

/// Detail of a capsule mesh: vertices around the axis and latitude rings in each
/// round end (pole excluded).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Detail {
    pub segments: u32,
    pub rings: u32,
}

/// For capsules that cover more than a few pixels (144 triangles).
pub(crate) const FINE: Detail = Detail { segments: 12, rings: 3 };
/// For small or distant capsules and the shadow pass (24 triangles).
pub(crate) const COARSE: Detail = Detail { segments: 6, rings: 1 };

/// A unit capsule's vertices and triangles (see [`unit_mesh`]).
pub(crate) type UnitMesh = (Vec<CapsuleVertex>, Vec<u16>);

/// One vertex of the unit capsule: a unit direction in the capsule's frame (axis =
/// +Z) and which end it hangs from (0 = `a`, 1 = `b`). Placed as
/// `mix(a, b, end) + radius * basis * dir`, which is also the normal.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub(crate) struct CapsuleVertex {
    pub dir: [f32; 3],
    pub end: f32,
}

/// Vertex attributes of [`CapsuleVertex`] (locations 0-1).
pub(crate) const VERTEX_ATTRIBUTES: [wgpu::VertexAttribute; 2] = wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32];

/// One capsule as the capsule shaders read it (linear colour).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub(crate) struct CapsuleInstance {
    pub a: [f32; 3],
    pub radius: f32,
    pub b: [f32; 3],
    pub color: [f32; 4],
}

/// Instance attributes of [`CapsuleInstance`] (locations 2-5).
pub(crate) const INSTANCE_ATTRIBUTES: [wgpu::VertexAttribute; 4] =
    wgpu::vertex_attr_array![2 => Float32x3, 3 => Float32, 4 => Float32x3, 5 => Float32x4];

impl CapsuleInstance {
    pub fn new(c: &Capsule) -> CapsuleInstance {
        CapsuleInstance { a: c.a.to_array(), radius: c.radius, b: c.b.to_array(), color: crate::srgb_to_linear(c.color) }
    }

    /// A sphere as a capsule of zero length.
    pub fn sphere(s: &crate::Sphere) -> CapsuleInstance {
        let center = s.center.to_array();
        CapsuleInstance { a: center, radius: s.radius, b: center, color: crate::srgb_to_linear(s.color) }
    }
}

/// The unit capsule: a UV sphere cut at its equator, the lower half at end `a`
/// and the upper half at end `b`, joined by the cylinder. Counter-clockwise
/// triangles seen from outside.
pub(crate) fn unit_mesh(detail: Detail) -> UnitMesh {
    let Detail { segments, rings } = detail;
    let mut vertices = Vec::new();
    // Rings from the `a` pole up to its equator, then from `b`'s equator to its pole.
    let ring = |vertices: &mut Vec<CapsuleVertex>, latitude: f32, end: f32| {
        for s in 0..segments {
            let theta = TAU * s as f32 / segments as f32;
            let (sin_t, cos_t) = theta.sin_cos();
            let (sin_l, cos_l) = latitude.sin_cos();
            vertices.push(CapsuleVertex { dir: [cos_t * cos_l, sin_t * cos_l, sin_l], end });
        }
    };
    vertices.push(CapsuleVertex { dir: [0.0, 0.0, -1.0], end: 0.0 });
    for r in (0..rings).rev() {
        ring(&mut vertices, -FRAC_PI_2 * r as f32 / rings as f32, 0.0);
    }
    for r in 0..rings {
        ring(&mut vertices, FRAC_PI_2 * r as f32 / rings as f32, 1.0);
    }
    let top = vertices.len() as u16;
    vertices.push(CapsuleVertex { dir: [0.0, 0.0, 1.0], end: 1.0 });

    let mut indices = Vec::new();
    let at = |ring: u32, s: u32| (1 + ring * segments + s % segments) as u16;
    for s in 0..segments {
        // Bottom pole fan (looking from below, -Z).
        indices.extend([0, at(0, s + 1), at(0, s)]);
        // Top pole fan.
        let last = 2 * rings - 1;
        indices.extend([top, at(last, s), at(last, s + 1)]);
    }
    for r in 0..2 * rings - 1 {
        for s in 0..segments {
            let (p, q, u, v) = (at(r, s), at(r, s + 1), at(r + 1, s), at(r + 1, s + 1));
            indices.extend([p, q, v, p, v, u]);
        }
    }
    (vertices, indices)
}

/// A capsule mesh vertex placed in the world on the CPU, lit like the
/// instanced ones (see [`expand_lit`]).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub(crate) struct PlacedVertex {
    pub position: [f32; 3],
    pub normal: [f32; 3],
    /// Linear colour.
    pub color: [f32; 4],
}

/// Vertex attributes of [`PlacedVertex`] (locations 0-2).
pub(crate) const PLACED_ATTRIBUTES: [wgpu::VertexAttribute; 3] = wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3, 2 => Float32x4];

/// Places `mesh` (from [`unit_mesh`]) for every capsule, as the capsule
/// shader's `place` does, calling `put` with each vertex's position and normal,
/// and appends the mesh's triangles, offset per capsule, to `indices`
/// (`first` is the number of vertices already placed). Stops before an index
/// would pass `u32::MAX`.
fn place_all(capsules: &[CapsuleInstance], mesh: &UnitMesh, mut first: usize, indices: &mut Vec<u32>, mut put: impl FnMut(&CapsuleInstance, Vec3, Vec3)) {
    let (vertices, triangles) = mesh;
    for c in capsules {
        let (a, b) = (Vec3::from(c.a), Vec3::from(c.b));
        let axis = b - a;
        let len = axis.length();
        let z = if len > 1e-12 { axis / len.max(1e-20) } else { Vec3::Y };
        let helper = if z.x.abs() > 0.8 { Vec3::Z } else { Vec3::X };
        let x = helper.cross(z).normalize();
        let y = z.cross(x);
        let Ok(base) = u32::try_from(first) else { return };
        if base.checked_add(vertices.len() as u32).is_none() {
            return;
        }
        for v in vertices {
            let n = x * v.dir[0] + y * v.dir[1] + z * v.dir[2];
            put(c, a.lerp(b, v.end) + n * c.radius, n);
        }
        indices.extend(triangles.iter().map(|&t| base + u32::from(t)));
        first += vertices.len();
    }
}

/// Appends `mesh` placed for every capsule: positions (w = 1) to `positions`,
/// triangles to `indices`. One plain draw of these costs a software rasteriser
/// far less than the same capsules instanced (it sets up every instance like a
/// draw of its own).
pub(crate) fn expand(capsules: &[CapsuleInstance], mesh: &UnitMesh, positions: &mut Vec<[f32; 4]>, indices: &mut Vec<u32>) {
    let first = positions.len();
    place_all(capsules, mesh, first, indices, |_, p, _| positions.push(p.extend(1.0).to_array()));
}

/// [`expand`] with normals and colours, for the lit pass.
pub(crate) fn expand_lit(capsules: &[CapsuleInstance], mesh: &UnitMesh, vertices: &mut Vec<PlacedVertex>, indices: &mut Vec<u32>) {
    let first = vertices.len();
    place_all(capsules, mesh, first, indices, |c, p, n| vertices.push(PlacedVertex { position: p.to_array(), normal: n.to_array(), color: c.color }));
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    #[test]
    fn expanded_capsules_lie_on_their_surfaces() {
        let capsules = [
            CapsuleInstance { a: [0.0, 0.0, 0.0], radius: 0.5, b: [1.0, 0.0, 0.0], color: [1.0; 4] },
            CapsuleInstance { a: [0.0, 1.0, 2.0], radius: 0.25, b: [0.0, 3.0, 2.0], color: [1.0; 4] },
            // A ball (a = b) takes the same mesh.
            CapsuleInstance { a: [5.0, 5.0, 5.0], radius: 1.0, b: [5.0, 5.0, 5.0], color: [1.0; 4] },
        ];
        let mesh = unit_mesh(COARSE);
        let (mut positions, mut indices) = (Vec::new(), Vec::new());
        expand(&capsules, &mesh, &mut positions, &mut indices);
        assert_eq!(positions.len(), capsules.len() * mesh.0.len());
        assert_eq!(indices.len(), capsules.len() * mesh.1.len());
        for (k, c) in capsules.iter().enumerate() {
            let (a, b) = (Vec3::from(c.a), Vec3::from(c.b));
            let placed = &positions[k * mesh.0.len()..(k + 1) * mesh.0.len()];
            for p in placed {
                assert_eq!(p[3], 1.0);
                let p = Vec3::new(p[0], p[1], p[2]);
                // Distance to the segment a-b is the radius.
                let ab = b - a;
                let t = if ab.length_squared() > 0.0 { ((p - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0) } else { 0.0 };
                let d = (p - (a + ab * t)).length();
                assert!((d - c.radius).abs() < 1e-5, "capsule {k}: {p} is {d} from its axis, radius {}", c.radius);
            }
            let first = (k * mesh.0.len()) as u32;
            let tris = &indices[k * mesh.1.len()..(k + 1) * mesh.1.len()];
            assert!(tris.iter().zip(&mesh.1).all(|(&i, &t)| i == first + u32::from(t)), "capsule {k}'s triangles index its own vertices");
        }
        // The lit version places the same points, with unit normals pointing
        // out from the axis and the capsule's colour; appended after what is there.
        let (mut lit, mut lit_indices) = (vec![PlacedVertex::zeroed()], Vec::new());
        expand_lit(&capsules, &mesh, &mut lit, &mut lit_indices);
        assert_eq!(lit.len(), 1 + positions.len());
        assert!(lit_indices.iter().zip(&indices).all(|(&l, &i)| l == i + 1), "indices follow the vertex already there");
        for (v, p) in lit[1..].iter().zip(&positions) {
            assert_eq!(v.position, [p[0], p[1], p[2]]);
            assert!((Vec3::from(v.normal).length() - 1.0).abs() < 1e-5);
            assert_eq!(v.color, [1.0; 4]);
        }
    }

    #[test]
    fn meshes_are_closed_and_face_outwards() {
        for detail in [FINE, COARSE] {
            check_mesh(detail);
        }
    }

    fn check_mesh(detail: Detail) {
        let (vertices, indices) = unit_mesh(detail);
        assert_eq!(indices.len() % 3, 0);
        assert!(indices.iter().all(|&i| (i as usize) < vertices.len()));
        // Every edge is shared by exactly two triangles, in opposite directions.
        let mut edges = std::collections::HashMap::new();
        for t in indices.chunks(3) {
            for (a, b) in [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])] {
                *edges.entry((a, b)).or_insert(0) += 1;
            }
        }
        assert!(edges.iter().all(|(&(a, b), &n)| n == 1 && edges.get(&(b, a)) == Some(&1)));
        // Place the capsule a = origin, b = +Z*2 and check every face normal points out.
        let place = |v: &CapsuleVertex| Vec3::from(v.dir) + Vec3::Z * 2.0 * v.end;
        for t in indices.chunks(3) {
            let [p, q, r] = [0, 1, 2].map(|k| place(&vertices[t[k] as usize]));
            let normal = (q - p).cross(r - p);
            let centre = (p + q + r) / 3.0;
            let axis_point = Vec3::Z * centre.z.clamp(0.0, 2.0);
            assert!(normal.dot(centre - axis_point) > 0.0, "triangle {t:?} faces inwards");
        }
    }
}
