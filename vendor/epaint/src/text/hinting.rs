//! Vendored change: a font's hinting instances, kept per size.
//!
//! Upstream kept one [`HintingInstance`] per font and reconfigured it whenever
//! a glyph of another size (or location, or target) was rasterised. For a font
//! without hinting programs (the automatic hinter) every reconfiguration made
//! the instance anew: the font's glyph styles (shaping its `GSUB` lookups over
//! every glyph) and, lazily, each style's metrics (the outlines of reference
//! glyphs). A frame whose text mixes sizes (a heading, body text, small text)
//! did that again at each change of size; in a browser's first, unoptimised
//! tier of WebAssembly about half of a first frame's text work (see
//! `VENDORED.md`). Here the glyph styles are computed once per font and the
//! last few instances are kept, each keeping its own metrics.

use skrifa::instance::{LocationRef, Size};
use skrifa::outline::{Engine, GlyphStyles, HintingInstance, HintingOptions, OutlineGlyphCollection, Target};

/// How many instances a font keeps (sizes in use at once, in practice).
const KEPT: usize = 8;

/// A font's hinting: its automatic hinter's glyph styles and its last
/// instances, the most recently used last.
pub(crate) struct Hinting {
    /// `None` until the first instance is made; then `Some(None)` where the
    /// font's own hinting programs are used (no automatic hinter).
    styles: Option<Option<GlyphStyles>>,
    instances: Vec<HintingInstance>,
}

impl Hinting {
    /// No instance yet; the first [`Hinting::instance`] makes one.
    pub(crate) fn new() -> Self {
        Self { styles: None, instances: Vec::new() }
    }

    /// The instance for `size`, `location` and `target`, made the first time
    /// (`None` where skrifa cannot make one: the glyph is not drawn, as
    /// upstream).
    pub(crate) fn instance(
        &mut self,
        outlines: &OutlineGlyphCollection<'_>,
        size: Size,
        location: LocationRef<'_>,
        target: Target,
    ) -> Option<&HintingInstance> {
        let kept = self.instances.iter().position(|i| {
            i.size() == size && i.location().coords() == location.coords() && i.target() == target
        });
        let instance = match kept {
            Some(at) => self.instances.remove(at),
            None => {
                let options = self.options(outlines, target);
                let made = HintingInstance::new(outlines, size, location, options).ok()?;
                if self.instances.len() >= KEPT {
                    self.instances.remove(0);
                }
                made
            }
        };
        self.instances.push(instance);
        self.instances.last()
    }

    /// The options of a new instance: the automatic hinter with the font's
    /// glyph styles where skrifa's default engine picks it, else that engine.
    fn options(&mut self, outlines: &OutlineGlyphCollection<'_>, target: Target) -> HintingOptions {
        let styles = self
            .styles
            .get_or_insert_with(|| (!outlines.prefer_interpreter()).then(|| GlyphStyles::new(outlines)));
        match styles {
            Some(styles) => HintingOptions { engine: Engine::Auto(Some(styles.clone())), target },
            None => target.into(),
        }
    }
}
