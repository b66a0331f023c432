//! The format-free mesh ([`MorphMesh`]) of a parsed MD2 model.

use super::{Md2, NORMALS, to_y_up};
use crate::model::mesh::{MeshParts, MorphMesh, SourceCounts};
use std::collections::HashMap;

impl MorphMesh {
    /// Builds the drawing mesh of a parsed MD2 model: file vertices split per texture
    /// coordinate, positions and normals of every frame decoded to Y-up (file units),
    /// texture coordinates divided by the header's skin size (not by any image's, so
    /// a skin of another size still maps).
    pub fn from_md2(model: &Md2) -> MorphMesh {
        let mut key_to_vertex: HashMap<(u16, u16), u32> = HashMap::new();
        let mut sources: Vec<(u16, u16)> = Vec::new();
        let mut indices = Vec::with_capacity(model.triangles.len() * 3);
        for triangle in &model.triangles {
            for corner in 0..3 {
                let key = (triangle.vertices[corner], triangle.tex_coords[corner]);
                let index = *key_to_vertex.entry(key).or_insert_with(|| {
                    sources.push(key);
                    (sources.len() - 1) as u32
                });
                indices.push(index);
            }
        }
        let (w, h) = (model.skin_width.max(1) as f32, model.skin_height.max(1) as f32);
        let tex_coords = sources
            .iter()
            .map(|&(_, t)| {
                model.tex_coords.get(usize::from(t)).map_or([0.0; 2], |st| [f32::from(st[0]) / w, f32::from(st[1]) / h])
            })
            .collect();
        let mut positions = Vec::with_capacity(sources.len() * model.frames.len());
        let mut normals = Vec::with_capacity(sources.len() * model.frames.len());
        for frame in &model.frames {
            for &(v, _) in &sources {
                let Some(packed) = frame.vertices.get(usize::from(v)) else { continue };
                positions.push(to_y_up(frame.quake_position(usize::from(v))));
                normals.push(to_y_up(NORMALS.get(usize::from(packed[3])).copied().unwrap_or([0.0, 0.0, 1.0])));
            }
        }
        MorphMesh::from_parts(MeshParts {
            positions,
            normals,
            tex_coords,
            indices,
            sources: sources.iter().map(|&(v, _)| u32::from(v)).collect(),
            frame_names: model.frames.iter().map(|f| f.name.clone()).collect(),
            animations: model.animations.clone(),
            skins: model.skins.clone(),
            skin_size: [model.skin_width, model.skin_height],
            source_counts: SourceCounts {
                vertices: model.vertex_count,
                triangles: model.triangles.len(),
                tex_coords: model.tex_coords.len(),
            },
        })
    }
}

#[cfg(test)]
mod tests {
    use crate::formats::md2::{self, Md2};
    use crate::model::mesh::MorphMesh;
    use glam::Vec3;

    /// A two-frame MD2: one triangle whose first corner uses two texture coordinates
    /// in a second triangle (so it splits), moving up by 2 units between frames.
    fn model() -> Md2 {
        let frame = |name: &str, z: f32| md2::Frame {
            name: name.to_owned(),
            scale: [1.0; 3],
            translate: [0.0, 0.0, z],
            vertices: vec![[0, 0, 0, 5], [10, 0, 0, 5], [0, 0, 20, 5]],
        };
        Md2 {
            skin_width: 64,
            skin_height: 32,
            skins: vec!["models/x/Skin.PCX".into()],
            tex_coords: vec![[0, 0], [64, 0], [0, 32], [32, 16]],
            triangles: vec![
                md2::Triangle { vertices: [0, 1, 2], tex_coords: [0, 1, 2] },
                md2::Triangle { vertices: [0, 2, 1], tex_coords: [3, 2, 1] },
            ],
            frames: vec![frame("run1", 0.0), frame("run2", 2.0), frame("jump1", 4.0)],
            animations: md2::group_animations(["run1", "run2", "jump1"]),
            vertex_count: 3,
        }
    }

    #[test]
    fn vertices_split_per_texture_coordinate_and_map_by_the_header_size() {
        let mesh = MorphMesh::from_md2(&model());
        assert_eq!(mesh.vertex_count(), 4, "vertex 0 is used with two texture coordinates");
        assert_eq!(mesh.indices(), &[0, 1, 2, 3, 2, 1]);
        assert_eq!(mesh.tex_coords(), &[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [0.5, 0.5]]);
        assert_eq!(mesh.frame_count(), 3);
        assert_eq!(mesh.positions().len(), 12);
        // Quake (0, 0, 20) is Y-up (0, 20, 0); frame 1 is 2 units higher.
        assert_eq!(mesh.frame_positions(0)[2], [0.0, 20.0, 0.0]);
        assert_eq!(mesh.frame_positions(1)[2], [0.0, 22.0, 0.0]);
        assert_eq!(mesh.frame_positions(1)[3], mesh.frame_positions(1)[0]);
        assert!(mesh.frame_positions(3).is_empty());
        assert_eq!(mesh.height(), 20.0);
        assert_eq!(mesh.bounds().max.y, 24.0);
        assert!(mesh.normals().iter().all(|n| (Vec3::from(*n).length() - 1.0).abs() < 1e-3));
    }
}
