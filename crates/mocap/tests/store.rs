//! The asset store (`formats::store`): every kind of asset comes back equal, bit
//! for bit (BVH, BVA, Acclaim, a glTF character with its look and takes, an edited
//! clip, an MD2 model with its skin and a chosen animation); edits go through
//! JSON; and damaged stores (every truncation, thousands of byte flips and extreme
//! values, huge length prefixes) read as assets that hold together or fail with a
//! located message, without a panic or a large allocation.

mod common;

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::sync::Arc;
use std::time::Instant;

use mocap::formats::store::{self, MAGIC};
use mocap::glam::{Quat, Vec3};
use mocap::ops::edit::{self, Edit};
use mocap::{Asset, Clip, Input};

const WALK: &[u8] = include_bytes!("../../../data/walk.bvh");
const WALK_BVA: &[u8] = include_bytes!("../../../data/walk.bva");

/// Counts the bytes this thread has allocated now and the most since the last
/// [`reset_peak`] (per thread: the tests run side by side).
struct Counting;

thread_local! {
    static NOW: Cell<isize> = const { Cell::new(0) };
    static PEAK: Cell<isize> = const { Cell::new(0) };
}

fn count(delta: isize) {
    let _ = NOW.try_with(|now| {
        now.set(now.get() + delta);
        let _ = PEAK.try_with(|peak| peak.set(peak.get().max(now.get())));
    });
}

// SAFETY: every call is passed on to the system allocator unchanged; only counters change.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let p = unsafe { System.alloc(layout) };
        if !p.is_null() {
            count(layout.size() as isize);
        }
        p
    }
    unsafe fn dealloc(&self, p: *mut u8, layout: Layout) {
        unsafe { System.dealloc(p, layout) };
        count(-(layout.size() as isize));
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

/// Starts a peak measurement on this thread; returns the bytes allocated now (the base).
fn reset_peak() -> isize {
    let now = NOW.with(Cell::get);
    PEAK.with(|p| p.set(now));
    now
}

/// A tiny deterministic generator (xorshift), so the damaged copies are the same every run.
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

fn walk() -> Clip {
    mocap::formats::bvh::parse(WALK).unwrap()
}

/// Reads one set of files through the loader, as the page does: one asset.
fn load(files: &[(&str, &[u8])]) -> Asset {
    let inputs: Vec<Input> = files.iter().map(|(name, bytes)| Input { name, bytes }).collect();
    let mut results = mocap::load(&inputs);
    assert_eq!(results.len(), 1, "one asset from the set");
    results.pop().unwrap().unwrap_or_else(|e| panic!("{e}")).asset
}

fn corpus(path: &str) -> Vec<u8> {
    let dir = common::corpus_dir().expect("the corpus (or MOCAP_SKIP_CORPUS=1, checked before)");
    std::fs::read(dir.join(path)).unwrap_or_else(|e| panic!("{path}: {e}"))
}

/// Stores `asset`, reads it back equal, and stores that again to the same bytes.
fn round_trip(name: &str, asset: &Asset) -> Vec<u8> {
    let bytes = store::write(asset);
    assert!(bytes.starts_with(MAGIC), "{name}");
    // Version 2 only for what has morph targets or weights.
    let version = if name.contains("morphing") { 2u32 } else { 1 };
    assert_eq!(bytes[8..12], version.to_le_bytes(), "{name}: version {version}");
    let back = store::parse(&bytes).unwrap_or_else(|e| panic!("{name}: {e}"));
    assert_eq!(&back, asset, "{name}: the stored asset comes back equal");
    assert_eq!(store::write(&back), bytes, "{name}: and stores to the same bytes");
    bytes
}

/// The walk as a glTF character (our writer, with its body mesh), read back: a
/// clip with a look and a take.
fn character() -> Clip {
    let glb = mocap::formats::gltf::to_glb(&walk(), &Default::default()).unwrap();
    mocap::formats::gltf::parse(&glb, &|_| None, None).unwrap()
}

#[test]
fn bvh_bva_and_acclaim_clips_come_back_equal() {
    round_trip("walk.bvh", &Asset::Clip(walk()));
    assert_eq!(
        mocap::Skeleton::default(),
        mocap::Skeleton::new(Vec::new(), mocap::EulerConvention::Intrinsic).unwrap()
    );
    round_trip("no joints", &Asset::Clip(Clip::default()));
    let still = mocap::Motion::new(0.25, 0, 3, Vec::new()).unwrap();
    let joint = mocap::Joint::new("a", None, Vec3::ONE, Vec::new());
    let skeleton = mocap::Skeleton::new(vec![joint], mocap::EulerConvention::Extrinsic).unwrap();
    round_trip("no channels, three frames", &Asset::Clip(Clip::new(skeleton, still).unwrap()));
    let bva = load(&[("walk.bva", WALK_BVA)]);
    assert!(!bva.clip().unwrap().skeleton().is_empty());
    round_trip("walk.bva", &bva);
    if common::corpus_dir().is_none() {
        return;
    }
    let (asf, amc) = (corpus("asf_amc/cmu/02.asf"), corpus("asf_amc/cmu/02_01.amc"));
    let acclaim = load(&[("02.asf", &asf), ("02_01.amc", &amc)]);
    let clip = acclaim.clip().unwrap();
    assert!(clip.frame_count() > 100 && !clip.metadata.is_empty() && !clip.warnings.is_empty());
    assert!(clip.skeleton().joints().iter().any(|j| j.rest_rotation != Quat::IDENTITY), "rest rotations kept");
    round_trip("02_01.amc", &acclaim);
}

#[test]
fn a_gltf_character_comes_back_with_its_look_takes_and_take() {
    let clip = character();
    let character = clip.character.clone().expect("a glTF clip has a character");
    let look = character.look.as_ref().expect("the body is the look");
    assert!(!look.skin.positions().is_empty() && look.colors.len() == look.skin.positions().len());
    assert!(!character.takes.is_empty() && character.summary.nodes > 0);
    round_trip("walk.glb", &Asset::Clip(clip.clone()));

    // A second take, made the motion: the take index is kept too.
    let mut more = (*character).clone();
    let half = edit::apply(&clip, &Edit::Trim { first: 0, last: 9 }).unwrap();
    more.takes.push(mocap::model::character::Take { name: "start".into(), motion: half.motion().clone(), weights: Vec::new() });
    let mut two = clip.clone().with_character(Arc::new(more));
    assert!(two.set_take("start"));
    assert_eq!(two.take_name(), Some("start"));
    let back = store::parse(&round_trip("two takes", &Asset::Clip(two))).unwrap();
    assert_eq!(back.clip().unwrap().take_name(), Some("start"));
}

#[test]
fn edited_clips_come_back_equal() {
    let trimmed = edit::apply(&walk(), &Edit::Trim { first: 0, last: 7 }).unwrap();
    assert_eq!(trimmed.frame_count(), 8);
    round_trip("walk trimmed", &Asset::Clip(trimmed));
    let knit = edit::apply(&walk(), &Edit::LoopKnit { frames: 4 }).unwrap();
    round_trip("walk knit", &Asset::Clip(knit));
    // An edit of a character keeps its look.
    let edited = edit::apply(&character(), &Edit::Trim { first: 2, last: 9 }).unwrap();
    assert!(edited.character.is_some());
    round_trip("character trimmed", &Asset::Clip(edited));
}

#[test]
fn an_md2_model_comes_back_with_its_skin_and_animation() {
    if common::corpus_dir().is_none() {
        return;
    }
    let (md2, pcx) = (corpus("md2/waste/weapon.md2"), corpus("md2/waste/weapon.PCX"));
    let mut model = load(&[("weapon.md2", &md2), ("weapon.PCX", &pcx)]);
    let m = model.model().unwrap();
    assert!(m.skin.is_some() && m.mesh.animations().len() > 1);
    round_trip("weapon.md2", &model);
    let last = m.mesh.animations().len() - 1;
    assert!(model.model_mut().unwrap().set_animation(Some(last)));
    let back = store::parse(&round_trip("weapon.md2, last animation", &model)).unwrap();
    assert_eq!(back.model().unwrap().animation(), Some(last));
}

#[test]
fn edits_round_trip_through_json() {
    let edits = vec![
        Edit::Trim { first: 2, last: 9 },
        Edit::Resample { fps: 24.0 },
        Edit::Reverse,
        Edit::PingPong,
        Edit::LoopKnit { frames: 5 },
        Edit::InPlace { remove_turning: true },
        Edit::UpAxis { from: 2, negative: false },
        Edit::Scale { factor: 0.01 },
        Edit::Rename { from: "Hips".into(), to: "pelvis \"root\"".into() },
        Edit::Correct {
            frame: 3,
            rotations: vec![("LeftArm".into(), Quat::from_rotation_z(0.3))],
            translations: vec![("Hips".into(), Vec3::new(1.0, 2.5, -3.0))],
            window: 4,
        },
        Edit::Key {
            frame: 7,
            rotations: vec![("Head".into(), Quat::IDENTITY)],
            translations: vec![],
            keys: vec![0, 12],
        },
        Edit::AddJoint { parent: "Head".into(), name: "Hat".into(), offset: Vec3::Y },
        Edit::SetOffset { name: "Hat".into(), offset: Vec3::new(0.0, 1.5, 0.25) },
        Edit::SetChannels { name: "Hips".into(), position: true, order: "ZXY".into() },
        Edit::RemoveJoint { name: "Hat".into(), fold: true },
    ];
    let json = serde_json::to_string(&edits).unwrap();
    let back: Vec<Edit> = serde_json::from_str(&json).unwrap();
    assert_eq!(back, edits);
    let one = serde_json::to_string(&Edit::Trim { first: 0, last: 7 }).unwrap();
    assert_eq!(one, r#"{"Trim":{"first":0,"last":7}}"#);
    assert_eq!(serde_json::from_str::<mocap::UpAxis>(r#""Z""#).unwrap(), mocap::UpAxis::Z);
}

#[test]
fn the_model_serde_form_is_checked_in_json_too() {
    let clip = edit::apply(&walk(), &Edit::Trim { first: 0, last: 1 }).unwrap();
    let json = serde_json::to_string(&clip).unwrap();
    assert_eq!(serde_json::from_str::<Clip>(&json).unwrap(), clip);
    // The first joint made its own child: the skeleton's own check refuses it.
    let broken = json.replacen(r#""parent":null"#, r#""parent":0"#, 1);
    let e = serde_json::from_str::<Clip>(&broken).unwrap_err().to_string();
    assert!(e.contains("skeleton: joint 0") && e.contains("parent does not come before it"), "{e}");
}

/// `asset` as JSON, changed by `change`, read back: the error message.
fn refused(asset: &Asset, change: impl FnOnce(&mut serde_json::Value)) -> String {
    let mut json = serde_json::to_value(asset).unwrap();
    change(&mut json);
    serde_json::from_value::<Asset>(json).unwrap_err().to_string()
}

#[test]
fn every_check_of_the_model_is_made_again_with_its_message() {
    let stores = small_stores();
    let [clip, character, model] = [0, 1, 2].map(|i| store::parse(&stores[i].1).unwrap());
    type Change = Box<dyn FnOnce(&mut serde_json::Value)>;
    let cases: Vec<(&Asset, &str, Change)> = vec![
        (&clip, "motion: row 1 has 1 values, row 0 has", Box::new(|j| j["Clip"]["motion"]["rows"][1] = [0.5].into())),
        (&clip, "rows of 0 values for", Box::new(|j| j["Clip"]["motion"]["rows"] = serde_json::json!([[]]))),
        (
            &clip,
            "frame time -1 s is not a positive duration",
            Box::new(|j| j["Clip"]["motion"]["frame_time"] = (-1).into()),
        ),
        (
            &clip,
            "skeleton: joint 1 (`Spine`): its rest rotation is not a unit quaternion",
            Box::new(|j| j["Clip"]["skeleton"]["joints"][1]["rest_rotation"] = [0.0, 0.0, 0.0, 2.0].into()),
        ),
        (
            &clip,
            "an End Site has no channels",
            Box::new(|j| j["Clip"]["skeleton"]["joints"][1]["end_site"] = true.into()),
        ),
        (&character, "the motion is take 7", Box::new(|j| j["Clip"]["take"] = 7.into())),
        (
            &character,
            "look: 2 colours for 3 vertices",
            Box::new(|j| j["Clip"]["character"]["look"]["colors"] = serde_json::json!([[0, 0, 0, 0], [1, 1, 1, 1]])),
        ),
        (
            &character,
            "look: skin: triangle corner 2 uses vertex 9",
            Box::new(|j| j["Clip"]["character"]["look"]["skin"]["indices"][2] = 9.into()),
        ),
        (
            &character,
            "weighted to joint 7",
            Box::new(|j| j["Clip"]["character"]["look"]["skin"]["joints"][0][0] = 7.into()),
        ),
        (
            &character,
            "(1 in a stored skin)",
            Box::new(|j| j["Clip"]["character"]["look"]["skin"]["weights"][1][0] = 0.5.into()),
        ),
        (
            &character,
            "2 inverse bind matrices for 3 joints",
            Box::new(|j| {
                let skin = &mut j["Clip"]["character"]["look"]["skin"];
                skin["inverse_bind"].as_array_mut().unwrap().pop();
                skin["joints"][2][0] = 1.into();
            }),
        ),
        (
            &character,
            "take 1 (`again`): 3 channels for a skeleton with 12",
            Box::new(|j| {
                j["Clip"]["character"]["takes"][1]["motion"] =
                    j["Clip"]["character"]["takes"][1]["motion"].clone().tap(|m| {
                        m["channel_count"] = 3.into();
                        m["rows"] = serde_json::json!([]);
                    })
            }),
        ),
        (&model, "animation 2 chosen but the mesh has 2", Box::new(|j| j["Model"]["animation"] = 2.into())),
        (
            &model,
            "skin: `skin.pcx`: 23 bytes of pixels for a 3 × 2 image",
            Box::new(|j| {
                j["Model"]["skin"]["image"]["pixels"].as_array_mut().unwrap().pop();
            }),
        ),
        (&model, "mesh: triangle corner 1 uses vertex 3", Box::new(|j| j["Model"]["mesh"]["indices"][1] = 3.into())),
        (
            &model,
            "mesh: 8 positions and 9 normals",
            Box::new(|j| {
                j["Model"]["mesh"]["positions"].as_array_mut().unwrap().pop();
            }),
        ),
        (
            &model,
            "mesh: animation `run` runs over frames 2 to 3 of 3",
            Box::new(|j| j["Model"]["mesh"]["animations"][1]["last"] = 3.into()),
        ),
        (
            &model,
            "mesh: vertex 0 comes from source vertex 5, but there are 3",
            Box::new(|j| j["Model"]["mesh"]["sources"][0] = 5.into()),
        ),
        (
            &model,
            "the mesh has no key frames",
            Box::new(|j| {
                let m = &mut j["Model"]["mesh"];
                for k in ["positions", "normals", "frame_names", "animations"] {
                    m[k] = serde_json::json!([]);
                }
            }),
        ),
    ];
    for (asset, expected, change) in cases {
        let message = refused(asset, change);
        assert!(message.contains(expected), "`{message}` should say `{expected}`");
    }
}

/// `tap` for building a changed copy inline.
trait Tap: Sized {
    fn tap(mut self, f: impl FnOnce(&mut Self)) -> Self {
        f(&mut self);
        self
    }
}

impl Tap for serde_json::Value {}

#[test]
fn headers_and_trailing_bytes_are_refused_by_name() {
    let bytes = store::write(&Asset::Clip(edit::apply(&walk(), &Edit::Trim { first: 0, last: 1 }).unwrap()));
    let message = |b: &[u8]| store::parse(b).unwrap_err().to_string();
    assert!(message(b"MOCAPCF1").starts_with("byte 0: not a stored asset"), "{}", message(b"MOCAPCF1"));
    assert!(message(b"").starts_with("byte 0:"));
    assert!(message(&bytes[..10]).starts_with("byte 8: the file ends before its version"));
    let mut v3 = bytes.clone();
    v3[8] = 3;
    assert!(message(&v3).starts_with("byte 8: version 3"), "{}", message(&v3));
    let mut longer = bytes.clone();
    longer.extend_from_slice(b"xyz");
    assert_eq!(message(&longer), format!("byte {}: 3 bytes after the end of the stored asset", bytes.len()));
    // A character's last byte is its take index (1 of 2 takes).
    let (_, character) = small_stores().swap_remove(1);
    let mut take = character.clone();
    *take.last_mut().unwrap() = 5;
    assert_eq!(
        message(&take),
        "byte 12: the stored asset does not hold together: the motion is take 5 but the clip has 2 takes"
    );
    let cut = message(&bytes[..bytes.len() - 1]);
    assert!(cut.starts_with(&format!("byte {}:", bytes.len() - 1)) && cut.contains("cut or damaged"), "{cut}");
}

/// What a consumer relies on, checked on whatever a damaged store reads as, and
/// what a user does next: bounds, a sampled pose, a BVH write → read, and a
/// store write → read back equal.
fn holds_together(asset: &Asset, what: &str) {
    match asset {
        Asset::Clip(clip) => {
            let (skeleton, motion) = (clip.skeleton(), clip.motion());
            assert_eq!(motion.channel_count(), skeleton.channel_count(), "{what}");
            assert_eq!(motion.data().len(), motion.frame_count() * motion.channel_count(), "{what}");
            for (i, j) in skeleton.joints().iter().enumerate() {
                assert!(j.parent.is_none_or(|p| p < i) && j.rest_rotation.is_normalized(), "{what}: joint {i}");
            }
            if let Some(character) = &clip.character {
                for take in &character.takes {
                    assert_eq!(take.motion.channel_count(), skeleton.channel_count(), "{what}");
                }
                if let Some(look) = &character.look {
                    let (skin, n) = (&look.skin, look.skin.positions().len());
                    assert_eq!(skin.inverse_bind().len(), skeleton.len(), "{what}");
                    assert!(look.colors.len() == n && skin.normals().len() == n && skin.weights().len() == n, "{what}");
                    if let Some(s) = &look.surface {
                        let texels = s.image.width as usize * s.image.height as usize;
                        assert!(s.uvs.len() == n && s.tints.len() == n && s.image.pixels.len() == texels * 4, "{what}");
                        assert!(s.uvs.iter().flatten().flatten().all(|x| x.is_finite()), "{what}");
                    }
                    assert!(skin.indices().len() % 3 == 0 && skin.indices().iter().all(|&v| (v as usize) < n));
                    for (js, ws) in skin.joints().iter().zip(skin.weights()) {
                        assert!(js.iter().zip(ws).all(|(j, w)| *w == 0.0 || (*j as usize) < skeleton.len()), "{what}");
                    }
                }
            }
            assert!(clip.take_name().is_some() || clip.takes().is_empty(), "{what}");
            let _ = clip.bounds();
            let mut out = Vec::new();
            clip.sample_world_positions_into(clip.duration() * 0.37, mocap::Interpolation::Linear, &mut out);
            // BVH holds neither a clip without joints (`Clip::default()`) nor the
            // frames of one without channels (its reader keeps one).
            if !clip.skeleton().is_empty() {
                let text = mocap::formats::bvh::write(clip);
                let again = mocap::formats::bvh::parse(text.as_bytes()).unwrap_or_else(|e| panic!("{what}: BVH: {e}"));
                if clip.skeleton().channel_count() > 0 {
                    assert_eq!(again.frame_count(), clip.frame_count(), "{what}");
                }
            }
        }
        Asset::Model(model) => {
            let mesh = &model.mesh;
            let (n, frames) = (mesh.vertex_count(), mesh.frame_count());
            assert!(frames > 0 && mesh.positions().len() == n * frames && mesh.normals().len() == n * frames);
            assert!(mesh.tex_coords().len() == n && mesh.indices().iter().all(|&v| (v as usize) < n), "{what}");
            for t in [0.0, 0.37, 5.0] {
                let s = model.frames_at(t, mocap::Interpolation::Linear);
                assert!(s.frame0 < frames && s.frame1 < frames, "{what}");
                assert_eq!(mesh.frame_positions(s.frame1).len(), n, "{what}");
            }
            assert_eq!(mesh.source_frames().len(), frames);
            let _ = model.bounds();
            if let Some(skin) = &model.skin {
                assert_eq!(skin.image.pixels.len(), skin.image.width as usize * skin.image.height as usize * 4);
            }
        }
    }
    let again = store::parse(&store::write(asset)).unwrap_or_else(|e| panic!("{what}: stored again: {e}"));
    assert!(format!("{again:?}") == format!("{asset:?}"), "{what}: stored again, not the same");
}

/// A parse of damaged bytes: an asset that holds together, or a located message.
/// True when it read.
fn check(data: &[u8], what: &str) -> bool {
    let base = reset_peak();
    let result = store::parse(data);
    let peak = PEAK.with(Cell::get) - base;
    let bound = (4 << 20) + 64 * data.len() as isize;
    assert!(peak <= bound, "{what}: {peak} bytes allocated to read {} bytes", data.len());
    match result {
        Ok(asset) => {
            holds_together(&asset, what);
            true
        }
        Err(e) => {
            let message = e.to_string();
            assert!(message.starts_with("byte ") && message.len() > 12, "{what}: `{message}`");
            false
        }
    }
}

/// Small stored assets of each kind: a clip, a clip with a character (look, two
/// takes), a model with a skin.
fn small_stores() -> Vec<(&'static str, Vec<u8>)> {
    let short = edit::apply(&walk(), &Edit::Trim { first: 0, last: 2 }).unwrap();
    let triangle = |y: f32| vec![Vec3::new(0.0, y, 0.0), Vec3::new(10.0, y, 0.0), Vec3::new(0.0, 20.0 + y, 0.0)];
    let frames: Vec<(String, Vec<Vec3>)> =
        vec![("stand1".into(), triangle(0.0)), ("stand2".into(), triangle(2.0)), ("run1".into(), triangle(4.0))];
    let md2 = mocap::formats::md2::build(&frames, &[[0, 1, 2]]).unwrap();
    let md2 = mocap::formats::md2::parse(&mocap::formats::md2::write(&md2)).unwrap();
    let image = mocap::formats::image::Rgba { width: 3, height: 2, pixels: (0..24).collect() };
    let skin = mocap::model::mesh::Skin { name: "skin.pcx".into(), image: Arc::new(image) };
    let mut model = mocap::Model::new(mocap::MorphMesh::from_md2(&md2), Some(skin));
    assert!(model.set_animation(Some(1)));
    // A tiny character: a two-joint skeleton with a one-triangle look and two takes.
    let bvh = b"HIERARCHY\nROOT a\n{\n OFFSET 0 0 0\n CHANNELS 3 Xposition Yposition Zrotation\n JOINT b\n {\n  OFFSET 0 1 0\n  CHANNELS 1 Xrotation\n  End Site\n  {\n   OFFSET 0 1 0\n  }\n }\n}\nMOTION\nFrames: 2\nFrame Time: 0.1\n0 0 0 10\n1 0 5 20\n";
    let tiny = mocap::formats::bvh::parse(bvh).unwrap();
    let glb =
        mocap::formats::gltf::to_glb(&tiny, &mocap::formats::gltf::Options { name: "t".into(), body: false }).unwrap();
    let mut clip = mocap::formats::gltf::parse(&glb, &|_| None, None).unwrap();
    let bind = clip.bind_pose();
    let look_skin = mocap::runtime::skin::Skin::new(
        vec![Vec3::ZERO, Vec3::X, Vec3::Y],
        vec![Vec3::Z; 3],
        vec![0, 1, 2],
        vec![[0, 1, 0, 0], [1, 0, 0, 0], [2, 0, 0, 0]],
        vec![[0.5, 0.5, 0.0, 0.0], [1.0, 0.0, 0.0, 0.0], [3.0, 0.0, 0.0, 0.0]],
        &bind,
    )
    .unwrap();
    let mut character = (*clip.character.clone().unwrap()).clone();
    // A texture drawn per pixel on two of the three vertices.
    let image = mocap::model::character::TextureImage {
        width: 2,
        height: 1,
        pixels: vec![255, 0, 0, 255, 0, 0, 255, 255],
        wrap: [mocap::model::character::Wrap::Mirror, mocap::model::character::Wrap::Clamp],
    };
    let surface = mocap::model::character::Surface {
        image: Arc::new(image),
        uvs: vec![Some([0.25, 0.5]), Some([0.75, 0.5]), None],
        tints: vec![[255; 4], [200, 200, 200, 255], [255, 0, 0, 255]],
    };
    character.look = Some(mocap::model::character::Look {
        skin: look_skin,
        colors: vec![[255, 0, 0, 255]; 3],
        surface: Some(surface),
        morph: None,
    });
    let take = character.takes[0].clone();
    character.takes.push(mocap::model::character::Take { name: "again".into(), ..take });
    // The same with one blend shape moving the second vertex and weights in its
    // second take (version 2's section).
    let mut morphing = character.clone();
    if let Some(look) = morphing.look.as_mut() {
        look.morph = Some(mocap::model::character::Morph { targets: vec![vec![(1, [0.0, 0.1, 0.0])]], rest: vec![0.25] });
    }
    let frames = morphing.takes[1].motion.frame_count();
    morphing.takes[1].weights = (0..frames).map(|f| f as f32 / frames as f32).collect();

    clip = clip.with_character(Arc::new(character));
    assert!(clip.set_take("again"));
    clip.warnings.push(mocap::Warning { line: Some(3), message: "odd".into() });
    clip.metadata.push(("name".into(), "tiny".into()));
    let morphing = clip.clone().with_character(Arc::new(morphing));
    vec![
        ("clip", round_trip("short", &Asset::Clip(short))),
        ("character", round_trip("tiny character", &Asset::Clip(clip))),
        ("model", round_trip("tiny model", &Asset::Model(model))),
        ("morphing character", round_trip("tiny morphing character", &Asset::Clip(morphing))),
    ]
}

#[test]
fn every_truncation_fails_with_a_located_message() {
    for (name, bytes) in small_stores() {
        for end in 0..bytes.len() {
            assert!(!check(&bytes[..end], &format!("{name} cut at {end}")), "{name} cut at {end} read");
        }
        println!("{name}: {} bytes, every truncation refused", bytes.len());
    }
}

const EXTREME_WORDS: [u32; 7] = [0, 1, 0x7f, 0x80, 0x7fff_ffff, 0xffff_ffff, 0x8000_0000];

#[test]
fn thousands_of_damaged_stores_read_or_fail_cleanly() {
    let mut total = 0;
    for (name, bytes) in small_stores() {
        let mut rng = Rng(0x9e37_79b9_7f4a_7c15 ^ bytes.len() as u64);
        let (copies, mut read) = (1500, 0);
        for k in 0..copies {
            let mut copy = bytes.clone();
            let what = if k % 2 == 0 {
                for _ in 0..1 + rng.below(4) {
                    let at = rng.below(copy.len());
                    copy[at] ^= 1 << rng.below(8);
                }
                format!("{name} copy {k}: bits flipped")
            } else {
                // An extreme value over 1-5 bytes: a varint, a length, a float.
                let v = EXTREME_WORDS[rng.below(EXTREME_WORDS.len())];
                let width = 1 + rng.below(5);
                let at = 12 + rng.below(copy.len() - 12);
                let value = [v.to_le_bytes().as_slice(), &[0xff]].concat();
                for (i, b) in value.iter().take(width).enumerate() {
                    if let Some(c) = copy.get_mut(at + i) {
                        *c = *b;
                    }
                }
                format!("{name} copy {k}: {width} bytes at {at} set to {v:#x}")
            };
            read += usize::from(check(&copy, &what));
        }
        println!("{name}: {copies} damaged copies, {read} read, {} refused with a message", copies - read);
        assert!(read < copies && read > 0, "{name}: the damage must be both caught and survived");
        total += copies;
    }
    assert!(total >= 3000);
}

/// LEB128 of `v`, as postcard writes lengths.
fn varint(mut v: u64) -> Vec<u8> {
    let mut out = Vec::new();
    loop {
        let byte = (v & 0x7f) as u8;
        v >>= 7;
        if v == 0 {
            out.push(byte);
            return out;
        }
        out.push(byte | 0x80);
    }
}

#[test]
fn huge_length_prefixes_allocate_nothing_large() {
    // The clip variant, then a joint count of 2^60 (and of u32::MAX): the joints
    // are not there, and nothing is reserved for them.
    for count in [1u64 << 60, u64::from(u32::MAX), 1 << 20] {
        let mut bytes = MAGIC.to_vec();
        bytes.extend_from_slice(&1u32.to_le_bytes());
        bytes.push(0);
        bytes.extend(varint(count));
        bytes.extend_from_slice(&[3, b'a', b'b', b'c']);
        let start = Instant::now();
        assert!(!check(&bytes, &format!("{count} joints")));
        assert!(start.elapsed().as_secs_f64() < 1.0, "{count} joints: {:?}", start.elapsed());
    }
    // A model whose position count says 2^40 in a store of a few bytes, and a
    // stored clip whose first row length is replaced by a huge one.
    let mut model = MAGIC.to_vec();
    model.extend_from_slice(&1u32.to_le_bytes());
    model.push(1);
    model.extend(varint(1 << 40));
    model.extend_from_slice(&[0; 64]);
    assert!(!check(&model, "2^40 positions"));
    // Where the rows start: the same clip with no frames ends there, then its
    // empty rows, warnings, metadata, character and take index (a byte each).
    let short = edit::apply(&walk(), &Edit::Trim { first: 0, last: 1 }).unwrap();
    let clip = |frames: usize| {
        let (m, w) = (short.motion(), short.skeleton().channel_count());
        let motion = mocap::Motion::new(m.frame_time(), w, frames, m.data()[..frames * w].to_vec()).unwrap();
        Clip::new(short.skeleton().clone(), motion).unwrap()
    };
    let rows_at = store::write(&Asset::Clip(clip(0))).len() - 5;
    let stored = store::write(&Asset::Clip(clip(2)));
    let width = varint(short.skeleton().channel_count() as u64);
    assert_eq!(stored[rows_at], 2, "two rows");
    assert_eq!(stored[rows_at + 1..rows_at + 1 + width.len()], width[..], "of the skeleton's width");
    let mut huge = stored[..rows_at + 1].to_vec();
    huge.extend(varint(u64::MAX >> 1));
    huge.extend_from_slice(&stored[rows_at + 1 + width.len()..]);
    assert!(!check(&huge, "a huge row"));
}

#[test]
fn the_walk_is_small_and_quick_to_read() {
    let asset = Asset::Clip(walk());
    let bytes = store::write(&asset);
    let clip = asset.clip().unwrap();
    let values = clip.frame_count() * clip.skeleton().channel_count();
    // The motion's floats, a byte per row, and the skeleton's names and offsets.
    assert!(bytes.len() < values * 4 + clip.frame_count() * 2 + 4096, "{} bytes", bytes.len());
    let runs = 20;
    let start = Instant::now();
    for _ in 0..runs {
        assert_eq!(store::parse(&bytes).unwrap(), asset);
    }
    let each = start.elapsed() / runs;
    let text = Instant::now();
    let _ = mocap::formats::bvh::parse(WALK).unwrap();
    println!(
        "walk.bvh: {} frames × {} channels; BVH {} bytes, stored {} bytes; store read {each:?} (BVH read {:?})",
        clip.frame_count(),
        clip.skeleton().channel_count(),
        WALK.len(),
        bytes.len(),
        text.elapsed()
    );
}
