//! A glTF whose mesh moves by morph targets alone, with no skin (an MD2 model
//! written by [`super::model`], a prop animated with blend shapes), read as a
//! vertex-animated [`Model`] that plays its `weights` animations.
//!
//! Input: the checked document. Output: `None` unless the scene has no skin and
//! a mesh node whose first triangle primitive has morph targets and at least
//! one animation drives that node's `weights`; else the model:
//! - each such animation sampled at [`FRAME_TIME`] steps (its keys blended as
//!   the spec says: `STEP`, `LINEAR`, or `CUBICSPLINE`'s Hermite form) gives
//!   key frames, base + Σ weightᵢ · targetᵢ, positions and normals, in the
//!   node's world space and in Quake units (the unit every [`Model`] is in);
//! - one named animation per glTF animation; the base-colour texture as skin.
//!
//! Key frames × vertices are bounded ([`MAX_VALUES`]): a file past it is read
//! as a character instead (its morph channels warned about).

use super::accessor::{floats, integers};
use super::document::{Parsed, Resources};
use super::graph::Graph;
use super::look::{computed_normals, image_bytes, triangles};
use crate::error::ParseError;
use crate::model::clip::Units;
use crate::model::mesh::{Animation, FRAME_TIME, MeshParts, Model, MorphMesh, QUAKE_PLAYER_HEIGHT, Skin, SourceCounts};
use glam::{Mat3, Mat4, Vec3};
use super::animation::weight_track;
use gltf::animation::Property;

/// Most key frames × vertices read (24 bytes each: about 200 MB).
pub const MAX_VALUES: usize = 8 << 20;

/// Most vertices of a model (MD2 triangles index vertices with 16 bits).
const MAX_VERTICES: usize = 1 << 16;

/// The model the document holds, when it is one (see the module documentation).
pub fn model(parsed: &Parsed<'_>, graph: &Graph, resources: Resources<'_>) -> Result<Option<Model>, ParseError> {
    let document = &parsed.document;
    if document.skins().len() > 0 {
        return Ok(None);
    }
    let Some((node, primitive)) = graph.order.iter().find_map(|&n| {
        let node = document.nodes().nth(n)?;
        let primitive = node.mesh()?.primitives().find(|p| p.morph_targets().len() > 0)?;
        Some((node, primitive))
    }) else {
        return Ok(None);
    };
    let channels: Vec<(String, gltf::animation::Channel<'_>)> = document
        .animations()
        .filter_map(|a| {
            let name = a.name().map_or_else(|| format!("animation {}", a.index()), str::to_owned);
            let channel = a.channels().find(|c| {
                c.target().node().index() == node.index() && c.target().property() == Property::MorphTargetWeights
            })?;
            Some((name, channel))
        })
        .collect();
    if channels.is_empty() {
        return Ok(None);
    }
    let shape = Shape::read(parsed, &primitive)?;
    let targets = shape.targets.len();
    let count = shape.positions.len();
    let mut weights_per_frame: Vec<Vec<f32>> = Vec::new();
    let mut animations = Vec::new();
    for (name, channel) in &channels {
        let first = weights_per_frame.len();
        let sampled = sample(parsed, channel, targets)?;
        if sampled.is_empty() {
            continue;
        }
        weights_per_frame.extend(sampled);
        animations.push(Animation { name: name.clone(), first, last: weights_per_frame.len() - 1 });
    }
    let frames = weights_per_frame.len();
    if frames == 0 || count == 0 || count > MAX_VERTICES || frames.saturating_mul(count) > MAX_VALUES {
        return Ok(None);
    }
    let to_quake = 1.0 / Units::guess(QUAKE_PLAYER_HEIGHT).meters_per_unit();
    let world = world_matrix(graph, node.index());
    let normal_matrix = Mat3::from_mat4(world).inverse().transpose();
    let (mut positions, mut normals) = (Vec::with_capacity(frames * count), Vec::with_capacity(frames * count));
    for weights in &weights_per_frame {
        for v in 0..count {
            let (mut p, mut n) = (shape.positions[v], shape.normals[v]);
            for (w, (dp, dn)) in weights.iter().zip(&shape.targets) {
                p += *w * dp.get(v).copied().unwrap_or(Vec3::ZERO);
                n += *w * dn.get(v).copied().unwrap_or(Vec3::ZERO);
            }
            positions.push((world.transform_point3(p) * to_quake).to_array());
            normals.push((normal_matrix * n).normalize_or(Vec3::Y).to_array());
        }
    }
    let mut frame_names = Vec::with_capacity(frames);
    for a in &animations {
        frame_names.extend((1..=a.last - a.first + 1).map(|k| format!("{}{k:02}", a.name)));
    }
    let skin = skin_of(parsed, &primitive, resources);
    let parts = MeshParts {
        positions,
        normals,
        tex_coords: shape.uvs,
        sources: (0..count as u32).collect(),
        source_counts: SourceCounts { vertices: count, triangles: shape.indices.len() / 3, tex_coords: count },
        indices: shape.indices,
        frame_names,
        animations,
        skins: skin.iter().map(|s| s.name.clone()).collect(),
        skin_size: skin.as_ref().map_or([0, 0], |s| [s.image.width, s.image.height]),
    };
    let mesh = MorphMesh::checked_from_parts(parts).map_err(|e| ParseError::new(0, 0, e))?;
    Ok(Some(Model::new(mesh, skin)))
}

/// The base mesh and its targets' offsets.
struct Shape {
    positions: Vec<Vec3>,
    normals: Vec<Vec3>,
    uvs: Vec<[f32; 2]>,
    indices: Vec<u32>,
    /// Per target: position and normal offsets per vertex.
    targets: Vec<(Vec<Vec3>, Vec<Vec3>)>,
}

impl Shape {
    fn read(parsed: &Parsed<'_>, primitive: &gltf::Primitive<'_>) -> Result<Shape, ParseError> {
        let buffers = &parsed.buffers;
        let vec3s = |a: &gltf::Accessor<'_>| -> Result<Vec<Vec3>, ParseError> {
            Ok(floats(a, buffers, 3)?.chunks_exact(3).map(Vec3::from_slice).collect())
        };
        let position = primitive
            .get(&gltf::Semantic::Positions)
            .ok_or_else(|| ParseError::new(0, 0, "the morphing mesh has no POSITION attribute"))?;
        let positions = vec3s(&position)?;
        let count = positions.len();
        let mut indices = match primitive.indices() {
            Some(a) => integers(&a, buffers, 1)?,
            None => (0..count as u32).collect(),
        };
        if let Some(v) = indices.iter().find(|v| **v as usize >= count) {
            return Err(ParseError::new(0, 0, format!("the morphing mesh's index {v} is past its {count} vertices")));
        }
        indices = triangles(primitive.mode(), &indices);
        let normals = match primitive.get(&gltf::Semantic::Normals) {
            Some(a) => vec3s(&a)?,
            None => computed_normals(&positions, &indices),
        };
        let uvs = match primitive.get(&gltf::Semantic::TexCoords(0)) {
            Some(a) => floats(&a, buffers, 2)?.chunks_exact(2).map(|c| [c[0], c[1]]).collect(),
            None => vec![[0.0; 2]; count],
        };
        let mut targets = Vec::new();
        for target in primitive.morph_targets() {
            let dp = target.positions().map(|a| vec3s(&a)).transpose()?.unwrap_or_default();
            let dn = target.normals().map(|a| vec3s(&a)).transpose()?.unwrap_or_default();
            targets.push((dp, dn));
        }
        let lengths_agree = normals.len() == count
            && uvs.len() == count
            && targets.iter().all(|(p, n)| (p.is_empty() || p.len() == count) && (n.is_empty() || n.len() == count));
        if !lengths_agree {
            return Err(ParseError::new(0, 0, "the morphing mesh's attributes and targets differ in length"));
        }
        Ok(Shape { positions, normals, uvs, indices, targets })
    }
}

/// The channel's weights at every [`FRAME_TIME`] step from its first key to its last.
fn sample(
    parsed: &Parsed<'_>,
    channel: &gltf::animation::Channel<'_>,
    targets: usize,
) -> Result<Vec<Vec<f32>>, ParseError> {
    let pointer = format!("animations[{}]", channel.animation().index());
    let track = weight_track(channel, &parsed.buffers, &pointer)?;
    if track.targets != targets {
        return Err(ParseError::new(
            0,
            0,
            format!("{pointer}: {} weights a key for a mesh of {targets} targets", track.targets),
        ));
    }
    let (start, end) = (track.times[0], track.end());
    let steps = (((end - start) as f64 / FRAME_TIME) + 1e-6).floor().max(0.0) as usize;
    if steps >= MAX_VALUES {
        return Ok(Vec::new());
    }
    let mut out = Vec::with_capacity(steps + 1);
    let mut cursor = 0;
    for s in 0..=steps {
        let mut weights = vec![0.0; targets];
        track.sample(start + (s as f64 * FRAME_TIME) as f32, &mut cursor, &mut weights);
        out.push(weights);
    }
    Ok(out)
}

/// The node's world matrix: its rest transform and its ancestors'.
fn world_matrix(graph: &Graph, node: usize) -> Mat4 {
    let mut m = Mat4::IDENTITY;
    let mut at = Some(node);
    // The graph has no cycles (Graph::new refuses them); its depth bounds the walk.
    for _ in 0..=graph.parent.len() {
        let Some(n) = at else { break };
        m = graph.rest.get(n).map_or(Mat4::IDENTITY, |r| r.matrix()) * m;
        at = graph.parent.get(n).copied().flatten();
    }
    m
}

/// The primitive's base-colour texture as the model's skin, when it decodes.
fn skin_of(parsed: &Parsed<'_>, primitive: &gltf::Primitive<'_>, resources: Resources<'_>) -> Option<Skin> {
    let info = primitive.material().pbr_metallic_roughness().base_color_texture()?;
    let image = info.texture().source();
    let bytes = image_bytes(parsed, &image, resources).ok()?;
    let name = image.name().map_or_else(|| format!("image {}", image.index()), str::to_owned);
    let rgba = crate::formats::image::decode_any(&name, &bytes).ok()?;
    Some(Skin { name, image: std::sync::Arc::new(rgba) })
}
