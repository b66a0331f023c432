//! Every BVH file of ../shared/corpus: parses as its MANIFEST says, FK gives finite
//! positions, and write → parse is exact. Fails when the corpus is absent unless MOCAP_SKIP_CORPUS=1.

use std::path::Path;

mod common;
use common::corpus_dir;

struct Entry {
    path: String,
    format: String,
    frames: String,
    joints: String,
    notes: String,
}

fn manifest(dir: &Path) -> Vec<Entry> {
    let text = std::fs::read_to_string(dir.join("MANIFEST.tsv")).unwrap();
    text.lines()
        .skip(1)
        .filter_map(|l| {
            let f: Vec<&str> = l.split('\t').collect();
            Some(Entry {
                path: f.first()?.to_string(),
                format: f.get(1)?.to_string(),
                frames: f.get(3)?.to_string(),
                joints: f.get(4)?.to_string(),
                notes: f.get(8).unwrap_or(&"").to_string(),
            })
        })
        .collect()
}

#[test]
fn corpus_bvh_files_parse_as_the_manifest_says() {
    let Some(dir) = corpus_dir() else {
        eprintln!("../shared/corpus not found: skipping corpus tests");
        return;
    };
    let entries: Vec<Entry> = manifest(&dir).into_iter().filter(|e| e.format == "bvh").collect();
    assert!(entries.len() >= 20, "manifest lists {} BVH files", entries.len());
    for e in &entries {
        let bytes = std::fs::read(dir.join(&e.path)).unwrap();
        let result = mocap::load_one(&e.path, &bytes);
        if e.notes.contains("MALFORMED") {
            let err = result.err().unwrap_or_else(|| panic!("{}: malformed file parsed", e.path));
            let text = err.to_string();
            assert!(text.starts_with(&format!("{}:", e.path)) && text.matches(':').count() >= 3, "{text}");
            continue;
        }
        let clip = result
            .unwrap_or_else(|err| panic!("{err}"))
            .clip()
            .cloned()
            .unwrap_or_else(|| panic!("{}: not a clip", e.path));
        // Frames: "N", "" (no motion) or "N declared / M rows".
        let expected_frames: usize = match e.frames.split_once(" declared / ") {
            Some((_, rows)) => rows.trim_end_matches(" rows").parse().unwrap(),
            None => e.frames.parse().unwrap_or(0),
        };
        assert_eq!(clip.frame_count(), expected_frames, "{}", e.path);
        if e.frames.contains("declared") {
            assert!(clip.warnings.iter().any(|w| w.message.contains("Frames:")), "{}", e.path);
        }
        let joints = clip.skeleton().joints().iter().filter(|j| !j.is_end_site()).count();
        assert_eq!(joints.to_string(), e.joints, "{}", e.path);
        // FK is finite on every frame.
        let mut pos = Vec::new();
        for f in 0..clip.frame_count() {
            clip.world_positions_into(f, &mut pos);
            assert!(pos.iter().all(|p| p.is_finite()), "{} frame {f}", e.path);
        }
        // Round trip: same hierarchy, bit-identical values.
        let again = mocap::formats::bvh::parse(mocap::formats::bvh::write(&clip).as_bytes())
            .unwrap_or_else(|err| panic!("{}: rewritten: {err}", e.path));
        assert_same(&clip, &again, &e.path);
    }
}

#[test]
fn unit_guesses_on_known_sources() {
    let Some(dir) = corpus_dir() else { return };
    let expect = [
        ("bvh/assimp_cmu/01_01.bvh", mocap::Units::CmuInches),
        ("bvh/bandai_namco/dataset-1_bow_active_001.bvh", mocap::Units::Centimeters),
        ("bvh/bandai_namco/dataset-2_walk_elderly_004.bvh", mocap::Units::Centimeters),
        ("bvh/axis_neuron/test.bvh", mocap::Units::Centimeters),
        ("bvh/mae_depthcam/bk_cut_single_01.bvh", mocap::Units::Millimeters),
        ("bvh/fairmotion/pfnn_hierarchy.bvh", mocap::Units::Meters),
    ];
    for (path, units) in expect {
        let clip = mocap::formats::bvh::parse(&std::fs::read(dir.join(path)).unwrap()).unwrap();
        assert_eq!(clip.units(), units, "{path}: height {}", clip.pose_height());
    }
}

#[test]
fn up_axis_guesses_on_every_corpus_clip() {
    let Some(dir) = corpus_dir() else { return };
    let mut checked = 0;
    for e in manifest(&dir) {
        if e.format != "bvh" || e.notes.contains("MALFORMED") {
            continue;
        }
        let Ok(clip) = mocap::formats::bvh::parse(&std::fs::read(dir.join(&e.path)).unwrap()) else { continue };
        // MakeHuman's skeletons and the dab of animated_drawings stand along Z
        // (drawn Y-up they lie on their backs); every other source is Y-up (the
        // Bandai Namco rest pose lies along X and Z, its motion stands in Y).
        // MakeHuman's one-frame T-pose is read as Y-up: its one pose is no evidence
        // either way (0.72).
        let z_up = ["bvh/makehuman/walk1.bvh", "bvh/makehuman/face-poseunits.bvh", "bvh/animated_drawings/dab.bvh"];
        let expected = if z_up.contains(&e.path.as_str()) { mocap::UpAxis::Z } else { mocap::UpAxis::Y };
        assert_eq!(clip.up_axis(), expected, "{}", e.path);
        checked += 1;
    }
    assert!(checked > 15, "{checked} clips");
    // CMU's Acclaim takes and the generated BVA walk are Y-up.
    for (asf, amc) in [("01.asf", "01_01.amc"), ("01.asf", "01_06.amc"), ("02.asf", "02_01.amc")] {
        let read = |name: &str| std::fs::read(dir.join("asf_amc/cmu").join(name)).unwrap();
        let (skeleton, motion) = (read(asf), read(amc));
        let files = [mocap::Input { name: asf, bytes: &skeleton }, mocap::Input { name: amc, bytes: &motion }];
        let loaded = mocap::load(&files).into_iter().find_map(Result::ok).expect("the take opens");
        assert_eq!(loaded.asset.clip().unwrap().up_axis(), mocap::UpAxis::Y, "{amc}");
    }
    let bva = std::fs::read(std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/walk.bva")).unwrap();
    assert_eq!(mocap::load_one("walk.bva", &bva).unwrap().clip().unwrap().up_axis(), mocap::UpAxis::Y);
    // The MakeHuman walk, read Z-up, is 1.7 m tall in decimetres.
    let walk = mocap::formats::bvh::parse(&std::fs::read(dir.join("bvh/makehuman/walk1.bvh")).unwrap()).unwrap();
    assert_eq!(walk.units(), mocap::Units::Decimeters, "height {}", walk.pose_height());
}

/// Same joints (names of real joints, parents, offsets, channels) and identical bits.
pub fn assert_same(a: &mocap::Clip, b: &mocap::Clip, what: &str) {
    assert_eq!(a.skeleton().len(), b.skeleton().len(), "{what}");
    for (ja, jb) in a.skeleton().joints().iter().zip(b.skeleton().joints()) {
        if !ja.is_end_site() {
            assert_eq!(ja.name.trim(), jb.name, "{what}");
        }
        assert_eq!(
            (ja.parent, ja.is_end_site(), &ja.channels, ja.first_channel()),
            (jb.parent, jb.is_end_site(), &jb.channels, jb.first_channel()),
            "{what}"
        );
        assert_eq!(ja.offset.to_array().map(f32::to_bits), jb.offset.to_array().map(f32::to_bits), "{what}");
    }
    assert_eq!(a.frame_count(), b.frame_count(), "{what}");
    assert_eq!(a.frame_time(), b.frame_time(), "{what}");
    let bits = |c: &mocap::Clip| c.motion().data().iter().map(|v| v.to_bits()).collect::<Vec<_>>();
    assert!(bits(a) == bits(b), "{what}: motion values differ after round trip");
}

#[test]
fn corpus_bvh_files_read_as_they_arrive_as_parse_reads_them() {
    // `bvh::Stream` (the page's drop) against `bvh::parse`, pushed in pieces
    // of several sizes: the same clip bit for bit and the same warnings, or the
    // same error.
    let Some(dir) = corpus_dir() else { return };
    let entries: Vec<Entry> = manifest(&dir).into_iter().filter(|e| e.format == "bvh").collect();
    assert!(entries.len() >= 20, "manifest lists {} BVH files", entries.len());
    for e in &entries {
        let bytes = std::fs::read(dir.join(&e.path)).unwrap();
        let whole = mocap::formats::bvh::parse(&bytes);
        for piece in [1000, 65536] {
            let mut stream = mocap::formats::bvh::Stream::with_capacity(bytes.len());
            bytes.chunks(piece).for_each(|c| stream.push(c));
            let what = format!("{} in pieces of {piece} bytes", e.path);
            match (&whole, stream.finish()) {
                (Ok(a), Ok(b)) => {
                    assert_same(a, &b, &what);
                    assert_eq!(a.frame_time().to_bits(), b.frame_time().to_bits(), "{what}");
                    let warnings = |c: &mocap::Clip| {
                        c.warnings.iter().map(|w| format!("{:?} {}", w.line, w.message)).collect::<Vec<_>>()
                    };
                    assert_eq!(warnings(a), warnings(&b), "{what}");
                }
                (Err(a), Err(b)) => assert_eq!(a.to_string(), b.to_string(), "{what}"),
                (a, b) => panic!("{what}: parse gave {:?}, the stream {:?}", a.as_ref().err(), b.err()),
            }
        }
    }
}
