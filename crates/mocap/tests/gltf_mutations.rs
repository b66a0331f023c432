//! What the `gltf_parse` fuzz target checks, run on thousands of damaged copies of
//! our own GLB and glTF files in every `cargo test`: byte flips, truncations,
//! extreme header and JSON values (counts, offsets, strides, indices, times,
//! NaN, huge numbers). Every copy reads or fails with a message; what reads
//! survives FK, every take and a write → read round trip.

use mocap::formats::gltf::{Options, to_glb, to_gltf};

const WALK: &[u8] = include_bytes!("../../../data/walk.bvh");

fn check(what: &str, data: &[u8]) {
    let none = |_: &str| None;
    match mocap::formats::gltf::parse(data, &none, None) {
        Ok(mut clip) => {
            let _ = clip.bounds();
            let mut out = Vec::new();
            clip.sample_world_positions_into(clip.duration() * 0.37, mocap::Interpolation::Linear, &mut out);
            let names: Vec<String> = clip.takes().iter().map(|t| t.name.clone()).collect();
            for name in names {
                assert!(clip.set_take(&name), "{what}: take {name}");
            }
            if let Ok(glb) = to_glb(&clip, &Options::default()) {
                mocap::formats::gltf::parse(&glb, &none, None).unwrap_or_else(|e| panic!("{what}: rewritten: {e}"));
            }
        }
        Err(e) => assert!(!e.to_string().is_empty(), "{what}: an empty message"),
    }
}

/// A tiny deterministic generator (xorshift), so the copies are the same every run.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
}

/// A short clip, so that each copy is quick: the walk's first 8 frames.
fn small_clip() -> mocap::Clip {
    let clip = mocap::formats::bvh::parse(WALK).unwrap();
    mocap::ops::edit::apply(&clip, &mocap::ops::edit::Edit::Trim { first: 0, last: 7 }).unwrap()
}

#[test]
fn damaged_glb_bytes_read_or_fail_cleanly() {
    let glb = to_glb(&small_clip(), &Options::default()).unwrap();
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    for k in 0..1500 {
        let mut copy = glb.clone();
        match k % 3 {
            0 => copy.truncate(rng.below(glb.len())),
            1 => {
                for _ in 0..1 + rng.below(8) {
                    let at = rng.below(copy.len());
                    copy[at] ^= 1 << rng.below(8);
                }
            }
            _ => {
                // An extreme 32-bit value somewhere in the headers or the JSON.
                let at = rng.below(copy.len().min(4096).saturating_sub(4));
                let v = [0u32, 1, 0x7fff_ffff, 0xffff_ffff, 0x8000_0000, 12][rng.below(6)];
                copy[at..at + 4].copy_from_slice(&v.to_le_bytes());
            }
        }
        check(&format!("glb copy {k}"), &copy);
    }
}

#[test]
fn extreme_json_values_read_or_fail_cleanly() {
    let text = to_gltf(&small_clip(), &Options::default()).unwrap();
    let json: serde_json::Value = serde_json::from_str(&text).unwrap();
    // Every numeric leaf of the document (not the data URI) replaced by each extreme.
    let mut paths = Vec::new();
    let mut stack = vec![(String::new(), &json)];
    while let Some((path, v)) = stack.pop() {
        match v {
            serde_json::Value::Object(m) => m.iter().for_each(|(k, v)| stack.push((format!("{path}/{k}"), v))),
            serde_json::Value::Array(a) => {
                a.iter().enumerate().for_each(|(i, v)| stack.push((format!("{path}/{i}"), v)))
            }
            serde_json::Value::Number(_) => paths.push(path),
            serde_json::Value::String(s) if !s.starts_with("data:") => paths.push(path),
            _ => {}
        }
    }
    assert!(paths.len() > 100, "{} numbers", paths.len());
    let extremes: [serde_json::Value; 8] = [
        (-1).into(),
        0.into(),
        3.into(),
        4_294_967_295u64.into(),
        1e38.into(),
        serde_json::json!(1e300),
        "x".into(),
        serde_json::json!([]),
    ];
    let mut rng = Rng(7);
    for k in 0..1600 {
        let path = &paths[rng.below(paths.len())];
        let mut copy = json.clone();
        if let Some(slot) = copy.pointer_mut(path) {
            *slot = extremes[rng.below(extremes.len())].clone();
        }
        check(&format!("json copy {k} ({path})"), &serde_json::to_vec(&copy).unwrap());
    }
}
