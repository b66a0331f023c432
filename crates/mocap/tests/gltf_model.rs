//! MD2 models as glTF ([`mocap::formats::gltf::model`], [`mocap::formats::gltf::morph`]):
//! every corpus model written as `.glb` and `.gltf` reads back as the same model
//! (every key frame, texture coordinates, triangles, animations and skin); a
//! hand-made morphing mesh plays its `STEP`, `LINEAR` and `CUBICSPLINE` weights as
//! the spec says; a morph animation too long to bake reads as a character.

mod common;

use mocap::formats::gltf::{model_to_glb, model_to_gltf, parse_asset};
use mocap::{Asset, Input, Model};

/// Every corpus model with its skin: (model, skin) paths under the corpus.
const MODELS: &[(&str, &str)] = &[
    ("md2/waste/tris.md2", "md2/waste/waste.pcx"),
    ("md2/waste/weapon.md2", "md2/waste/weapon.PCX"),
    ("md2/telias_dolphin/dolphin.md2", "md2/telias_dolphin/dolphin_f.bmp"),
    ("md2/irrlicht_faerie/faerie.md2", "md2/irrlicht_faerie/faerie2.bmp"),
];

fn model_of(asset: Asset) -> Model {
    match asset {
        Asset::Model(m) => m,
        Asset::Clip(_) => panic!("read as a clip, not a model"),
    }
}

fn none(_: &str) -> Option<Vec<u8>> {
    None
}

#[test]
fn every_corpus_model_reads_back_from_glb_and_gltf() {
    let Some(dir) = common::corpus_dir() else { return };
    for (md2, skin) in MODELS {
        let (a, b) = (std::fs::read(dir.join(md2)).unwrap(), std::fs::read(dir.join(skin)).unwrap());
        let inputs = [Input { name: md2, bytes: &a }, Input { name: skin, bytes: &b }];
        let model = model_of(mocap::load(&inputs).remove(0).unwrap().asset);
        assert!(model.skin.is_some(), "{md2}: its skin");
        let glb = model_to_glb(&model, "model").unwrap();
        let text = model_to_gltf(&model, "model").unwrap();
        for (what, bytes) in [("glb", glb.as_slice()), ("gltf", text.as_bytes())] {
            let back = model_of(parse_asset(bytes, &none).unwrap_or_else(|e| panic!("{md2} as {what}: {e}")));
            let (m, n) = (&model.mesh, &back.mesh);
            assert_eq!(n.frame_count(), m.frame_count(), "{md2} {what}: frames");
            assert_eq!(n.indices(), m.indices(), "{md2} {what}: triangles");
            assert_eq!(n.tex_coords(), m.tex_coords(), "{md2} {what}: texture coordinates");
            let names = |x: &mocap::model::mesh::MorphMesh| {
                x.animations().iter().map(|a| (a.name.clone(), a.first, a.last)).collect::<Vec<_>>()
            };
            assert_eq!(names(n), names(m), "{md2} {what}: animations");
            let height = m.height();
            for f in 0..m.frame_count() {
                for (p, q) in n.frame_positions(f).iter().zip(m.frame_positions(f)) {
                    let d = (0..3).map(|k| (p[k] - q[k]).abs()).fold(0.0f32, f32::max);
                    assert!(d < 1e-5 * height.max(1.0), "{md2} {what}: frame {f}: {p:?} vs {q:?}");
                }
            }
            let (s, t) = (back.skin.as_ref().unwrap(), model.skin.as_ref().unwrap());
            assert_eq!(s.image, t.image, "{md2} {what}: the skin's pixels (PNG is lossless)");
        }
    }
}

/// A triangle with two morph targets (+X and +Y, 1 m each) and one animation of
/// three keys at 0, 0.2 and 0.4 s with weights (0, 0), (1, 0), (0, 1).
fn morphing(interpolation: &str) -> Vec<u8> {
    let mut bin: Vec<u8> = Vec::new();
    let mut floats = |v: &[f32]| {
        let at = bin.len();
        bin.extend(v.iter().flat_map(|x| x.to_le_bytes()));
        (at, v.len() * 4)
    };
    let base = floats(&[0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0]);
    let dx = floats(&[1.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 0.0, 0.0]);
    let dy = floats(&[0.0, 1.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 0.0]);
    let times = floats(&[0.0, 0.2, 0.4]);
    let keys: Vec<f32> = if interpolation == "CUBICSPLINE" {
        // In-tangent, value, out-tangent per key; zero tangents.
        [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]].iter().flat_map(|v| [0.0, 0.0, v[0], v[1], 0.0, 0.0]).collect()
    } else {
        vec![0.0, 0.0, 1.0, 0.0, 0.0, 1.0]
    };
    let weights = floats(&keys);
    let views: Vec<serde_json::Value> = [base, dx, dy, times, weights]
        .iter()
        .map(|(at, len)| serde_json::json!({ "buffer": 0, "byteOffset": at, "byteLength": len }))
        .collect();
    let json = serde_json::json!({
        "asset": { "version": "2.0" },
        "scenes": [{ "nodes": [0] }],
        "nodes": [{ "name": "blob", "mesh": 0 }],
        "meshes": [{ "primitives": [{ "attributes": { "POSITION": 0 }, "targets": [{ "POSITION": 1 }, { "POSITION": 2 }] }], "weights": [0, 0] }],
        "accessors": [
            { "bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0] },
            { "bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC3", "min": [1, 0, 0], "max": [1, 0, 0] },
            { "bufferView": 2, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 1, 0], "max": [0, 1, 0] },
            { "bufferView": 3, "componentType": 5126, "count": 3, "type": "SCALAR", "min": [0.0], "max": [0.4] },
            { "bufferView": 4, "componentType": 5126, "count": keys.len(), "type": "SCALAR" }
        ],
        "bufferViews": views,
        "animations": [{ "name": "wobble", "samplers": [{ "input": 3, "output": 4, "interpolation": interpolation }], "channels": [{ "sampler": 0, "target": { "node": 0, "path": "weights" } }] }],
        "buffers": [{ "byteLength": bin.len(), "uri": format!("data:application/octet-stream;base64,{}", base64(&bin)) }]
    });
    serde_json::to_vec(&json).unwrap()
}

fn base64(bytes: &[u8]) -> String {
    use base64::Engine as _;
    base64::engine::general_purpose::STANDARD.encode(bytes)
}

#[test]
fn morph_weights_play_as_the_spec_samples_them() {
    // The first vertex, in metres, at frames 0.1 s apart: 0.1 s is halfway to (1, 0).
    let metres = |model: &Model, f: usize| {
        let m = model.mesh.units().meters_per_unit();
        let p = model.mesh.frame_positions(f)[0];
        [p[0] * m, p[1] * m]
    };
    let close = |a: [f32; 2], b: [f32; 2]| (a[0] - b[0]).abs() < 1e-4 && (a[1] - b[1]).abs() < 1e-4;
    let linear = model_of(parse_asset(&morphing("LINEAR"), &none).unwrap());
    assert_eq!(linear.mesh.frame_count(), 5, "0 to 0.4 s in 0.1 s steps");
    assert_eq!(linear.mesh.animations()[0].name, "wobble");
    for (f, want) in [(0, [0.0, 0.0]), (1, [0.5, 0.0]), (2, [1.0, 0.0]), (3, [0.5, 0.5]), (4, [0.0, 1.0])] {
        assert!(close(metres(&linear, f), want), "LINEAR frame {f}: {:?} vs {want:?}", metres(&linear, f));
    }
    let step = model_of(parse_asset(&morphing("STEP"), &none).unwrap());
    for (f, want) in [(1, [0.0, 0.0]), (3, [1.0, 0.0])] {
        assert!(close(metres(&step, f), want), "STEP frame {f}: {:?}", metres(&step, f));
    }
    // Hermite with zero tangents: halfway is the mean of the neighbours (smoothstep at ½).
    let cubic = model_of(parse_asset(&morphing("CUBICSPLINE"), &none).unwrap());
    assert!(close(metres(&cubic, 1), [0.5, 0.0]) && close(metres(&cubic, 2), [1.0, 0.0]), "CUBICSPLINE");
}

#[test]
fn a_morph_animation_too_long_to_bake_reads_as_a_character() {
    // The same triangle whose last key is a billion seconds away: no huge allocation.
    let text = String::from_utf8(morphing("LINEAR")).unwrap().replace("\"max\":[0.4]", "\"max\":[1000000000.0]");
    let mut json: serde_json::Value = serde_json::from_str(&text).unwrap();
    let uri = json["buffers"][0]["uri"].as_str().unwrap().to_owned();
    use base64::Engine as _;
    let mut bin = base64::engine::general_purpose::STANDARD.decode(uri.split(',').nth(1).unwrap()).unwrap();
    let times_at = 36 * 3;
    bin[times_at + 8..times_at + 12].copy_from_slice(&1.0e9f32.to_le_bytes());
    json["buffers"][0]["uri"] = format!("data:application/octet-stream;base64,{}", base64(&bin)).into();
    let started = std::time::Instant::now();
    let asset = parse_asset(&serde_json::to_vec(&json).unwrap(), &none).unwrap();
    assert!(matches!(asset, Asset::Clip(_)), "read as a character instead");
    assert!(started.elapsed().as_secs() < 5);
}
