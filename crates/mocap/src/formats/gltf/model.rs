//! An MD2 model ([`Model`]) as glTF: one textured mesh whose vertex animation is
//! morph targets, and a `weights` animation per named animation.
//!
//! Input: the model (its key frames, texture coordinates and skin). Output: a
//! `.glb` or `.gltf` in metres, Y up ([`MorphMesh::units`]):
//! - the mesh's base is key frame 0; target `k` holds key frame `k` less the
//!   base (positions and normals), so the weights one-hot at `k` give frame `k`
//!   and a `LINEAR` blend of two one-hot keys is Quake 2's blend of two frames;
//! - every named animation (`stand`, `run`, …) is one glTF animation whose keys
//!   are its frames, [`FRAME_TIME`] apart, each one-hot at its frame;
//! - the skin, when the model has one, is the material's base-colour texture
//!   (PNG in the buffer); texture coordinates are the model's (v down).

use super::buffer::{Binary, bounds, glb, push_accessor, vertex_accessor};
use super::write::WriteError;
use crate::model::mesh::{FRAME_TIME, Model, MorphMesh};
use glam::Vec3;
use serde_json::{Value, json};

/// The model as a binary glTF (`.glb`), named `name`.
pub fn model_to_glb(model: &Model, name: &str) -> Result<Vec<u8>, WriteError> {
    let (json, bin) = document(model, name, false)?;
    glb(&json, bin)
}

/// The model as a text glTF (`.gltf`), its buffer inline as a `data:` URI.
pub fn model_to_gltf(model: &Model, name: &str) -> Result<String, WriteError> {
    let (json, _) = document(model, name, true)?;
    Ok(serde_json::to_string_pretty(&json).unwrap_or_default())
}

/// The JSON document and its binary buffer.
fn document(model: &Model, name: &str, inline: bool) -> Result<(Value, Vec<u8>), WriteError> {
    let mesh = &model.mesh;
    let scale = mesh.units().meters_per_unit();
    let (count, frames) = (mesh.vertex_count(), mesh.frame_count());
    let frame = |k: usize| -> (Vec<Vec3>, Vec<Vec3>) {
        let at = k.saturating_mul(count);
        let slice = |all: &[[f32; 3]]| all.get(at..at + count).unwrap_or(&[]).iter().map(|p| Vec3::from(*p)).collect();
        let positions: Vec<Vec3> = slice(mesh.positions());
        (positions.into_iter().map(|p| p * scale).collect(), slice(mesh.normals()))
    };
    let mut bin = Binary::default();
    let mut accessors = Vec::new();
    let (base, base_normals) = frame(0);
    let flat = |v: &[Vec3]| v.iter().flat_map(|p| p.to_array()).collect::<Vec<f32>>();
    let position = vertex_accessor(&mut accessors, &mut bin, &flat(&base), "VEC3", count, Some(bounds(&base)));
    let normal = vertex_accessor(&mut accessors, &mut bin, &flat(&base_normals), "VEC3", count, None);
    let uvs: Vec<f32> = mesh.tex_coords().iter().flatten().copied().collect();
    let texcoord = vertex_accessor(&mut accessors, &mut bin, &uvs, "VEC2", count, None);
    let indices_at = bin.u32s(mesh.indices());
    let indices = push_accessor(&mut accessors, indices_at, "SCALAR", 5125, mesh.indices().len(), None);
    let targets: Vec<Value> = (0..frames)
        .map(|k| {
            let (p, n) = frame(k);
            let dp: Vec<Vec3> = p.iter().zip(&base).map(|(a, b)| *a - *b).collect();
            let dn: Vec<Vec3> = n.iter().zip(&base_normals).map(|(a, b)| *a - *b).collect();
            let position = vertex_accessor(&mut accessors, &mut bin, &flat(&dp), "VEC3", count, Some(bounds(&dp)));
            let normal = vertex_accessor(&mut accessors, &mut bin, &flat(&dn), "VEC3", count, None);
            json!({ "POSITION": position, "NORMAL": normal })
        })
        .collect();
    let mut document = json!({
        "asset": { "version": "2.0", "generator": "mocap (motion-capture viewer and editor)" },
        "scene": 0,
        "scenes": [{ "name": name, "nodes": [0] }],
        "nodes": [{ "name": name, "mesh": 0 }],
        "meshes": [{
            "name": name,
            "primitives": [{
                "attributes": { "POSITION": position, "NORMAL": normal, "TEXCOORD_0": texcoord },
                "indices": indices,
                "material": 0,
                "targets": targets,
            }],
            "weights": vec![0.0; frames],
            "extras": { "targetNames": mesh.frame_names() },
        }],
    });
    document["materials"] = json!([material(model, &mut bin, &mut document)?]);
    document["animations"] = Value::Array(animations(mesh, &mut accessors, &mut bin));
    document["accessors"] = Value::Array(accessors);
    let data = bin.finish(&mut document, inline)?;
    Ok((document, data))
}

/// The material: the skin as its base-colour texture, or a plain grey.
fn material(model: &Model, bin: &mut Binary, document: &mut Value) -> Result<Value, WriteError> {
    let plain = json!({ "name": "skin", "pbrMetallicRoughness": { "baseColorFactor": [0.7, 0.7, 0.7, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.8 } });
    let Some(skin) = &model.skin else { return Ok(plain) };
    let image = &skin.image;
    let mut png = Vec::new();
    image::ImageEncoder::write_image(
        image::codecs::png::PngEncoder::new(&mut png),
        &image.pixels,
        image.width,
        image.height,
        image::ExtendedColorType::Rgba8,
    )
    .map_err(|e| WriteError::Image(e.to_string()))?;
    let view = bin.view(&png, None);
    document["images"] = json!([{ "name": skin.name, "bufferView": view, "mimeType": "image/png" }]);
    document["samplers"] = json!([{ "magFilter": 9729, "minFilter": 9729, "wrapS": 10497, "wrapT": 10497 }]);
    document["textures"] = json!([{ "source": 0, "sampler": 0 }]);
    Ok(json!({
        "name": "skin",
        "pbrMetallicRoughness": { "baseColorTexture": { "index": 0 }, "metallicFactor": 0.0, "roughnessFactor": 0.8 },
    }))
}

/// One `weights` animation per named animation (all frames as `all` when the
/// model names none): a key per frame, one-hot at it.
fn animations(mesh: &MorphMesh, accessors: &mut Vec<Value>, bin: &mut Binary) -> Vec<Value> {
    let frames = mesh.frame_count();
    let all = [(String::from("all"), 0, frames.saturating_sub(1))];
    let named: Vec<(String, usize, usize)> =
        mesh.animations().iter().map(|a| (a.name.clone(), a.first, a.last)).collect();
    let list: &[(String, usize, usize)] = if named.is_empty() { &all } else { &named };
    list.iter()
        .filter(|(_, first, last)| first <= last && *last < frames)
        .map(|(name, first, last)| {
            let keys = last - first + 1;
            let times: Vec<f32> = (0..keys).map(|i| (i as f64 * FRAME_TIME) as f32).collect();
            let end = times.last().copied().unwrap_or(0.0);
            let input_at = bin.f32s(&times, None);
            let input = push_accessor(accessors, input_at, "SCALAR", 5126, keys, Some((vec![0.0], vec![end])));
            let mut weights = vec![0.0f32; keys * frames];
            for i in 0..keys {
                weights[i * frames + first + i] = 1.0;
            }
            let output_at = bin.f32s(&weights, None);
            let output = push_accessor(accessors, output_at, "SCALAR", 5126, keys * frames, None);
            json!({
                "name": name,
                "samplers": [{ "input": input, "output": output, "interpolation": "LINEAR" }],
                "channels": [{ "sampler": 0, "target": { "node": 0, "path": "weights" } }],
            })
        })
        .collect()
}
