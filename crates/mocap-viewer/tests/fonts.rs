//! The viewer's fonts (`data/fonts/`, cut down by `cargo xtask gen-fonts`) have a
//! glyph for every character the viewer, the page's JS API and the core's
//! messages write, and the whole UI draws without falling back to a box.

use mocap_viewer::Command;
use mocap_viewer::Viewer;
use std::path::{Path, PathBuf};

const WALK: &[u8] = include_bytes!("../../../data/walk.bvh");

/// A context with the viewer's fonts, which panics on a character no font has.
fn context() -> egui::Context {
    let ctx = egui::Context::default();
    mocap_viewer::fonts::install(&ctx);
    ctx.set_missing_glyph_policy(egui::MissingGlyphPolicy::Panic);
    frame(&ctx, None, 0.0);
    ctx
}

fn frame(ctx: &egui::Context, mut viewer: Option<&mut Viewer>, time: f64) {
    let input = egui::RawInput {
        time: Some(time),
        screen_rect: Some(egui::Rect::from_min_size(egui::Pos2::ZERO, egui::vec2(1280.0, 800.0))),
        ..Default::default()
    };
    let mut output = ctx.run_ui(input, |ui| {
        if let Some(v) = viewer.as_deref_mut() {
            v.ui(ui, None);
        }
    });
    output.textures_delta.clear();
}

/// Every `.rs` file under `dir`.
fn sources(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display())).flatten() {
        let path = entry.path();
        if path.is_dir() {
            sources(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// The characters inside string literals of `text` (comments skipped).
fn literal_chars(text: &str) -> Vec<char> {
    let mut chars = Vec::new();
    for line in text.lines().filter(|l| !l.trim_start().starts_with("//")) {
        let (mut inside, mut escaped) = (false, false);
        for c in line.chars() {
            match (inside, escaped, c) {
                (true, false, '\\') => escaped = true,
                (_, false, '"') => inside = !inside,
                (true, _, c) => {
                    escaped = false;
                    chars.push(c);
                }
                _ => {}
            }
        }
    }
    chars
}

#[test]
fn every_character_in_the_viewers_strings_has_a_glyph_in_both_families() {
    let crates = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let mut files = Vec::new();
    for dir in ["mocap-viewer/src", "mocap-web/src", "mocap/src"] {
        sources(&crates.join(dir), &mut files);
    }
    let mut wanted: Vec<char> = (' '..='~').collect();
    for file in &files {
        let text = std::fs::read_to_string(file).unwrap_or_else(|e| panic!("{}: {e}", file.display()));
        wanted.extend(literal_chars(&text).into_iter().filter(|c| !c.is_ascii()));
    }
    wanted.sort_unstable();
    wanted.dedup();
    assert!(wanted.contains(&'→') && wanted.contains(&'…'), "the scan finds the viewer's strings: {wanted:?}");
    let ctx = context();
    for family in [egui::FontFamily::Proportional, egui::FontFamily::Monospace] {
        let font = egui::FontId::new(14.0, family.clone());
        let missing: String = ctx.fonts_mut(|f| wanted.iter().copied().filter(|&c| !f.has_glyph(&font, c)).collect());
        assert!(missing.is_empty(), "{family:?} has no glyph for {missing:?}");
    }
}

#[test]
fn the_cut_fonts_keep_what_each_family_is_for() {
    let ctx = context();
    let sans = egui::FontId::proportional(14.0);
    let mono = egui::FontId::monospace(14.0);
    ctx.fonts_mut(|f| {
        // Joint and file names in Latin, Greek and Cyrillic scripts (Ubuntu's coverage).
        assert!(f.has_glyphs(&sans, "Łódź Ωμέγα Привет ŠŽČ ñ"));
        assert!(f.has_glyphs(&mono, "0123456789 -+.,: frame / s"));
    });
}

#[test]
fn the_whole_ui_draws_without_a_missing_glyph() {
    let ctx = context();
    let mut v = Viewer::default();
    frame(&ctx, Some(&mut v), 0.1);
    v.load("walk.bvh", WALK).expect("walk.bvh");
    v.add("again.bvh", WALK).expect("second character");
    v.apply(Command::Select { character: v.state().current(), joint: Some(7) }).unwrap();
    frame(&ctx, Some(&mut v), 0.2);
    frame(&ctx, Some(&mut v), 0.3);
    let _ = v.load("bad.bvh", b"HIERARCHY\nJOINT");
    frame(&ctx, Some(&mut v), 0.4);
    assert!(v.snapshot().error.is_some(), "the error banner was drawn");
}

/// Each glyph's pixels in the font atlas for the last of `runs` (text, size in
/// points), laid out one after the other in a new context (hinting on, as
/// the viewer draws).
fn last_glyphs(runs: &[(&str, f32)]) -> Vec<Vec<egui::Color32>> {
    let ctx = context();
    ctx.fonts_mut(|fonts| {
        let mut last = None;
        for &(text, size) in runs {
            last = Some(fonts.layout_no_wrap(text.to_owned(), egui::FontId::proportional(size), egui::Color32::WHITE));
        }
        let image = fonts.image();
        let galley = last.expect("at least one run");
        let glyphs = galley.rows.iter().flat_map(|row| row.glyphs.iter());
        glyphs
            .map(|g| {
                let ([x0, y0], [x1, y1]) = (g.uv_rect.min, g.uv_rect.max);
                (y0..y1).flat_map(|y| (x0..x1).map(move |x| (x as usize, y as usize))).map(|at| image[at]).collect()
            })
            .collect()
    })
}

/// Vendored epaint keeps a font's hinting instances per size (`hinting.rs`):
/// a glyph must come out the same whatever sizes the font drew before it,
/// including a size it drew, left, and comes back to.
#[test]
fn a_glyph_is_drawn_the_same_whatever_sizes_the_font_drew_before() {
    let alone = last_glyphs(&[("Hamburgefonstiv 0123", 20.0)]);
    assert!(alone.iter().filter(|g| !g.is_empty()).count() > 10, "glyphs drawn");
    let after_others = last_glyphs(&[("Hamburgefonstiv 0123", 11.0), ("Hamburgefonstiv", 14.0), ("Hamburgefonstiv 0123", 20.0)]);
    assert_eq!(after_others, alone);
    let back = last_glyphs(&[("xyz", 20.0), ("Hamburgefonstiv 0123", 14.0), ("Hamburgefonstiv 0123", 20.0)]);
    assert_eq!(back, alone);
}

/// Each glyph's place, advance and size in the atlas in the last of `texts`,
/// laid out one after the other at 14 points in a new context.
fn last_layout(texts: &[&str]) -> Vec<String> {
    let ctx = context();
    ctx.fonts_mut(|fonts| {
        let mut last = None;
        for text in texts {
            last = Some(fonts.layout_no_wrap((*text).to_owned(), egui::FontId::proportional(14.0), egui::Color32::WHITE));
        }
        let galley = last.expect("at least one text");
        let glyphs = galley.rows.iter().flat_map(|row| row.glyphs.iter());
        glyphs
            .map(|g| {
                let size = [g.uv_rect.max[0] - g.uv_rect.min[0], g.uv_rect.max[1] - g.uv_rect.min[1]];
                format!("{} {:?} {} {size:?}", g.chr, g.pos, g.advance_width)
            })
            .collect()
    })
}

/// Vendored epaint keeps a face's shape plans by the run's direction, script
/// and language (`shape_plans.rs`): a text must be shaped the same whatever
/// texts of other scripts, or of no script, were shaped before it (a plan
/// kept for the wrong script fails harfrust's own check, or shapes otherwise).
#[test]
fn a_text_is_shaped_the_same_whatever_was_shaped_before() {
    let text = "AVATAR fi Tä Wo, 12.5 → ok";
    let alone = last_layout(&[text]);
    assert!(alone.len() > 20, "glyphs laid out: {alone:?}");
    for before in [&["Ωμέγα"][..], &["Привет", "0123"], &["12:34", "Ωμέγα Привет", "ŠŽČ ñ"]] {
        let texts: Vec<&str> = before.iter().copied().chain([text]).collect();
        assert_eq!(last_layout(&texts), alone, "after {before:?}");
    }
    // And a text of another script the same, alone or after Latin.
    assert_eq!(last_layout(&[text, "Ωμέγα"]), last_layout(&["Ωμέγα"]));
}
