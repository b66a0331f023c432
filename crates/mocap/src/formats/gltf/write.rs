//! Writes a clip as glTF 2.0 (`.glb`, or `.gltf` with its buffer inline): one
//! node per joint (its name, its rest transform), a skin over them, a body mesh
//! skinned to it ([`crate::build::body`], so an importer shows an armature with
//! a visible body rather than bare empties), and one animation at the clip's
//! frame times.
//!
//! Lengths are metres (from the clip's unit, [`Clip::units`]) and Y is up (a
//! Z-up clip is turned, [`Clip::up_axis`]). Each node's animated transform is
//! derived from the core's own world transforms ([`Clip::world_transforms_into`]),
//! so every joint's world position in the written file is ours at every frame,
//! whatever the channels do (stretch, scale, rest rotations). Rotations are unit
//! quaternions, sampled `LINEAR`, each the same hemisphere as the one before (so
//! importers slerp the short way); translations are written for the joints that
//! move them, scales for the joints that scale.
//!
//! Inputs: a clip and [`Options`]. Output: the file's bytes (or text). One pass
//! over the frames, no recursion; a clip without frames writes the rest pose and
//! no animation.

use super::buffer::{Binary, accessor, bounds, glb, push_accessor, vertex_accessor};
use crate::build::body;
use crate::model::clip::Clip;
use crate::runtime::fk::{Transform, local_to_model};
use crate::runtime::pose::LocalPose;
use crate::runtime::skin::MAX_INFLUENCES;
use glam::{Mat4, Quat, Vec3};
use serde_json::{Value, json};

/// What to write besides the skeleton and its animation.
#[derive(Clone, Debug, PartialEq)]
pub struct Options {
    /// The animation's (and the scene's) name, e.g. the file stem.
    pub name: String,
    /// Write the generated body mesh skinned to the skeleton.
    pub body: bool,
}

impl Default for Options {
    fn default() -> Options {
        Options { name: "motion".to_owned(), body: true }
    }
}

/// Why a clip could not be written.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum WriteError {
    /// A joint's transform at a frame is not finite (a NaN in the motion).
    #[error("joint `{joint}` at frame {frame}: the transform is not finite")]
    NotFinite {
        /// The joint's name.
        joint: String,
        /// The frame.
        frame: usize,
    },
    /// The binary chunk would pass glTF's 4 GiB limit.
    #[error("{0} bytes of data: more than a glTF buffer can hold")]
    TooLarge(usize),
    /// The look's texture could not be encoded as PNG.
    #[error("the texture cannot be written as PNG: {0}")]
    Image(String),
}

/// The clip as a binary glTF (`.glb`).
pub fn to_glb(clip: &Clip, options: &Options) -> Result<Vec<u8>, WriteError> {
    let (json, bin) = document(clip, options, None)?;
    glb(&json, bin)
}

/// The clip as a text glTF (`.gltf`), its buffer inline as a `data:` URI.
pub fn to_gltf(clip: &Clip, options: &Options) -> Result<String, WriteError> {
    let (json, _) = document(clip, options, Some(()))?;
    Ok(serde_json::to_string_pretty(&json).unwrap_or_default())
}

/// The JSON document and its binary buffer (inline as base64 when `inline`).
fn document(clip: &Clip, options: &Options, inline: Option<()>) -> Result<(Value, Vec<u8>), WriteError> {
    let joints = clip.skeleton().joints();
    let n = joints.len();
    let convert = Convert::of(clip);
    let mut bin = Binary::default();
    let mut accessors = Vec::new();

    // Rest pose: the nodes' own transforms.
    let mut world = Vec::new();
    local_to_model(clip.skeleton(), &LocalPose::rest(clip.skeleton()), &mut world);
    let world: Vec<Transform> = world.iter().map(|w| convert.world(*w)).collect();
    let rest = convert.locals(clip, &world, 0)?;

    // The bind pose (frame 0, as the viewer's body) for the skin and the mesh.
    let bind: Vec<Transform> = clip.bind_pose().iter().map(|t| convert.world(*t)).collect();
    let mut nodes: Vec<Value> = joints
        .iter()
        .enumerate()
        .map(|(i, j)| {
            let mut node = json!({ "name": j.name });
            let (t, r, s) = rest[i];
            if t != Vec3::ZERO {
                node["translation"] = json!(t.to_array());
            }
            if r != Quat::IDENTITY {
                node["rotation"] = json!(r.to_array());
            }
            if s != Vec3::ONE {
                node["scale"] = json!(s.to_array());
            }
            let children: Vec<usize> = (0..n).filter(|&c| parent_of(clip, c) == Some(i)).collect();
            if !children.is_empty() {
                node["children"] = json!(children);
            }
            node
        })
        .collect();
    let mut roots: Vec<usize> = (0..n).filter(|&i| parent_of(clip, i).is_none()).collect();

    // A character's own look is written as it was read (its file space is the
    // written one: metres, Y up), with its own inverse bind matrices.
    let look = own_look(clip, &convert);
    let inverse_bind: Vec<f32> = match look {
        Some(look) => look.skin.inverse_bind().iter().flat_map(|m| m.to_cols_array()).collect(),
        None => bind.iter().flat_map(|t| inverse_bind_matrix(t).to_cols_array()).collect(),
    };
    let ibm = accessor(&mut accessors, &mut bin, &inverse_bind, "MAT4", 5126, n, None);
    let mut document = json!({
        "asset": { "version": "2.0", "generator": "mocap (motion-capture viewer and editor)" },
        "scene": 0,
        "scenes": [{ "name": options.name, "nodes": [] }],
        "skins": [{ "name": options.name, "joints": (0..n).collect::<Vec<_>>(), "inverseBindMatrices": ibm }],
    });
    if let Some(root) = roots.first() {
        document["skins"][0]["skeleton"] = json!(root);
    }

    let mesh = match look {
        Some(look) => look_mesh(look),
        None => body_mesh(clip, &bind, &convert),
    };
    if options.body
        && let Some(mesh) = mesh
    {
        let positions: Vec<f32> = mesh.positions.iter().flat_map(|p| p.to_array()).collect();
        let (min, max) = bounds(&mesh.positions);
        let normals: Vec<f32> = mesh.normals.iter().flat_map(|p| p.to_array()).collect();
        let position =
            vertex_accessor(&mut accessors, &mut bin, &positions, "VEC3", mesh.positions.len(), Some((min, max)));
        let normal = vertex_accessor(&mut accessors, &mut bin, &normals, "VEC3", mesh.normals.len(), None);
        let joints_at = bin.u16s(&mesh.joints.concat());
        let joints_0 = push_accessor(&mut accessors, joints_at, "VEC4", 5123, mesh.joints.len(), None);
        let weights: Vec<f32> = mesh.weights.concat();
        let weights_0 = vertex_accessor(&mut accessors, &mut bin, &weights, "VEC4", mesh.weights.len(), None);
        let mut attributes =
            json!({ "POSITION": position, "NORMAL": normal, "JOINTS_0": joints_0, "WEIGHTS_0": weights_0 });
        let whole = |attributes: &Value, accessors: &mut Vec<Value>, bin: &mut Binary| {
            let at = bin.u32s(&mesh.indices);
            let indices = push_accessor(accessors, at, "SCALAR", 5125, mesh.indices.len(), None);
            vec![json!({ "attributes": attributes, "indices": indices, "material": 0 })]
        };
        let mut primitives = Vec::new();
        if let Some(look) = look {
            // With a texture: the colours it is multiplied with, and the texture.
            let surface = look.surface.as_ref();
            let colors = surface.map_or(&look.colors, |s| &s.tints);
            let colors: Vec<f32> = colors.iter().flat_map(|c| c.map(crate::model::character::srgb_to_linear)).collect();
            attributes["COLOR_0"] =
                json!(vertex_accessor(&mut accessors, &mut bin, &colors, "VEC4", look.colors.len(), None));
            if let Some(surface) = surface {
                primitives = textured_primitives(
                    surface,
                    &mesh.indices,
                    &mut attributes,
                    &mut accessors,
                    &mut bin,
                    &mut document,
                )?;
            }
        }
        if primitives.is_empty() {
            primitives = whole(&attributes, &mut accessors, &mut bin);
        }
        document["meshes"] = json!([{ "name": format!("{} body", options.name), "primitives": primitives }]);
        if let Some(morph) = look.and_then(|l| l.morph.as_ref()) {
            write_targets(morph, mesh.positions.len(), &mut document, &mut accessors, &mut bin);
        }
        let factor = if look.is_some() { [1.0, 1.0, 1.0, 1.0] } else { [0.8, 0.8, 0.82, 1.0] };
        let material = |name: &str| json!({ "name": name, "pbrMetallicRoughness": { "baseColorFactor": factor, "metallicFactor": 0.0, "roughnessFactor": 0.7 } });
        let mut materials = vec![material("body")];
        if document.get("textures").is_some() {
            let mut textured = material("body, textured");
            textured["pbrMetallicRoughness"]["baseColorTexture"] = json!({ "index": 0 });
            materials.push(textured);
        }
        document["materials"] = Value::Array(materials);
        nodes.push(json!({ "name": format!("{} body", options.name), "mesh": 0, "skin": 0 }));
        roots.push(nodes.len() - 1);
    }
    document["scenes"][0]["nodes"] = json!(roots);
    document["nodes"] = Value::Array(nodes);

    if clip.frame_count() > 0 {
        let mut animation = animation(clip, options, &convert, &rest, &mut accessors, &mut bin)?;
        let morphs = document.get("meshes").and_then(|m| m[0].get("weights")).is_some();
        if morphs {
            // The body node is the last one written.
            let node = document["nodes"].as_array().map_or(0, |n| n.len().saturating_sub(1));
            add_weights(clip, node, &mut animation, &mut accessors, &mut bin);
        }
        document["animations"] = json!([animation]);
    }
    document["accessors"] = Value::Array(accessors);
    let data = bin.finish(&mut document, inline.is_some())?;
    Ok((document, data))
}

/// The clip's parent of joint `i` (only a parent listed before it counts).
fn parent_of(clip: &Clip, i: usize) -> Option<usize> {
    clip.skeleton().joints().get(i)?.parent.filter(|&p| p < i)
}

/// The one animation: every joint's rotation, and translations and scales where
/// they leave the rest pose's (`rest`, the nodes' own transforms).
fn animation(
    clip: &Clip,
    options: &Options,
    convert: &Convert,
    rest: &[(Vec3, Quat, Vec3)],
    accessors: &mut Vec<Value>,
    bin: &mut Binary,
) -> Result<Value, WriteError> {
    let n = clip.skeleton().len();
    let frames = clip.frame_count();
    let timeline = clip.timeline();
    let times: Vec<f32> = (0..frames).map(|f| timeline.time_of(f) as f32).collect();
    let (first, last) = (times.first().copied().unwrap_or(0.0), times.last().copied().unwrap_or(0.0));
    let input = accessor(accessors, bin, &times, "SCALAR", 5126, frames, Some((vec![first], vec![last])));
    // Frame-major locals, gathered joint-major for the samplers.
    let (mut t, mut r, mut s) =
        (vec![Vec3::ZERO; n * frames], vec![Quat::IDENTITY; n * frames], vec![Vec3::ONE; n * frames]);
    let mut world = Vec::new();
    for f in 0..frames {
        clip.world_transforms_into(f, &mut world);
        let world: Vec<Transform> = world.iter().map(|w| convert.world(*w)).collect();
        for (j, (tj, rj, sj)) in convert.locals(clip, &world, f)?.into_iter().enumerate() {
            t[j * frames + f] = tj;
            s[j * frames + f] = sj;
            let previous = if f > 0 { r[j * frames + f - 1] } else { Quat::IDENTITY };
            r[j * frames + f] = if previous.dot(rj) < 0.0 { -rj } else { rj };
        }
    }
    let (mut samplers, mut channels) = (Vec::new(), Vec::new());
    let mut add =
        |path: &str, joint: usize, values: Vec<f32>, kind: &str, accessors: &mut Vec<Value>, bin: &mut Binary| {
            let output = accessor(accessors, bin, &values, kind, 5126, frames, None);
            samplers.push(json!({ "input": input, "output": output, "interpolation": "LINEAR" }));
            channels.push(json!({ "sampler": samplers.len() - 1, "target": { "node": joint, "path": path } }));
        };
    for j in 0..n {
        let span = j * frames..(j + 1) * frames;
        let rotations: Vec<f32> = r[span.clone()].iter().flat_map(|q| q.to_array()).collect();
        add("rotation", j, rotations, "VEC4", accessors, bin);
        let (rest_t, _, rest_s) = rest.get(j).copied().unwrap_or((Vec3::ZERO, Quat::IDENTITY, Vec3::ONE));
        let moves = t[span.clone()].iter().any(|x| (*x - rest_t).abs().max_element() > 1e-7);
        if moves {
            add("translation", j, t[span.clone()].iter().flat_map(|x| x.to_array()).collect(), "VEC3", accessors, bin);
        }
        if s[span.clone()].iter().any(|x| *x != rest_s) {
            add("scale", j, s[span].iter().flat_map(|x| x.to_array()).collect(), "VEC3", accessors, bin);
        }
    }
    Ok(json!({ "name": options.name, "samplers": samplers, "channels": channels }))
}

/// The file's lengths in metres and its up along +Y.
struct Convert {
    up: Quat,
    meters: f32,
}

impl Convert {
    fn of(clip: &Clip) -> Convert {
        Convert { up: clip.up_axis().rotation(), meters: clip.units().meters_per_unit() }
    }

    /// A world transform of the file, in the written world.
    fn world(&self, t: Transform) -> Transform {
        Transform {
            rotation: (self.up * t.rotation).normalize(),
            translation: self.up * t.translation * self.meters,
            scale: t.scale,
        }
    }

    /// Each joint's transform relative to its parent's, from the world transforms
    /// (the parent's rotation and uniform scale undone; roots are their world).
    fn locals(&self, clip: &Clip, world: &[Transform], frame: usize) -> Result<Vec<(Vec3, Quat, Vec3)>, WriteError> {
        let joints = clip.skeleton().joints();
        let mut out = Vec::with_capacity(world.len());
        for (i, w) in world.iter().enumerate() {
            let local = match parent_of(clip, i).and_then(|p| world.get(p)) {
                None => (w.translation, w.rotation, w.scale),
                Some(p) => {
                    let inv = p.rotation.inverse();
                    let ps = p.scale;
                    let safe = |x: f32| if x.abs() > 1e-12 { x } else { 1.0 };
                    let per = Vec3::new(safe(ps.x), safe(ps.y), safe(ps.z));
                    ((inv * (w.translation - p.translation)) / per, (inv * w.rotation).normalize(), w.scale / per)
                }
            };
            let finite = local.0.is_finite() && local.1.is_finite() && local.2.is_finite();
            if !finite {
                let joint = joints.get(i).map_or_else(String::new, |j| j.name.clone());
                return Err(WriteError::NotFinite { joint, frame });
            }
            out.push(local);
        }
        Ok(out)
    }
}

/// The inverse of a bind transform, its last row exactly `0 0 0 1` (glTF requires
/// an affine inverse bind matrix; a general inverse rounds it).
fn inverse_bind_matrix(t: &Transform) -> Mat4 {
    let mut m = Mat4::from_scale_rotation_translation(t.scale, t.rotation, t.translation).inverse();
    m.x_axis.w = 0.0;
    m.y_axis.w = 0.0;
    m.z_axis.w = 0.0;
    m.w_axis.w = 1.0;
    m
}

/// The generated body around the bind pose, in the written world, with each
/// vertex's joints unique (repeats merged) and its weights summing to 1.
struct BodyMesh {
    positions: Vec<Vec3>,
    normals: Vec<Vec3>,
    indices: Vec<u32>,
    joints: Vec<[u16; MAX_INFLUENCES]>,
    weights: Vec<[f32; MAX_INFLUENCES]>,
}

/// The body mesh, or none when the skeleton has too many bones for one (or more
/// joints than 16-bit joint indices reach).
fn body_mesh(clip: &Clip, bind: &[Transform], convert: &Convert) -> Option<BodyMesh> {
    if clip.skeleton().len() > usize::from(u16::MAX) {
        return None;
    }
    let extent = clip.pose_extent() * convert.meters;
    let radius = |_: usize, l: f32| (l * 0.2).clamp(extent * 0.008, extent * 0.04) * 1.8;
    let skin = body::build(clip.skeleton(), bind, radius).ok()?;
    let mut joints = Vec::with_capacity(skin.joints().len());
    let mut weights = Vec::with_capacity(skin.weights().len());
    for (js, ws) in skin.joints().iter().zip(skin.weights()) {
        let mut j = [0u16; MAX_INFLUENCES];
        let mut w = [0f32; MAX_INFLUENCES];
        let mut used = 0;
        for (&joint, &weight) in js.iter().zip(ws) {
            if weight <= 0.0 {
                continue;
            }
            let joint = u16::try_from(joint).ok()?;
            match j[..used].iter().position(|&x| x == joint) {
                Some(k) => w[k] += weight,
                None => {
                    j[used] = joint;
                    w[used] = weight;
                    used += 1;
                }
            }
        }
        let sum: f32 = w.iter().sum();
        if used == 0 || sum <= 0.0 {
            w[0] = 1.0;
        } else {
            w.iter_mut().for_each(|x| *x /= sum);
        }
        joints.push(j);
        weights.push(w);
    }
    Some(BodyMesh {
        positions: skin.positions().to_vec(),
        normals: skin.normals().iter().map(|n| n.normalize_or(Vec3::Y)).collect(),
        indices: skin.indices().to_vec(),
        joints,
        weights,
    })
}

/// The clip's character look, when it can be written as it is: one inverse bind
/// matrix per joint, and the clip already in metres with Y up.
fn own_look<'c>(clip: &'c Clip, convert: &Convert) -> Option<&'c crate::model::character::Look> {
    let look = clip.character.as_ref()?.look.as_ref()?;
    let same_space = convert.meters == 1.0 && convert.up.abs_diff_eq(Quat::IDENTITY, 1e-6);
    (same_space && look.skin.inverse_bind().len() == clip.skeleton().len() && clip.skeleton().len() <= 65535)
        .then_some(look)
}

/// A look's texture written into `document` (its PNG in the buffer, a texture
/// and its sampler; material 1 uses it) and the mesh's primitives: the triangles
/// whose corners all have a texture coordinate with the texture (material 1),
/// the rest without (material 0). `attributes` gains `TEXCOORD_0` (0, 0 where a
/// vertex has none).
fn textured_primitives(
    surface: &crate::model::character::Surface,
    indices: &[u32],
    attributes: &mut Value,
    accessors: &mut Vec<Value>,
    bin: &mut Binary,
    document: &mut Value,
) -> Result<Vec<Value>, WriteError> {
    use crate::model::character::Wrap;
    use image::ImageEncoder;
    let image = &surface.image;
    let mut png = Vec::new();
    image::codecs::png::PngEncoder::new(&mut png)
        .write_image(&image.pixels, image.width, image.height, image::ExtendedColorType::Rgba8)
        .map_err(|e| WriteError::Image(e.to_string()))?;
    let png_view = bin.view(&png, None);
    let code = |w: Wrap| match w {
        Wrap::Repeat => 10497,
        Wrap::Mirror => 33648,
        Wrap::Clamp => 33071,
    };
    document["images"] = json!([{ "bufferView": png_view, "mimeType": "image/png" }]);
    document["samplers"] =
        json!([{ "magFilter": 9729, "minFilter": 9987, "wrapS": code(image.wrap[0]), "wrapT": code(image.wrap[1]) }]);
    document["textures"] = json!([{ "source": 0, "sampler": 0 }]);
    let uvs: Vec<f32> = surface.uvs.iter().flat_map(|uv| uv.unwrap_or([0.0; 2])).collect();
    attributes["TEXCOORD_0"] = json!(vertex_accessor(accessors, bin, &uvs, "VEC2", surface.uvs.len(), None));
    let textured = |t: &[u32]| t.iter().all(|&v| surface.uvs.get(v as usize).is_some_and(Option::is_some));
    let (with, without): (Vec<&[u32]>, Vec<&[u32]>) = indices.chunks_exact(3).partition(|t| textured(t));
    let mut primitives = Vec::new();
    for (triangles, material) in [(without, 0), (with, 1)] {
        if triangles.is_empty() {
            continue;
        }
        let list: Vec<u32> = triangles.concat();
        let at = bin.u32s(&list);
        let indices = push_accessor(accessors, at, "SCALAR", 5125, list.len(), None);
        primitives.push(json!({ "attributes": attributes.clone(), "indices": indices, "material": material }));
    }
    Ok(primitives)
}

/// A look's morph targets on the written mesh: per target a `POSITION`
/// accessor of every vertex's offset (with its bounds, as the specification
/// asks) on each primitive, and the rest weights as the mesh's `weights`.
fn write_targets(
    morph: &crate::model::character::Morph,
    vertices: usize,
    document: &mut Value,
    accessors: &mut Vec<Value>,
    bin: &mut Binary,
) {
    let mut targets = Vec::with_capacity(morph.targets.len());
    for target in &morph.targets {
        let mut offsets = vec![Vec3::ZERO; vertices];
        for &(v, d) in target {
            if let Some(slot) = offsets.get_mut(v as usize) {
                *slot = Vec3::from_array(d);
            }
        }
        let values: Vec<f32> = offsets.iter().flat_map(|d| d.to_array()).collect();
        let position = vertex_accessor(accessors, bin, &values, "VEC3", vertices, Some(bounds(&offsets)));
        targets.push(json!({ "POSITION": position }));
    }
    if let Some(primitives) = document["meshes"][0]["primitives"].as_array_mut() {
        for primitive in primitives {
            primitive["targets"] = json!(targets);
        }
    }
    document["meshes"][0]["weights"] = json!(morph.rest);
}

/// The clip's morph-target weights at each frame ([`Clip::morph_weights_at`])
/// as a `LINEAR` weights channel on mesh node `node` of `animation`, when a
/// take sets them (rest weights alone need no channel).
fn add_weights(clip: &Clip, node: usize, animation: &mut Value, accessors: &mut Vec<Value>, bin: &mut Binary) {
    let timeline = clip.timeline();
    let frames = clip.frame_count();
    let (mut values, mut weights) = (Vec::new(), Vec::new());
    for f in 0..frames {
        if !clip.morph_weights_at(timeline.time_of(f), &mut weights) {
            return;
        }
        values.extend_from_slice(&weights);
    }
    let rest = clip.character.as_deref().and_then(|c| c.look.as_ref()?.morph.as_ref()).map(|m| m.rest.as_slice());
    if rest.is_none_or(|rest| values.chunks(rest.len().max(1)).all(|w| w == rest)) {
        return;
    }
    // The same key times as the joints' channels (their first sampler's input).
    let Some(input) = animation["samplers"].get(0).and_then(|s| s.get("input")).cloned() else { return };
    let output = accessor(accessors, bin, &values, "SCALAR", 5126, values.len(), None);
    let Some(samplers) = animation["samplers"].as_array_mut() else { return };
    samplers.push(json!({ "input": input, "output": output, "interpolation": "LINEAR" }));
    let sampler = samplers.len() - 1;
    if let Some(channels) = animation["channels"].as_array_mut() {
        channels.push(json!({ "sampler": sampler, "target": { "node": node, "path": "weights" } }));
    }
}

/// A character's look as the written mesh.
fn look_mesh(look: &crate::model::character::Look) -> Option<BodyMesh> {
    let skin = &look.skin;
    Some(BodyMesh {
        positions: skin.positions().to_vec(),
        normals: skin.normals().iter().map(|n| n.normalize_or(Vec3::Y)).collect(),
        indices: skin.indices().to_vec(),
        joints: skin.joints().iter().map(|js| js.map(|j| u16::try_from(j).unwrap_or(0))).collect(),
        weights: skin.weights().to_vec(),
    })
}
