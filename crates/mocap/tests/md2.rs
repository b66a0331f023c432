//! The Quake 2 MD2 reader: hand-built files (valid and every malformed case), the
//! corpus, and robustness (no truncation or byte change panics).
//!
//! Tests live in `mod md2` so that `cargo test -p mocap md2` selects them.

mod common;

mod md2 {
    use mocap::formats::md2::{self, Md2, NORMALS};
    use proptest::prelude::*;
    use std::time::{Duration, Instant};

    // Header field offsets.
    const VERSION: usize = 4;
    const FRAMESIZE: usize = 16;
    const NUM_SKINS: usize = 20;
    const NUM_XYZ: usize = 24;
    const NUM_ST: usize = 28;
    const NUM_FRAMES: usize = 40;
    const OFS_SKINS: usize = 44;
    const OFS_ST: usize = 48;
    const OFS_TRIS: usize = 52;
    const OFS_FRAMES: usize = 56;
    const OFS_GLCMDS: usize = 60;
    const OFS_END: usize = 64;

    // Where the sections of `tiny()` are.
    const AT_SKINS: usize = 68;
    const AT_ST: usize = AT_SKINS + 64;
    const AT_TRIS: usize = AT_ST + 3 * 4;
    const AT_FRAMES: usize = AT_TRIS + 12;
    const FRAME_SIZE: usize = 40 + 3 * 4;
    const AT_GLCMDS: usize = AT_FRAMES + 2 * FRAME_SIZE;
    const LEN: usize = AT_GLCMDS + 3 * 4;

    fn set_i32(bytes: &mut [u8], at: usize, value: i32) {
        bytes[at..at + 4].copy_from_slice(&value.to_le_bytes());
    }

    /// A valid model: 1 skin, 3 vertices, 3 texture coordinates, 1 triangle, frames
    /// `stand01` and `stand02`, 3 GL command words.
    fn tiny() -> Vec<u8> {
        let mut b = Vec::new();
        b.extend(b"IDP2");
        let header = [8, 32, 16, FRAME_SIZE, 1, 3, 3, 1, 3, 2, AT_SKINS, AT_ST, AT_TRIS, AT_FRAMES, AT_GLCMDS, LEN];
        for v in header {
            b.extend((v as i32).to_le_bytes());
        }
        let mut skin = [0u8; 64];
        skin[..14].copy_from_slice(b"models/x/a.pcx");
        b.extend(skin);
        for st in [[0i16, 0], [31, 0], [-1, 15]] {
            b.extend(st[0].to_le_bytes());
            b.extend(st[1].to_le_bytes());
        }
        for i in [0u16, 1, 2, 0, 1, 2] {
            b.extend(i.to_le_bytes());
        }
        let frames: [([f32; 3], [f32; 3], &[u8], [[u8; 4]; 3]); 2] = [
            ([1.0, 1.0, 1.0], [0.0, 0.0, 0.0], b"stand01", [[0, 0, 0, 5], [10, 0, 0, 5], [0, 10, 20, 5]]),
            ([2.0, 1.0, 0.5], [1.0, 2.0, 3.0], b"stand02", [[3, 4, 5, 0], [255, 0, 7, 161], [1, 2, 3, 84]]),
        ];
        for (scale, translate, name, vertices) in frames {
            for c in scale.iter().chain(&translate) {
                b.extend(c.to_le_bytes());
            }
            let mut n = [0u8; 16];
            n[..name.len()].copy_from_slice(name);
            b.extend(n);
            b.extend(vertices.as_flattened());
        }
        for w in [1i32, 2, 0] {
            b.extend(w.to_le_bytes());
        }
        assert_eq!(b.len(), LEN);
        b
    }

    fn parse_err(bytes: &[u8]) -> String {
        match md2::parse(bytes) {
            Ok(_) => panic!("parsed a malformed file"),
            Err(e) => {
                assert_eq!((e.line, e.column), (0, 0), "binary errors carry the offset in the message");
                let offset: Option<u32> =
                    e.message.strip_prefix("byte ").and_then(|m| m.split(':').next()).and_then(|n| n.parse().ok());
                assert!(offset.is_some(), "{e}");
                e.message
            }
        }
    }

    fn assert_err(bytes: &[u8], starts: &str, contains: &[&str]) {
        let message = parse_err(bytes);
        assert!(message.starts_with(starts), "{message:?} should start with {starts:?}");
        for c in contains {
            assert!(message.contains(c), "{message:?} should contain {c:?}");
        }
    }

    #[test]
    fn tiny_file_reads() {
        let bytes = tiny();
        assert!(md2::sniff(&bytes));
        let m = md2::parse(&bytes).unwrap();
        assert_eq!((m.skin_width, m.skin_height), (32, 16));
        assert_eq!(m.skins, ["models/x/a.pcx"]);
        assert_eq!(m.tex_coords, [[0, 0], [31, 0], [-1, 15]]);
        assert_eq!(m.triangles.len(), 1);
        assert_eq!(m.triangles[0].vertices, [0, 1, 2]);
        assert_eq!(m.triangles[0].tex_coords, [0, 1, 2]);
        assert_eq!(m.vertex_count, 3);
        assert_eq!(m.frames.len(), 2);
        assert_eq!(m.frames[1].name, "stand02");
        assert_eq!(m.frames[1].vertices[1], [255, 0, 7, 161]);
        assert_eq!(m.animations, [md2::Animation { name: "stand".into(), first: 0, last: 1 }]);
        assert_eq!(m.animation_of(1).unwrap().name, "stand");

        let mut p = Vec::new();
        m.frame_positions(0, &mut p);
        // Quake (x, y, z) → Y-up (x, z, -y).
        assert_eq!(p, [[0.0, 0.0, 0.0], [10.0, 0.0, 0.0], [0.0, 20.0, -10.0]]);
        m.frame_positions(1, &mut p);
        assert_eq!(p[0], [1.0 + 2.0 * 3.0, 3.0 + 0.5 * 5.0, -(2.0 + 4.0)]);
        assert_eq!(m.height(), 20.0);

        let mut n = Vec::new();
        m.frame_normals(0, &mut n);
        assert_eq!(n, [[0.0, 1.0, 0.0]; 3]);
        m.frame_normals(1, &mut n);
        assert_eq!(n[1], md2::to_y_up(NORMALS[161]));
    }

    #[test]
    fn interpolation_at_half_is_the_mean() {
        let m = md2::parse(&tiny()).unwrap();
        let (mut a, mut b, mut mid) = (Vec::new(), Vec::new(), Vec::new());
        m.frame_positions(0, &mut a);
        m.frame_positions(1, &mut b);
        m.interpolated_positions(0, 1, 0.5, &mut mid);
        assert_eq!(mid.len(), 3);
        for v in 0..3 {
            for k in 0..3 {
                assert!((mid[v][k] - (a[v][k] + b[v][k]) / 2.0).abs() < 1e-5, "{v} {k}: {mid:?}");
            }
        }
        m.interpolated_positions(0, 1, 0.0, &mut mid);
        assert_eq!(mid, a);
        m.interpolated_positions(0, 1, 1.0, &mut mid);
        assert_eq!(mid, b);
    }

    #[test]
    fn wrong_ident_and_version() {
        let mut b = tiny();
        b[3] = b'3';
        assert!(!md2::sniff(&b));
        assert_err(&b, "byte 0: not an MD2 file", &["IDP3"]);
        assert_err(b"", "byte 0: not an MD2 file", &[]);
        let mut b = tiny();
        set_i32(&mut b, VERSION, 7);
        assert_err(&b, "byte 4: MD2 version 7, expected 8", &[]);
    }

    #[test]
    fn every_offset_past_the_end() {
        for (field, name) in [
            (OFS_SKINS, "ofs_skins"),
            (OFS_ST, "ofs_st"),
            (OFS_TRIS, "ofs_tris"),
            (OFS_FRAMES, "ofs_frames"),
            (OFS_GLCMDS, "ofs_glcmds"),
        ] {
            for ofs in [LEN as i32 - 1, 9999, i32::MAX] {
                let mut b = tiny();
                set_i32(&mut b, field, ofs);
                assert_err(
                    &b,
                    &format!("byte {field}: {name} {ofs} + "),
                    &["runs past the end of the file (272 bytes)"],
                );
            }
            let mut b = tiny();
            set_i32(&mut b, field, -4);
            assert_err(&b, &format!("byte {field}: {name} is -4, which is negative"), &[]);
        }
        let mut b = tiny();
        set_i32(&mut b, OFS_END, LEN as i32 + 1);
        assert_err(&b, "byte 64: ofs_end is 273 but the file has only 272 bytes", &["truncated"]);
    }

    #[test]
    fn truncated_files() {
        let b = tiny();
        assert_err(&b[..40], "byte 40: the file ends inside the 68-byte MD2 header", &[]);
        assert_err(&b[..LEN - 1], "byte 64: ofs_end is 272", &["truncated"]);
        // Even when ofs_end is made to agree, the sections run past the end.
        let mut short = b[..LEN - 4].to_vec();
        set_i32(&mut short, OFS_END, (LEN - 4) as i32);
        assert_err(&short, "byte 60: ofs_glcmds", &["runs past the end of the file (268 bytes)"]);
    }

    #[test]
    fn framesize_must_match_the_vertex_count() {
        let mut b = tiny();
        set_i32(&mut b, FRAMESIZE, FRAME_SIZE as i32 + 4);
        assert_err(&b, "byte 16: framesize is 56 bytes but 3 vertices need 52", &[]);
        let mut b = tiny();
        set_i32(&mut b, NUM_XYZ, 4);
        assert_err(&b, "byte 16: framesize is 52 bytes but 4 vertices need 56", &[]);
        let mut b = tiny();
        set_i32(&mut b, NUM_XYZ, i32::MAX);
        assert_err(&b, "byte 16:", &["framesize"]);
    }

    #[test]
    fn zero_vertices_or_frames() {
        let mut b = tiny();
        set_i32(&mut b, NUM_XYZ, 0);
        assert_err(&b, "byte 24: num_xyz is 0", &["zero vertices"]);
        let mut b = tiny();
        set_i32(&mut b, NUM_FRAMES, 0);
        assert_err(&b, "byte 40: num_frames is 0", &["no frames"]);
    }

    #[test]
    fn huge_counts_fail_fast_without_allocating() {
        // A 10 KB file that claims a million frames (and a consistent framesize).
        let mut b = tiny();
        b.resize(10_000, 0);
        set_i32(&mut b, OFS_END, 10_000);
        let start = Instant::now();
        for (field, value) in
            [(NUM_FRAMES, 1_000_000), (NUM_FRAMES, i32::MAX), (NUM_SKINS, i32::MAX), (NUM_ST, i32::MAX)]
        {
            let mut b = b.clone();
            set_i32(&mut b, field, value);
            assert_err(&b, "byte ", &["runs past the end of the file (10000 bytes)"]);
        }
        let mut huge = b.clone();
        set_i32(&mut huge, NUM_XYZ, 1 << 28);
        set_i32(&mut huge, FRAMESIZE, 40 + 4 * (1 << 28));
        set_i32(&mut huge, NUM_FRAMES, 1 << 30);
        assert_err(&huge, "byte 56: ofs_frames", &["runs past the end"]);
        assert!(start.elapsed() < Duration::from_secs(1), "{:?}", start.elapsed());
        // The padding itself is fine.
        assert_eq!(md2::parse(&b).unwrap().frames.len(), 2);
    }

    #[test]
    fn triangle_indices_in_range() {
        let mut b = tiny();
        b[AT_TRIS + 2..AT_TRIS + 4].copy_from_slice(&3u16.to_le_bytes());
        assert_err(&b, &format!("byte {}: triangle 0 uses vertex 3 but the model has 3 vertices", AT_TRIS + 2), &[]);
        let mut b = tiny();
        b[AT_TRIS + 10..AT_TRIS + 12].copy_from_slice(&u16::MAX.to_le_bytes());
        assert_err(
            &b,
            &format!(
                "byte {}: triangle 0 uses texture coordinate 65535 but the model has 3 texture coordinates",
                AT_TRIS + 10
            ),
            &[],
        );
    }

    #[test]
    fn normal_index_past_the_table() {
        let mut b = tiny();
        let at = AT_FRAMES + FRAME_SIZE + 40 + 4 * 2 + 3;
        b[at] = 162;
        assert_err(&b, &format!("byte {at}: frame 1 (\"stand02\") vertex 2 has normal index 162"), &["161"]);
    }

    #[test]
    fn names_need_a_nul() {
        let mut b = tiny();
        b[AT_SKINS..AT_SKINS + 64].fill(b'a');
        assert_err(&b, "byte 68: skin 0's name has no NUL terminator within its 64 bytes", &[]);
        let mut b = tiny();
        let at = AT_FRAMES + FRAME_SIZE + 24;
        b[at..at + 16].fill(b'x');
        assert_err(&b, &format!("byte {at}: frame 1's name has no NUL terminator within its 16 bytes"), &[]);
    }

    #[test]
    fn non_finite_frame_transforms() {
        let mut b = tiny();
        b[AT_FRAMES + 4..AT_FRAMES + 8].copy_from_slice(&f32::NAN.to_le_bytes());
        assert_err(&b, &format!("byte {AT_FRAMES}: frame 0 (\"stand01\") has a non-finite scale"), &[]);
        let mut b = tiny();
        b[AT_FRAMES + 12..AT_FRAMES + 16].copy_from_slice(&f32::INFINITY.to_le_bytes());
        assert_err(&b, &format!("byte {}: frame 0 (\"stand01\") has a non-finite translate", AT_FRAMES + 12), &[]);
    }

    /// Every truncation, and every value of every byte, gives a model or an error.
    #[test]
    fn no_truncation_or_byte_change_panics() {
        let b = tiny();
        for n in 0..b.len() {
            assert!(md2::parse(&b[..n]).is_err(), "truncated to {n}");
        }
        let mut m = b.clone();
        for at in 0..b.len() {
            for v in 0..=255u8 {
                m[at] = v;
                if let Ok(model) = md2::parse(&m) {
                    check_invariants(&model);
                }
            }
            m[at] = b[at];
        }
    }

    fn check_invariants(m: &Md2) {
        assert!(m.vertex_count > 0 && !m.frames.is_empty() && !m.animations.is_empty());
        for f in &m.frames {
            assert_eq!(f.vertices.len(), m.vertex_count);
            assert!(f.vertices.iter().all(|v| usize::from(v[3]) < NORMALS.len()));
        }
        for t in &m.triangles {
            assert!(t.vertices.iter().all(|&v| usize::from(v) < m.vertex_count));
            assert!(t.tex_coords.iter().all(|&s| usize::from(s) < m.tex_coords.len()));
        }
        let mut out = Vec::new();
        for f in 0..m.frames.len() {
            m.frame_positions(f, &mut out);
            m.frame_normals(f, &mut out);
        }
        let _ = m.height();
    }

    proptest! {
        // No regression file: this is a test binary, not a crate with a lib.rs beside it.
        #![proptest_config(ProptestConfig { cases: 512, failure_persistence: None, ..ProptestConfig::default() })]

        #[test]
        fn md2_random_edits_never_panic(edits in proptest::collection::vec((0..LEN, any::<u8>()), 1..8), cut in 0..=LEN) {
            let mut b = tiny();
            for (at, v) in edits {
                b[at] = v;
            }
            b.truncate(cut);
            if let Ok(m) = md2::parse(&b) {
                check_invariants(&m);
            }
        }

        #[test]
        fn md2_random_bytes_never_panic(tail in proptest::collection::vec(any::<u8>(), 0..400)) {
            let mut b = b"IDP2\x08\0\0\0".to_vec();
            b.extend(tail);
            let _ = md2::parse(&b);
        }
    }

    // --- The corpus -------------------------------------------------------------

    fn corpus(path: &str) -> Option<Vec<u8>> {
        let dir = crate::common::corpus_dir()?;
        let path = dir.join("md2").join(path);
        Some(std::fs::read(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display())))
    }

    fn read_corpus(path: &str) -> Option<Md2> {
        let bytes = corpus(path)?;
        assert!(md2::sniff(&bytes), "{path}");
        let m = md2::parse(&bytes).unwrap_or_else(|e| panic!("{path}: {e}"));
        check_invariants(&m);
        let mut out = Vec::new();
        for f in 0..m.frames.len() {
            m.frame_positions(f, &mut out);
            assert!(out.iter().flatten().all(|c| c.is_finite()), "{path} frame {f}");
        }
        let names: Vec<_> = m.animations.iter().map(|a| format!("{} {}..={}", a.name, a.first, a.last)).collect();
        println!("{path}: height {} animations {}", m.height(), names.join(", "));
        // The animations cover every frame, in order.
        assert_eq!(m.animations[0].first, 0);
        assert_eq!(m.animations.last().unwrap().last, m.frames.len() - 1);
        assert!(m.animations.windows(2).all(|w| w[1].first == w[0].last + 1));
        Some(m)
    }

    fn animation_names(m: &Md2) -> Vec<&str> {
        m.animations.iter().map(|a| a.name.as_str()).collect()
    }

    #[test]
    fn corpus_faerie() {
        let Some(m) = read_corpus("irrlicht_faerie/faerie.md2") else { return };
        assert_eq!((m.skin_width, m.skin_height), (220, 193));
        assert!(m.skins.is_empty());
        assert_eq!((m.vertex_count, m.tex_coords.len(), m.triangles.len(), m.frames.len()), (366, 487, 654, 198));
        assert_eq!((m.frames[0].name.as_str(), m.frames[1].name.as_str()), ("stand01", "stand02"));
        assert_eq!(m.animations[0], md2::Animation { name: "stand".into(), first: 0, last: 39 });
        assert_eq!(m.animations[1], md2::Animation { name: "run".into(), first: 40, last: 45 });
        let names = animation_names(&m);
        for name in ["attack", "pain1", "pain2", "pain3", "jump", "flip", "crattak", "death1", "death3"] {
            assert!(names.contains(&name), "{name} in {names:?}");
        }
        assert_eq!(names.len(), 20, "{names:?}");
    }

    #[test]
    fn corpus_dolphin() {
        let Some(m) = read_corpus("telias_dolphin/dolphin.md2") else { return };
        assert_eq!((m.skin_width, m.skin_height), (256, 256));
        assert_eq!(m.skins, ["settings/elias1/desktop/frames/dolphin_f.bmp"]);
        assert_eq!((m.vertex_count, m.tex_coords.len(), m.triangles.len(), m.frames.len()), (324, 293, 500, 59));
        assert_eq!((m.frames[0].name.as_str(), m.frames[1].name.as_str()), ("glide1", "glide2"));
        assert_eq!(
            m.animations,
            [
                md2::Animation { name: "glide".into(), first: 0, last: 13 },
                md2::Animation { name: "jump".into(), first: 14, last: 58 },
            ]
        );
    }

    #[test]
    fn corpus_quake_player() {
        let Some(m) = read_corpus("waste/tris.md2") else { return };
        assert_eq!(m.frames.len(), 198);
        assert_eq!(m.frames[0].name, "stand01");
        assert_eq!(animation_names(&m)[..4], ["stand", "run", "attack", "pain1"]);
        let h = m.height();
        assert!((45.0..70.0).contains(&h), "a Quake player is about 56 units tall, got {h}");
        // Y-up: the head is above the feet, and the player stands around the origin.
        let mut p = Vec::new();
        m.frame_positions(0, &mut p);
        let (lo, hi) = p.iter().fold((f32::MAX, f32::MIN), |(lo, hi), v| (lo.min(v[1]), hi.max(v[1])));
        assert!((hi - lo - h).abs() < 1e-3 && lo < 0.0 && hi > 0.0, "{lo}..{hi}");
    }

    #[test]
    fn corpus_quake_weapon() {
        let Some(m) = read_corpus("waste/weapon.md2") else { return };
        assert_eq!(m.frames.len(), 173);
        assert_eq!(m.frames[0].name, "stand01");
        assert_eq!(m.animations.last().unwrap().name, "crpain");
        assert_eq!(m.skins.len(), 1);
    }

    #[test]
    fn corpus_zero_vertices_is_an_error() {
        let Some(bytes) = corpus("assimp_malformed/malformed_zero_numvertices.md2") else { return };
        let e = md2::parse(&bytes).unwrap_err();
        assert!(e.message.contains("zero vertices"), "{e}");
        assert!(e.message.starts_with("byte 24:"), "{e}");
    }
}

#[test]
fn quake_pcx_skins_decode_to_the_known_pixels() {
    let Some(dir) = common::corpus_dir() else { return };
    // Reference values from an independent decoder (Pillow 11).
    let skin = mocap::formats::image::pcx::decode(&std::fs::read(dir.join("md2/waste/waste.pcx")).unwrap()).unwrap();
    assert_eq!((skin.width, skin.height), (308, 175), "the size tris.md2's header gives");
    assert_eq!(skin.pixel(0, 0), Some([0, 0, 0, 255]));
    assert_eq!(skin.pixel(10, 20), Some([167, 139, 119, 255]));
    assert_eq!(skin.pixel(100, 50), Some([107, 107, 107, 255]));
    assert_eq!(skin.pixel(307, 174), Some([0, 0, 0, 255]));
    let weapon = mocap::formats::image::pcx::decode(&std::fs::read(dir.join("md2/waste/weapon.PCX")).unwrap()).unwrap();
    assert_eq!((weapon.width, weapon.height), (136, 59));
    assert_eq!(weapon.pixel(0, 0), Some([15, 15, 15, 255]));
    assert_eq!(weapon.pixel(10, 20), Some([0, 0, 0, 255]));
    assert_eq!(weapon.pixel(100, 50), Some([15, 15, 15, 255]));
    assert_eq!(weapon.pixel(135, 58), Some([23, 23, 23, 255]));
}

/// Loads corpus files (under `md2/`) as one dropped set.
fn load_set(paths: &[&str]) -> Option<Vec<Result<mocap::Loaded, mocap::LoadError>>> {
    let dir = common::corpus_dir()?.join("md2");
    let bytes: Vec<(String, Vec<u8>)> =
        paths.iter().map(|p| (p.to_string(), std::fs::read(dir.join(p)).unwrap())).collect();
    let inputs: Vec<mocap::Input> = bytes.iter().map(|(name, b)| mocap::Input { name, bytes: b }).collect();
    Some(mocap::load(&inputs))
}

fn model(result: &Result<mocap::Loaded, mocap::LoadError>) -> &mocap::Model {
    result.as_ref().unwrap_or_else(|e| panic!("{e}")).asset.model().expect("a model")
}

#[test]
fn a_dropped_folder_pairs_models_with_their_skins() {
    // The weapon names players/waste/weapon.pcx (the file is WEAPON.PCX in upper
    // case); the player names none and takes the other image, even listed after.
    let Some(set) = load_set(&["waste/weapon.PCX", "waste/waste.pcx", "waste/tris.md2", "waste/weapon.md2"]) else {
        return;
    };
    assert_eq!(set.len(), 2, "two models; images are not characters");
    let (player, weapon) = (model(&set[0]), model(&set[1]));
    assert_eq!(player.skin.as_ref().map(|s| s.name.as_str()), Some("waste/waste.pcx"));
    assert_eq!(weapon.skin.as_ref().map(|s| s.name.as_str()), Some("waste/weapon.PCX"));
    assert_eq!(player.mesh.frame_count(), 198);
    assert_eq!(
        player.mesh.source_counts,
        mocap::model::mesh::SourceCounts { vertices: 312, triangles: 596, tex_coords: 435 }
    );
    // Every MD2 model is in Quake units, read as inches: the player is about 1.4 m.
    let height = player.mesh.height() * player.mesh.units().meters_per_unit();
    assert!((1.2..1.6).contains(&height), "{height} m");
    assert_eq!(weapon.mesh.units(), player.mesh.units());
}

#[test]
fn embedded_skin_names_match_any_folder_and_bmp_skins_decode() {
    let Some(set) =
        load_set(&["telias_dolphin/dolphin.md2", "irrlicht_faerie/faerie2.bmp", "telias_dolphin/dolphin_f.bmp"])
    else {
        return;
    };
    let dolphin = model(&set[0]);
    let skin = dolphin.skin.as_ref().expect("dolphin_f.bmp, named settings/elias1/desktop/frames/dolphin_f.bmp");
    assert_eq!(skin.name, "telias_dolphin/dolphin_f.bmp");
    // Reference values from an independent decoder (Pillow 11). The image is 480×92
    // while the header says 256×256: coordinates still divide by the header's size.
    assert_eq!((skin.image.width, skin.image.height), (480, 92));
    assert_eq!(skin.image.pixel(100, 50), Some([92, 98, 117, 255]));
    assert_eq!(dolphin.mesh.skin_size, [256, 256]);
    assert!(dolphin.mesh.tex_coords().iter().all(|t| t.iter().all(|c| (0.0..=1.0).contains(c))));
    let Some(set) = load_set(&["irrlicht_faerie/faerie.md2", "irrlicht_faerie/faerie2.bmp"]) else { return };
    let faerie = model(&set[0]).skin.as_ref().expect("the only image of the set");
    assert_eq!(faerie.image.pixel(10, 20), Some([105, 23, 0, 255]));
    assert_eq!(faerie.image.pixel(219, 192), Some([0, 23, 26, 255]));
}

#[test]
fn images_without_a_model_and_broken_images_are_errors() {
    let Some(set) = load_set(&["waste/waste.pcx"]) else { return };
    let e = set[0].as_ref().unwrap_err().to_string();
    assert!(e.starts_with("waste/waste.pcx: an image is used as a model's skin"), "{e}");
    let Some(dir) = common::corpus_dir() else { return };
    let model_bytes = std::fs::read(dir.join("md2/waste/weapon.md2")).unwrap();
    let set = mocap::load(&[
        mocap::Input { name: "weapon.md2", bytes: &model_bytes },
        mocap::Input { name: "weapon.pcx", bytes: b"\x0a\x05\x01\x08" },
    ]);
    assert_eq!(set.len(), 2);
    assert!(model(&set[0]).skin.is_none(), "an image that cannot be decoded gives the neutral material");
    let e = set[1].as_ref().unwrap_err().to_string();
    assert!(e.starts_with("weapon.pcx:byte "), "{e}");
    let big_bmp = {
        // A BMP header claiming 100000 × 100000 pixels in 60 bytes.
        let mut b = vec![0u8; 60];
        b[..2].copy_from_slice(b"BM");
        b[14] = 40;
        b[18..22].copy_from_slice(&100_000i32.to_le_bytes());
        b[22..26].copy_from_slice(&100_000i32.to_le_bytes());
        b[26] = 1;
        b[28] = 24;
        b
    };
    let set = mocap::load(&[
        mocap::Input { name: "weapon.md2", bytes: &model_bytes },
        mocap::Input { name: "huge.bmp", bytes: &big_bmp },
    ]);
    assert!(set[1].as_ref().is_err_and(|e| e.to_string().starts_with("huge.bmp:")), "{:?}", set[1].as_ref().err());
}
