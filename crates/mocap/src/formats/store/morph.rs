//! Version 2's trailing section: a glTF character's morph targets and its
//! takes' weights ([`crate::model::character::Morph`], [`crate::model::character::Take::weights`]),
//! after the version-1 body, so that a store without them stays version 1 byte
//! for byte and a version-1 store still reads.
//!
//! Postcard: an `Option` of the look's targets (per target its (vertex, offset
//! xyz) pairs) and rest weights, then one weight sequence per take.

use crate::model::asset::Asset;
use crate::model::character::Morph;
use serde::{Deserialize, Serialize};
use std::borrow::Cow;

/// The section as stored.
#[derive(Serialize, Deserialize)]
pub(super) struct MorphSection<'a> {
    targets: Option<(Vec<Cow<'a, [(u32, [f32; 3])]>>, Cow<'a, [f32]>)>,
    takes: Vec<Cow<'a, [f32]>>,
}

impl<'a> MorphSection<'a> {
    /// The section of `asset`; `None` when it has no morph targets nor weights.
    pub fn of(asset: &'a Asset) -> Option<MorphSection<'a>> {
        let Asset::Clip(clip) = asset else { return None };
        let character = clip.character.as_deref()?;
        let morph = character.look.as_ref().and_then(|l| l.morph.as_ref());
        let weighted = character.takes.iter().any(|t| !t.weights.is_empty());
        if morph.is_none() && !weighted {
            return None;
        }
        Some(MorphSection {
            targets: morph.map(|m| {
                (m.targets.iter().map(|t| Cow::Borrowed(t.as_slice())).collect(), Cow::Borrowed(m.rest.as_slice()))
            }),
            takes: character.takes.iter().map(|t| Cow::Borrowed(t.weights.as_slice())).collect(),
        })
    }

    /// Puts the section into `asset` (read from the body), checked: it is a clip
    /// with a character and a look, every vertex index is the look's, one rest
    /// weight per target, one weight list per take, each empty or a weight per
    /// target for every frame of its take.
    pub fn apply(self, asset: &mut Asset) -> Result<(), String> {
        let Asset::Clip(clip) = asset else { return Err("morph targets stored for a model".into()) };
        let Some(character) = clip.character.as_mut() else { return Err("morph targets stored without a character".into()) };
        let character = std::sync::Arc::make_mut(character);
        if self.takes.len() != character.takes.len() {
            return Err(format!("weights for {} takes, the character has {}", self.takes.len(), character.takes.len()));
        }
        let count = match (self.targets, character.look.as_mut()) {
            (None, _) => 0,
            (Some(_), None) => return Err("morph targets stored without a look".into()),
            (Some((targets, rest)), Some(look)) => {
                let vertices = look.skin.positions().len();
                if rest.len() != targets.len() {
                    return Err(format!("{} rest weights for {} morph targets", rest.len(), targets.len()));
                }
                for (t, list) in targets.iter().enumerate() {
                    if let Some((v, _)) = list.iter().find(|(v, _)| *v as usize >= vertices) {
                        return Err(format!("morph target {t} moves vertex {v} of {vertices}"));
                    }
                }
                let n = targets.len();
                look.morph =
                    Some(Morph { targets: targets.into_iter().map(Cow::into_owned).collect(), rest: rest.into_owned() });
                n
            }
        };
        for (k, (take, weights)) in character.takes.iter_mut().zip(self.takes).enumerate() {
            let frames = take.motion.frame_count();
            if !weights.is_empty() && weights.len() != frames.saturating_mul(count) {
                return Err(format!(
                    "take {} (`{}`): {} weights for {frames} frames of {count} targets",
                    k + 1,
                    take.name,
                    weights.len()
                ));
            }
            take.weights = weights.into_owned();
        }
        Ok(())
    }
}
