//! `cargo xtask gen-fonts`: the viewer's two user-interface fonts, made from
//! egui's own (`epaint_default_fonts`) with fontTools (from PyPI, in a virtual
//! environment under `target/`), and written to `data/fonts/`.
//!
//! egui's fonts carry TrueType hinting programs (and Hack an auto-hinter's
//! tables) that make up most of their size; egui renders anti-aliased text and
//! hints with skrifa's auto-hinter when a font has no programs. Without them, and
//! with Hack cut to the characters a monospaced number or label needs, the two
//! fonts go from 319 KB to about 71 KB gzipped in the page's download.
//!
//! - `ui-sans.ttf`: Ubuntu Light, every character it has but polytonic Greek,
//!   no hinting, no glyph names; renamed "Ubuntu Light derivative mocap" as the Ubuntu Font Licence
//!   asks of a modified version (`data/fonts/UFL.txt`).
//! - `ui-mono.ttf`: Hack, ASCII, Latin-1's signs, punctuation, arrows and a few
//!   mathematical and geometric signs, no hinting (`data/fonts/Hack-LICENSE.txt`).
//!
//! `data/fonts/SOURCES` records hashes of the sources, the recipe and the
//! results; a test checks it, so a change to egui's fonts or to the recipe fails
//! until the fonts are made again.

use crate::util::{root, run};
use std::path::{Path, PathBuf};
use std::process::Command;

/// fontTools version the fonts are made with (pinned: its output is stable for one version).
const FONTTOOLS: &str = "fonttools==4.68.0";

/// Characters kept from Ubuntu Light: all it has but polytonic Greek (U+1F00-1FFF).
const SANS_UNICODES: &str = "U+0000-1EFF,U+2000-FFFF";

/// Characters kept from Hack (the proportional font falls back to it for arrows
/// and shapes Ubuntu lacks; monospaced text falls back to Ubuntu for letters
/// beyond ASCII and the rest).
const MONO_UNICODES: &str = "U+0020-007E,U+00A0-00BF,U+00D7,U+00F7,U+2010-2027,U+2030-203A,U+2190-2199,U+2212,U+2248,U+221E,U+2264,U+2265,U+25A0,U+25A1,U+25B2-25C5,U+25CB,U+25CF";

/// The recipe, run by fontTools' Python: `make(source, unicodes, out, rename_suffix, all_names)` per font.
const SCRIPT: &str = r#"
import sys
from fontTools import subset
from fontTools.ttLib import TTFont

def make(source, unicodes, out, suffix, all_names):
    options = subset.Options()
    options.hinting = False
    options.layout_features = ['*']
    if all_names:
        options.name_IDs = ['*']
    options.glyph_names = False
    options.notdef_outline = True
    options.drop_tables += ['DSIG', 'hdmx', 'VDMX', 'LTSH', 'TTFA']
    font = TTFont(source, recalcTimestamp=False)
    subsetter = subset.Subsetter(options)
    subsetter.populate(unicodes=subset.parse_unicodes(unicodes))
    subsetter.subset(font)
    if suffix:
        for record in font['name'].names:
            if record.nameID in (1, 3, 4, 16):
                record.string = record.toUnicode() + ' derivative ' + suffix
            elif record.nameID == 6:
                record.string = record.toUnicode() + '-derivative-' + suffix
    font.save(out, reorderTables=True)

make(sys.argv[1], sys.argv[2], sys.argv[3], 'mocap', True)
make(sys.argv[4], sys.argv[5], sys.argv[6], '', False)
"#;

/// The fonts' folder in the repository.
pub fn dir() -> PathBuf {
    root().join("data/fonts")
}

/// Makes `data/fonts/` (see the module docs).
pub fn gen_fonts() -> Result<(), String> {
    let python = fonttools_python()?;
    let work = root().join("target/fonts");
    std::fs::create_dir_all(&work).map_err(|e| format!("{}: {e}", work.display()))?;
    let sans_src = work.join("Ubuntu-Light.ttf");
    let mono_src = work.join("Hack-Regular.ttf");
    write(&sans_src, epaint_default_fonts::UBUNTU_LIGHT)?;
    write(&mono_src, epaint_default_fonts::HACK_REGULAR)?;
    let out = dir();
    std::fs::create_dir_all(&out).map_err(|e| format!("{}: {e}", out.display()))?;
    run(Command::new(&python)
        .arg("-c")
        .arg(SCRIPT)
        .arg(&sans_src)
        .arg(SANS_UNICODES)
        .arg(out.join("ui-sans.ttf"))
        .arg(&mono_src)
        .arg(MONO_UNICODES)
        .arg(out.join("ui-mono.ttf")))?;
    write(&out.join("SOURCES"), sources_record()?.as_bytes())?;
    for f in ["ui-sans.ttf", "ui-mono.ttf"] {
        let (raw, gz) = crate::dist::sizes(&out.join(f));
        println!("wrote data/fonts/{f}: {raw} bytes, {gz} gzipped");
    }
    Ok(())
}

/// What `data/fonts/SOURCES` says for the fonts now in `data/fonts/`.
pub fn sources_record() -> Result<String, String> {
    let read = |name: &str| std::fs::read(dir().join(name)).map_err(|e| format!("data/fonts/{name}: {e}"));
    Ok(format!(
        "# made by `cargo xtask gen-fonts` ({FONTTOOLS}); FNV-1a 64 of each input and output\n\
         Ubuntu-Light.ttf\t{:016x}\n\
         Hack-Regular.ttf\t{:016x}\n\
         recipe\t{:016x}\n\
         ui-sans.ttf\t{:016x}\n\
         ui-mono.ttf\t{:016x}\n",
        fnv1a(epaint_default_fonts::UBUNTU_LIGHT),
        fnv1a(epaint_default_fonts::HACK_REGULAR),
        fnv1a(format!("{SCRIPT}{SANS_UNICODES}{MONO_UNICODES}{FONTTOOLS}").as_bytes()),
        fnv1a(&read("ui-sans.ttf")?),
        fnv1a(&read("ui-mono.ttf")?),
    ))
}

/// 64-bit FNV-1a: a stable fingerprint (not a security hash).
fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325_u64, |h, &b| (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3))
}

/// A Python with fontTools: a virtual environment under `target/`, made on first use.
fn fonttools_python() -> Result<PathBuf, String> {
    let venv = root().join("target/fonttools");
    let python = venv.join("bin/python");
    let has = |p: &Path| Command::new(p).args(["-c", "import fontTools"]).status().is_ok_and(|s| s.success());
    if !has(&python) {
        run(Command::new("python3").args(["-m", "venv"]).arg(&venv))?;
        run(Command::new(&python).args(["-m", "pip", "install", "-q", FONTTOOLS]))?;
    }
    Ok(python)
}

fn write(path: &Path, bytes: &[u8]) -> Result<(), String> {
    std::fs::write(path, bytes).map_err(|e| format!("{}: {e}", path.display()))
}

#[cfg(test)]
mod tests {
    #[test]
    fn committed_fonts_match_their_sources_and_recipe() {
        let committed = std::fs::read_to_string(super::dir().join("SOURCES")).unwrap_or_default();
        let now = super::sources_record().unwrap_or_else(|e| panic!("{e}: run `cargo xtask gen-fonts`"));
        assert!(
            committed == now,
            "data/fonts is stale (egui's fonts or the recipe changed, or a font was edited): run `cargo xtask gen-fonts`\ncommitted:\n{committed}\nnow:\n{now}"
        );
    }
}
