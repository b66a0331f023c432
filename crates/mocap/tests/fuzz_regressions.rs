//! Inputs found by `cargo fuzz run bvh_parse` (and hand-made hostile inputs) stay
//! here forever: each must parse or fail cleanly, and what parses must survive FK,
//! bounds and a write → parse round trip — exactly what the fuzz target checks —
//! and read as it arrives (`bvh::Stream`) it must give what `parse` gives.

use std::path::Path;

fn check(name: &str, data: &[u8]) {
    // Read as it arrives (the page's drop), in pieces of a few sizes: the same
    // frames and the same error.
    let whole = mocap::formats::bvh::parse(data);
    for piece in [1, 7, 4096] {
        let mut stream = mocap::formats::bvh::Stream::with_capacity(data.len());
        data.chunks(piece).for_each(|c| stream.push(c));
        let streamed = stream.finish();
        let outcome = |r: &Result<mocap::Clip, mocap::ParseError>| {
            r.as_ref()
                .map(|c| {
                    (
                        c.frame_count(),
                        c.skeleton().len(),
                        c.motion().data().iter().map(|v| v.to_bits()).collect::<Vec<_>>(),
                    )
                })
                .map_err(|e| e.to_string())
        };
        assert!(
            outcome(&whole) == outcome(&streamed),
            "{name}: streamed in pieces of {piece} bytes differs from parse"
        );
    }
    if let Ok(clip) = whole {
        let _ = clip.bounds();
        let _ = clip.units();
        let mut out = Vec::new();
        clip.sample_world_positions_into(clip.duration() * 0.37, mocap::Interpolation::Linear, &mut out);
        let again = mocap::formats::bvh::parse(mocap::formats::bvh::write(&clip).as_bytes())
            .unwrap_or_else(|e| panic!("{name}: rewritten clip fails: {e}"));
        assert_eq!(again.frame_count(), clip.frame_count(), "{name}");
        assert_eq!(again.skeleton().len(), clip.skeleton().len(), "{name}");
    }
}

#[test]
fn saved_fuzz_inputs() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fuzz-regressions");
    let mut entries: Vec<_> = std::fs::read_dir(&dir).unwrap().filter_map(|e| e.ok()).map(|e| e.path()).collect();
    entries.sort();
    assert!(entries.len() >= 3, "regression inputs missing from {}", dir.display());
    for path in entries.iter().filter(|p| p.is_file() && p.extension().is_none_or(|e| e != "md")) {
        check(&path.display().to_string(), &std::fs::read(path).unwrap());
    }
}

#[test]
fn hand_made_hostile_inputs() {
    let deep: String =
        "HIERARCHY\nROOT A\n{\n".to_string() + &"JOINT B\n{\nOFFSET 0 1 0\n".repeat(50_000) + &"}\n".repeat(50_001);
    let inputs: Vec<(&str, Vec<u8>)> = vec![
        ("deep nesting", deep.into_bytes()),
        ("nul bytes", vec![0; 1000]),
        ("only braces", b"HIERARCHY {{{{}}}}".to_vec()),
        ("channels count huge", b"HIERARCHY\nROOT A\n{\nCHANNELS 4294967295 Xrotation\n}\n".to_vec()),
        ("frames huge with no rows", b"HIERARCHY\nROOT A\n{\nOFFSET 0 0 0\nCHANNELS 1 Xrotation\n}\nMOTION\nFrames: 18446744073709551615\nFrame Time: 1e-300\n".to_vec()),
        ("frame time inf", b"HIERARCHY\nROOT A\n{\nOFFSET 0 0 0\nCHANNELS 1 Xrotation\n}\nMOTION\nFrames: 1\nFrame Time: inf\n1e39\n".to_vec()),
        ("latin1 garbage names", b"HIERARCHY\nROOT \xff\xfe\n{\nOFFSET 0 0 0\n}\n".to_vec()),
    ];
    for (name, data) in inputs {
        check(name, &data);
    }
}
