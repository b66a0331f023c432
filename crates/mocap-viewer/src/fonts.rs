//! The viewer's user-interface fonts: egui's own two, made smaller by `cargo
//! xtask gen-fonts` (no hinting programs, Hack cut to what numbers and labels
//! need; see `data/fonts/`), 71 KB gzipped in the page's download instead of 319.

use egui::{FontData, FontDefinitions, FontFamily};
use std::sync::Arc;

/// Ubuntu Light (every character it has but polytonic Greek), the proportional font.
const SANS: &[u8] = include_bytes!("../../../data/fonts/ui-sans.ttf");
/// Hack (ASCII, Latin-1 signs, punctuation, arrows, a few more signs), the monospaced font.
const MONO: &[u8] = include_bytes!("../../../data/fonts/ui-mono.ttf");

/// The viewer's fonts: proportional text in Ubuntu Light, falling back to Hack
/// for the arrows and shapes Ubuntu lacks; monospaced text in Hack, falling back
/// to Ubuntu Light for the letters cut from Hack.
pub fn definitions() -> FontDefinitions {
    let mut fonts = FontDefinitions::empty();
    fonts.font_data.insert("ui-sans".to_owned(), Arc::new(FontData::from_static(SANS)));
    fonts.font_data.insert("ui-mono".to_owned(), Arc::new(FontData::from_static(MONO)));
    fonts.families.insert(FontFamily::Proportional, vec!["ui-sans".to_owned(), "ui-mono".to_owned()]);
    fonts.families.insert(FontFamily::Monospace, vec!["ui-mono".to_owned(), "ui-sans".to_owned()]);
    fonts
}

/// Installs [`definitions`] in `ctx`.
pub fn install(ctx: &egui::Context) {
    ctx.set_fonts(definitions());
}
