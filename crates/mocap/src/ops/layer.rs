//! Motion layers: a second clip drives a subtree of a base clip (a wave on the
//! right arm over a walk). Joints are matched by name, through the common naming
//! conventions ([`canonical_name`]: `LeftArm`, `lShldr`, `l_upperarm`,
//! `mixamorig:LeftArm` … are one joint), or by an explicit map.
//!
//! Inputs: the base clip, the layer clip, the subtree's root (a base joint name),
//! a weight 0–1, fade-in and fade-out times, and override or additive. Output: a
//! clip with the base's skeleton (its bone lengths kept) and frames: outside the
//! subtree every channel value is the base's, bit for bit; inside, each matched
//! joint's local rotation is the layer's (override) or the base's turned by the
//! layer's change from its own first frame (additive), blended by the weight.
//! The layer loops when it is shorter than the base.

use crate::model::clip::Clip;
use crate::ops::bake;
use crate::runtime::pose::{LocalPose, from_row};
use crate::runtime::sample::{Interpolation, SampleScratch, sample};
use glam::Quat;

/// How the layer combines with the base.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Blend {
    /// The layer's rotations replace the base's.
    #[default]
    Override,
    /// The layer's change from its own first frame is added to the base.
    Additive,
}

/// A layer's settings.
#[derive(Clone, Debug, PartialEq)]
pub struct Layer {
    /// The base joint whose subtree the layer drives.
    pub subtree: String,
    /// 0 (base only) to 1 (layer only).
    pub weight: f32,
    /// Seconds over which the layer fades in from the start.
    pub fade_in: f64,
    /// Seconds over which it fades out before the end.
    pub fade_out: f64,
    /// Override or additive.
    pub blend: Blend,
    /// Explicit matches (base name, layer name) that win over name matching; an
    /// empty layer name leaves the base joint out of the layer.
    pub map: Vec<(String, String)>,
}

impl Layer {
    /// A full-weight override layer on `subtree`, no fades, names matched.
    pub fn on(subtree: &str) -> Layer {
        Layer {
            subtree: subtree.to_owned(),
            weight: 1.0,
            fade_in: 0.0,
            fade_out: 0.0,
            blend: Blend::Override,
            map: Vec::new(),
        }
    }
}

/// Why a layer cannot be applied.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{0}")]
pub struct LayerError(pub String);

/// A joint name reduced to what the common conventions agree on: side (`left`,
/// `right` or none) and part (`upperarm`, `forearm`, `hand`, `clavicle`, `upleg`,
/// `leg`, `foot`, `toe`, `hips`, `spine`, `chest`, `neck`, `head`, else the name
/// itself, lower-cased, without separators or rig prefixes).
pub fn canonical_name(name: &str) -> String {
    let lower = name.to_ascii_lowercase();
    // Rig prefixes: "mixamorig:", "character1_", "bip01 ".
    let mut s = lower.rsplit(':').next().unwrap_or(&lower).to_owned();
    for prefix in ["character1_", "bip01_", "bip01 ", "bip001 ", "def-", "b_"] {
        if let Some(rest) = s.strip_prefix(prefix) {
            s = rest.to_owned();
        }
    }
    let compact: String = s.chars().filter(|c| c.is_ascii_alphanumeric()).collect();
    let suffix_side = |suffix: &str| s.ends_with(&format!(".{suffix}")) || s.ends_with(&format!("_{suffix}"));
    let (side, rest) = if let Some(r) = compact.strip_prefix("left") {
        ("left", r.to_owned())
    } else if let Some(r) = compact.strip_prefix("right") {
        ("right", r.to_owned())
    } else if suffix_side("l") {
        ("left", compact.trim_end_matches('l').to_owned())
    } else if suffix_side("r") {
        ("right", compact.trim_end_matches('r').to_owned())
    } else if compact.starts_with('l')
        && compact.len() > 2
        && s.chars().nth(1).is_some_and(|c| {
            c == '_' || c.is_ascii_uppercase() || name.chars().nth(1).is_some_and(|n| n.is_ascii_uppercase())
        })
    {
        ("left", compact[1..].to_owned())
    } else if compact.starts_with('r')
        && compact.len() > 2
        && (s.chars().nth(1) == Some('_') || name.chars().nth(1).is_some_and(|n| n.is_ascii_uppercase()))
    {
        ("right", compact[1..].to_owned())
    } else if let Some(side) = one_letter_side(&compact) {
        // CMU's Acclaim names: `lfemur`, `rhumerus`, `lwrist`.
        (side, compact[1..].to_owned())
    } else {
        ("", compact.clone())
    };
    let part = match rest.as_str() {
        "hips" | "pelvis" | "hip" | "root" if side.is_empty() => "hips",
        "shoulder" | "collar" | "clavicle" => "clavicle",
        "arm" | "upperarm" | "shldr" | "uparm" | "humerus" => "upperarm",
        "forearm" | "lowerarm" | "elbow" | "radius" => "forearm",
        "hand" | "wrist" => "hand",
        "upleg" | "thigh" | "upperleg" | "hip" | "femur" => "upleg",
        "leg" | "shin" | "knee" | "lowerleg" | "calf" | "tibia" => "leg",
        "foot" | "ankle" => "foot",
        "toe" | "toebase" | "toes" => "toe",
        "spine" | "abdomen" | "lowerback" => "spine",
        "chest" | "spine1" | "thorax" => "chest",
        "neck" | "neck1" => "neck",
        "head" => "head",
        other => other,
    };
    format!("{side}{part}")
}

/// `left` or `right` for a name that is `l` or `r` and then a limb part written
/// in full (`lfemur`, `rhand`).
fn one_letter_side(compact: &str) -> Option<&'static str> {
    const PARTS: [&str; 25] = [
        "shoulder", "collar", "clavicle", "upperarm", "shldr", "uparm", "humerus", "forearm", "lowerarm", "elbow",
        "radius", "hand", "wrist", "upleg", "thigh", "upperleg", "femur", "shin", "knee", "lowerleg", "calf", "tibia",
        "foot", "ankle", "toes",
    ];
    let side = match compact.as_bytes().first() {
        Some(b'l') => "left",
        Some(b'r') => "right",
        _ => return None,
    };
    PARTS.contains(&compact.get(1..)?).then_some(side)
}

/// Matches the base joints of the subtree rooted at `root` to layer joints:
/// explicit pairs first (a pair with an empty layer name leaves that joint out),
/// then equal names, then equal [`canonical_name`]s.
/// Returns (base joint, layer joint) pairs.
pub fn match_joints(
    base: &crate::Skeleton,
    layer: &crate::Skeleton,
    root: usize,
    map: &[(String, String)],
) -> Vec<(usize, usize)> {
    let joints = base.joints();
    let mut inside = vec![false; joints.len()];
    for (i, j) in joints.iter().enumerate() {
        inside[i] = i == root || j.parent.is_some_and(|p| p < i && inside[p]);
    }
    let canonical: Vec<String> = layer.joints().iter().map(|j| canonical_name(&j.name)).collect();
    (0..joints.len())
        .filter(|&i| inside[i] && !joints[i].is_end_site())
        .filter_map(|i| {
            let name = &joints[i].name;
            let explicit = map.iter().find(|(b, _)| b == name);
            if explicit.is_some_and(|(_, l)| l.is_empty()) {
                // Mapped to nothing: the joint keeps the base's motion.
                return None;
            }
            let matched = explicit.and_then(|(_, l)| layer.find(l)).or_else(|| layer.find(name)).or_else(|| {
                let c = canonical_name(name);
                canonical.iter().position(|x| *x == c).filter(|&k| !layer.is_end_site(k))
            });
            matched.map(|l| (i, l))
        })
        .collect()
}

/// The base clip with the layer on the subtree (see the module documentation).
pub fn apply(base: &Clip, layer_clip: &Clip, layer: &Layer) -> Result<Clip, LayerError> {
    let (base, _) = bake::to_bvh(base);
    let skeleton = base.skeleton();
    let root = skeleton
        .find(&layer.subtree)
        .ok_or_else(|| LayerError(format!("no joint named `{}` in the base", layer.subtree)))?;
    let pairs = match_joints(skeleton, layer_clip.skeleton(), root, &layer.map);
    if pairs.is_empty() {
        return Err(LayerError(format!(
            "no joint of the layer matches the subtree of `{}` (map them by name)",
            layer.subtree
        )));
    }
    if !(layer.weight.is_finite() && (0.0..=1.0).contains(&layer.weight)) {
        return Err(LayerError(format!("weight {}: expected 0 to 1", layer.weight)));
    }
    let frames = base.frame_count();
    let duration = base.duration();
    let period = layer_clip.duration() + layer_clip.frame_time();
    let mut first_layer = LocalPose::default();
    from_row(layer_clip.skeleton(), layer_clip.motion().row(0), layer_clip.motion().angle_unit(), &mut first_layer);
    let mut scratch = SampleScratch::default();
    let (mut base_pose, mut layer_pose) = (LocalPose::default(), LocalPose::default());
    let width = skeleton.channel_count();
    let mut data = Vec::with_capacity(width * frames);
    let mut values = Vec::new();
    let unit = base.motion().angle_unit();
    for f in 0..frames {
        let t = base.timeline().time_of(f);
        let fade_in = if layer.fade_in > 0.0 { (t / layer.fade_in).clamp(0.0, 1.0) } else { 1.0 };
        let fade_out = if layer.fade_out > 0.0 { ((duration - t) / layer.fade_out).clamp(0.0, 1.0) } else { 1.0 };
        let w = layer.weight * (fade_in.min(fade_out) as f32);
        let row = base.motion().row(f);
        if w <= 0.0 {
            data.extend_from_slice(row);
            continue;
        }
        from_row(skeleton, row, unit, &mut base_pose);
        let lt = if period > 0.0 { t % period } else { 0.0 };
        sample(layer_clip.skeleton(), layer_clip.motion(), lt, Interpolation::Linear, &mut scratch, &mut layer_pose);
        let mut changed = row.to_vec();
        for &(b, l) in &pairs {
            let target = match layer.blend {
                Blend::Override => layer_pose.rotation[l],
                Blend::Additive => {
                    (base_pose.rotation[b] * first_layer.rotation[l].inverse() * layer_pose.rotation[l]).normalize()
                }
            };
            let q: Quat = base_pose.rotation[b].slerp(target, w).normalize();
            let joint = &skeleton.joints()[b];
            values.clear();
            crate::ops::edit::joint_values(joint, base_pose.translation[b], q, unit, &mut values);
            // Only rotation channels change: translations stay the base's (its bone lengths).
            for (k, channel) in joint.channels.iter().enumerate() {
                if channel.is_rotation() {
                    if let (Some(slot), Some(v)) = (changed.get_mut(joint.first_channel() + k), values.get(k)) {
                        *slot = *v;
                    }
                }
            }
        }
        data.extend_from_slice(&changed);
    }
    let motion = crate::Motion::new(base.frame_time(), width, frames, data)
        .ok_or_else(|| LayerError("the layer made no valid motion".into()))?
        .with_angle_unit(unit);
    let mut out = Clip::new(skeleton.clone(), motion).map_err(|e| LayerError(e.to_string()))?;
    out.metadata = base.metadata.clone();
    out.keep_character_of(&base);
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::canonical_name;

    #[test]
    fn naming_conventions_meet() {
        for group in [
            ["LeftArm", "lShldr", "l_upperarm", "mixamorig:LeftArm"],
            ["RightForeArm", "rForeArm", "r_forearm", "Character1_RightForeArm"],
            ["Hips", "hip", "pelvis", "mixamorig:Hips"],
            ["LeftUpLeg", "lThigh", "l_thigh", "upperleg.L"],
        ] {
            let c = canonical_name(group[0]);
            for name in group {
                assert_eq!(canonical_name(name), c, "{name} vs {}", group[0]);
            }
        }
        assert_ne!(canonical_name("LeftHand"), canonical_name("RightHand"));
        assert_ne!(canonical_name("LeftArm"), canonical_name("LeftForeArm"));
    }
}
