//! The `mocap` binary end to end: outputs, exit codes and error format.

use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn mocap(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_mocap")).args(args).output().expect("run mocap")
}

fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

const SIMPLE: &str = "HIERARCHY\nROOT Hips\n{\n\tOFFSET 0 0 0\n\tCHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation\n\tJOINT Spine\n\t{\n\t\tOFFSET 0 10 0\n\t\tCHANNELS 3 Zrotation Xrotation Yrotation\n\t\tEnd Site\n\t\t{\n\t\t\tOFFSET 0 5 0\n\t\t}\n\t}\n}\nMOTION\nFrames: 3\nFrame Time: 0.5\n0 90 0 0 0 0 0 0 0\n1 90 0 90 0 0 0 0 0\n2 90 0 0 0 0 0 0 90\n";

fn write_temp(dir: &Path, name: &str, text: &str) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

#[test]
fn pose_json_has_the_documented_shape() {
    let dir = tempfile::tempdir().unwrap();
    let file = write_temp(dir.path(), "s.bvh", SIMPLE);
    let out = mocap(&["pose", file.to_str().unwrap(), "--frame", "1", "--json"]);
    assert!(out.status.success(), "{}", stderr(&out));
    let v: Value = serde_json::from_str(&stdout(&out)).unwrap();
    assert_eq!(v["frame"], 1);
    assert_eq!(v["time"], 0.5);
    let joints = v["joints"].as_array().unwrap();
    assert_eq!(joints.len(), 3);
    assert_eq!(joints[0]["name"], "Hips");
    assert_eq!(joints[0]["parent"], Value::Null);
    assert_eq!(joints[0]["end_site"], false);
    assert_eq!(joints[2]["end_site"], true);
    assert_eq!(joints[2]["parent"], 1);
    // Frame 1: root at (1,90,0) turned 90° about Z: the spine (0,10,0) points to -X.
    let p: Vec<f64> = joints[1]["position"].as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect();
    assert!((p[0] + 9.0).abs() < 1e-4 && (p[1] - 90.0).abs() < 1e-4 && p[2].abs() < 1e-4, "{p:?}");
    // Keys in the documented order.
    let text = stdout(&out);
    assert!(text.find("\"frame\"").unwrap() < text.find("\"time\"").unwrap());
}

#[test]
fn info_json_reports_counts_timing_bounds_units() {
    let dir = tempfile::tempdir().unwrap();
    let file = write_temp(dir.path(), "s.bvh", &SIMPLE.replace("Frames: 3", "Frames: 5"));
    let out = mocap(&["info", file.to_str().unwrap(), "--json"]);
    assert!(out.status.success(), "{}", stderr(&out));
    let v: Value = serde_json::from_str(&stdout(&out)).unwrap();
    assert_eq!(v["skeletons"], 1);
    assert_eq!(v["joints"], 2);
    assert_eq!(v["end_sites"], 1);
    assert_eq!(v["channels"], 9);
    assert_eq!(v["frames"], 3);
    assert_eq!(v["fps"], 2.0);
    assert_eq!(v["duration"], 1.0);
    assert_eq!(v["bounds"]["max"][1], 105.0);
    assert!(v["warnings"][0].as_str().unwrap().contains("Frames: says 5"));
    let text = mocap(&["info", file.to_str().unwrap()]);
    assert!(stdout(&text).contains("frames:     3"));
}

#[test]
fn info_says_which_axis_is_up() {
    // A figure standing along +Z: hips at 1, spine up, arms along X, legs down to 0.
    let mut z_up = String::from(
        "HIERARCHY\nROOT Hips\n{\nOFFSET 0 0 1\nCHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation\n",
    );
    z_up.push_str("JOINT Chest\n{\nOFFSET 0 0 0.5\nCHANNELS 3 Zrotation Xrotation Yrotation\nJOINT L\n{\nOFFSET 0.6 0 0.3\nCHANNELS 3 Zrotation Xrotation Yrotation\nEnd Site\n{\nOFFSET 0 0 0.4\n}\n}\n}\n");
    z_up.push_str("JOINT Leg\n{\nOFFSET 0.1 0 0\nCHANNELS 3 Zrotation Xrotation Yrotation\nEnd Site\n{\nOFFSET 0 0 -1\n}\n}\n}\nMOTION\nFrames: 2\nFrame Time: 0.1\n");
    z_up.push_str(&format!("0 0 1{}\n0 0.1 1{}\n", " 0".repeat(12), " 0".repeat(12)));
    let dir = tempfile::tempdir().unwrap();
    for (name, text, up) in [("z.bvh", z_up.as_str(), "z"), ("y.bvh", SIMPLE, "y")] {
        let file = write_temp(dir.path(), name, text);
        let out = mocap(&["info", file.to_str().unwrap(), "--json"]);
        assert!(out.status.success(), "{}", stderr(&out));
        let v: Value = serde_json::from_str(&stdout(&out)).unwrap();
        assert_eq!(v["up"], up, "{name}");
        let text = stdout(&mocap(&["info", file.to_str().unwrap()]));
        assert!(text.contains(&format!("up:         {up} (guessed from the motion)")), "{text}");
    }
}

#[test]
fn errors_are_file_line_col_with_failure_status_and_no_backtrace() {
    let dir = tempfile::tempdir().unwrap();
    let file = write_temp(dir.path(), "bad.bvh", &SIMPLE.replace("0 10 0", "0 ten 0"));
    for args in [vec!["info"], vec!["pose", "--frame", "0"]] {
        let mut a = args.clone();
        a.insert(1, file.to_str().unwrap());
        let out = mocap(&a);
        assert!(!out.status.success());
        let err = stderr(&out);
        assert_eq!(
            err.trim(),
            format!("{}:8:12: expected the y value of OFFSET (a number), found `ten`", file.display())
        );
        assert!(!err.contains("panicked"));
    }
    let out = mocap(&["pose", dir.path().join("missing.bvh").to_str().unwrap()]);
    assert!(!out.status.success() && stderr(&out).contains("cannot read"));
}

#[test]
fn pose_frame_out_of_range_is_an_error() {
    let dir = tempfile::tempdir().unwrap();
    let file = write_temp(dir.path(), "s.bvh", SIMPLE);
    let out = mocap(&["pose", file.to_str().unwrap(), "--frame", "3"]);
    assert!(!out.status.success());
    assert!(stderr(&out).contains("out of range"));
}

#[test]
fn convert_round_trips() {
    let dir = tempfile::tempdir().unwrap();
    let file = write_temp(dir.path(), "s.bvh", &SIMPLE.replace('\n', "\r\n"));
    let out_file = dir.path().join("out.bvh");
    let out = mocap(&["convert", file.to_str().unwrap(), "-o", out_file.to_str().unwrap()]);
    assert!(out.status.success(), "{}", stderr(&out));
    let written = std::fs::read_to_string(&out_file).unwrap();
    assert!(!written.contains('\r'));
    let a = mocap::formats::bvh::parse(SIMPLE.as_bytes()).unwrap();
    let b = mocap::formats::bvh::parse(written.as_bytes()).unwrap();
    assert_eq!(a.motion(), b.motion());
    assert_eq!(a.skeleton(), b.skeleton());
    let bad = mocap(&["convert", file.to_str().unwrap(), "-o", dir.path().join("x.txt").to_str().unwrap()]);
    assert!(!bad.status.success());
}

#[test]
fn convert_writes_glb_and_gltf() {
    let dir = tempfile::tempdir().unwrap();
    let file = write_temp(dir.path(), "s.bvh", SIMPLE);
    for name in ["out.glb", "out.gltf"] {
        let out_file = dir.path().join(name);
        let out = mocap(&["convert", file.to_str().unwrap(), "-o", out_file.to_str().unwrap()]);
        assert!(out.status.success(), "{}", stderr(&out));
        let bytes = std::fs::read(&out_file).unwrap();
        if name.ends_with(".glb") {
            assert_eq!(&bytes[..4], b"glTF");
            assert_eq!(u32::from_le_bytes(bytes[8..12].try_into().unwrap()) as usize, bytes.len());
        } else {
            let json: serde_json::Value = serde_json::from_slice(&bytes).unwrap();
            assert_eq!(json["asset"]["version"], "2.0");
            assert_eq!(json["animations"][0]["name"], "s", "the animation is named after the input");
        }
    }
}

#[test]
fn an_md2_model_converts_to_glb_with_its_animations_and_reads_back() {
    let Some(corpus) = corpus() else { return };
    let dir = tempfile::tempdir().unwrap();
    let (md2, pcx) = (corpus.join("md2/waste/tris.md2"), corpus.join("md2/waste/waste.pcx"));
    let glb = dir.path().join("waste.glb");
    let out = mocap(&["convert", md2.to_str().unwrap(), pcx.to_str().unwrap(), "-o", glb.to_str().unwrap()]);
    assert!(out.status.success(), "{}", stderr(&out));
    let bytes = std::fs::read(&glb).unwrap();
    let length = u32::from_le_bytes(bytes[12..16].try_into().unwrap()) as usize;
    let json: serde_json::Value = serde_json::from_slice(&bytes[20..20 + length]).unwrap();
    assert_eq!(json["meshes"][0]["primitives"][0]["targets"].as_array().unwrap().len(), 198, "a target per key frame");
    let names: Vec<&str> = json["animations"].as_array().unwrap().iter().map(|a| a["name"].as_str().unwrap()).collect();
    assert_eq!(names.len(), 20);
    assert!(names.contains(&"run") && names.contains(&"stand"), "{names:?}");
    assert_eq!(json["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["index"], 0, "textured by its skin");
    // Read back: the same model, 198 frames, with its animations.
    let info = mocap(&["info", glb.to_str().unwrap()]);
    assert!(info.status.success(), "{}", stderr(&info));
    let text = stdout(&info);
    assert!(text.contains("frames:     198") && text.contains("animation:  run"), "{text}");
    // Without its skin: untextured, and said so.
    let bare = dir.path().join("bare.glb");
    let out = mocap(&["convert", md2.to_str().unwrap(), "-o", bare.to_str().unwrap()]);
    assert!(out.status.success() && stderr(&out).contains("untextured"), "{}", stderr(&out));
}

#[test]
fn retarget_maps_saves_its_map_and_reads_one_back() {
    let dir = tempfile::tempdir().unwrap();
    let walk = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/walk.bvh");
    let (out_file, map_file) = (dir.path().join("out.bvh"), dir.path().join("map.json"));
    let args = |extra: &[&str]| -> Vec<String> {
        let mut a: Vec<String> = ["retarget", walk.to_str().unwrap(), "--onto", walk.to_str().unwrap(), "-o"]
            .iter()
            .map(|s| s.to_string())
            .collect();
        a.push(out_file.to_str().unwrap().to_owned());
        a.extend(extra.iter().map(|s| s.to_string()));
        a
    };
    let run = |a: Vec<String>| mocap(&a.iter().map(String::as_str).collect::<Vec<_>>());
    let out = run(args(&["--save-map", map_file.to_str().unwrap()]));
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(stderr(&out).contains("mapped 21 of 21 target joints"), "{}", stderr(&out));
    let map: serde_json::Value = serde_json::from_slice(&std::fs::read(&map_file).unwrap()).unwrap();
    assert_eq!(map["LeftForeArm"], "LeftForeArm");
    let a = mocap::formats::bvh::parse(&std::fs::read(&walk).unwrap()).unwrap();
    let b = mocap::formats::bvh::parse(&std::fs::read(&out_file).unwrap()).unwrap();
    for (p, q) in a.world_positions(20).iter().zip(b.world_positions(20)) {
        assert!(p.distance(q) < 0.2, "onto itself: the same motion ({p} vs {q})");
    }
    // A map leaving a joint out, and a bad one named with its place.
    std::fs::write(&map_file, r#"{"LeftArm": ""}"#).unwrap();
    let out = run(args(&["--map", map_file.to_str().unwrap()]));
    assert!(stderr(&out).contains("mapped 20 of 21"), "{}", stderr(&out));
    std::fs::write(&map_file, r#"{"LeftArm": 3}"#).unwrap();
    let out = run(args(&["--map", map_file.to_str().unwrap()]));
    assert!(!out.status.success() && stderr(&out).contains("/LeftArm: expected a joint name"), "{}", stderr(&out));
    std::fs::write(&map_file, r#"{"LeftArm": "Wing"}"#).unwrap();
    let out = run(args(&["--map", map_file.to_str().unwrap()]));
    assert!(
        !out.status.success() && stderr(&out).contains("`Wing`, which is not a joint of the source"),
        "{}",
        stderr(&out)
    );
}

#[test]
fn validate_walks_directories_and_fails_on_any_bad_file() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir(dir.path().join("sub")).unwrap();
    write_temp(dir.path(), "a.bvh", SIMPLE);
    write_temp(&dir.path().join("sub"), "b.BVH", SIMPLE);
    write_temp(dir.path(), "notes.txt", "not motion");
    let ok = mocap(&["validate", dir.path().to_str().unwrap()]);
    assert!(ok.status.success(), "{}", stdout(&ok));
    assert_eq!(stdout(&ok).lines().count(), 2);
    write_temp(&dir.path().join("sub"), "c.bvh", "HIERARCHY\nROOT A\n{\n");
    let bad = mocap(&["validate", dir.path().to_str().unwrap()]);
    assert!(!bad.status.success());
    let text = stdout(&bad);
    assert_eq!(text.lines().count(), 3);
    assert!(text.contains("c.bvh:4:1: unexpected end of file"), "{text}");
}

/// A root and two bones (the second with an axis), and a two-frame motion.
const ASF: &str = ":version 1.10\n:name T\n:units\n  mass 1.0\n  length 1.0\n  angle deg\n:documentation\n  two bones\n:root\n  order TX TY TZ RX RY RZ\n  axis XYZ\n  position 0 0 0\n  orientation 0 0 0\n:bonedata\n  begin\n    id 1\n    name up\n    direction 0 1 0\n    length 10\n    axis 0 0 30 XYZ\n    dof rx ry rz\n  end\n  begin\n    id 2\n    name side\n    direction 1 0 0\n    length 5\n    axis 0 0 0 XYZ\n    dof rx rz\n  end\n:hierarchy\n  begin\n    root up\n    up side\n  end\n";
const AMC: &str = ":FULLY-SPECIFIED\n:DEGREES\n1\nroot 1 2 3 0 0 0\nup 10 20 30\nside 5 6\n2\nroot 1 2 3 0 90 0\nup -10 0 45\nside 0 0\n";

fn positions(json: &Value) -> Vec<[f64; 3]> {
    json["joints"]
        .as_array()
        .unwrap()
        .iter()
        .map(|j| {
            let p = j["position"].as_array().unwrap();
            [p[0].as_f64().unwrap(), p[1].as_f64().unwrap(), p[2].as_f64().unwrap()]
        })
        .collect()
}

#[test]
fn an_amc_alone_finds_its_skeleton_and_converts_to_bvh_and_bva() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    write_temp(d, "07.asf", ASF);
    write_temp(d, "other.asf", ASF);
    let amc = write_temp(d, "07_01.amc", AMC);
    let info = mocap(&["info", amc.to_str().unwrap(), "--json"]);
    assert!(info.status.success(), "{}", stderr(&info));
    let v: Value = serde_json::from_str(&stdout(&info)).unwrap();
    assert_eq!(v["frames"], 2);
    assert_eq!(v["joints"], 3);
    assert!(v["metadata"].to_string().contains("two bones"), "{}", v["metadata"]);
    // Both files given explicitly work too; pose agrees either way.
    let pose_alone = mocap(&["pose", amc.to_str().unwrap(), "--frame", "1", "--json"]);
    let asf = d.join("07.asf");
    let pose_pair = mocap(&["pose", asf.to_str().unwrap(), amc.to_str().unwrap(), "--frame", "1", "--json"]);
    assert_eq!(stdout(&pose_alone), stdout(&pose_pair));
    let expected = positions(&serde_json::from_str(&stdout(&pose_pair)).unwrap());
    // ASF + AMC → BVH keeps every position.
    let bvh = d.join("out.bvh");
    let out = mocap(&["convert", asf.to_str().unwrap(), amc.to_str().unwrap(), "-o", bvh.to_str().unwrap()]);
    assert!(out.status.success(), "{}", stderr(&out));
    let back = positions(
        &serde_json::from_str(&stdout(&mocap(&["pose", bvh.to_str().unwrap(), "--frame", "1", "--json"]))).unwrap(),
    );
    assert_eq!(back.len(), expected.len());
    for (a, b) in expected.iter().zip(&back) {
        assert!((0..3).all(|k| (a[k] - b[k]).abs() < 1e-4), "{a:?} vs {b:?}");
    }
    // → BVA: each joint a segment at its position.
    let bva = d.join("out.bva");
    let out = mocap(&["convert", amc.to_str().unwrap(), "-o", bva.to_str().unwrap()]);
    assert!(out.status.success(), "{}", stderr(&out));
    let segs = positions(
        &serde_json::from_str(&stdout(&mocap(&["pose", bva.to_str().unwrap(), "--frame", "1", "--json"]))).unwrap(),
    );
    for (j, seg) in [(0, 0), (1, 2), (2, 4)] {
        assert!(
            (0..3).all(|k| (expected[j][k] - segs[seg][k]).abs() < 1e-3),
            "joint {j}: {:?} vs {:?}",
            expected[j],
            segs[seg]
        );
    }
    // BVA → BVH says that scale is dropped.
    let again = d.join("again.bvh");
    let out = mocap(&["convert", bva.to_str().unwrap(), "-o", again.to_str().unwrap()]);
    assert!(out.status.success() && stderr(&out).contains("scale"), "{}", stderr(&out));
}

#[test]
fn an_amc_without_a_skeleton_says_what_it_needs() {
    let dir = tempfile::tempdir().unwrap();
    let amc = write_temp(dir.path(), "take.amc", AMC);
    let out = mocap(&["info", amc.to_str().unwrap()]);
    assert!(!out.status.success());
    assert!(stderr(&out).contains("needs its skeleton") && stderr(&out).contains(".asf"), "{}", stderr(&out));
    write_temp(dir.path(), "a.asf", ASF);
    write_temp(dir.path(), "b.asf", ASF);
    let out = mocap(&["info", amc.to_str().unwrap()]);
    assert!(!out.status.success() && stderr(&out).contains("give the right one"), "{}", stderr(&out));
    // A Windows Media file named .asf is refused clearly.
    let wm = dir.path().join("movie.asf");
    std::fs::write(
        &wm,
        [0x30, 0x26, 0xB2, 0x75, 0x8E, 0x66, 0xCF, 0x11, 0xA6, 0xD9, 0x00, 0xAA, 0x00, 0x62, 0xCE, 0x6C, 0, 0, 0, 1],
    )
    .unwrap();
    let out = mocap(&["validate", wm.to_str().unwrap()]);
    assert!(
        !out.status.success() && stdout(&out).contains("movie.asf:1:1: not an Acclaim skeleton"),
        "{}",
        stdout(&out)
    );
}

#[test]
fn render_frame_counts_use_the_shared_timeline_even_for_absurd_frame_times() {
    let dir = tempfile::tempdir().unwrap();
    let tiny = write_temp(dir.path(), "tiny.bvh", &SIMPLE.replace("Frame Time: 0.5", "Frame Time: 1e-300"));
    let png = dir.path().join("x.png");
    // Frame 5 of a 3-frame clip is out of range; the count must not overflow.
    let out = mocap(&["render", tiny.to_str().unwrap(), "--frame", "5", "--out", png.to_str().unwrap()]);
    assert!(!out.status.success() && stderr(&out).contains("out of range"), "{}", stderr(&out));
}

/// `../shared/corpus`, required unless `MOCAP_SKIP_CORPUS=1`.
fn corpus() -> Option<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/corpus");
    if dir.join("MANIFEST.tsv").is_file() {
        return Some(dir);
    }
    assert!(
        std::env::var("MOCAP_SKIP_CORPUS").is_ok_and(|v| v == "1"),
        "{}: corpus not found (opt out with MOCAP_SKIP_CORPUS=1)",
        dir.display()
    );
    None
}

#[test]
fn info_and_validate_read_md2_models() {
    let Some(corpus) = corpus() else { return };
    let faerie = corpus.join("md2/irrlicht_faerie/faerie.md2");
    let out = mocap(&["info", faerie.to_str().unwrap(), "--json"]);
    assert!(out.status.success(), "{}", stderr(&out));
    let v: Value = serde_json::from_str(&stdout(&out)).unwrap();
    assert_eq!(
        (v["frames"].as_u64(), v["vertices"].as_u64(), v["triangles"].as_u64(), v["tex_coords"].as_u64()),
        (Some(198), Some(366), Some(654), Some(487))
    );
    assert_eq!(v["skin_size"], serde_json::json!([220, 193]));
    assert_eq!(v["animations"][0]["name"], "stand");
    let text = stdout(&mocap(&["info", faerie.to_str().unwrap()]));
    assert!(text.contains("Quake 2 MD2 model") && text.contains("animation:  stand (frames 0–"), "{text}");
    let bad = corpus.join("md2/assimp_malformed/malformed_zero_numvertices.md2");
    let out = mocap(&["validate", corpus.join("md2").to_str().unwrap()]);
    assert!(!out.status.success());
    let lines = stdout(&out);
    assert_eq!(lines.lines().filter(|l| l.starts_with("ok ")).count(), 4, "{lines}");
    assert!(lines.contains(&format!("FAIL {}:byte 24: num_xyz is 0", bad.display())), "{lines}");
    // With its skin the info says which image is used; a skin alone is an error.
    let weapon = corpus.join("md2/waste/weapon.md2");
    let skin = corpus.join("md2/waste/weapon.PCX");
    let out = mocap(&["info", weapon.to_str().unwrap(), skin.to_str().unwrap(), "--json"]);
    let v: Value = serde_json::from_str(&stdout(&out)).unwrap();
    assert_eq!(v["skin"], serde_json::json!(skin.to_str().unwrap()));
    assert_eq!(v["units"], "in", "every MD2 model is in Quake units, the weapon too");
    let out = mocap(&["info", skin.to_str().unwrap()]);
    assert!(!out.status.success() && stderr(&out).contains("an image is used as a model's skin"), "{}", stderr(&out));
    // A model has no motion to convert, and --animation must name one of its animations.
    let out = mocap(&["convert", weapon.to_str().unwrap(), "-o", "/tmp/never.bvh"]);
    assert!(!out.status.success() && stderr(&out).contains("a model has no skeleton or motion"), "{}", stderr(&out));
    let out = mocap(&["render", weapon.to_str().unwrap(), "--animation", "fly", "--out", "/tmp/never.png"]);
    assert!(!out.status.success() && stderr(&out).contains("--animation fly: no model"), "{}", stderr(&out));
}

#[test]
fn ik_moves_a_hand_to_a_target_and_reports_the_pose() {
    let walk = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/walk.bvh");
    let walk = walk.to_str().unwrap();
    let pose: Value = serde_json::from_str(&stdout(&mocap(&["pose", walk, "--frame", "12", "--json"]))).unwrap();
    let hand = pose["joints"].as_array().unwrap().iter().find(|j| j["name"] == "LeftHand").unwrap()["position"].clone();
    let p: Vec<f64> = hand.as_array().unwrap().iter().map(|v| v.as_f64().unwrap()).collect();
    let target = format!("{},{},{}", p[0] + 6.0, p[1] + 8.0, p[2] - 4.0);
    for solver in ["two-bone", "ccd", "fabrik"] {
        let out = mocap(&[
            "ik", walk, "--joint", "LeftHand", "--target", &target, "--frame", "12", "--solver", solver, "--json",
        ]);
        assert!(out.status.success(), "{}", stderr(&out));
        let v: Value = serde_json::from_str(&stdout(&out)).unwrap();
        assert_eq!(v["chain"], serde_json::json!(["LeftArm", "LeftForeArm", "LeftHand"]), "the default arm chain");
        assert_eq!(v["reached"], true, "{solver}: {}", v["distance"]);
        let got = v["joints"].as_array().unwrap().iter().find(|j| j["name"] == "LeftHand").unwrap()["position"].clone();
        let g: Vec<f64> = got.as_array().unwrap().iter().map(|v| v.as_f64().unwrap()).collect();
        let d = ((g[0] - p[0] - 6.0).powi(2) + (g[1] - p[1] - 8.0).powi(2) + (g[2] - p[2] + 4.0).powi(2)).sqrt();
        assert!(d < 1e-2, "{solver}: the hand is {d} from the target");
        // The other hand did not move.
        let other = |v: &Value| {
            v["joints"].as_array().unwrap().iter().find(|j| j["name"] == "RightHand").unwrap()["position"].clone()
        };
        assert_eq!(other(&v), other(&pose));
    }
    for (args, needle) in [
        (vec!["--joint", "Nope", "--target", "0,0,0"], "no joint named `Nope`"),
        (vec!["--joint", "LeftHand", "--target", "1,2"], "expected x,y,z"),
        (vec!["--joint", "LeftHand", "--target", "0,0,0", "--solver", "magic"], "expected two-bone, ccd or fabrik"),
        (
            vec!["--joint", "LeftHand", "--target", "0,0,0", "--bones", "4", "--solver", "two-bone"],
            "needs a chain of two bones",
        ),
    ] {
        let mut all = vec!["ik", walk];
        all.extend(args);
        let out = mocap(&all);
        assert!(!out.status.success() && stderr(&out).contains(needle), "{all:?}: {}", stderr(&out));
    }
}

#[test]
fn edit_applies_its_flags_in_the_order_given() {
    let walk = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/walk.bvh");
    let walk = walk.to_str().unwrap();
    let dir = tempfile::tempdir().unwrap();
    let out = |name: &str| dir.path().join(name).to_str().unwrap().to_owned();
    let frames = |path: &str| -> u64 {
        let v: Value = serde_json::from_str(&stdout(&mocap(&["info", path, "--json"]))).unwrap();
        v["frames"].as_u64().unwrap()
    };
    // Trim to 10 frames, then double the rate: 19 frames; the other way round: 10.
    let a = out("a.bvh");
    assert!(mocap(&["edit", walk, "--trim", "0:9", "--fps", "60", "-o", &a]).status.success());
    assert_eq!(frames(&a), 19);
    let b = out("b.bvh");
    assert!(mocap(&["edit", walk, "--fps", "60", "--trim", "0:9", "-o", &b]).status.success());
    assert_eq!(frames(&b), 10);
    // `--fps N:cubic` resamples with cubic in-betweens: the same frames where
    // the old ones fall (every other), other values between them.
    let cubic = out("cubic.bvh");
    let run = mocap(&["edit", walk, "--trim", "0:9", "--fps", "60:cubic", "-o", &cubic]);
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    assert_eq!(frames(&cubic), 19);
    let motion = |path: &str| -> Vec<Vec<f64>> {
        let text = std::fs::read_to_string(path).unwrap();
        let body = text.split("Frame Time:").nth(1).unwrap();
        body.lines().skip(1).filter(|l| !l.trim().is_empty()).map(|l| l.split_whitespace().map(|v| v.parse().unwrap()).collect()).collect()
    };
    let (linear, smooth) = (motion(&a), motion(&cubic));
    let most = |x: &[f64], y: &[f64]| x.iter().zip(y).map(|(p, q)| (p - q).abs()).fold(0.0, f64::max);
    for k in (0..19).step_by(2) {
        assert!(most(&linear[k], &smooth[k]) < 1e-3, "frame {k} is an original frame");
    }
    assert!((1..19).step_by(2).any(|k| most(&linear[k], &smooth[k]) > 1e-3), "cubic in-betweens differ from linear ones");
    let bad = mocap(&["edit", walk, "--fps", "60:smooth", "-o", &out("bad.bvh")]);
    assert!(!bad.status.success());
    assert!(String::from_utf8_lossy(&bad.stderr).contains("expected a frame rate (N or N:cubic)"), "{}", String::from_utf8_lossy(&bad.stderr));
    // Every edit kind runs and writes a file that reads back.
    let c = out("c.bvh");
    let all = [
        "edit",
        walk,
        "--reverse",
        "--ping-pong",
        "--knit",
        "4",
        "--in-place",
        "--up",
        "z",
        "--units",
        "m",
        "--scale",
        "2",
        "--rename",
        "Head=Kopf",
        "--remove",
        "LeftForeArm",
        "--drop-joint",
        "RightForeArm",
        "-o",
        &c,
    ];
    let r = mocap(&all);
    assert!(r.status.success(), "{}", stderr(&r));
    let v: Value = serde_json::from_str(&stdout(&mocap(&["info", &c, "--json"]))).unwrap();
    assert_eq!(v["joints"].as_u64(), Some(19));
    for (args, needle) in [
        (vec!["--trim", "5:1"], "trim 5:1"),
        (vec!["--up", "q"], "--up q"),
        (vec!["--units", "furlong"], "--units furlong"),
        (vec!["--rename", "Head"], "expected OLD=NEW"),
        (vec!["--remove", "Tail"], "no joint named `Tail`"),
    ] {
        let mut full = vec!["edit", walk];
        full.extend(args);
        full.extend(["-o", &c]);
        let r = mocap(&full);
        assert!(!r.status.success() && stderr(&r).contains(needle), "{full:?}: {}", stderr(&r));
    }
    let r = mocap(&["edit", walk, "--reverse", "-o", &out("x.bva")]);
    assert!(!r.status.success() && stderr(&r).contains("writes .bvh"));
}

#[test]
fn layer_puts_a_second_motion_on_a_subtree() {
    let walk = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/walk.bvh");
    let walk = walk.to_str().unwrap();
    let dir = tempfile::tempdir().unwrap();
    let wave = dir.path().join("wave.bvh");
    let wave = wave.to_str().unwrap();
    assert!(mocap(&["edit", walk, "--reverse", "-o", wave]).status.success());
    let out = dir.path().join("out.bvh");
    let out = out.to_str().unwrap();
    let r = mocap(&["layer", walk, "--subtree", "RightShoulder", wave, "--weight", "1", "-o", out]);
    assert!(r.status.success(), "{}", stderr(&r));
    let pose = |file: &str, frame: &str| -> Value {
        serde_json::from_str(&stdout(&mocap(&["pose", file, "--frame", frame, "--json"]))).unwrap()
    };
    let at = |v: &Value, name: &str| {
        v["joints"].as_array().unwrap().iter().find(|j| j["name"] == name).unwrap()["position"].clone()
    };
    let (layered, base, layer) = (pose(out, "10"), pose(walk, "10"), pose(wave, "10"));
    assert_eq!(at(&layered, "LeftHand"), at(&base, "LeftHand"), "outside the subtree: the base");
    let (h, w) = (at(&layered, "RightHand"), at(&layer, "RightHand"));
    let (hips_l, hips_w) = (at(&layered, "Hips"), at(&layer, "Hips"));
    // The hand hangs from the base's shoulder but turned as in the layer: relative to the hips it moved.
    assert_ne!(h, at(&base, "RightHand"));
    let rel =
        |p: &Value, o: &Value| (0..3).map(|k| p[k].as_f64().unwrap() - o[k].as_f64().unwrap()).collect::<Vec<_>>();
    let (a, c) = (rel(&h, &hips_l), rel(&w, &hips_w));
    let d: f64 = a.iter().zip(&c).map(|(x, y)| (x - y).powi(2)).sum::<f64>().sqrt();
    assert!(d < 15.0, "the layered hand is near the layer's (relative to the hips): {a:?} vs {c:?}");
    let r = mocap(&["layer", walk, "--subtree", "Wing", wave, "-o", out]);
    assert!(!r.status.success() && stderr(&r).contains("no joint named `Wing`"));
    let r = mocap(&["layer", walk, "--subtree", "RightShoulder", wave, "--map", "nonsense", "-o", out]);
    assert!(!r.status.success() && stderr(&r).contains("expected BASE=LAYER"));
}

#[test]
fn capture_turns_an_md2_into_bvh_with_a_report_a_rig_and_the_frame_layout() {
    let Some(corpus) = corpus() else { return };
    let dir = std::env::temp_dir().join(format!("mocap-capture-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let model = corpus.join("md2/waste/tris.md2");
    let (out, rig, frames) = (dir.join("waste.bvh"), dir.join("rig.json"), dir.join("waste.cap"));
    let o = mocap(&[
        "capture",
        model.to_str().unwrap(),
        "--split",
        "--save-rig",
        rig.to_str().unwrap(),
        "--frames-out",
        frames.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let report = stdout(&o);
    assert!(report.contains("max resid") && report.contains("198 frames") && report.contains("run 40–45"), "{report}");
    let all = mocap(&["info", out.to_str().unwrap(), "--json"]);
    let v: Value = serde_json::from_str(&stdout(&all)).unwrap();
    assert_eq!(v["frames"].as_u64(), Some(198));
    assert_eq!(v["units"], "m", "written in metres, as the viewer reads the model");
    let run = mocap(&["info", dir.join("waste-run.bvh").to_str().unwrap(), "--json"]);
    let v: Value = serde_json::from_str(&stdout(&run)).unwrap();
    assert_eq!(v["frames"].as_u64(), Some(6), "--split writes one BVH per animation");
    let bytes = std::fs::read(&frames).unwrap();
    assert_eq!(&bytes[..8], b"MOCAPCF1");
    // The saved rig captures the same again, and one animation alone.
    let again = dir.join("run.bvh");
    let o = mocap(&[
        "capture",
        model.to_str().unwrap(),
        "--rig",
        rig.to_str().unwrap(),
        "--animation",
        "run",
        "-o",
        again.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(std::fs::read(&again).unwrap(), std::fs::read(dir.join("waste-run.bvh")).unwrap());
    // Errors say what is wrong.
    let o = mocap(&["capture", model.to_str().unwrap(), "--animation", "fly", "-o", again.to_str().unwrap()]);
    assert!(
        !o.status.success() && stderr(&o).contains("--animation fly: ") && stderr(&o).contains("stand"),
        "{}",
        stderr(&o)
    );
    std::fs::write(dir.join("bad.json"), "{\"format\": \"x\"").unwrap();
    let o = mocap(&[
        "capture",
        model.to_str().unwrap(),
        "--rig",
        dir.join("bad.json").to_str().unwrap(),
        "-o",
        again.to_str().unwrap(),
    ]);
    assert!(!o.status.success() && stderr(&o).contains("bad.json: rig: line 1"), "{}", stderr(&o));
    let o = mocap(&[
        "capture",
        corpus.join("md2/assimp_malformed/malformed_zero_numvertices.md2").to_str().unwrap(),
        "-o",
        again.to_str().unwrap(),
    ]);
    assert!(!o.status.success() && stderr(&o).contains("num_xyz is 0"), "{}", stderr(&o));
    let _ = std::fs::remove_dir_all(&dir);
}

/// A GLB of the walk with a second animation (the first one's channels under
/// another name), written by `mocap convert` and edited as JSON.
fn two_take_glb(dir: &Path) -> PathBuf {
    let walk = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/walk.bvh");
    let glb = dir.join("walk.glb");
    let out = mocap(&["convert", walk.to_str().unwrap(), "-o", glb.to_str().unwrap()]);
    assert!(out.status.success(), "{}", stderr(&out));
    let bytes = std::fs::read(&glb).unwrap();
    let json_len = u32::from_le_bytes(bytes[12..16].try_into().unwrap()) as usize;
    let mut json: Value = serde_json::from_slice(&bytes[20..20 + json_len]).unwrap();
    let mut second = json["animations"][0].clone();
    second["name"] = "walk again".into();
    json["animations"].as_array_mut().unwrap().push(second);
    let mut text = serde_json::to_vec(&json).unwrap();
    while text.len() % 4 != 0 {
        text.push(b' ');
    }
    let bin = &bytes[20 + json_len..];
    let mut out = b"glTF".to_vec();
    out.extend(2u32.to_le_bytes());
    out.extend(((12 + 8 + text.len() + bin.len()) as u32).to_le_bytes());
    out.extend((text.len() as u32).to_le_bytes());
    out.extend(b"JSON");
    out.extend(&text);
    out.extend(bin);
    let path = dir.join("two.glb");
    std::fs::write(&path, out).unwrap();
    path
}

#[test]
fn gltf_files_have_info_poses_by_animation_and_convert_and_retarget() {
    let dir = tempfile::tempdir().unwrap();
    let glb = two_take_glb(dir.path());
    let g = glb.to_str().unwrap();
    let out = mocap(&["info", g, "--json"]);
    assert!(out.status.success(), "{}", stderr(&out));
    let info: Value = serde_json::from_str(&stdout(&out)).unwrap();
    assert_eq!(info["format"], "gltf");
    let names: Vec<&str> =
        info["gltf"]["animations"].as_array().unwrap().iter().map(|a| a["name"].as_str().unwrap()).collect();
    assert_eq!(names, ["walk", "walk again"]);
    assert!((info["gltf"]["animations"][1]["duration"].as_f64().unwrap() - 2.2).abs() < 1e-3);
    assert_eq!(info["gltf"]["skins"][0]["joints"], info["joints"]);
    assert!(info["gltf"]["vertices"].as_u64().unwrap() > 1000);
    assert!((info["fps"].as_f64().unwrap() - 30.0).abs() < 1e-3, "the key rate");

    // A pose at a time of a named animation; an unknown name lists the names.
    let out = mocap(&["pose", g, "--time", "0.5", "--animation", "walk again", "--json"]);
    assert!(out.status.success(), "{}", stderr(&out));
    let pose: Value = serde_json::from_str(&stdout(&out)).unwrap();
    assert_eq!(pose["animation"], "walk again");
    assert_eq!(pose["joints"][0]["name"], "Hips");
    let out = mocap(&["pose", g, "--animation", "run"]);
    assert!(!out.status.success() && stderr(&out).contains("the file has: walk, walk again"), "{}", stderr(&out));

    // To BVH by animation; and a BVH motion onto the GLB keeps its mesh.
    let bvh = dir.path().join("again.bvh");
    let out = mocap(&["convert", g, "--animation", "walk again", "-o", bvh.to_str().unwrap()]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(std::fs::read_to_string(&bvh).unwrap().contains("Frames: 67"));
    let bow = dir.path().join("bow.glb");
    let walk = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/walk.bvh");
    let out = mocap(&["retarget", walk.to_str().unwrap(), "--onto", g, "-o", bow.to_str().unwrap()]);
    assert!(out.status.success(), "{}", stderr(&out));
    let out = mocap(&["info", bow.to_str().unwrap(), "--json"]);
    let onto: Value = serde_json::from_str(&stdout(&out)).unwrap();
    assert_eq!(onto["gltf"]["vertices"], info["gltf"]["vertices"], "the character's own mesh");
    assert_eq!(onto["gltf"]["animations"][0]["name"], "walk", "named after the source");
    assert_eq!(onto["joints"], info["joints"]);
}

#[test]
fn a_gltf_finds_its_bin_beside_it() {
    let dir = tempfile::tempdir().unwrap();
    let walk = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/walk.bvh");
    let gltf = dir.path().join("walk.gltf");
    assert!(mocap(&["convert", walk.to_str().unwrap(), "-o", gltf.to_str().unwrap()]).status.success());
    let mut json: Value = serde_json::from_slice(&std::fs::read(&gltf).unwrap()).unwrap();
    let uri = json["buffers"][0]["uri"].as_str().unwrap().to_owned();
    use base64::Engine as _;
    let data = base64::engine::general_purpose::STANDARD.decode(uri.split_once(',').unwrap().1).unwrap();
    std::fs::write(dir.path().join("walk data.bin"), data).unwrap();
    json["buffers"][0]["uri"] = "walk%20data.bin".into();
    std::fs::write(&gltf, serde_json::to_vec(&json).unwrap()).unwrap();
    let out = mocap(&["info", gltf.to_str().unwrap()]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(stdout(&out).contains("frames:     67"), "{}", stdout(&out));
    std::fs::remove_file(dir.path().join("walk data.bin")).unwrap();
    let out = mocap(&["info", gltf.to_str().unwrap()]);
    assert!(!out.status.success() && stderr(&out).contains("buffers[0]") && stderr(&out).contains("walk data.bin"));
}

#[test]
fn validate_and_info_list_the_reader_warnings_with_their_lines() {
    // A root written JOINT: read, with the warning on line 2 in both commands.
    let dir = tempfile::tempdir().unwrap();
    let file = write_temp(dir.path(), "joint_root.bvh", &SIMPLE.replacen("ROOT", "JOINT", 1));
    let out = mocap(&["validate", file.to_str().unwrap()]);
    assert!(out.status.success(), "{}", stdout(&out));
    let text = stdout(&out);
    assert!(text.contains("1 warnings"), "{text}");
    assert!(
        text.contains("warning: ") && text.contains("joint_root.bvh:2: the skeleton's root is written JOINT"),
        "{text}"
    );
    let info = mocap(&["info", file.to_str().unwrap(), "--json"]);
    assert!(info.status.success(), "{}", stderr(&info));
    let v: Value = serde_json::from_str(&stdout(&info)).unwrap();
    assert!(v["warnings"][0].as_str().unwrap().contains("written JOINT"), "{v}");
}
