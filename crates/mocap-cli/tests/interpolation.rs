//! `--interpolation` on `mocap pose`: cubic gives the core's cubic sample,
//! linear the blend, and a bad name is refused.

use std::path::Path;
use std::process::Command;

fn pose(args: &[&str]) -> std::process::Output {
    let walk = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/walk.bvh");
    Command::new(env!("CARGO_BIN_EXE_mocap")).arg("pose").arg(walk).args(args).output().unwrap()
}

fn positions(out: &std::process::Output) -> Vec<[f32; 3]> {
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    v["joints"].as_array().unwrap().iter().map(|j| {
        let p = j["position"].as_array().unwrap();
        [0, 1, 2].map(|i| p[i].as_f64().unwrap() as f32)
    }).collect()
}

#[test]
fn cubic_and_linear_sampling_between_frames() {
    let clip = mocap::formats::bvh::parse(include_bytes!("../../../data/walk.bvh")).unwrap();
    for (name, interpolation) in [("cubic", mocap::Interpolation::Cubic), ("linear", mocap::Interpolation::Linear)] {
        let out = pose(&["--time", "0.35", "--interpolation", name]);
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        let mut expected = Vec::new();
        clip.sample_world_positions_into(0.35, interpolation, &mut expected);
        for (p, e) in positions(&out).iter().zip(&expected) {
            assert!((p[0] - e.x).abs() < 1e-3 && (p[1] - e.y).abs() < 1e-3 && (p[2] - e.z).abs() < 1e-3, "{name}");
        }
    }
    assert_ne!(positions(&pose(&["--time", "0.35", "--interpolation", "cubic"])), positions(&pose(&["--time", "0.35"])));
    let bad = pose(&["--time", "0.35", "--interpolation", "sideways"]);
    assert!(String::from_utf8_lossy(&bad.stderr).contains("expected nearest, linear or cubic"));
}
