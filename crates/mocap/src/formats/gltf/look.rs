//! The meshes of a glTF scene as one [`Look`] skinned to the skeleton.
//!
//! Inputs: the parsed document, the [`Graph`], a way to find external images.
//! Output: every triangle primitive of every mesh node of the scene, merged:
//! skinned meshes keep their `JOINTS_n`/`WEIGHTS_n` (any allowed type, the four
//! largest influences of sets 0 and 1, renormalised) and the skins' inverse bind
//! matrices; a mesh on a plain node moves rigidly with its nearest joint. Normals
//! are computed when absent. Each vertex's colour is the material's base colour
//! factor times its `COLOR_0` times its base-colour texture (PNG or JPEG, through
//! `KHR_texture_transform` and the sampler's wrap modes) at the vertex. The image
//! most textured vertices use is also kept to draw per pixel ([`Surface`]): its
//! vertices' texture coordinates and untextured colours.

use super::accessor::{floats, integers};
use super::document::{Parsed, Resources, fetch};
use super::graph::Graph;
use crate::error::{ParseError, Warning};
use crate::model::character::{Look, Morph, Surface, TextureImage, Wrap, linear_to_srgb, srgb_to_linear};
use crate::model::mesh::Rgba;
use crate::runtime::skin::{MAX_INFLUENCES, Skin};
use glam::{Mat3, Mat4, Vec2, Vec3};
use gltf::mesh::Mode;
use gltf::texture::WrappingMode;

/// The merged mesh being built.
#[derive(Default)]
struct Merged {
    positions: Vec<Vec3>,
    normals: Vec<Vec3>,
    indices: Vec<u32>,
    joints: Vec<[u32; MAX_INFLUENCES]>,
    weights: Vec<[f32; MAX_INFLUENCES]>,
    colors: Vec<[u8; 4]>,
    /// Per vertex: the image that textures it, its (transformed) coordinate and
    /// its colour without the texture.
    textured: Vec<Option<(usize, [f32; 2])>>,
    tints: Vec<[u8; 4]>,
    /// Per image index: its wrap modes where a primitive first used it.
    wraps: Vec<(usize, [WrappingMode; 2])>,
    /// Morph targets of every mesh node, one after another: the vertices each moves.
    targets: Vec<Vec<(u32, [f32; 3])>>,
    /// Their weights at rest (the node's or the mesh's `weights`, else 0).
    rest: Vec<f32>,
    /// Offsets kept so far, all targets together (bounded by [`MAX_MORPH_OFFSETS`]).
    offsets: usize,
}

/// Most morph-target offsets (vertex, target) a look keeps (16 bytes each:
/// about 128 MB); a file past it is drawn without its later targets' shapes.
const MAX_MORPH_OFFSETS: usize = 8 << 20;

/// Which of the look's morph targets a mesh node's `weights` are: the node
/// index, the first target and how many.
pub type MorphNodes = Vec<(usize, usize, usize)>;

/// A decoded base-colour texture with how it is sampled.
struct Texture<'i> {
    /// Its index in the file's images.
    index: usize,
    image: &'i Rgba,
    wrap: [WrappingMode; 2],
    /// `KHR_texture_transform` as a 3×3 matrix on `(u, v, 1)`.
    transform: Mat3,
}

/// Builds the look (`None` when the scene has no drawable mesh) and where each
/// mesh node's morph targets are among the look's.
pub fn build(
    parsed: &Parsed<'_>,
    graph: &Graph,
    resources: Resources<'_>,
    warnings: &mut Vec<Warning>,
) -> Result<(Option<Look>, MorphNodes), ParseError> {
    let mut morph_nodes = MorphNodes::new();
    let document = &parsed.document;
    let inverse_bind = inverse_binds(parsed, graph)?;
    let mut images: Vec<Option<Option<Rgba>>> = vec![None; document.images().len()];
    let mut merged = Merged::default();
    let nodes: Vec<gltf::Node<'_>> = document.nodes().collect();
    for &n in &graph.order {
        let Some(node) = nodes.get(n) else { continue };
        let Some(mesh) = node.mesh() else { continue };
        // Where each skin joint index goes, or the one joint a rigid mesh follows
        // with the transform that puts its vertices in that joint's bind space.
        let binding = match node.skin() {
            Some(skin) => {
                Binding::Skinned(skin.joints().map(|j| graph.joint_of.get(j.index()).copied().flatten()).collect())
            }
            None => {
                let Some(j) = graph.joint_of.get(n).copied().flatten().or(graph.above.get(n).copied().flatten()) else {
                    warnings.push(note(format!("nodes[{n}]: its mesh is outside the skeleton and is not drawn")));
                    continue;
                };
                let rel = if graph.joint_of[n].is_some() {
                    Mat4::IDENTITY
                } else {
                    graph.between[n] * graph.rest[n].matrix()
                };
                let to_bind = inverse_bind.get(j).copied().unwrap_or(Mat4::IDENTITY).inverse() * rel;
                Binding::Rigid(j as u32, to_bind)
            }
        };
        let first_target = merged.targets.len();
        let targets = mesh.primitives().map(|p| p.morph_targets().len()).max().unwrap_or(0);
        if targets > 0 {
            let rest = node.weights().or(mesh.weights()).unwrap_or(&[]);
            merged.targets.extend((0..targets).map(|_| Vec::new()));
            merged.rest.extend((0..targets).map(|i| rest.get(i).copied().filter(|w| w.is_finite()).unwrap_or(0.0)));
            morph_nodes.push((n, first_target, targets));
        }
        for (p, primitive) in mesh.primitives().enumerate() {
            let pointer = format!("meshes[{}].primitives[{p}]", mesh.index());
            let texture = texture(parsed, &primitive, &mut images, resources, warnings);
            let at = (pointer.as_str(), first_target);
            add_primitive(parsed, &primitive, at, &binding, texture.as_ref(), &mut merged, warnings)?;
        }
    }
    if merged.positions.is_empty() {
        return Ok((None, MorphNodes::new()));
    }
    if merged.offsets >= MAX_MORPH_OFFSETS {
        warnings.push(note(format!("more than {MAX_MORPH_OFFSETS} morph-target offsets: the later ones are left out")));
    }
    let surface = surface(&merged, &images);
    let Merged { positions, normals, indices, joints, weights, colors, targets, rest, .. } = merged;
    let skin = Skin::with_inverse_bind(positions, normals, indices, joints, weights, inverse_bind)
        .map_err(|e| ParseError::new(0, 0, format!("the mesh cannot be skinned: {e}")))?;
    let morph = (!targets.is_empty()).then_some(Morph { targets, rest });
    Ok((Some(Look { skin, colors, surface, morph }), morph_nodes))
}

/// The texture drawn per pixel: the image the most vertices use, with each
/// vertex's coordinate (`None` where another image or none colours it: its
/// baked colour is used) and untextured colour.
fn surface(merged: &Merged, images: &[Option<Option<Rgba>>]) -> Option<Surface> {
    let mut counts: Vec<usize> = vec![0; images.len()];
    for (index, _) in merged.textured.iter().flatten() {
        if let Some(c) = counts.get_mut(*index) {
            *c += 1;
        }
    }
    let (chosen, _) = counts.iter().enumerate().filter(|(_, c)| **c > 0).max_by_key(|(_, c)| **c)?;
    let rgba = images.get(chosen)?.as_ref()?.as_ref()?;
    let wrap_of = |m: WrappingMode| match m {
        WrappingMode::Repeat => Wrap::Repeat,
        WrappingMode::MirroredRepeat => Wrap::Mirror,
        WrappingMode::ClampToEdge => Wrap::Clamp,
    };
    let modes = merged.wraps.iter().find(|(i, _)| *i == chosen).map_or([WrappingMode::Repeat; 2], |(_, m)| *m);
    let image =
        TextureImage { width: rgba.width, height: rgba.height, pixels: rgba.pixels.clone(), wrap: modes.map(wrap_of) };
    let uvs = merged.textured.iter().map(|t| t.filter(|(i, _)| *i == chosen).map(|(_, uv)| uv)).collect();
    let tints = merged
        .textured
        .iter()
        .zip(merged.tints.iter().zip(&merged.colors))
        .map(|(t, (tint, baked))| if t.is_some_and(|(i, _)| i == chosen) { *tint } else { *baked })
        .collect();
    Some(Surface { image: std::sync::Arc::new(image), uvs, tints })
}

/// How a mesh node's vertices are bound.
enum Binding {
    /// Skin joint index → skeleton joint.
    Skinned(Vec<Option<usize>>),
    /// One joint, and the matrix taking the mesh's vertices into its bind space.
    Rigid(u32, Mat4),
}

fn note(message: String) -> Warning {
    Warning { line: None, message }
}

/// One inverse bind matrix per skeleton joint: from the skins (the first skin
/// naming a joint wins; a skin without the accessor means identity), else the
/// inverse of the joint's world transform at rest.
fn inverse_binds(parsed: &Parsed<'_>, graph: &Graph) -> Result<Vec<Mat4>, ParseError> {
    let mut out: Vec<Mat4> = graph.joint_world_rest().iter().map(|m| m.inverse()).collect();
    let mut set = vec![false; out.len()];
    for skin in parsed.document.skins() {
        let matrices = match skin.inverse_bind_matrices() {
            Some(accessor) => Some(floats(&accessor, &parsed.buffers, 16)?),
            None => None,
        };
        for (k, joint) in skin.joints().enumerate() {
            let Some(j) = graph.joint_of.get(joint.index()).copied().flatten() else { continue };
            if set[j] {
                continue;
            }
            let m = match &matrices {
                Some(values) => match values.get(16 * k..16 * k + 16) {
                    Some(cols) => Mat4::from_cols_slice(cols),
                    None => {
                        return Err(ParseError::new(
                            0,
                            0,
                            format!("skins[{}].inverseBindMatrices: fewer matrices than joints", skin.index()),
                        ));
                    }
                },
                None => Mat4::IDENTITY,
            };
            out[j] = m;
            set[j] = true;
        }
    }
    Ok(out)
}

/// Reads one primitive into the merged mesh.
fn add_primitive(
    parsed: &Parsed<'_>,
    primitive: &gltf::Primitive<'_>,
    (pointer, first_target): (&str, usize),
    binding: &Binding,
    texture: Option<&Texture<'_>>,
    merged: &mut Merged,
    warnings: &mut Vec<Warning>,
) -> Result<(), ParseError> {
    let buffers = &parsed.buffers;
    let mode = primitive.mode();
    if !matches!(mode, Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan) {
        warnings.push(note(format!("{pointer}: {mode:?} are not drawn (only triangles)")));
        return Ok(());
    }
    let at = |m: String| ParseError::new(0, 0, format!("{pointer}: {m}"));
    let position = primitive.get(&gltf::Semantic::Positions).ok_or_else(|| at("no POSITION attribute".into()))?;
    let positions: Vec<Vec3> = floats(&position, buffers, 3)?.chunks_exact(3).map(Vec3::from_slice).collect();
    let count = positions.len();
    let attribute = |semantic: gltf::Semantic, width: usize| -> Result<Option<Vec<f32>>, ParseError> {
        let Some(a) = primitive.get(&semantic) else { return Ok(None) };
        let values = floats(&a, buffers, width)?;
        if values.len() != count * width {
            return Err(at(format!("{semantic:?} has {} elements, POSITION {count}", values.len() / width)));
        }
        Ok(Some(values))
    };
    let normals: Option<Vec<Vec3>> =
        attribute(gltf::Semantic::Normals, 3)?.map(|v| v.chunks_exact(3).map(Vec3::from_slice).collect());
    let uvs: Option<Vec<f32>> = attribute(gltf::Semantic::TexCoords(0), 2)?;
    let vertex_colors: Option<Vec<f32>> = match primitive.get(&gltf::Semantic::Colors(0)) {
        Some(a) if a.dimensions() == gltf::accessor::Dimensions::Vec3 => attribute(gltf::Semantic::Colors(0), 3)?
            .map(|c| c.chunks_exact(3).flat_map(|c| [c[0], c[1], c[2], 1.0]).collect()),
        Some(_) => attribute(gltf::Semantic::Colors(0), 4)?,
        None => None,
    };
    let mut influences: Vec<Vec<(u32, f32)>> = vec![Vec::new(); count];
    if let Binding::Skinned(map) = binding {
        for set in 0..2 {
            let (Some(j), Some(w)) =
                (primitive.get(&gltf::Semantic::Joints(set)), attribute(gltf::Semantic::Weights(set), 4)?)
            else {
                continue;
            };
            let js = integers(&j, buffers, 4)?;
            if js.len() != count * 4 {
                return Err(at(format!("JOINTS_{set} has {} elements, POSITION {count}", js.len() / 4)));
            }
            for (v, slot) in influences.iter_mut().enumerate() {
                for c in 0..4 {
                    let (k, weight) = (js[4 * v + c], w[4 * v + c]);
                    if weight <= 0.0 {
                        continue;
                    }
                    let joint = map.get(k as usize).ok_or_else(|| {
                        at(format!(
                            "attributes.JOINTS_{set}: vertex {v} names skin joint {k}, past the skin's {}",
                            map.len()
                        ))
                    })?;
                    if let Some(joint) = joint {
                        slot.push((*joint as u32, weight));
                    }
                }
            }
        }
    }
    let mut indices: Vec<u32> = match primitive.indices() {
        Some(a) => integers(&a, buffers, 1)?,
        None => (0..count as u32).collect(),
    };
    if let Some((corner, &v)) = indices.iter().enumerate().find(|(_, v)| **v as usize >= count) {
        return Err(at(format!("indices[{corner}] is {v}, but there are {count} vertices")));
    }
    indices = triangles(mode, &indices);
    let base = merged.positions.len() as u32;
    let normals = normals.unwrap_or_else(|| computed_normals(&positions, &indices));
    let factor = primitive.material().pbr_metallic_roughness().base_color_factor();
    let mut unweighted = 0usize;
    for v in 0..count {
        let (joints, weights, to_bind) = match binding {
            Binding::Rigid(j, m) => ([*j, 0, 0, 0], [1.0, 0.0, 0.0, 0.0], Some(m)),
            Binding::Skinned(_) => {
                let (joints, weights) = strongest(&mut influences[v]);
                if weights[0] > 0.0 {
                    (joints, weights, None)
                } else {
                    unweighted += 1;
                    ([0, 0, 0, 0], [1.0, 0.0, 0.0, 0.0], None)
                }
            }
        };
        let (p, n) = match to_bind {
            Some(m) => (m.transform_point3(positions[v]), m.transform_vector3(normals[v]).normalize_or_zero()),
            None => (positions[v], normals[v].normalize_or_zero()),
        };
        merged.positions.push(p);
        merged.normals.push(n);
        merged.joints.push(joints);
        merged.weights.push(weights);
        let uv = uvs.as_ref().map_or(Vec2::ZERO, |u| Vec2::new(u[2 * v], u[2 * v + 1]));
        let mut factor = factor;
        if let Some(c) = &vertex_colors {
            (0..4).for_each(|k| factor[k] *= c.get(4 * v + k).copied().unwrap_or(1.0));
        }
        merged.colors.push(color(factor, texture, uv));
        merged.tints.push(color(factor, None, uv));
        merged.textured.push(texture.map(|t| {
            let uv = t.transform * uv.extend(1.0);
            (t.index, [uv.x, uv.y])
        }));
    }
    if let Some(t) = texture
        && !merged.wraps.iter().any(|(i, _)| *i == t.index)
    {
        merged.wraps.push((t.index, t.wrap));
    }
    if unweighted > 0 {
        warnings.push(note(format!("{pointer}: {unweighted} vertices have no weights; they follow the first joint")));
    }
    merged.indices.extend(indices.iter().map(|i| i + base));
    let to_bind = match binding {
        Binding::Rigid(_, m) => *m,
        Binding::Skinned(_) => Mat4::IDENTITY,
    };
    add_targets(parsed, primitive, (pointer, first_target), base, count, to_bind, merged)
}

/// Reads the primitive's morph-target position offsets (vertices from `base`,
/// `count` of them, taken into bind space by `to_bind`) into the look's targets
/// from `first_target` on, keeping only the vertices each moves.
fn add_targets(
    parsed: &Parsed<'_>,
    primitive: &gltf::Primitive<'_>,
    (pointer, first_target): (&str, usize),
    base: u32,
    count: usize,
    to_bind: Mat4,
    merged: &mut Merged,
) -> Result<(), ParseError> {
    for (t, target) in primitive.morph_targets().enumerate() {
        let Some(accessor) = target.positions() else { continue };
        let offsets = floats(&accessor, &parsed.buffers, 3)?;
        if offsets.len() != count * 3 {
            let n = offsets.len() / 3;
            return Err(ParseError::new(0, 0, format!("{pointer}.targets[{t}].POSITION has {n} elements, POSITION {count}")));
        }
        let Some(list) = merged.targets.get_mut(first_target + t) else { continue };
        for (v, d) in offsets.chunks_exact(3).enumerate() {
            let d = to_bind.transform_vector3(Vec3::from_slice(d));
            if d == Vec3::ZERO || !d.is_finite() || merged.offsets >= MAX_MORPH_OFFSETS {
                continue;
            }
            list.push((base + v as u32, d.to_array()));
            merged.offsets += 1;
        }
    }
    Ok(())
}

/// The four largest influences, renormalised to sum to 1 (all zero when none).
fn strongest(list: &mut [(u32, f32)]) -> ([u32; MAX_INFLUENCES], [f32; MAX_INFLUENCES]) {
    list.sort_by(|a, b| b.1.total_cmp(&a.1));
    let (mut joints, mut weights) = ([0u32; MAX_INFLUENCES], [0f32; MAX_INFLUENCES]);
    for (k, (j, w)) in list.iter().take(MAX_INFLUENCES).enumerate() {
        joints[k] = *j;
        weights[k] = *w;
    }
    let sum: f32 = weights.iter().sum();
    if sum > 0.0 {
        weights.iter_mut().for_each(|w| *w /= sum);
    }
    (joints, weights)
}

/// Strips and fans as a triangle list.
pub(super) fn triangles(mode: Mode, indices: &[u32]) -> Vec<u32> {
    match mode {
        Mode::TriangleStrip => (2..indices.len())
            .flat_map(|i| {
                let (a, b, c) = (indices[i - 2], indices[i - 1], indices[i]);
                if i % 2 == 0 { [a, b, c] } else { [b, a, c] }
            })
            .collect(),
        Mode::TriangleFan => (2..indices.len()).flat_map(|i| [indices[0], indices[i - 1], indices[i]]).collect(),
        _ => indices.chunks_exact(3).flatten().copied().collect(),
    }
}

/// Area-weighted vertex normals.
pub(super) fn computed_normals(positions: &[Vec3], indices: &[u32]) -> Vec<Vec3> {
    let mut out = vec![Vec3::ZERO; positions.len()];
    for t in indices.chunks_exact(3) {
        let [a, b, c] = [t[0] as usize, t[1] as usize, t[2] as usize];
        let (Some(pa), Some(pb), Some(pc)) = (positions.get(a), positions.get(b), positions.get(c)) else { continue };
        let n = (*pb - *pa).cross(*pc - *pa);
        for v in [a, b, c] {
            out[v] += n;
        }
    }
    out.iter().map(|n| n.try_normalize().unwrap_or(Vec3::Y)).collect()
}

/// The primitive's base-colour texture, decoded once per image (an image that
/// cannot be had is warned about once and the factor alone is used).
fn texture<'i>(
    parsed: &Parsed<'_>,
    primitive: &gltf::Primitive<'_>,
    images: &'i mut [Option<Option<Rgba>>],
    resources: Resources<'_>,
    warnings: &mut Vec<Warning>,
) -> Option<Texture<'i>> {
    let info = primitive.material().pbr_metallic_roughness().base_color_texture()?;
    let texture = info.texture();
    let image = texture.source();
    let index = image.index();
    let slot = images.get_mut(index)?;
    if slot.is_none() {
        let decoded = image_bytes(parsed, &image, resources).and_then(|bytes| {
            crate::formats::image::decode_any(image.name().unwrap_or(""), &bytes).map_err(|e| e.to_string())
        });
        *slot = Some(match decoded {
            Ok(rgba) => Some(rgba),
            Err(message) => {
                warnings.push(note(format!("images[{index}]: {message}; the base colour alone is used")));
                None
            }
        });
    }
    let sampler = texture.sampler();
    let mut transform = Mat3::IDENTITY;
    if let Some(t) = info.texture_transform() {
        let [ox, oy] = t.offset();
        let [sx, sy] = t.scale();
        let (sin, cos) = t.rotation().sin_cos();
        // The extension's order: translate · rotate · scale.
        transform = Mat3::from_cols_array(&[1.0, 0.0, 0.0, 0.0, 1.0, 0.0, ox, oy, 1.0])
            * Mat3::from_cols_array(&[cos, -sin, 0.0, sin, cos, 0.0, 0.0, 0.0, 1.0])
            * Mat3::from_cols_array(&[sx, 0.0, 0.0, 0.0, sy, 0.0, 0.0, 0.0, 1.0]);
    }
    let image = slot.as_ref()?.as_ref()?;
    Some(Texture { index, image, wrap: [sampler.wrap_s(), sampler.wrap_t()], transform })
}

/// The encoded bytes of an image: a buffer view, a data URI or another file.
pub(super) fn image_bytes(
    parsed: &Parsed<'_>,
    image: &gltf::Image<'_>,
    resources: Resources<'_>,
) -> Result<Vec<u8>, String> {
    match image.source() {
        gltf::image::Source::View { view, .. } => {
            let buffer: &[u8] = parsed.buffers.get(view.buffer().index()).map_or(&[][..], |b| b);
            let end = view.offset().checked_add(view.length()).unwrap_or(usize::MAX);
            buffer
                .get(view.offset()..end)
                .map(<[u8]>::to_vec)
                .ok_or_else(|| "its buffer view is outside its buffer".into())
        }
        gltf::image::Source::Uri { uri, .. } => fetch(uri, resources),
    }
}

/// The vertex's base colour: the factor (linear) times the texture (sRGB) at `uv`.
fn color(factor: [f32; 4], texture: Option<&Texture<'_>>, uv: Vec2) -> [u8; 4] {
    let texel = texture.map_or([1.0; 4], |t| {
        let uv = t.transform * uv.extend(1.0);
        let p = bilinear(t.image, t.wrap, uv.x, uv.y);
        [srgb_to_linear(p[0]), srgb_to_linear(p[1]), srgb_to_linear(p[2]), p[3] as f32 / 255.0]
    });
    [
        linear_to_srgb(factor[0] * texel[0]),
        linear_to_srgb(factor[1] * texel[1]),
        linear_to_srgb(factor[2] * texel[2]),
        (factor[3] * texel[3] * 255.0).round().clamp(0.0, 255.0) as u8,
    ]
}

/// A texel coordinate under a wrap mode.
fn wrap(mode: WrappingMode, i: i64, size: u32) -> u32 {
    let n = size.max(1) as i64;
    let i = match mode {
        WrappingMode::ClampToEdge => i.clamp(0, n - 1),
        WrappingMode::Repeat => i.rem_euclid(n),
        WrappingMode::MirroredRepeat => {
            let m = i.rem_euclid(2 * n);
            if m < n { m } else { 2 * n - 1 - m }
        }
    };
    i as u32
}

/// The image at `(u, v)` (glTF: v down from the top row), bilinear.
fn bilinear(image: &Rgba, modes: [WrappingMode; 2], u: f32, v: f32) -> [u8; 4] {
    if !(u.is_finite() && v.is_finite()) {
        return [255; 4];
    }
    let x = u * image.width as f32 - 0.5;
    let y = v * image.height as f32 - 0.5;
    let (x0, y0) = (x.floor(), y.floor());
    let (fx, fy) = (x - x0, y - y0);
    let mut out = [0f32; 4];
    for (dx, dy, w) in
        [(0, 0, (1.0 - fx) * (1.0 - fy)), (1, 0, fx * (1.0 - fy)), (0, 1, (1.0 - fx) * fy), (1, 1, fx * fy)]
    {
        let px = wrap(modes[0], x0 as i64 + dx, image.width);
        let py = wrap(modes[1], y0 as i64 + dy, image.height);
        let p = image.pixel(px, py).unwrap_or([255; 4]);
        (0..4).for_each(|c| out[c] += p[c] as f32 * w);
    }
    out.map(|c| c.round().clamp(0.0, 255.0) as u8)
}
