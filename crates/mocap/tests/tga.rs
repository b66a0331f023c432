//! TGA skins: every layout Quake 2 tools wrote (raw and RLE, 24 and 32 bits, either
//! origin), built here byte by byte, read to the same pixels; a model's `.pcx` skin
//! name taken by a `.tga` of the same name; damaged files refused with a message.

mod common;

use mocap::formats::image::{ImageFormat, Rgba, decode, decode_any};

/// A TGA file of `image` (RGBA rows, top row first): true-colour, `bits` 24 or 32,
/// RLE or raw, rows stored from the top (`top`) or, as most tools write, the bottom.
fn tga(image: &Rgba, bits: u8, rle: bool, top: bool) -> Vec<u8> {
    let (w, h) = (image.width as usize, image.height as usize);
    let mut out = vec![0u8; 18];
    out[2] = if rle { 10 } else { 2 };
    out[12..14].copy_from_slice(&(w as u16).to_le_bytes());
    out[14..16].copy_from_slice(&(h as u16).to_le_bytes());
    out[16] = bits;
    out[17] = (if bits == 32 { 8 } else { 0 }) | if top { 0x20 } else { 0 };
    let pixel = |x: usize, y: usize| {
        let p = &image.pixels[(y * w + x) * 4..][..4];
        let mut bgra = vec![p[2], p[1], p[0]];
        if bits == 32 {
            bgra.push(p[3]);
        }
        bgra
    };
    for row in 0..h {
        let y = if top { row } else { h - 1 - row };
        let mut x = 0;
        while x < w {
            if !rle {
                out.extend(pixel(x, y));
                x += 1;
                continue;
            }
            // A run of equal pixels (up to 128, within the row), else one raw pixel.
            let run = (x..w).take(128).take_while(|&k| pixel(k, y) == pixel(x, y)).count();
            if run > 1 {
                out.push(0x80 | (run - 1) as u8);
                out.extend(pixel(x, y));
                x += run;
            } else {
                out.push(0);
                out.extend(pixel(x, y));
                x += 1;
            }
        }
    }
    out
}

/// A 7×5 picture with runs (a flat band) and detail (a gradient), alpha varying.
fn picture() -> Rgba {
    let (width, height) = (7u32, 5u32);
    let mut pixels = Vec::new();
    for y in 0..height {
        for x in 0..width {
            let flat = y == 2;
            let c = if flat { [200, 10, 30] } else { [(x * 30) as u8, (y * 50) as u8, (x * y * 7) as u8] };
            pixels.extend([c[0], c[1], c[2], (255 - x * 20) as u8]);
        }
    }
    Rgba { width, height, pixels }
}

#[test]
fn raw_and_rle_24_and_32_bit_either_origin_read_to_the_same_pixels() {
    let image = picture();
    for bits in [24u8, 32] {
        for rle in [false, true] {
            for top in [false, true] {
                let file = tga(&image, bits, rle, top);
                let what = format!("{bits}-bit, rle {rle}, top {top}");
                assert_eq!(ImageFormat::detect(&file), Some(ImageFormat::Tga), "{what}: known without a name");
                let read = decode_any("skin.tga", &file).unwrap_or_else(|e| panic!("{what}: {e}"));
                assert_eq!((read.width, read.height), (image.width, image.height), "{what}");
                for y in 0..image.height {
                    for x in 0..image.width {
                        let mut want = image.pixel(x, y).unwrap();
                        if bits == 24 {
                            want[3] = 255;
                        }
                        assert_eq!(read.pixel(x, y), Some(want), "{what}: pixel ({x}, {y})");
                    }
                }
            }
        }
    }
}

#[test]
fn damaged_tga_files_are_refused_with_a_message_and_never_panic() {
    let file = tga(&picture(), 32, true, false);
    // Cut anywhere, every byte changed: an error or an image, never a panic.
    for end in 0..file.len() {
        let _ = decode(ImageFormat::Tga, &file[..end]);
    }
    for at in 0..file.len() {
        for value in [0u8, 0x7F, 0x80, 0xFF] {
            let mut bad = file.clone();
            bad[at] = value;
            let _ = decode_any("skin.tga", &bad);
        }
    }
    let cut = decode_any("skin.tga", &file[..30]).expect_err("the pixels stop early");
    assert!(cut.to_string().contains("TGA"), "{cut}");
    // A size past the limit is refused before anything is allocated.
    let mut huge = file.clone();
    huge[12..14].copy_from_slice(&u16::MAX.to_le_bytes());
    huge[14..16].copy_from_slice(&u16::MAX.to_le_bytes());
    assert!(decode_any("huge.tga", &huge).is_err());
    // Text is not taken for a TGA without the extension.
    assert_eq!(ImageFormat::detect(b"not an image, just some notes\n"), None);
    assert!(decode_any("notes.txt", b"HIERARCHY\nROOT A\n").is_err());
}

#[test]
fn a_model_naming_a_pcx_skin_takes_the_tga_of_that_name() {
    let Some(dir) = common::corpus_dir() else { return };
    let dir = dir.join("md2/waste");
    let model = std::fs::read(dir.join("weapon.md2")).unwrap();
    let pcx = mocap::formats::image::pcx::decode(&std::fs::read(dir.join("weapon.PCX")).unwrap()).unwrap();
    let skin = tga(&pcx, 24, true, false);
    // The weapon names players/waste/weapon.pcx; only weapon.tga is dropped, listed
    // after an image of another name; the model file is named unlike either.
    let other = tga(&picture(), 24, false, true);
    let inputs = [
        mocap::Input { name: "other.tga", bytes: &other },
        mocap::Input { name: "waste/weapon.tga", bytes: &skin },
        mocap::Input { name: "waste/w_gun.md2", bytes: &model },
    ];
    let set = mocap::load(&inputs);
    assert_eq!(set.len(), 1, "one model; images are not characters");
    let loaded = set[0].as_ref().unwrap_or_else(|e| panic!("{e}"));
    let skin = loaded.asset.model().and_then(|m| m.skin.as_ref()).expect("a skin");
    assert_eq!(skin.name, "waste/weapon.tga");
    assert_eq!(*skin.image, pcx, "the TGA's pixels are the PCX's");
}
