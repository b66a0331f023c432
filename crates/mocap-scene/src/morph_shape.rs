//! A glTF character's look under its morph-target weights (blend shapes): the
//! bind-space positions the renderer skins instead of the mesh's own, made
//! again only when the weights change.
//!
//! Input: a clip whose look has morph targets, a time. Output: the positions
//! ([`mocap::model::character::Morph::shape`] at [`mocap::Clip::morph_weights_at`]),
//! or `None` when the look has no targets or every weight is 0 (the mesh as it is).

use mocap::Clip;
use mocap::glam::Vec3;
use std::sync::Arc;

/// The last shape made, by look and weights.
#[derive(Clone, Debug, Default)]
pub struct MorphShape {
    look: usize,
    weights: Vec<f32>,
    scratch: Vec<f32>,
    shape: Option<Arc<[Vec3]>>,
}

impl MorphShape {
    /// The look of `clip` at `time` seconds (see the module documentation).
    pub fn at(&mut self, clip: &Clip, time: f64) -> Option<Arc<[Vec3]>> {
        let look = clip.character.as_deref().and_then(|c| c.look.as_ref());
        let morph = look.and_then(|l| Some((l, l.morph.as_ref()?)));
        let Some((look, morph)) = morph.filter(|_| clip.morph_weights_at(time, &mut self.scratch)) else {
            self.shape = None;
            return None;
        };
        if self.scratch.iter().all(|w| *w == 0.0) {
            self.shape = None;
            return None;
        }
        let key = std::ptr::from_ref(look) as usize;
        if self.shape.is_none() || self.look != key || self.weights != self.scratch {
            let mut positions = Vec::new();
            morph.shape(look.skin.positions(), &self.scratch, &mut positions);
            self.shape = Some(positions.into());
            self.look = key;
            self.weights.clone_from(&self.scratch);
        }
        self.shape.clone()
    }
}
