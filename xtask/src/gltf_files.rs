//! The glTF files the browser suite checks (`tests/browser/gltf.mjs`): the core's
//! writer on the generated walk (`.glb` and `.gltf`, a Z-up copy, the skeleton
//! alone), a glTF character read and written again, a motion retargeted onto
//! it, that character wearing a striped texture, and on corpus clips (BVH and
//! Acclaim), with the joint positions we compute (metres, Y up) at a few frames
//! in `expected.json`; and a corpus MD2 model as morph targets, with its
//! vertices at one time in `models.json`. `cargo xtask gltf-files DIR` writes them.

use mocap::formats::gltf::{Options, to_glb, to_gltf};
use mocap::ops::edit::{Edit, apply};
use mocap::{Asset, Clip, Input};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// Corpus clips written as glTF: (files read together, name).
const CORPUS: &[(&[&str], &str)] = &[
    (&["bvh/bandai_namco/dataset-1_bow_active_001.bvh"], "bandai-bow"),
    (&["asf_amc/cmu/02.asf", "asf_amc/cmu/02_01.amc"], "cmu-02_01"),
];

/// Writes the files and `expected.json` into `dir`; returns `dir`.
pub fn write(dir: &Path, corpus: Option<&Path>) -> Result<PathBuf, String> {
    std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let walk = mocap::formats::bvh::parse(include_bytes!("../../data/walk.bvh")).map_err(|e| e.to_string())?;
    let lying = apply(&walk, &Edit::UpAxis { from: 1, negative: true }).map_err(|e| e.to_string())?;
    let mut clips: Vec<(String, Clip, bool, bool)> = vec![
        ("walk.glb".into(), walk.clone(), true, false),
        ("walk.gltf".into(), walk.clone(), true, true),
        ("walk-z-up.glb".into(), lying, true, false),
        ("walk-bones.glb".into(), walk, false, false),
    ];
    if let Some(corpus) = corpus {
        for (files, name) in CORPUS {
            let bytes: Vec<Vec<u8>> = files
                .iter()
                .map(|f| std::fs::read(corpus.join(f)).map_err(|e| format!("{f}: {e}")))
                .collect::<Result<_, _>>()?;
            let inputs: Vec<Input> = files.iter().zip(&bytes).map(|(name, bytes)| Input { name, bytes }).collect();
            let clip = mocap::load(&inputs)
                .into_iter()
                .find_map(|r| match r.map(|l| l.asset) {
                    Ok(Asset::Clip(c)) => Some(c),
                    _ => None,
                })
                .ok_or_else(|| format!("{name}: no clip read"))?;
            clips.push((format!("{name}.glb"), clip, true, false));
        }
    }
    // A glTF character read back and written again (its own mesh, COLOR_0), and
    // the walk retargeted onto it wearing its look.
    let character_glb = to_glb(&clips[0].1, &Options { name: "walk".into(), body: true }).map_err(|e| e.to_string())?;
    let none = |_: &str| None;
    let character = mocap::formats::gltf::parse(&character_glb, &none, None).map_err(|e| format!("walk.glb: {e}"))?;
    clips.push(("walk-again.glb".into(), character.clone(), true, false));
    let source = clips[2].1.clone();
    let (on, _) =
        mocap::ops::retarget::retarget(&source, &character, &Default::default()).map_err(|e| e.to_string())?;
    clips.push(("walk-z-up-on-walk.glb".into(), on, true, false));
    clips.push(("walk-textured.glb".into(), textured(&character)?, true, false));
    clips.push(("walk-breathing.glb".into(), breathing(&character)?, true, false));
    let mut entries = Vec::new();
    for (file, clip, body, text) in &clips {
        let options = Options { name: file.split('.').next().unwrap_or("motion").to_owned(), body: *body };
        let bytes = if *text { to_gltf(clip, &options).map(String::into_bytes) } else { to_glb(clip, &options) }
            .map_err(|e| format!("{file}: {e}"))?;
        std::fs::write(dir.join(file), bytes).map_err(|e| format!("{file}: {e}"))?;
        entries.push(expected(file, clip, *body));
    }
    std::fs::write(dir.join("expected.json"), format!("[{}]", entries.join(",\n"))).map_err(|e| e.to_string())?;
    let models = match corpus {
        Some(corpus) => vec![model_file(dir, corpus, MODEL)?],
        None => Vec::new(),
    };
    std::fs::write(dir.join("models.json"), format!("[{}]", models.join(",\n"))).map_err(|e| e.to_string())?;
    Ok(dir.to_path_buf())
}

/// The corpus model written as glTF (model, skin, file written, animation and
/// time checked).
const MODEL: (&str, &str, &str, &str, f64) = ("md2/waste/tris.md2", "md2/waste/waste.pcx", "waste.glb", "run", 0.25);

/// Writes an MD2 model as `.glb` (morph targets, an animation per named
/// animation, its skin); its `models.json` entry: every vertex in metres at the
/// time checked (between two frames), as our sampling puts it.
fn model_file(
    dir: &Path,
    corpus: &Path,
    (md2, skin, file, animation, time): (&str, &str, &str, &str, f64),
) -> Result<String, String> {
    let read = |f: &str| std::fs::read(corpus.join(f)).map_err(|e| format!("{f}: {e}"));
    let (a, b) = (read(md2)?, read(skin)?);
    let inputs = [Input { name: md2, bytes: &a }, Input { name: skin, bytes: &b }];
    let mut model = match mocap::load(&inputs).into_iter().next() {
        Some(Ok(loaded)) => match loaded.asset {
            Asset::Model(m) => m,
            Asset::Clip(_) => return Err(format!("{md2}: not a model")),
        },
        _ => return Err(format!("{md2}: not read")),
    };
    let bytes = mocap::formats::gltf::model_to_glb(&model, "waste").map_err(|e| format!("{file}: {e}"))?;
    std::fs::write(dir.join(file), bytes).map_err(|e| format!("{file}: {e}"))?;
    if !model.set_animation_by_name(animation) {
        return Err(format!("{md2}: no animation {animation}"));
    }
    let sample = model.frames_at(time, mocap::Interpolation::Linear);
    let m = model.mesh.units().meters_per_unit();
    let (p, q) = (model.mesh.frame_positions(sample.frame0), model.mesh.frame_positions(sample.frame1));
    let mut vertices = String::new();
    for (i, (a, b)) in p.iter().zip(q).enumerate() {
        let at = |k: usize| (a[k] + (b[k] - a[k]) * sample.blend) * m;
        let _ = write!(vertices, "{}[{},{},{}]", if i > 0 { "," } else { "" }, at(0), at(1), at(2));
    }
    Ok(format!(
        "{{\"file\":{file:?},\"animation\":{animation:?},\"time\":{time},\"tolerance\":{},\"vertices\":[{vertices}]}}",
        1e-4 * model.mesh.height() * m
    ))
}

/// Stripes of the textured character's image, top to bottom (sRGB).
pub const STRIPES: [[u8; 4]; 2] = [[240, 140, 30, 255], [30, 170, 170, 255]];

/// `character` (a glTF character read back) wearing a texture drawn per pixel:
/// a 64×64 image of eight-texel stripes alternating [`STRIPES`], wrapped around
/// the body (u by the angle about the vertical, v down from the top).
fn textured(character: &Clip) -> Result<Clip, String> {
    use mocap::model::character::{Surface, TextureImage, Wrap};
    let mut c = (**character.character.as_ref().ok_or("walk-again.glb: no character")?).clone();
    let look = c.look.as_mut().ok_or("walk-again.glb: no look")?;
    let positions = look.skin.positions();
    let (lo, hi) = positions.iter().fold((f32::INFINITY, f32::NEG_INFINITY), |(a, b), p| (a.min(p.y), b.max(p.y)));
    let uvs: Vec<Option<[f32; 2]>> = positions
        .iter()
        .map(|p| Some([p.x.atan2(p.z) / std::f32::consts::TAU + 0.5, 1.0 - (p.y - lo) / (hi - lo).max(1e-6)]))
        .collect();
    let stripe = |v: f32| STRIPES[((v.clamp(0.0, 0.999) * 64.0) as usize / 8) % 2];
    let pixels: Vec<u8> = (0..64).flat_map(|y| std::iter::repeat_n(stripe(y as f32 / 64.0), 64)).flatten().collect();
    // Without the texture (a writer or renderer that has none), the stripe at each vertex.
    look.colors = uvs.iter().map(|uv| stripe(uv.map_or(0.0, |[_, v]| v))).collect();
    let image = TextureImage { width: 64, height: 64, pixels, wrap: [Wrap::Repeat; 2] };
    let tints = vec![[255; 4]; uvs.len()];
    look.surface = Some(Surface { image: std::sync::Arc::new(image), uvs, tints });
    Ok(character.clone().with_character(std::sync::Arc::new(c)))
}

/// `character` (a glTF character read back) with one morph target, `swell`,
/// lifting the vertices of its top tenth by a tenth of its height, and weights
/// from 0 at the first frame to 1 at the last in its take (validated and loaded
/// by three.js with the other files).
fn breathing(character: &Clip) -> Result<Clip, String> {
    use mocap::model::character::Morph;
    let mut c = (**character.character.as_ref().ok_or("walk-again.glb: no character")?).clone();
    let look = c.look.as_mut().ok_or("walk-again.glb: no look")?;
    let positions = look.skin.positions();
    let (lo, hi) = positions.iter().fold((f32::INFINITY, f32::NEG_INFINITY), |(a, b), p| (a.min(p.y), b.max(p.y)));
    let lift = 0.1 * (hi - lo);
    let moved: Vec<(u32, [f32; 3])> = (positions.iter().enumerate())
        .filter(|(_, p)| p.y > hi - lift)
        .map(|(v, _)| (v as u32, [0.0, lift, 0.0]))
        .collect();
    look.morph = Some(Morph { targets: vec![moved], rest: vec![0.0] });
    let take = c.takes.first_mut().ok_or("walk-again.glb: no take")?;
    let frames = take.motion.frame_count();
    take.weights = (0..frames).map(|f| f as f32 / (frames.max(2) - 1) as f32).collect();
    Ok(character.clone().with_character(std::sync::Arc::new(c)))
}

/// One file's entry: its joints' positions at the first, middle and last frames.
fn expected(file: &str, clip: &Clip, body: bool) -> String {
    let (up, m) = (clip.up_axis().rotation(), clip.units().meters_per_unit());
    let last = clip.frame_count().saturating_sub(1);
    let mut frames = Vec::new();
    for f in [0, last / 2, last] {
        let mut positions = String::new();
        for (i, p) in clip.world_positions(f).into_iter().enumerate() {
            let p = up * p * m;
            let _ = write!(positions, "{}[{},{},{}]", if i > 0 { "," } else { "" }, p.x, p.y, p.z);
        }
        frames.push(format!("{{\"time\":{},\"positions\":[{positions}]}}", clip.timeline().time_of(f)));
    }
    let tolerance = (1e-4 * clip.pose_height() * m).max(1e-4);
    format!(
        "{{\"file\":{file:?},\"joints\":{},\"body\":{body},\"animated\":{},\"tolerance\":{tolerance},\"frames\":[{}]}}",
        clip.skeleton().len(),
        clip.frame_count() > 0,
        frames.join(",")
    )
}

/// The GLB `bench-web` drops: CMU's take 01_01 with its rows repeated to 5,000
/// frames, written by our writer (about 5 MB), into `dir`.
pub fn bench_glb(corpus: &Path, dir: &Path) -> Result<PathBuf, String> {
    let src = std::fs::read(corpus.join("bvh/assimp_cmu/01_01.bvh")).map_err(|e| format!("01_01.bvh: {e}"))?;
    let text = String::from_utf8_lossy(&src);
    let start = text.find("Frame Time").ok_or("01_01.bvh: no Frame Time line")?;
    let rows_at = start + text[start..].find('\n').ok_or("01_01.bvh: short")? + 1;
    let rows: Vec<&str> = text[rows_at..].lines().filter(|l| !l.trim().is_empty()).collect();
    let frames = 5_000;
    let mut bvh = text[..rows_at].replace(&format!("Frames: {}", rows.len()), &format!("Frames: {frames}"));
    for i in 0..frames {
        bvh.push_str(rows.get(i % rows.len().max(1)).copied().unwrap_or(""));
        bvh.push('\n');
    }
    let clip = mocap::formats::bvh::parse(bvh.as_bytes()).map_err(|e| e.to_string())?;
    let glb = to_glb(&clip, &Options { name: "01_01".into(), body: true }).map_err(|e| e.to_string())?;
    std::fs::create_dir_all(dir).map_err(|e| e.to_string())?;
    let path = dir.join("01_01x5000.glb");
    std::fs::write(&path, glb).map_err(|e| format!("{}: {e}", path.display()))?;
    Ok(path)
}
