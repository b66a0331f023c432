//! Vertex-animated meshes on the GPU: [`MorphMeshData`] (what the caller hands
//! over once, shared through an `Arc`), [`MeshDraw`] (one placed copy in a frame)
//! and the renderer's cache of their buffers and skin textures.
//!
//! A mesh's key frames are uploaded once into one vertex buffer (frame after frame,
//! position and normal per vertex); a draw binds two frames at their offsets and
//! the vertex shader blends them, so playing costs no CPU vertex work and no
//! upload. The renderer keeps a mesh's GPU copy while the caller holds its `Arc`.

use crate::buffer::GrowingBuffer;
use crate::texture::{SkinImage, skin_group};
use bytemuck::{Pod, Zeroable};
use glam::{Mat4, Vec3};
use std::collections::HashMap;
use std::sync::{Arc, Weak};
use wgpu::util::DeviceExt;

/// One vertex of one key frame.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct MorphVertex {
    /// Position (model space).
    pub position: [f32; 3],
    /// Unit normal.
    pub normal: [f32; 3],
}

/// A triangle mesh whose vertices move from key frame to key frame.
#[derive(Debug, PartialEq)]
pub struct MorphMeshData {
    vertex_count: u32,
    frame_count: u32,
    vertices: Vec<MorphVertex>,
    tex_coords: Vec<[f32; 2]>,
    indices: Vec<u32>,
    skin: Option<SkinImage>,
    bounds: (Vec3, Vec3),
}

impl MorphMeshData {
    /// A mesh of `vertex_count` vertices per frame: `vertices` holds every frame,
    /// frame after frame; `tex_coords` one per vertex; `indices` three per triangle.
    /// Refused (with why) when the lengths do not agree, an index is out of range or
    /// the skin's pixels are not `width × height × 4` bytes.
    pub fn new(
        vertex_count: usize,
        vertices: Vec<MorphVertex>,
        tex_coords: Vec<[f32; 2]>,
        indices: Vec<u32>,
        skin: Option<SkinImage>,
    ) -> Result<MorphMeshData, String> {
        if vertex_count == 0 || vertices.is_empty() || vertices.len() % vertex_count != 0 {
            return Err(format!(
                "{} frame vertices are not a whole number of frames of {vertex_count}",
                vertices.len()
            ));
        }
        if tex_coords.len() != vertex_count {
            return Err(format!("{} texture coordinates for {vertex_count} vertices", tex_coords.len()));
        }
        if indices.len() % 3 != 0 || indices.iter().any(|&i| i as usize >= vertex_count) {
            return Err("triangle indices out of range".into());
        }
        if let Some(s) = &skin {
            if s.pixels.len() as u64 != u64::from(s.width) * u64::from(s.height) * 4 || s.width == 0 || s.height == 0 {
                return Err(format!(
                    "a {}×{} skin needs {} bytes, not {}",
                    s.width,
                    s.height,
                    u64::from(s.width) * u64::from(s.height) * 4,
                    s.pixels.len()
                ));
            }
        }
        let count = u32::try_from(vertex_count).map_err(|_| "too many vertices")?;
        let frames = u32::try_from(vertices.len() / vertex_count).map_err(|_| "too many frames")?;
        let (mut min, mut max) = (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY));
        for v in &vertices {
            let p = Vec3::from(v.position);
            if p.is_finite() {
                min = min.min(p);
                max = max.max(p);
            }
        }
        Ok(MorphMeshData {
            vertex_count: count,
            frame_count: frames,
            vertices,
            tex_coords,
            indices,
            skin,
            bounds: (min, max),
        })
    }

    /// [`MorphMeshData::new`] from separate arrays: `positions` and `normals` of every
    /// frame (frame after frame, `vertex_count` per frame).
    pub fn from_frames(
        vertex_count: usize,
        positions: &[[f32; 3]],
        normals: &[[f32; 3]],
        tex_coords: &[[f32; 2]],
        indices: &[u32],
        skin: Option<SkinImage>,
    ) -> Result<MorphMeshData, String> {
        if positions.len() != normals.len() {
            return Err(format!("{} positions and {} normals", positions.len(), normals.len()));
        }
        let vertices =
            positions.iter().zip(normals).map(|(&position, &normal)| MorphVertex { position, normal }).collect();
        MorphMeshData::new(vertex_count, vertices, tex_coords.to_vec(), indices.to_vec(), skin)
    }

    /// Vertices per frame.
    pub fn vertex_count(&self) -> u32 {
        self.vertex_count
    }

    /// Key frames.
    pub fn frame_count(&self) -> u32 {
        self.frame_count
    }

    /// Whether a skin is drawn on it.
    pub fn has_skin(&self) -> bool {
        self.skin.is_some()
    }

    /// Bounds of every frame (model space); empty (min > max) when no vertex is finite.
    pub fn bounds(&self) -> (Vec3, Vec3) {
        self.bounds
    }
}

/// The tint of a mesh without a skin: a neutral light grey.
pub const NEUTRAL_TINT: [u8; 4] = [196, 192, 186, 255];

/// One placed copy of a mesh in a frame: two key frames blended on the GPU.
#[derive(Clone, Debug, PartialEq)]
pub struct MeshDraw {
    /// The mesh (uploaded on first sight, kept while an `Arc` to it lives).
    pub mesh: Arc<MorphMeshData>,
    /// The two key frames (clamped to the mesh's).
    pub frames: [u32; 2],
    /// Weight of the second frame (0–1).
    pub blend: f32,
    /// Model space to world: a uniform scale and a translation (and any rotation).
    pub transform: Mat4,
    /// sRGB tint multiplied with the skin (the colour itself without a skin).
    pub tint: [u8; 4],
}

impl MeshDraw {
    /// World-space bounds of the whole mesh (every frame) where it is drawn.
    pub fn world_bounds(&self) -> Option<(Vec3, Vec3)> {
        let (min, max) = self.mesh.bounds();
        crate::bounds::transform_box(&self.transform, min, max)
    }
}

/// Per-draw data the morph shader reads (slot 3).
#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
pub(crate) struct MeshInstance {
    model: [[f32; 4]; 4],
    tint_blend: [f32; 4],
}

/// Byte size of a [`MeshInstance`].
pub(crate) const INSTANCE_SIZE: u64 = std::mem::size_of::<MeshInstance>() as u64;
const VERTEX_SIZE: u64 = std::mem::size_of::<MorphVertex>() as u64;

/// Vertex buffer layouts of the morph pipeline: frame a, frame b, texture
/// coordinates, instance.
pub(crate) fn buffer_layouts() -> [Option<wgpu::VertexBufferLayout<'static>>; 4] {
    const A: [wgpu::VertexAttribute; 2] = wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3];
    const B: [wgpu::VertexAttribute; 2] = wgpu::vertex_attr_array![2 => Float32x3, 3 => Float32x3];
    const UV: [wgpu::VertexAttribute; 1] = wgpu::vertex_attr_array![4 => Float32x2];
    const INSTANCE: [wgpu::VertexAttribute; 5] =
        wgpu::vertex_attr_array![5 => Float32x4, 6 => Float32x4, 7 => Float32x4, 8 => Float32x4, 9 => Float32x4];
    let vertex = |attributes, stride| {
        Some(wgpu::VertexBufferLayout { array_stride: stride, step_mode: wgpu::VertexStepMode::Vertex, attributes })
    };
    [
        vertex(&A, VERTEX_SIZE),
        vertex(&B, VERTEX_SIZE),
        vertex(&UV, 8),
        Some(wgpu::VertexBufferLayout {
            array_stride: INSTANCE_SIZE,
            step_mode: wgpu::VertexStepMode::Instance,
            attributes: &INSTANCE,
        }),
    ]
}

/// A mesh's GPU copy.
struct GpuMesh {
    owner: Weak<MorphMeshData>,
    frames: wgpu::Buffer,
    tex_coords: wgpu::Buffer,
    indices: wgpu::Buffer,
    index_count: u32,
    vertex_count: u32,
    frame_count: u32,
    skin: wgpu::BindGroup,
}

/// A draw recorded for this frame: which mesh, which frames, which instance.
struct Prepared {
    key: usize,
    frames: [u32; 2],
    instance: u32,
}

/// The meshes on the GPU and this frame's draws.
pub(crate) struct MeshCache {
    pub skin_layout: wgpu::BindGroupLayout,
    sampler: wgpu::Sampler,
    /// A 1×1 white texture for meshes without a skin (made on first use).
    neutral: Option<wgpu::BindGroup>,
    meshes: HashMap<usize, GpuMesh>,
    instances: GrowingBuffer,
    scratch: Vec<MeshInstance>,
    draws: Vec<Prepared>,
}

impl MeshCache {
    pub fn new(device: &wgpu::Device) -> MeshCache {
        let skin_layout = crate::pipeline::color_texture_layout(device, "mocap skin");
        let sampler = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("mocap skin"),
            address_mode_u: wgpu::AddressMode::Repeat,
            address_mode_v: wgpu::AddressMode::Repeat,
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            ..Default::default()
        });
        MeshCache {
            skin_layout,
            sampler,
            neutral: None,
            meshes: HashMap::new(),
            instances: GrowingBuffer::new("mocap mesh instances"),
            scratch: Vec::new(),
            draws: Vec::new(),
        }
    }

    /// Uploads meshes seen for the first time, forgets those whose owner is gone,
    /// and uploads this frame's instances. Meshes too big for the device are skipped.
    pub fn prepare(&mut self, device: &wgpu::Device, queue: &wgpu::Queue, draws: &[MeshDraw]) {
        self.meshes.retain(|_, m| m.owner.strong_count() > 0);
        if self.neutral.is_none() && !draws.is_empty() {
            let white = SkinImage { width: 1, height: 1, pixels: vec![255; 4] };
            self.neutral = Some(skin_group(device, queue, &self.skin_layout, &self.sampler, &white));
        }
        self.scratch.clear();
        self.draws.clear();
        for draw in draws {
            let key = Arc::as_ptr(&draw.mesh) as usize;
            if !self.meshes.contains_key(&key) {
                let Some(gpu) = self.upload(device, queue, &draw.mesh) else { continue };
                self.meshes.insert(key, gpu);
            }
            let Some(mesh) = self.meshes.get(&key) else { continue };
            let last = mesh.frame_count.saturating_sub(1);
            let [r, g, b, _] = crate::srgb_to_linear(draw.tint);
            self.draws.push(Prepared {
                key,
                frames: draw.frames.map(|f| f.min(last)),
                instance: self.scratch.len() as u32,
            });
            self.scratch.push(MeshInstance {
                model: draw.transform.to_cols_array_2d(),
                tint_blend: [r, g, b, draw.blend.clamp(0.0, 1.0)],
            });
        }
        self.instances.upload(device, queue, &self.scratch);
    }

    fn upload(&self, device: &wgpu::Device, queue: &wgpu::Queue, data: &Arc<MorphMeshData>) -> Option<GpuMesh> {
        let bytes: &[u8] = bytemuck::cast_slice(&data.vertices);
        if bytes.len() as u64 > device.limits().max_buffer_size {
            return None;
        }
        let buffer = |label, contents: &[u8], usage| {
            device.create_buffer_init(&wgpu::util::BufferInitDescriptor { label: Some(label), contents, usage })
        };
        let skin = match &data.skin {
            Some(s) => skin_group(device, queue, &self.skin_layout, &self.sampler, s),
            None => self.neutral.clone()?,
        };
        Some(GpuMesh {
            owner: Arc::downgrade(data),
            frames: buffer("mocap mesh frames", bytes, wgpu::BufferUsages::VERTEX),
            tex_coords: buffer("mocap mesh uvs", bytemuck::cast_slice(&data.tex_coords), wgpu::BufferUsages::VERTEX),
            indices: buffer("mocap mesh indices", bytemuck::cast_slice(&data.indices), wgpu::BufferUsages::INDEX),
            index_count: data.indices.len() as u32,
            vertex_count: data.vertex_count,
            frame_count: data.frame_count,
            skin,
        })
    }

    /// Whether this frame draws any mesh.
    pub fn has_draws(&self) -> bool {
        !self.draws.is_empty()
    }

    /// Records this frame's draws into `pass` (its pipeline and group 0 set);
    /// `textured` binds each skin at group 2 (the colour pass). Returns the number
    /// of draw calls.
    pub fn draw<'a>(&'a self, pass: &mut wgpu::RenderPass<'a>, textured: bool) -> u32 {
        let Some((instances, _)) = self.instances.get() else { return 0 };
        let mut calls = 0;
        for d in &self.draws {
            let Some(mesh) = self.meshes.get(&d.key) else { continue };
            if mesh.index_count == 0 {
                continue;
            }
            let frame_bytes = u64::from(mesh.vertex_count) * VERTEX_SIZE;
            let at = |f: u32| u64::from(f) * frame_bytes;
            pass.set_vertex_buffer(0, mesh.frames.slice(at(d.frames[0])..at(d.frames[0]) + frame_bytes));
            pass.set_vertex_buffer(1, mesh.frames.slice(at(d.frames[1])..at(d.frames[1]) + frame_bytes));
            pass.set_vertex_buffer(2, mesh.tex_coords.slice(..));
            let i = u64::from(d.instance) * INSTANCE_SIZE;
            pass.set_vertex_buffer(3, instances.slice(i..i + INSTANCE_SIZE));
            pass.set_index_buffer(mesh.indices.slice(..), wgpu::IndexFormat::Uint32);
            if textured {
                pass.set_bind_group(2, &mesh.skin, &[]);
            }
            pass.draw_indexed(0..mesh.index_count, 0, 0..1);
            calls += 1;
        }
        calls
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn v(y: f32) -> MorphVertex {
        MorphVertex { position: [0.0, y, 0.0], normal: [0.0, 1.0, 0.0] }
    }

    #[test]
    fn inconsistent_meshes_are_refused() {
        assert!(MorphMeshData::new(2, vec![v(0.0), v(1.0), v(2.0)], vec![[0.0; 2]; 2], vec![], None).is_err());
        assert!(MorphMeshData::new(1, vec![v(0.0)], vec![[0.0; 2]; 1], vec![0, 0, 1], None).is_err());
        assert!(
            MorphMeshData::new(
                1,
                vec![v(0.0)],
                vec![[0.0; 2]; 1],
                vec![0, 0, 0],
                Some(SkinImage { width: 2, height: 2, pixels: vec![0; 4] })
            )
            .is_err()
        );
        let ok = MorphMeshData::new(1, vec![v(0.0), v(3.0)], vec![[0.0; 2]; 1], vec![0, 0, 0], None).unwrap();
        assert_eq!((ok.vertex_count(), ok.frame_count()), (1, 2));
        assert_eq!(ok.bounds(), (Vec3::ZERO, Vec3::new(0.0, 3.0, 0.0)));
        let draw = MeshDraw {
            mesh: Arc::new(ok),
            frames: [0, 1],
            blend: 0.5,
            transform: Mat4::from_translation(Vec3::X),
            tint: [255; 4],
        };
        assert_eq!(draw.world_bounds(), Some((Vec3::X, Vec3::new(1.0, 3.0, 0.0))));
    }
}
