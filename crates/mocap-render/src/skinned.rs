//! Skinned meshes on the GPU: [`SkinnedMeshData`] (the bind-pose mesh with its
//! joint weights, handed over once through an `Arc`), [`SkinnedDraw`] (one posed
//! copy: a matrix per joint) and the renderer's cache of their buffers.
//!
//! A mesh may carry a colour texture ([`SkinnedMeshData::set_texture`]), drawn
//! per pixel on the vertices that have a texture coordinate.
//!
//! The vertex buffer is uploaded once per mesh; per frame only the joint matrices
//! move, all draws' into one RGBA32F texture (three texels per matrix: the rows of
//! its affine part) that the vertex shader reads, the same code on WebGPU, WebGL2
//! and Vulkan.

use crate::buffer::GrowingBuffer;
use crate::texture::{SkinImage, skin_group};
use bytemuck::{Pod, Zeroable};
use glam::{Mat4, Vec3};
use std::collections::HashMap;
use std::sync::{Arc, Weak};
use wgpu::util::DeviceExt;

/// Matrices per row of the joint texture (must match skinned.wgsl).
const MATRICES_PER_ROW: u32 = 256;
/// Texels per matrix: the three rows of its affine part.
const TEXELS_PER_MATRIX: u32 = 3;

/// One vertex: bind-pose position and normal, four joints and their weights.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct SkinnedVertex {
    /// Bind-pose position.
    pub position: [f32; 3],
    /// Bind-pose unit normal.
    pub normal: [f32; 3],
    /// Joint indices (into the draw's matrices).
    pub joints: [u32; 4],
    /// Weights (summing to 1).
    pub weights: [f32; 4],
    /// sRGB colour, multiplied with the draw's tint (white for a plain body).
    pub color: [u8; 4],
    /// Texture coordinate (u, v: v down from the image's top row) and 1 where the
    /// mesh's texture colours this vertex (times `color`), else 0.
    pub tex: [f32; 4],
}

/// A mesh's colour texture and how coordinates outside 0–1 wrap (u, v).
#[derive(Clone, Debug, PartialEq)]
pub struct SkinnedTexture {
    /// The picture.
    pub image: SkinImage,
    /// Wrap along u and v.
    pub wrap: [wgpu::AddressMode; 2],
}

/// A mesh bound to joints, as the renderer draws it: closed surfaces whose
/// triangles wind counter-clockwise seen from outside (as `mocap::build::body` and
/// `mocap::build::demo::tentacle_skin` make them). Only their front faces are drawn,
/// so a view from inside a surface sees through it.
#[derive(Debug, PartialEq)]
pub struct SkinnedMeshData {
    vertices: Vec<SkinnedVertex>,
    indices: Vec<u32>,
    joint_count: u32,
    /// Per joint, the bind-pose box around the vertices it moves (empty, min
    /// past max, for a joint that moves none): a skinned vertex is a weighted
    /// mean of its joints' matrices applied to it, so the posed mesh lies inside
    /// these boxes carried by their joints' matrices.
    joint_boxes: Vec<(Vec3, Vec3)>,
    texture: Option<SkinnedTexture>,
}

impl SkinnedMeshData {
    /// A mesh from per-vertex arrays of equal length and three indices per
    /// triangle; every weighted joint must be below `joint_count`. Refused (with
    /// why) otherwise.
    pub fn new(
        positions: &[Vec3],
        normals: &[Vec3],
        joints: &[[u32; 4]],
        weights: &[[f32; 4]],
        indices: Vec<u32>,
        joint_count: usize,
    ) -> Result<SkinnedMeshData, String> {
        let n = positions.len();
        if normals.len() != n || joints.len() != n || weights.len() != n {
            return Err("positions, normals, joints and weights differ in length".into());
        }
        if indices.len() % 3 != 0 || indices.iter().any(|&i| i as usize >= n) {
            return Err("triangle indices out of range".into());
        }
        if joints.iter().zip(weights).any(|(j, w)| j.iter().zip(w).any(|(j, w)| *w > 0.0 && *j as usize >= joint_count))
        {
            return Err("a vertex is weighted to a joint past the skeleton".into());
        }
        let joint_count_u32 = u32::try_from(joint_count).map_err(|_| "too many joints")?;
        let mut joint_boxes = vec![(Vec3::INFINITY, Vec3::NEG_INFINITY); joint_count];
        for ((p, js), ws) in positions.iter().zip(joints).zip(weights) {
            for (j, w) in js.iter().zip(ws) {
                if let (true, Some(b)) = (*w > 0.0 && p.is_finite(), joint_boxes.get_mut(*j as usize)) {
                    *b = (b.0.min(*p), b.1.max(*p));
                }
            }
        }
        let vertices = (0..n)
            .map(|i| SkinnedVertex {
                position: positions[i].to_array(),
                normal: normals[i].to_array(),
                joints: joints[i].map(|j| j.min(joint_count_u32.saturating_sub(1))),
                weights: weights[i],
                color: [255; 4],
                tex: [0.0; 4],
            })
            .collect();
        Ok(SkinnedMeshData { vertices, indices, joint_count: joint_count_u32, joint_boxes, texture: None })
    }

    /// Draws the mesh with `texture`: each vertex with a coordinate takes the
    /// texture there times its `tints` colour; one without takes `tints`' colour
    /// (sRGB) alone. Refused, and the mesh left as it was, unless one coordinate
    /// and one colour per vertex, the coordinates finite and the image's bytes
    /// its size.
    pub fn set_texture(
        &mut self,
        texture: SkinnedTexture,
        uvs: &[Option<[f32; 2]>],
        tints: &[[u8; 4]],
    ) -> Result<(), String> {
        if uvs.len() != self.vertices.len() || tints.len() != self.vertices.len() {
            return Err("one texture coordinate and one colour per vertex".into());
        }
        if uvs.iter().flatten().flatten().any(|x| !x.is_finite()) {
            return Err("a texture coordinate is not finite".into());
        }
        let image = &texture.image;
        if u64::from(image.width) * u64::from(image.height) * 4 != image.pixels.len() as u64 || image.width == 0 {
            return Err("the texture's bytes do not match its size".into());
        }
        for ((v, uv), tint) in self.vertices.iter_mut().zip(uvs).zip(tints) {
            v.color = *tint;
            v.tex = uv.map_or([0.0; 4], |[x, y]| [x, y, 1.0, 0.0]);
        }
        self.texture = Some(texture);
        Ok(())
    }

    /// The same mesh with a colour per vertex (sRGB; a character's own look:
    /// its material's base colour and texture); refused unless one per vertex.
    pub fn with_colors(mut self, colors: &[[u8; 4]]) -> Result<SkinnedMeshData, String> {
        if colors.len() != self.vertices.len() {
            return Err("one colour per vertex".into());
        }
        for (v, c) in self.vertices.iter_mut().zip(colors) {
            v.color = *c;
        }
        Ok(self)
    }

    /// Joints the mesh is bound to (matrices a draw needs).
    pub fn joint_count(&self) -> u32 {
        self.joint_count
    }

    /// Vertices.
    pub fn vertex_count(&self) -> usize {
        self.vertices.len()
    }
}

/// One posed copy of a skinned mesh in a frame.
#[derive(Clone, Debug, PartialEq)]
pub struct SkinnedDraw {
    /// The mesh (uploaded on first sight, kept while an `Arc` to it lives).
    pub mesh: Arc<SkinnedMeshData>,
    /// A coarser mesh of the same body, bound to the same joints, that the
    /// fast look draws instead when the body spans under
    /// [`COARSE_BODY_SPAN_PX`] on screen (see [`crate::SceneRenderer::fast_look`]).
    pub coarse: Option<Arc<SkinnedMeshData>>,
    /// One matrix per joint, bind pose to world (`world · bind⁻¹`); missing ones
    /// count as identity.
    pub matrices: Vec<Mat4>,
    /// sRGB colour.
    pub tint: [u8; 4],
    /// Colour by bone influences instead of the tint.
    pub weights_view: bool,
    /// Bind-pose positions to skin instead of the mesh's own, one per vertex
    /// (its morph targets blended); `None` for the mesh as it is. The mesh's
    /// GPU copy is rewritten when this changes, so two draws of one mesh in a
    /// frame share the shape of the last.
    pub shape: Option<Arc<[Vec3]>>,
}

impl SkinnedDraw {
    /// A box around the posed mesh (for fitting the shadow map and sizing the
    /// draw on screen): each joint's bind-pose box around the vertices it moves,
    /// carried by its matrix, together. `None` when no joint moves a vertex.
    pub fn world_bounds(&self) -> Option<(Vec3, Vec3)> {
        self.mesh.joint_boxes.iter().enumerate().fold(None, |bounds, (j, &(min, max))| {
            let m = self.matrices.get(j).copied().unwrap_or(Mat4::IDENTITY);
            crate::bounds::union(bounds, crate::bounds::transform_box(&m, min, max))
        })
    }
}

/// A linear sampler wrapping as `wrap` says (u, v).
fn sampler(device: &wgpu::Device, wrap: [wgpu::AddressMode; 2]) -> wgpu::Sampler {
    device.create_sampler(&wgpu::SamplerDescriptor {
        label: Some("mocap skinned texture"),
        address_mode_u: wrap[0],
        address_mode_v: wrap[1],
        mag_filter: wgpu::FilterMode::Linear,
        min_filter: wgpu::FilterMode::Linear,
        ..Default::default()
    })
}

/// Bodies spanning fewer pixels than this on screen (their bounding sphere)
/// are drawn with their coarse mesh in the fast look.
pub const COARSE_BODY_SPAN_PX: f32 = 200.0;

/// Per-draw data (slot 1).
#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
struct Instance {
    base: [u32; 4],
    tint_mode: [f32; 4],
}

const INSTANCE_SIZE: u64 = std::mem::size_of::<Instance>() as u64;

/// Vertex buffer layouts of the skinned pipeline: the mesh, then the instance.
pub(crate) fn buffer_layouts() -> [Option<wgpu::VertexBufferLayout<'static>>; 2] {
    const VERTEX: [wgpu::VertexAttribute; 6] = wgpu::vertex_attr_array![
        0 => Float32x3, 1 => Float32x3, 2 => Uint32x4, 3 => Float32x4, 6 => Unorm8x4, 7 => Float32x4
    ];
    const INSTANCE: [wgpu::VertexAttribute; 2] = wgpu::vertex_attr_array![4 => Uint32x4, 5 => Float32x4];
    [
        Some(wgpu::VertexBufferLayout {
            array_stride: std::mem::size_of::<SkinnedVertex>() as u64,
            step_mode: wgpu::VertexStepMode::Vertex,
            attributes: &VERTEX,
        }),
        Some(wgpu::VertexBufferLayout {
            array_stride: INSTANCE_SIZE,
            step_mode: wgpu::VertexStepMode::Instance,
            attributes: &INSTANCE,
        }),
    ]
}

struct GpuMesh {
    owner: Weak<SkinnedMeshData>,
    vertices: wgpu::Buffer,
    indices: wgpu::Buffer,
    index_count: u32,
    /// Its colour texture (white when it has none).
    texture: wgpu::BindGroup,
    /// The shape its vertex buffer holds ([`SkinnedDraw::shape`], by address),
    /// `None` for the mesh's own positions.
    shaped: Option<usize>,
}

/// The skinned meshes on the GPU, the joint texture and this frame's draws.
pub(crate) struct SkinnedCache {
    pub layout: wgpu::BindGroupLayout,
    /// The meshes' colour textures (group 3).
    pub texture_layout: wgpu::BindGroupLayout,
    /// A white texture for meshes without one (made on first use).
    white: Option<wgpu::BindGroup>,
    meshes: HashMap<usize, GpuMesh>,
    texture: Option<(wgpu::Texture, wgpu::BindGroup, u32)>,
    instances: GrowingBuffer,
    scratch: Vec<Instance>,
    texels: Vec<[f32; 4]>,
    draws: Vec<(usize, u32)>,
    /// Vertices with a shape's positions, before they are written.
    shaped: Vec<SkinnedVertex>,
}

impl SkinnedCache {
    pub fn new(device: &wgpu::Device) -> SkinnedCache {
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("mocap joint matrices"),
            entries: &[wgpu::BindGroupLayoutEntry {
                binding: 0,
                visibility: wgpu::ShaderStages::VERTEX,
                ty: wgpu::BindingType::Texture {
                    sample_type: wgpu::TextureSampleType::Float { filterable: false },
                    view_dimension: wgpu::TextureViewDimension::D2,
                    multisampled: false,
                },
                count: None,
            }],
        });
        SkinnedCache {
            layout,
            texture_layout: crate::pipeline::color_texture_layout(device, "mocap skinned texture"),
            white: None,
            meshes: HashMap::new(),
            texture: None,
            instances: GrowingBuffer::new("mocap skinned instances"),
            scratch: Vec::new(),
            texels: Vec::new(),
            draws: Vec::new(),
            shaped: Vec::new(),
        }
    }

    /// Uploads new meshes, forgets dropped ones, and writes this frame's matrices
    /// and instances. A draw for which `coarse` says so is drawn with its
    /// coarse mesh, where it has one.
    pub fn prepare(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        draws: &[SkinnedDraw],
        coarse: impl Fn(&SkinnedDraw) -> bool,
    ) {
        self.meshes.retain(|_, m| m.owner.strong_count() > 0);
        self.scratch.clear();
        self.texels.clear();
        self.draws.clear();
        for draw in draws {
            let data = match &draw.coarse {
                Some(mesh) if coarse(draw) => mesh,
                _ => &draw.mesh,
            };
            let key = Arc::as_ptr(data) as usize;
            if !self.meshes.contains_key(&key) {
                let bytes: &[u8] = bytemuck::cast_slice(&data.vertices);
                if bytes.len() as u64 > device.limits().max_buffer_size || data.indices.is_empty() {
                    continue;
                }
                let buffer = |label, contents: &[u8], usage| {
                    device.create_buffer_init(&wgpu::util::BufferInitDescriptor { label: Some(label), contents, usage })
                };
                let texture = match &data.texture {
                    Some(t) => {
                        let sampler = sampler(device, t.wrap);
                        skin_group(device, queue, &self.texture_layout, &sampler, &t.image)
                    }
                    None => self.white(device, queue),
                };
                let mesh = GpuMesh {
                    texture,
                    owner: Arc::downgrade(data),
                    vertices: buffer(
                        "mocap skinned vertices",
                        bytes,
                        wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::COPY_DST,
                    ),
                    shaped: None,
                    indices: buffer(
                        "mocap skinned indices",
                        bytemuck::cast_slice(&data.indices),
                        wgpu::BufferUsages::INDEX,
                    ),
                    index_count: data.indices.len() as u32,
                };
                self.meshes.insert(key, mesh);
            }
            self.write_shape(queue, key, data, draw.shape.as_ref());
            let base = (self.texels.len() / TEXELS_PER_MATRIX as usize) as u32;
            for j in 0..data.joint_count as usize {
                let m = draw.matrices.get(j).copied().filter(|m| m.is_finite()).unwrap_or(Mat4::IDENTITY);
                self.texels.extend([m.row(0), m.row(1), m.row(2)].map(|r| r.to_array()));
            }
            let [r, g, b, _] = crate::srgb_to_linear(draw.tint);
            self.draws.push((key, self.scratch.len() as u32));
            self.scratch.push(Instance {
                base: [base, 0, 0, 0],
                tint_mode: [r, g, b, if draw.weights_view { 1.0 } else { 0.0 }],
            });
        }
        self.instances.upload(device, queue, &self.scratch);
        self.upload_matrices(device, queue);
    }

    /// Makes mesh `key`'s vertex buffer hold `shape`'s positions (one per
    /// vertex; else the mesh's own), writing it only when that changes.
    fn write_shape(&mut self, queue: &wgpu::Queue, key: usize, data: &SkinnedMeshData, shape: Option<&Arc<[Vec3]>>) {
        let Some(mesh) = self.meshes.get_mut(&key) else { return };
        let shape = shape.filter(|s| s.len() == data.vertices.len());
        let wanted = shape.map(|s| Arc::as_ptr(s).cast::<Vec3>() as usize);
        if mesh.shaped == wanted {
            return;
        }
        match shape {
            Some(shape) => {
                self.shaped.clear();
                let moved = data.vertices.iter().zip(shape.iter());
                self.shaped.extend(moved.map(|(v, p)| SkinnedVertex { position: p.to_array(), ..*v }));
                queue.write_buffer(&mesh.vertices, 0, bytemuck::cast_slice(&self.shaped));
            }
            None => queue.write_buffer(&mesh.vertices, 0, bytemuck::cast_slice(&data.vertices)),
        }
        mesh.shaped = wanted;
    }

    /// The white texture's bind group (made once).
    fn white(&mut self, device: &wgpu::Device, queue: &wgpu::Queue) -> wgpu::BindGroup {
        let layout = &self.texture_layout;
        self.white
            .get_or_insert_with(|| {
                let white = SkinImage { width: 1, height: 1, pixels: vec![255; 4] };
                skin_group(device, queue, layout, &sampler(device, [wgpu::AddressMode::Repeat; 2]), &white)
            })
            .clone()
    }

    /// Writes the matrices into the joint texture, growing it (rows doubling) when needed.
    fn upload_matrices(&mut self, device: &wgpu::Device, queue: &wgpu::Queue) {
        let matrices = (self.texels.len() / TEXELS_PER_MATRIX as usize) as u32;
        if matrices == 0 {
            return;
        }
        let rows = matrices.div_ceil(MATRICES_PER_ROW);
        let max_rows = device.limits().max_texture_dimension_2d;
        if rows > max_rows {
            self.draws.clear();
            return;
        }
        if self.texture.as_ref().is_none_or(|(_, _, have)| *have < rows) {
            let height = rows.next_power_of_two().min(max_rows);
            let texture = device.create_texture(&wgpu::TextureDescriptor {
                label: Some("mocap joint matrices"),
                size: wgpu::Extent3d { width: MATRICES_PER_ROW * TEXELS_PER_MATRIX, height, depth_or_array_layers: 1 },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format: wgpu::TextureFormat::Rgba32Float,
                usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
                view_formats: &[],
            });
            let view = texture.create_view(&Default::default());
            let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("mocap joint matrices"),
                layout: &self.layout,
                entries: &[wgpu::BindGroupEntry { binding: 0, resource: wgpu::BindingResource::TextureView(&view) }],
            });
            self.texture = Some((texture, group, height));
        }
        let Some((texture, _, _)) = &self.texture else { return };
        // Whole rows: pad the last one.
        let row_texels = (MATRICES_PER_ROW * TEXELS_PER_MATRIX) as usize;
        self.texels.resize(rows as usize * row_texels, [0.0; 4]);
        queue.write_texture(
            wgpu::TexelCopyTextureInfo {
                texture,
                mip_level: 0,
                origin: wgpu::Origin3d::ZERO,
                aspect: wgpu::TextureAspect::All,
            },
            bytemuck::cast_slice(&self.texels),
            wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(MATRICES_PER_ROW * TEXELS_PER_MATRIX * 16),
                rows_per_image: Some(rows),
            },
            wgpu::Extent3d { width: MATRICES_PER_ROW * TEXELS_PER_MATRIX, height: rows, depth_or_array_layers: 1 },
        );
    }

    /// Whether this frame draws any skinned mesh.
    pub fn has_draws(&self) -> bool {
        !self.draws.is_empty() && self.texture.is_some()
    }

    /// Records the draws into `pass` (pipeline and group 0 set); binds the joint
    /// texture at group 2 and, with `textured` (the colour pass), each mesh's
    /// colour texture at group 3. Returns the draw calls made.
    pub fn draw<'a>(&'a self, pass: &mut wgpu::RenderPass<'a>, textured: bool) -> u32 {
        let (Some((instances, _)), Some((_, group, _))) = (self.instances.get(), &self.texture) else { return 0 };
        pass.set_bind_group(2, group, &[]);
        let mut calls = 0;
        for &(key, instance) in &self.draws {
            let Some(mesh) = self.meshes.get(&key) else { continue };
            let at = u64::from(instance) * INSTANCE_SIZE;
            pass.set_vertex_buffer(0, mesh.vertices.slice(..));
            pass.set_vertex_buffer(1, instances.slice(at..at + INSTANCE_SIZE));
            if textured {
                pass.set_bind_group(3, &mesh.texture, &[]);
            }
            pass.set_index_buffer(mesh.indices.slice(..), wgpu::IndexFormat::Uint32);
            pass.draw_indexed(0..mesh.index_count, 0, 0..1);
            calls += 1;
        }
        calls
    }
}
