//! Every reader over thousands of deterministic damaged copies of real and
//! generated files, in every `cargo test`: truncations, byte flips, extreme header
//! fields (binary formats), numbers replaced by NaN, infinities, huge and negative
//! values and keywords damaged (text formats). Each copy goes in through the entry
//! the page and the CLI use (`mocap::load`, with the files it comes with), or the
//! reader's own `parse` for the rig and capture layouts. Every copy must read or
//! fail with a message that names a file of the set; none may panic, hang (a
//! watchdog fails the test when one copy takes over 30 s) or allocate more than a
//! bound set by its size (a counting allocator measures each copy's peak); what
//! reads must survive bounds, sampling and a BVH write → read round trip.
//!
//! The same checks, run without end on random inputs, are the fuzz targets in
//! `fuzz/` (see docs/testing.md).

mod common;

use mocap::formats::image::Rgba;
use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

/// Counts the bytes allocated now and the most since the last [`Counting::reset_peak`].
struct Counting;

static NOW: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);

// SAFETY: every call is passed on to the system allocator unchanged; only counters change.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let p = unsafe { System.alloc(layout) };
        if !p.is_null() {
            let now = NOW.fetch_add(layout.size(), Ordering::Relaxed) + layout.size();
            PEAK.fetch_max(now, Ordering::Relaxed);
        }
        p
    }
    unsafe fn dealloc(&self, p: *mut u8, layout: Layout) {
        unsafe { System.dealloc(p, layout) };
        NOW.fetch_sub(layout.size(), Ordering::Relaxed);
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

impl Counting {
    fn reset_peak() -> usize {
        let now = NOW.load(Ordering::Relaxed);
        PEAK.store(now, Ordering::Relaxed);
        now
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

/// How a damaged file is read.
#[derive(Clone, Copy)]
enum Reader {
    /// Through `mocap::load`, with the other files of its set intact.
    Load,
    /// `capture::Rig::from_json`.
    Rig,
    /// `capture::frames::parse`.
    Frames,
}

/// One file to damage, the files dropped with it, and how it is read.
struct Source {
    name: String,
    bytes: Vec<u8>,
    text: bool,
    with: Vec<(String, Vec<u8>)>,
    reader: Reader,
}

fn corpus(path: &str) -> Vec<u8> {
    let dir = common::corpus_dir().expect("the corpus (or MOCAP_SKIP_CORPUS=1, checked before)");
    std::fs::read(dir.join(path)).unwrap_or_else(|e| panic!("{path}: {e}"))
}

/// The first `frames` frames of an AMC (its header and the frame blocks before frame `frames + 1`).
fn amc_head(bytes: &[u8], frames: usize) -> Vec<u8> {
    let text = String::from_utf8_lossy(bytes);
    let cut = text.find(&format!("\n{}\n", frames + 1)).map_or(text.len(), |i| i + 1);
    text[..cut].as_bytes().to_vec()
}

fn picture() -> Rgba {
    let (width, height) = (24u32, 16u32);
    let pixels = (0..width * height).flat_map(|i| [(i * 7) as u8, (i / 3) as u8, 200, 255]).collect();
    Rgba { width, height, pixels }
}

fn encode(format: image::ImageFormat) -> Vec<u8> {
    let p = picture();
    let img = image::RgbaImage::from_raw(p.width, p.height, p.pixels).unwrap();
    let mut out = std::io::Cursor::new(Vec::new());
    if format == image::ImageFormat::Jpeg {
        image::DynamicImage::ImageRgba8(img).to_rgb8().write_to(&mut out, format).unwrap();
    } else {
        img.write_to(&mut out, format).unwrap();
    }
    out.into_inner()
}

fn sources() -> Vec<Source> {
    let load = |name: &str, bytes: Vec<u8>, text: bool, with: Vec<(String, Vec<u8>)>| Source {
        name: name.into(),
        bytes,
        text,
        with,
        reader: Reader::Load,
    };
    let weapon = || vec![("weapon.md2".to_owned(), corpus("md2/waste/weapon.md2"))];
    let asf = corpus("asf_amc/cmu/02.asf");
    let amc = amc_head(&corpus("asf_amc/cmu/02_01.amc"), 6);
    let walk = mocap::formats::bvh::parse(include_bytes!("../../../data/walk.bvh")).unwrap();
    let short = mocap::ops::edit::apply(&walk, &mocap::ops::edit::Edit::Trim { first: 0, last: 5 }).unwrap();
    let bva = mocap::formats::bva::write(&mocap::formats::bva::from_clip(&short).0).into_bytes();
    let glb = mocap::formats::gltf::to_glb(&short, &Default::default()).unwrap();
    // A rig and a capture of the corpus player, in their own layouts.
    let md2 = mocap::formats::md2::parse(&corpus("md2/waste/tris.md2")).unwrap();
    let frames = mocap::capture::model_frames(&md2);
    let rig = mocap::capture::Rig::fit(&frames[0], 0, None);
    let mut captured = mocap::capture::capture(&md2, &rig, &Default::default()).unwrap().frames();
    captured.frames.truncate(4);
    vec![
        load("test_simple.bvh", corpus("bvh/bvh_anim/test_simple.bvh"), true, vec![]),
        load("example.bvh", corpus("bvh/bvhio/example.bvh"), true, vec![]),
        load("02.asf", asf.clone(), true, vec![("02_01.amc".into(), amc.clone())]),
        load("simple_test.asf", corpus("asf_amc/handmade/simple_test.asf"), true, vec![]),
        load("02_01.amc", amc, true, vec![("02.asf".into(), asf)]),
        load("walk.bva", bva, true, vec![]),
        load("walk.glb", glb, false, vec![]),
        load(
            "weapon.md2",
            corpus("md2/waste/weapon.md2"),
            false,
            vec![("weapon.pcx".into(), corpus("md2/waste/weapon.PCX"))],
        ),
        load("weapon.pcx", corpus("md2/waste/weapon.PCX"), false, weapon()),
        load("weapon.bmp", corpus("md2/telias_dolphin/dolphin_f.bmp"), false, weapon()),
        load("weapon.png", encode(image::ImageFormat::Png), false, weapon()),
        load("weapon.jpg", encode(image::ImageFormat::Jpeg), false, weapon()),
        load("weapon.tga", encode(image::ImageFormat::Tga), false, weapon()),
        Source {
            name: "player.rig.json".into(),
            bytes: rig.to_json().into_bytes(),
            text: true,
            with: vec![],
            reader: Reader::Rig,
        },
        Source {
            name: "player.frames".into(),
            bytes: mocap::capture::frames::write(&captured),
            text: false,
            with: vec![],
            reader: Reader::Frames,
        },
    ]
}

const EXTREME_NUMBERS: [&str; 12] = [
    "nan",
    "NaN",
    "inf",
    "-inf",
    "1e39",
    "-1e39",
    "4294967296",
    "18446744073709551616",
    "-1",
    "0",
    "-0",
    "99999999999999999999999999",
];
const EXTREME_WORDS: [u32; 7] = [0, 1, 0x7fff_ffff, 0xffff_ffff, 0x8000_0000, 0x0001_0000, 0xffff];

/// Byte ranges of the number tokens of a text file.
fn numbers(text: &[u8]) -> Vec<(usize, usize)> {
    let mut out = Vec::new();
    let mut i = 0;
    while i < text.len() {
        let starts = text[i].is_ascii_digit() || (text[i] == b'-' && text.get(i + 1).is_some_and(u8::is_ascii_digit));
        let after_gap = i == 0 || !text[i - 1].is_ascii_alphanumeric();
        if starts && after_gap {
            let end = (i + 1..text.len())
                .find(|&k| !(text[k].is_ascii_digit() || matches!(text[k], b'.' | b'e' | b'E' | b'-' | b'+')))
                .unwrap_or(text.len());
            out.push((i, end));
            i = end;
        } else {
            i += 1;
        }
    }
    out
}

/// Copy `k` of `source`: one kind of damage chosen by `k`.
fn damage(source: &Source, numbers: &[(usize, usize)], k: usize, rng: &mut Rng) -> (String, Vec<u8>) {
    let b = &source.bytes;
    let mut copy = b.clone();
    let what = match k % 4 {
        0 => {
            let end = rng.below(b.len());
            copy.truncate(end);
            format!("cut at byte {end}")
        }
        1 => {
            for _ in 0..1 + rng.below(6) {
                let at = rng.below(copy.len());
                copy[at] ^= 1 << rng.below(8);
            }
            "bits flipped".to_owned()
        }
        _ if source.text && !numbers.is_empty() => {
            // One to three numbers replaced by extremes (rewritten from the back, so
            // the earlier ranges stay valid), or a keyword's letters changed.
            let mut picked: Vec<(usize, usize)> =
                (0..1 + rng.below(3)).map(|_| numbers[rng.below(numbers.len())]).collect();
            picked.sort_unstable();
            picked.dedup();
            for &(start, end) in picked.iter().rev() {
                copy.splice(start..end, EXTREME_NUMBERS[rng.below(EXTREME_NUMBERS.len())].bytes());
            }
            if k % 4 == 3 {
                let at = rng.below(copy.len());
                if copy[at].is_ascii_alphabetic() {
                    copy[at] = b'Q';
                }
            }
            format!("numbers at {picked:?} replaced")
        }
        _ => {
            // An extreme 16- or 32-bit value over a header field (the first 256 bytes).
            let span = copy.len().min(256).saturating_sub(4);
            let at = rng.below(span + 1) & !1;
            let v = EXTREME_WORDS[rng.below(EXTREME_WORDS.len())];
            let width = if rng.below(2) == 0 { 2 } else { 4 };
            if at + width <= copy.len() {
                copy[at..at + width].copy_from_slice(&v.to_le_bytes()[..width]);
            }
            format!("{width}-byte field at {at} set to {v:#x}")
        }
    };
    (what, copy)
}

/// Reads one damaged copy as `source` is read, checking what reads and what fails;
/// true when it read.
fn check(source: &Source, what: &str, data: &[u8]) -> bool {
    match source.reader {
        Reader::Load => {
            let mut inputs = vec![mocap::Input { name: &source.name, bytes: data }];
            inputs.extend(source.with.iter().map(|(name, bytes)| mocap::Input { name, bytes }));
            let mut read = true;
            for result in mocap::load(&inputs) {
                match result {
                    Ok(loaded) => exercise(&loaded.asset, what),
                    Err(e) => {
                        read = false;
                        let message = e.to_string();
                        let named = inputs.iter().any(|i| message.starts_with(&format!("{}:", i.name)));
                        assert!(named && message.len() > source.name.len() + 3, "{what}: `{message}` names no file");
                    }
                }
            }
            read
        }
        Reader::Rig => match mocap::capture::Rig::from_json(&String::from_utf8_lossy(data)) {
            Ok(_) => true,
            Err(e) => {
                assert!(e.to_string().len() > 6, "{what}: an empty message");
                false
            }
        },
        Reader::Frames => match mocap::capture::frames::parse(data) {
            Ok(frames) => {
                for f in 0..frames.bones.len() {
                    let _ = frames.frames.first().and_then(|frame| frame.to_y_up(f));
                }
                true
            }
            Err(e) => {
                assert!(e.to_string().starts_with("byte "), "{what}: {e}");
                false
            }
        },
    }
}

/// What a user does next with what was read: bounds, a sampled pose, a BVH round trip.
fn exercise(asset: &mocap::Asset, what: &str) {
    match asset {
        mocap::Asset::Clip(clip) => {
            let _ = clip.bounds();
            let mut out = Vec::new();
            clip.sample_world_positions_into(clip.duration() * 0.37, mocap::Interpolation::Linear, &mut out);
            let text = mocap::formats::bvh::write(clip);
            let again =
                mocap::formats::bvh::parse(text.as_bytes()).unwrap_or_else(|e| panic!("{what}: rewritten: {e}"));
            assert_eq!(again.frame_count(), clip.frame_count(), "{what}");
        }
        mocap::Asset::Model(model) => {
            let _ = model.mesh.height();
            let _ = model.skin.as_ref().map(|s| s.image.pixel(0, 0));
        }
    }
}

#[test]
fn every_reader_survives_thousands_of_damaged_files() {
    if common::corpus_dir().is_none() {
        return;
    }
    let progress = Arc::new(AtomicUsize::new(0));
    let current = Arc::new(Mutex::new(String::new()));
    let (worker_progress, worker_current) = (progress.clone(), current.clone());
    let worker = std::thread::spawn(move || {
        let mut total = 0;
        for source in sources() {
            let numbers = if source.text { numbers(&source.bytes) } else { Vec::new() };
            let mut rng = Rng(0x9e37_79b9_7f4a_7c15 ^ source.bytes.len() as u64);
            let copies = 240;
            let mut read = 0;
            for k in 0..copies {
                let (damage, data) = damage(&source, &numbers, k, &mut rng);
                let what = format!("{} copy {k} ({damage})", source.name);
                if let Ok(mut slot) = worker_current.lock() {
                    slot.clone_from(&what);
                }
                let base = Counting::reset_peak();
                read += usize::from(check(&source, &what, &data));
                let peak = PEAK.load(Ordering::Relaxed).saturating_sub(base);
                let set_bytes: usize = data.len() + source.with.iter().map(|(_, b)| b.len()).sum::<usize>();
                let bound = 64 << 20 | set_bytes * 64;
                assert!(peak <= bound, "{what}: {peak} bytes allocated for {set_bytes} bytes of files");
                worker_progress.fetch_add(1, Ordering::Relaxed);
            }
            println!("{}: {copies} copies, {read} read, {} refused with a message", source.name, copies - read);
            // Damage must sometimes be caught and sometimes be survivable: a reader
            // refusing or taking every copy is not being exercised.
            assert!(read < copies, "{}: every damaged copy read", source.name);
            total += copies;
        }
        total
    });
    let mut seen = 0;
    let mut since = Instant::now();
    while !worker.is_finished() {
        std::thread::sleep(Duration::from_millis(50));
        let now = progress.load(Ordering::Relaxed);
        if now != seen {
            (seen, since) = (now, Instant::now());
        } else if since.elapsed() > Duration::from_secs(30) {
            panic!("no progress for 30 s: a hang on {}", current.lock().map(|s| s.clone()).unwrap_or_default());
        }
    }
    let total = worker.join().unwrap_or_else(|e| std::panic::resume_unwind(e));
    println!("{total} damaged copies read or refused cleanly");
    assert!(total >= 3000, "{total} copies");
}
