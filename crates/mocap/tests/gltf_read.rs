//! The glTF reader: our own GLB and glTF files of every corpus BVH and Acclaim
//! clip read back to the same world positions; the sampling rules of the
//! specification (STEP, LINEAR slerp, CUBICSPLINE Hermite) on hand-made files;
//! external buffers, data URIs, quantized attributes, a matrix node, nodes above
//! the skeleton; and every kind of damaged file refused with a located message.

mod common;

use base64::Engine as _;
use mocap::formats::gltf::{Options, to_glb, to_gltf};
use mocap::glam::{Quat, Vec3};
use mocap::{Clip, Input};

const WALK: &[u8] = include_bytes!("../../../data/walk.bvh");

/// Reads one file (and its companions) through the loader, as the page and the CLI do.
fn read(files: &[(&str, &[u8])]) -> Result<Clip, String> {
    let inputs: Vec<Input> = files.iter().map(|(name, bytes)| Input { name, bytes }).collect();
    let mut results = mocap::load(&inputs);
    assert_eq!(results.len(), 1, "one asset from the set");
    match results.pop().unwrap() {
        Ok(loaded) => loaded.into_clip().ok_or_else(|| "not a clip".to_owned()),
        Err(e) => Err(e.to_string()),
    }
}

/// `clip`'s world positions at `frame`, in metres, Y up (what the writer writes).
fn ours(clip: &Clip, frame: usize) -> Vec<Vec3> {
    let (up, m) = (clip.up_axis().rotation(), clip.units().meters_per_unit());
    clip.world_positions(frame).into_iter().map(|p| up * p * m).collect()
}

/// Writes `clip` as GLB, reads it back, and compares every joint on up to 60
/// frames spread over the clip; the look skinned at frame 0 is its bind mesh.
fn round_trip(name: &str, clip: &Clip) {
    let glb = to_glb(clip, &Options { name: "take".into(), body: true }).unwrap();
    let back = read(&[("x.glb", &glb)]).unwrap_or_else(|e| panic!("{name}: {e}"));
    let names: Vec<&str> = back.skeleton().joints().iter().map(|j| j.name.as_str()).collect();
    let expected: Vec<&str> = clip.skeleton().joints().iter().map(|j| j.name.as_str()).collect();
    assert_eq!(names, expected, "{name}: one joint per node, same names");
    assert_eq!(back.frame_count(), clip.frame_count().max(1), "{name}: frames");
    if clip.frame_count() > 1 {
        assert!((back.frame_time() - clip.frame_time()).abs() < 1e-6, "{name}: frame time");
    }
    if clip.frame_count() > 1 {
        assert_eq!(back.take_name(), Some("take"), "{name}");
    }
    let height = clip.pose_height() * clip.units().meters_per_unit();
    let tolerance = 1e-4 * height.max(0.01);
    let step = (clip.frame_count() / 60).max(1);
    let mut worst = 0.0f32;
    for f in (0..clip.frame_count()).step_by(step) {
        for (a, b) in ours(clip, f).iter().zip(back.world_positions(f)) {
            worst = worst.max(a.distance(b));
        }
    }
    assert!(worst <= tolerance, "{name}: a joint is {worst} m off (tolerance {tolerance})");
    let look = back.character.as_ref().and_then(|c| c.look.as_ref()).expect("the body comes back as the look");
    let mut model = Vec::new();
    back.world_transforms_into(0, &mut model);
    let mut matrices = Vec::new();
    mocap::runtime::skin::skinning_matrices(&model, look.skin.inverse_bind(), &mut matrices);
    let (mut p, mut n) = (Vec::new(), Vec::new());
    mocap::runtime::skin::skin_vertices(&look.skin, &matrices, &mut p, &mut n);
    let off = p.iter().zip(look.skin.positions()).map(|(a, b)| a.distance(*b)).fold(0.0f32, f32::max);
    assert!(off <= tolerance * 10.0, "{name}: the skinned look at frame 0 is its bind mesh ({off} m off)");
}

#[test]
fn the_walk_reads_back_as_glb_and_as_gltf_text() {
    let clip = mocap::formats::bvh::parse(WALK).unwrap();
    round_trip("walk", &clip);
    let text = to_gltf(&clip, &Options::default()).unwrap();
    let back = read(&[("walk.gltf", text.as_bytes())]).unwrap();
    assert_eq!(back.frame_count(), clip.frame_count());
    let (a, b) = (ours(&clip, 17), back.world_positions(17));
    assert!(a.iter().zip(&b).all(|(a, b)| a.distance(*b) < 1e-4));
    assert_eq!(back.units(), mocap::Units::Meters);
}

#[test]
fn every_corpus_bvh_and_acclaim_clip_reads_back() {
    let Some(dir) = common::corpus_dir() else { return };
    let mut done = 0;
    let mut stack = vec![dir.join("bvh")];
    while let Some(d) = stack.pop() {
        for entry in std::fs::read_dir(&d).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                stack.push(path);
            } else if path.extension().is_some_and(|e| e.eq_ignore_ascii_case("bvh")) {
                let bytes = std::fs::read(&path).unwrap();
                if let Ok(clip) = mocap::formats::bvh::parse(&bytes) {
                    round_trip(&path.display().to_string(), &clip);
                    done += 1;
                }
            }
        }
    }
    let asf = std::fs::read(dir.join("asf_amc/cmu/02.asf")).unwrap();
    let amc = std::fs::read(dir.join("asf_amc/cmu/02_01.amc")).unwrap();
    let inputs = [Input { name: "02.asf", bytes: &asf }, Input { name: "02_01.amc", bytes: &amc }];
    for loaded in mocap::load(&inputs) {
        round_trip("02_01.amc", &loaded.unwrap().into_clip().unwrap());
        done += 1;
    }
    assert!(done >= 10, "{done} corpus clips");
}

/// A little glTF by hand: `json` with `bin` as its one buffer (a data URI).
fn gltf_with(json: serde_json::Value, bin: &[u8]) -> Vec<u8> {
    let mut json = json;
    let uri = format!("data:application/octet-stream;base64,{}", base64::engine::general_purpose::STANDARD.encode(bin));
    json["buffers"] = serde_json::json!([{ "byteLength": bin.len(), "uri": uri }]);
    json["asset"] = serde_json::json!({ "version": "2.0" });
    serde_json::to_vec(&json).unwrap()
}

fn floats(values: &[f32]) -> Vec<u8> {
    values.iter().flat_map(|v| v.to_le_bytes()).collect()
}

/// Two nodes (hips → spine) and one rotation channel on the spine about Z, keys
/// at 0, 1 and 3 s (90° then 180° about Z), with `interpolation`; for cubic, the
/// tangents are given in `tangents` (in, out per key).
fn turning(interpolation: &str, tangents: Option<[[f32; 4]; 6]>) -> Vec<u8> {
    let times = [0.0f32, 1.0, 3.0];
    let half = std::f32::consts::FRAC_1_SQRT_2;
    let keys = [[0.0, 0.0, 0.0, 1.0], [0.0, 0.0, half, half], [0.0, 0.0, 1.0, 0.0]];
    let mut values = Vec::new();
    for (k, q) in keys.iter().enumerate() {
        match tangents {
            Some(t) => {
                values.extend(t[2 * k]);
                values.extend(q);
                values.extend(t[2 * k + 1]);
            }
            None => values.extend(q),
        }
    }
    let mut bin = floats(&times);
    let values_at = bin.len();
    bin.extend(floats(&values));
    let json = serde_json::json!({
        "scene": 0,
        "scenes": [{ "nodes": [0] }],
        "nodes": [
            { "name": "hips", "children": [1], "translation": [0.0, 1.0, 0.0] },
            { "name": "spine", "translation": [0.0, 0.5, 0.0], "children": [2] },
            { "name": "head", "translation": [0.0, 0.25, 0.0] }
        ],
        "bufferViews": [
            { "buffer": 0, "byteOffset": 0, "byteLength": 12 },
            { "buffer": 0, "byteOffset": values_at, "byteLength": values.len() * 4 }
        ],
        "accessors": [
            { "bufferView": 0, "componentType": 5126, "count": 3, "type": "SCALAR", "min": [0.0], "max": [3.0] },
            { "bufferView": 1, "componentType": 5126, "count": values.len() / 4, "type": "VEC4" }
        ],
        "animations": [{
            "name": "turn",
            "samplers": [{ "input": 0, "output": 1, "interpolation": interpolation }],
            "channels": [{ "sampler": 0, "target": { "node": 1, "path": "rotation" } }]
        }]
    });
    gltf_with(json, &bin)
}

/// The spine's world rotation at time `t`.
fn spine_at(clip: &Clip, t: f64) -> Quat {
    let mut out = Vec::new();
    clip.sample_world_transforms_into(t, mocap::Interpolation::Linear, &mut out);
    out[1].rotation
}

fn angle(a: Quat, b: Quat) -> f32 {
    a.angle_between(b).to_degrees()
}

#[test]
fn linear_rotations_slerp_step_holds_and_cubic_is_hermite() {
    let linear = read(&[("turn.gltf", &turning("LINEAR", None))]).unwrap();
    // Keys at 0, 1, 3 s → a frame every 1/24 s at most; 1.5 s is a quarter of the way from 90° to 180°.
    assert!(angle(spine_at(&linear, 0.5), Quat::from_rotation_z(45f32.to_radians())) < 0.05);
    assert!(angle(spine_at(&linear, 1.5), Quat::from_rotation_z(112.5f32.to_radians())) < 0.05);
    assert!(
        angle(spine_at(&linear, 5.0), Quat::from_rotation_z(180f32.to_radians())) < 0.05,
        "holds after the last key"
    );
    let head = linear.world_positions(0)[2];
    assert!(head.distance(Vec3::new(0.0, 1.75, 0.0)) < 1e-5);

    let step = read(&[("turn.gltf", &turning("STEP", None))]).unwrap();
    assert!(angle(spine_at(&step, 0.9), Quat::IDENTITY) < 0.05, "STEP holds the key before");
    assert!(angle(spine_at(&step, 2.9), Quat::from_rotation_z(90f32.to_radians())) < 0.05);

    // Cubic with zero tangents: s' = 3s² − 2s³ of the way (componentwise on the
    // quaternion, then normalised).
    let cubic = read(&[("turn.gltf", &turning("CUBICSPLINE", Some([[0.0; 4]; 6])))]).unwrap();
    let s: f32 = 0.25;
    let h = 3.0 * s * s - 2.0 * s * s * s;
    let half = std::f32::consts::FRAC_1_SQRT_2;
    let q = Quat::from_xyzw(0.0, 0.0, half + (1.0 - half) * h, half * (1.0 - h)).normalize();
    assert!(angle(spine_at(&cubic, 1.5), q) < 0.05, "Hermite with zero tangents");
    // With tangents, the in/out-tangent of each key moves the curve (by dt-scaled tangents).
    let mut t = [[0.0; 4]; 6];
    t[3] = [0.0, 0.0, 0.2, -0.2]; // key 1's out-tangent
    let bent = read(&[("turn.gltf", &turning("CUBICSPLINE", Some(t)))]).unwrap();
    let m0 = 0.2 * 2.0; // tangent × dt
    let hm = s * s * s - 2.0 * s * s + s;
    let q = Quat::from_xyzw(0.0, 0.0, half + (1.0 - half) * h + m0 * hm, half * (1.0 - h) - m0 * hm).normalize();
    assert!(angle(spine_at(&bent, 1.5), q) < 0.05, "Hermite with the out-tangent");
}

/// One node with a mesh of one triangle, its POSITION as normalized i16
/// (`KHR_mesh_quantization`), the node placed by a matrix and under a scaled parent.
fn quantized_triangle(required: &[&str]) -> serde_json::Value {
    let positions: Vec<u8> =
        [[0i16, 0, 0], [32767, 0, 0], [0, 32767, 0]].iter().flatten().flat_map(|v| v.to_le_bytes()).collect();
    let mut bin = positions;
    bin.extend([0u8, 0]); // padding to 4
    let mut json = serde_json::json!({
        "extensionsUsed": ["KHR_mesh_quantization"],
        "extensionsRequired": required,
        "scenes": [{ "nodes": [0] }],
        "nodes": [
            { "name": "root", "scale": [2.0, 2.0, 2.0], "children": [1] },
            { "name": "part", "mesh": 0, "matrix": [1,0,0,0, 0,1,0,0, 0,0,1,0, 1,0,0,1] }
        ],
        "meshes": [{ "primitives": [{ "attributes": { "POSITION": 0 } }] }],
        "bufferViews": [{ "buffer": 0, "byteLength": 18, "byteStride": 6 }],
        "accessors": [{ "bufferView": 0, "componentType": 5122, "normalized": true, "count": 3, "type": "VEC3",
                        "min": [0, 0, 0], "max": [32767, 32767, 0] }]
    });
    let bytes = gltf_with(json.clone(), &bin);
    json = serde_json::from_slice(&bytes).unwrap();
    json
}

#[test]
fn quantized_positions_matrix_nodes_and_parents_above_are_read() {
    let bytes = serde_json::to_vec(&quantized_triangle(&["KHR_mesh_quantization"])).unwrap();
    let clip = read(&[("tri.gltf", &bytes)]).unwrap();
    // No skin: every node is a joint; the part is rigid on itself.
    assert_eq!(clip.skeleton().len(), 2);
    let world = clip.world_positions(0);
    assert!(world[1].distance(Vec3::new(2.0, 0.0, 0.0)) < 1e-5, "the matrix's translation under the parent's scale");
    let look = clip.character.as_ref().unwrap().look.as_ref().unwrap();
    let mut model = Vec::new();
    clip.world_transforms_into(0, &mut model);
    let mut m = Vec::new();
    mocap::runtime::skin::skinning_matrices(&model, look.skin.inverse_bind(), &mut m);
    let (mut p, mut n) = (Vec::new(), Vec::new());
    mocap::runtime::skin::skin_vertices(&look.skin, &m, &mut p, &mut n);
    // (1, 0, 0) normalized → 1.0, moved by the matrix (+1 x) and scaled by 2.
    assert!(p[1].distance(Vec3::new(4.0, 0.0, 0.0)) < 1e-3, "{:?}", p[1]);
    assert!(p[2].distance(Vec3::new(2.0, 2.0, 0.0)) < 1e-3, "{:?}", p[2]);
    assert!(n.iter().all(|n| (n.z.abs() - 1.0).abs() < 1e-4), "normals computed from the triangle");
}

#[test]
fn an_external_buffer_comes_from_the_same_set_of_files() {
    let clip = mocap::formats::bvh::parse(WALK).unwrap();
    let text = to_gltf(&clip, &Options::default()).unwrap();
    let mut json: serde_json::Value = serde_json::from_str(&text).unwrap();
    let uri = json["buffers"][0]["uri"].as_str().unwrap().to_owned();
    let data = base64::engine::general_purpose::STANDARD.decode(uri.split_once(',').unwrap().1).unwrap();
    json["buffers"][0]["uri"] = "walk%20data.bin".into();
    let gltf = serde_json::to_vec(&json).unwrap();
    let back = read(&[("walk.gltf", &gltf), ("walk data.bin", &data)]).unwrap();
    assert_eq!(back.frame_count(), clip.frame_count());
    let e = read(&[("walk.gltf", &gltf)]).unwrap_err();
    assert!(e.contains("walk.gltf") && e.contains("buffers[0]") && e.contains("walk data.bin"), "{e}");
}

#[test]
fn damaged_and_unsupported_files_get_located_messages() {
    let clip = mocap::formats::bvh::parse(WALK).unwrap();
    let glb = to_glb(&clip, &Options::default()).unwrap();
    let fails = |files: &[(&str, &[u8])], wants: &[&str]| {
        let e = read(files).unwrap_err();
        for w in wants {
            assert!(e.contains(w), "`{e}` should say `{w}`");
        }
    };
    // Truncated anywhere: never a panic, always the file's name.
    for cut in [3, 11, 12, 19, 20, 100, glb.len() / 2, glb.len() - 1] {
        fails(&[("cut.glb", &glb[..cut])], &["cut.glb"]);
    }
    fails(&[("cut.glb", &glb[..glb.len() / 2])], &["byte 8", "bytes"]);
    // A chunk longer than the file.
    let mut long = glb.clone();
    long[12..16].copy_from_slice(&u32::MAX.to_le_bytes());
    fails(&[("long.glb", &long)], &["byte 12", "past the end"]);
    // Draco required: refused by name.
    let mut draco = quantized_triangle(&["KHR_draco_mesh_compression"]);
    draco["extensionsUsed"] = serde_json::json!(["KHR_draco_mesh_compression"]);
    fails(
        &[("d.gltf", &serde_json::to_vec(&draco).unwrap())],
        &["extensionsRequired[0]", "KHR_draco_mesh_compression"],
    );
    // An accessor past its view, a stride smaller than an element, a huge count.
    let mut json = quantized_triangle(&[]);
    json["accessors"][0]["count"] = 4.into();
    fails(&[("a.gltf", &serde_json::to_vec(&json).unwrap())], &["accessors[0]", "count 4", "bufferViews[0]"]);
    let mut json = quantized_triangle(&[]);
    json["bufferViews"][0]["byteStride"] = 4.into();
    fails(&[("s.gltf", &serde_json::to_vec(&json).unwrap())], &["bufferViews[0].byteStride is 4"]);
    let mut json = quantized_triangle(&[]);
    json["accessors"][0]["count"] = 4_000_000_000u64.into();
    fails(&[("h.gltf", &serde_json::to_vec(&json).unwrap())], &["accessors[0]", "count 4000000000"]);
    // A view outside its buffer.
    let mut json = quantized_triangle(&[]);
    json["bufferViews"][0]["byteOffset"] = 1000.into();
    fails(&[("v.gltf", &serde_json::to_vec(&json).unwrap())], &["bufferViews[0]", "outside its buffer"]);
    // An index out of range is the crate's check, with its JSON path.
    let mut json = quantized_triangle(&[]);
    json["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = 7.into();
    fails(&[("i.gltf", &serde_json::to_vec(&json).unwrap())], &["meshes[0].primitives[0].attributes"]);
    // Two parents, and a cycle.
    let mut json = quantized_triangle(&[]);
    json["nodes"][1]["children"] = serde_json::json!([1]);
    fails(&[("c.gltf", &serde_json::to_vec(&json).unwrap())], &["nodes[1]"]);
    let mut json = quantized_triangle(&[]);
    json["nodes"] = serde_json::json!([{ "children": [2] }, { "children": [2] }, {}]);
    json["scenes"] = serde_json::json!([{ "nodes": [0, 1] }]);
    fails(&[("p.gltf", &serde_json::to_vec(&json).unwrap())], &["nodes[2]", "both"]);
    // Not finite.
    let mut json = quantized_triangle(&[]);
    json["nodes"][0]["translation"] = serde_json::json!([1e39, 0, 0]);
    let e = read(&[("n.gltf", &serde_json::to_vec(&json).unwrap())]);
    assert!(e.is_err() || e.unwrap().world_positions(0).iter().all(|p| p.is_finite()));
    // Broken JSON: its line and column.
    fails(&[("j.gltf", b"{\"asset\": {\"version\": \"2.0\"},\n  \"nodes\": [ }")], &["j.gltf:2:"]);
    // Not glTF at all, named .glb.
    fails(&[("not.glb", b"hello, this is not a model")], &["not.glb"]);
}

#[test]
fn the_base_colour_texture_and_factor_colour_each_vertex() {
    // A 2×2 PNG: red, green / blue, white; a quad whose corners sit on the texel
    // centres (through KHR_texture_transform's scale and offset); factor ½ green.
    let mut png = Vec::new();
    let pixels: Vec<u8> = [[255, 0, 0, 255], [0, 255, 0, 255], [0, 0, 255, 255], [255, 255, 255, 255]].concat();
    image::ImageEncoder::write_image(
        image::codecs::png::PngEncoder::new(&mut png),
        &pixels,
        2,
        2,
        image::ExtendedColorType::Rgba8,
    )
    .unwrap();
    let positions = floats(&[0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0]);
    let uvs = floats(&[0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 1.0, 1.0]);
    let mut bin = positions.clone();
    bin.extend(&uvs);
    let png_at = bin.len();
    bin.extend(&png);
    while bin.len() % 4 != 0 {
        bin.push(0);
    }
    let json = serde_json::json!({
        "extensionsUsed": ["KHR_texture_transform"],
        "scenes": [{ "nodes": [0] }],
        "nodes": [{ "name": "quad", "mesh": 0 }],
        "meshes": [{ "primitives": [{ "attributes": { "POSITION": 0, "TEXCOORD_0": 1 }, "indices": null, "material": 0 }] }],
        "materials": [{ "pbrMetallicRoughness": {
            "baseColorFactor": [1.0, 0.5, 1.0, 1.0],
            "baseColorTexture": { "index": 0, "extensions": { "KHR_texture_transform": { "offset": [0.25, 0.25], "scale": [0.5, 0.5] } } }
        } }],
        "textures": [{ "source": 0, "sampler": 0 }],
        "samplers": [{ "wrapS": 33071, "wrapT": 33071 }],
        "images": [{ "bufferView": 2, "mimeType": "image/png" }],
        "bufferViews": [
            { "buffer": 0, "byteOffset": 0, "byteLength": 48 },
            { "buffer": 0, "byteOffset": 48, "byteLength": 32 },
            { "buffer": 0, "byteOffset": png_at, "byteLength": png.len() }
        ],
        "accessors": [
            { "bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0] },
            { "bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC2" }
        ]
    });
    let mut json = json;
    json["meshes"][0]["primitives"][0].as_object_mut().unwrap().remove("indices");
    let clip = read(&[("quad.gltf", &gltf_with(json, &bin))]).unwrap();
    let look = clip.character.as_ref().unwrap().look.as_ref().unwrap();
    // Linear ½ on green is sRGB 188.
    assert_eq!(look.colors, vec![[255, 0, 0, 255], [0, 188, 0, 255], [0, 0, 255, 255], [255, 188, 255, 255]]);
    // Drawn per pixel: the image itself, the coordinates through the transform,
    // and the factor alone as each vertex's colour.
    let surface = look.surface.as_ref().expect("the texture is kept to draw per pixel");
    assert_eq!((surface.image.width, surface.image.height, &surface.image.pixels), (2, 2, &pixels));
    assert_eq!(surface.image.wrap, [mocap::model::character::Wrap::Clamp; 2]);
    assert_eq!(surface.uvs, vec![Some([0.25, 0.25]), Some([0.75, 0.25]), Some([0.25, 0.75]), Some([0.75, 0.75])]);
    assert_eq!(surface.tints, vec![[255, 188, 255, 255]; 4]);
    // Stored (the page's autosave) and read back whole.
    let again = mocap::formats::store::parse(&mocap::formats::store::write(&mocap::Asset::Clip(clip.clone()))).unwrap();
    assert_eq!(again, mocap::Asset::Clip(clip.clone()));
    // Written as glTF and read again: the same texture, coordinates and colours.
    let glb = mocap::formats::gltf::write::to_glb(&clip, &Default::default()).unwrap();
    let back = read(&[("quad-again.glb", &glb)]).unwrap();
    let look_back = back.character.as_ref().unwrap().look.as_ref().unwrap();
    assert_eq!(look_back.colors, look.colors);
    assert_eq!(look_back.surface, look.surface);
}

#[test]
fn a_chain_of_200000_nodes_reads_without_recursion() {
    let n = 200_000;
    let nodes: Vec<serde_json::Value> = (0..n)
        .map(|i| {
            if i + 1 < n {
                serde_json::json!({ "children": [i + 1], "translation": [0.0, 0.001, 0.0] })
            } else {
                serde_json::json!({ "translation": [0.0, 0.001, 0.0] })
            }
        })
        .collect();
    let json = serde_json::json!({ "asset": { "version": "2.0" }, "scenes": [{ "nodes": [0] }], "nodes": nodes });
    let clip = read(&[("chain.gltf", &serde_json::to_vec(&json).unwrap())]).unwrap();
    assert_eq!(clip.skeleton().len(), n);
    let last = clip.world_positions(0)[n - 1];
    assert!((last.y - 200.0).abs() < 1.0, "{last} (f32 sums drift over 200,000 joints)");
}

/// A skinned triangle with two morph targets (the third vertex up 1, the second
/// along x 2) on a mesh whose rest weights are 0.1 and 0: animation `blink`
/// moves the root and sets the weights from (0, 0) at 0 s to (1, 0.5) at 1 s;
/// `still` only moves the root; `bad` gives three weights a key.
fn blend_shapes() -> Vec<u8> {
    let mut bin = Vec::new();
    let mut views = Vec::new();
    let mut push = |bytes: Vec<u8>, bin: &mut Vec<u8>| {
        views.push(serde_json::json!({ "buffer": 0, "byteOffset": bin.len(), "byteLength": bytes.len() }));
        bin.extend(bytes);
        views.len() - 1
    };
    let positions = push(floats(&[0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0]), &mut bin);
    let joints = push(vec![0u8; 12], &mut bin);
    let weights = push(floats(&[1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0]), &mut bin);
    let up = push(floats(&[0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0]), &mut bin);
    let along = push(floats(&[0.0, 0.0, 0.0, 2.0, 0.0, 0.0, 0.0, 0.0, 0.0]), &mut bin);
    let times = push(floats(&[0.0, 1.0]), &mut bin);
    let moves = push(floats(&[0.0, 0.0, 0.0, 0.0, 0.0, 1.0]), &mut bin);
    let keyed = push(floats(&[0.0, 0.0, 1.0, 0.5]), &mut bin);
    let three = push(floats(&[0.0, 0.0, 0.0, 1.0, 1.0, 1.0]), &mut bin);
    let json = serde_json::json!({
        "scene": 0,
        "scenes": [{ "nodes": [0, 1] }],
        "nodes": [
            { "name": "root" },
            { "name": "face", "mesh": 0, "skin": 0 }
        ],
        "skins": [{ "joints": [0] }],
        "meshes": [{
            "weights": [0.1, 0.0],
            "primitives": [{
                "attributes": { "POSITION": 0, "JOINTS_0": 1, "WEIGHTS_0": 2 },
                "targets": [{ "POSITION": 3 }, { "POSITION": 4 }]
            }]
        }],
        "bufferViews": views,
        "accessors": [
            { "bufferView": positions, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0] },
            { "bufferView": joints, "componentType": 5121, "count": 3, "type": "VEC4" },
            { "bufferView": weights, "componentType": 5126, "count": 3, "type": "VEC4" },
            { "bufferView": up, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [0, 1, 0] },
            { "bufferView": along, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [2, 0, 0] },
            { "bufferView": times, "componentType": 5126, "count": 2, "type": "SCALAR", "min": [0.0], "max": [1.0] },
            { "bufferView": moves, "componentType": 5126, "count": 2, "type": "VEC3" },
            { "bufferView": keyed, "componentType": 5126, "count": 4, "type": "SCALAR" },
            { "bufferView": three, "componentType": 5126, "count": 6, "type": "SCALAR" }
        ],
        "animations": [
            { "name": "blink",
              "samplers": [{ "input": 5, "output": 6 }, { "input": 5, "output": 7 }],
              "channels": [{ "sampler": 0, "target": { "node": 0, "path": "translation" } },
                           { "sampler": 1, "target": { "node": 1, "path": "weights" } }] },
            { "name": "still",
              "samplers": [{ "input": 5, "output": 6 }],
              "channels": [{ "sampler": 0, "target": { "node": 0, "path": "translation" } }] },
            { "name": "bad",
              "samplers": [{ "input": 5, "output": 6 }, { "input": 5, "output": 8 }],
              "channels": [{ "sampler": 0, "target": { "node": 0, "path": "translation" } },
                           { "sampler": 1, "target": { "node": 1, "path": "weights" } }] }
        ]
    });
    gltf_with(json, &bin)
}

#[test]
fn a_skinned_mesh_plays_its_morph_target_weights() {
    let clip = read(&[("face.gltf", &blend_shapes())]).unwrap();
    let character = clip.character.as_deref().unwrap();
    let look = character.look.as_ref().unwrap();
    let morph = look.morph.as_ref().expect("the look keeps its two targets");
    assert_eq!(morph.rest, [0.1, 0.0]);
    assert_eq!(morph.targets, [vec![(2, [0.0, 1.0, 0.0])], vec![(1, [2.0, 0.0, 0.0])]], "only the vertices each moves");
    let [blink, still, bad] = &character.takes[..] else { panic!("three takes") };
    let mut w = Vec::new();
    assert!(blink.weights_at(0.5, 2, &mut w));
    assert!((w[0] - 0.5).abs() < 1e-5 && (w[1] - 0.25).abs() < 1e-5, "{w:?}");
    assert!(blink.weights_at(1.0, 2, &mut w) && w == [1.0, 0.5], "{w:?}");
    let mut shape = Vec::new();
    morph.shape(look.skin.positions(), &w, &mut shape);
    assert!(shape[1].distance(Vec3::new(2.0, 0.0, 0.0)) < 1e-6 && shape[2].distance(Vec3::new(0.0, 2.0, 0.0)) < 1e-6);
    // A take without weights, or whose channel does not fit the mesh, leaves the rest weights.
    assert!(!still.weights_at(0.5, 2, &mut w) && !bad.weights_at(0.5, 2, &mut w));
    morph.shape(look.skin.positions(), &[], &mut shape);
    assert!(shape[2].distance(Vec3::new(0.0, 1.1, 0.0)) < 1e-6, "rest weight 0.1: {:?}", shape[2]);
    let warned = clip.warnings.iter().map(|w| w.message.clone()).collect::<Vec<_>>().join("\n");
    assert!(warned.contains("animation `bad`: nodes[1] has 2 morph targets but its weights channel sets 3"), "{warned}");
    // Written as glTF and read back with them: the targets, the rest weights and
    // the take's weights.
    let glb = mocap::formats::gltf::to_glb(&clip, &mocap::formats::gltf::Options::default()).unwrap();
    let again = read(&[("again.glb", &glb)]).unwrap();
    let back = again.character.as_deref().unwrap();
    assert_eq!(back.look.as_ref().unwrap().morph.as_ref(), Some(morph), "targets and rest weights");
    assert!(back.takes[0].weights_at(0.5, 2, &mut w), "the take's weights");
    assert!((w[0] - 0.5).abs() < 1e-5 && (w[1] - 0.25).abs() < 1e-5, "{w:?}");
    // Stored and read back with them.
    let asset = mocap::Asset::Clip(clip);
    assert_eq!(mocap::formats::store::parse(&mocap::formats::store::write(&asset)).unwrap(), asset);
}
