//! Reads a glTF 2.0 file (`.glb`, or `.gltf` with its `.bin` and images) into a
//! clip that carries a [`Character`]: the skeleton is the joints of the scene's
//! skins (every node when there is no skin) with their names, parents and rest
//! transforms; every animation becomes a [`Take`] sampled on that skeleton at its
//! own key rate; the meshes become the character's [`crate::model::character::Look`].
//!
//! Inputs: bytes, a [`Resources`] lookup, and the animation to start with.
//! Output: the clip (its motion the chosen take, or the rest pose when the file
//! has no animation), in the file's own world space: the nodes above the
//! skeleton are folded into its roots, no unit conversion (glTF is metres, Y up).
//! Stages: [`super::document`] (bytes → checked document and buffers),
//! [`super::graph`] (nodes → joints), [`super::animation`] (channels → tracks),
//! [`super::look`] (meshes → skinned look).

use super::animation::{Path, Track, WeightTrack, tracks};
use super::look::MorphNodes;
use super::document::{self, Resources};
use super::graph::{Graph, Trs};
use crate::error::{ParseError, Warning};
use crate::model::channel::Channel;
use crate::model::character::{Character, Summary, Take};
use crate::model::clip::Clip;
use crate::model::motion::Motion;
use crate::model::skeleton::{EulerConvention, Joint, Skeleton};
use glam::{Quat, Vec3};
use std::sync::Arc;

/// Most values (frames × channels) one animation may be sampled into.
const MAX_VALUES: usize = 1 << 26;

/// Reads a glTF file as what it holds: a vertex-animated model when its mesh
/// moves by morph targets alone ([`super::morph`]), else a clip carrying a
/// character ([`parse`]).
pub fn parse_asset(bytes: &[u8], resources: Resources<'_>) -> Result<crate::model::asset::Asset, ParseError> {
    let parsed = document::parse(bytes, resources)?;
    let graph = Graph::new(&parsed.document)?;
    if let Some(model) = super::morph::model(&parsed, &graph, resources)? {
        return Ok(crate::model::asset::Asset::Model(model));
    }
    character(&parsed, graph, resources, None).map(crate::model::asset::Asset::from)
}

/// Reads a glTF file; `animation` picks the take the clip starts on (the first
/// when `None`; an unknown name is an error that lists the names).
pub fn parse(bytes: &[u8], resources: Resources<'_>, animation: Option<&str>) -> Result<Clip, ParseError> {
    let parsed = document::parse(bytes, resources)?;
    let graph = Graph::new(&parsed.document)?;
    character(&parsed, graph, resources, animation)
}

/// The clip carrying a character that a read document holds (see [`parse`]).
fn character(
    parsed: &document::Parsed<'_>,
    graph: Graph,
    resources: Resources<'_>,
    animation: Option<&str>,
) -> Result<Clip, ParseError> {
    if graph.joints.is_empty() {
        return Err(ParseError::new(0, 0, "the scene has no nodes: nothing to show"));
    }
    let mut warnings = Vec::new();
    let mut all = Vec::new();
    let mut all_weights = Vec::new();
    for a in parsed.document.animations() {
        let (t, weights) = tracks(&a, &parsed.buffers)?;
        let name = a.name().map_or_else(|| format!("animation {}", a.index()), str::to_owned);
        all.push((name, t));
        all_weights.push(weights);
    }
    let (look, morph_nodes) = super::look::build(parsed, &graph, resources, &mut warnings)?;
    let layout = Layout::new(&graph, &all);
    let skeleton = skeleton(&parsed.document, &graph, &layout)?;
    let rest = look.as_ref().and_then(|l| l.morph.as_ref()).map_or(&[][..], |m| m.rest.as_slice());
    let mut takes = Vec::new();
    for ((name, t), weight_tracks) in all.iter().zip(&all_weights) {
        warn_outside(&graph, name, t, &mut warnings);
        let mut played = played_weights(weight_tracks, &morph_nodes, name, &mut warnings);
        let (_, frames) = frames_of(t, &played);
        if !played.is_empty() && frames.saturating_mul(skeleton.channel_count().max(rest.len())) > MAX_VALUES {
            warnings.push(Warning {
                line: None,
                message: format!("animation `{name}`: its weights last {frames} frames, too long to play; not played"),
            });
            played.clear();
        }
        let motion = sample_take(&graph, &layout, &skeleton, t, &played, name)?;
        let weights = sample_weights(&motion, &played, rest);
        takes.push(Take { name: name.clone(), motion, weights });
    }
    let start = match animation {
        None => 0,
        Some(wanted) => takes.iter().position(|t| t.name == wanted).ok_or_else(|| {
            let names: Vec<&str> = takes.iter().map(|t| t.name.as_str()).collect();
            ParseError::new(0, 0, format!("no animation named `{wanted}`; the file has: {}", names.join(", ")))
        })?,
    };
    let motion = match takes.get(start) {
        Some(take) => take.motion.clone(),
        None => sample_take(&graph, &layout, &skeleton, &[], &[], "rest")?,
    };
    let summary = summary(&parsed, &all);
    let character = Character { look, takes, summary };
    let mut clip = Clip::new(skeleton, motion)
        .map_err(|e| ParseError::new(0, 0, format!("internal: {e}")))?
        .with_warnings(warnings)
        .with_character(Arc::new(character));
    if start > 0 {
        let name = clip.takes().get(start).map(|t| t.name.clone()).unwrap_or_default();
        clip.set_take(&name);
    }
    clip.metadata.push(("format".into(), "glTF 2.0".into()));
    if let Some(generator) = parsed.document.as_json().asset.generator.clone() {
        clip.metadata.push(("generator".into(), generator));
    }
    Ok(clip)
}

/// Which channels each joint gets: rotations always; translations for roots and
/// for joints some animation translates; scales for joints some animation scales
/// or whose rest scale is not 1.
struct Layout {
    translate: Vec<bool>,
    scale: Vec<bool>,
}

impl Layout {
    fn new(graph: &Graph, all: &[(String, Vec<Track>)]) -> Layout {
        let n = graph.joints.len();
        let mut translate: Vec<bool> = (0..n).map(|j| graph.joint_parent[j].is_none()).collect();
        let mut scale: Vec<bool> = (0..n).map(|j| !graph.joint_rest(j).s.abs_diff_eq(Vec3::ONE, 1e-5)).collect();
        for track in all.iter().flat_map(|(_, t)| t) {
            if let Some(j) = graph.joint_of.get(track.node).copied().flatten() {
                match track.path {
                    Path::Translation => translate[j] = true,
                    Path::Scale => scale[j] = true,
                    Path::Rotation => {}
                }
            }
        }
        Layout { translate, scale }
    }
}

/// The skeleton: one joint per graph joint, rest transform `between · TRS`.
fn skeleton(document: &gltf::Document, graph: &Graph, layout: &Layout) -> Result<Skeleton, ParseError> {
    let nodes: Vec<gltf::Node<'_>> = document.nodes().collect();
    let mut joints = Vec::with_capacity(graph.joints.len());
    for (j, &n) in graph.joints.iter().enumerate() {
        let rest = graph.joint_rest(j);
        let mut channels = Vec::with_capacity(9);
        if layout.translate[j] {
            channels.extend([Channel::Xposition, Channel::Yposition, Channel::Zposition]);
        }
        channels.extend([Channel::Zrotation, Channel::Xrotation, Channel::Yrotation]);
        if layout.scale[j] {
            channels.extend([Channel::Xscale, Channel::Yscale, Channel::Zscale]);
        }
        let name = nodes.get(n).and_then(|node| node.name()).map_or_else(|| format!("node {n}"), str::to_owned);
        if !rest.t.is_finite() || !rest.r.is_finite() || !rest.s.is_finite() {
            return Err(ParseError::new(0, 0, format!("nodes[{n}]: its transform is not finite")));
        }
        joints.push(Joint::new(name, graph.joint_parent[j], rest.t, channels).with_rest_rotation(rest.r));
    }
    Skeleton::new(joints, EulerConvention::Intrinsic).map_err(|e| ParseError::new(0, 0, e.to_string()))
}

/// Warns once per animation about tracks on nodes that are not joints.
fn warn_outside(graph: &Graph, name: &str, tracks: &[Track], warnings: &mut Vec<Warning>) {
    let outside = tracks.iter().filter(|t| graph.joint_of.get(t.node).copied().flatten().is_none()).count();
    if outside > 0 {
        warnings.push(Warning {
            line: None,
            message: format!(
                "animation `{name}`: {outside} channels move nodes outside the skeleton and are not played"
            ),
        });
    }
}

/// The frame time and count of an animation: its densest track's mean key
/// interval (within 1/240–1/24 s; a common frame rate when within 0.1% of one,
/// as f32 key times drift), adjusted so that the last key falls on the last frame.
fn frames_of(tracks: &[Track], weights: &[Played<'_>]) -> (f64, usize) {
    let times = || tracks.iter().map(|t| t.times.as_slice()).chain(weights.iter().map(|w| w.track.times.as_slice()));
    let end = times().filter_map(|t| t.last().copied()).fold(0.0f32, f32::max) as f64;
    let mean = times()
        .filter(|t| t.len() >= 2)
        .map(|t| (t[t.len() - 1] as f64 - t[0] as f64) / (t.len() - 1) as f64)
        .filter(|d| *d > 0.0)
        .fold(f64::INFINITY, f64::min);
    let mut step = if mean.is_finite() { mean.clamp(1.0 / 240.0, 1.0 / 24.0) } else { 1.0 / 30.0 };
    let common = [24.0, 25.0, 30.0, 48.0, 50.0, 60.0, 90.0, 100.0, 120.0, 240.0]
        .into_iter()
        .find(|fps: &f64| ((1.0 / step) / fps - 1.0).abs() < 1e-3);
    if let Some(fps) = common {
        step = 1.0 / fps;
    }
    if !(end > 0.0) {
        return (1.0 / 30.0, 1);
    }
    let intervals = (end / step).round().max(1.0);
    // The last key on the last frame: the file's own rate (0.033333 is not 1/30).
    (end / intervals, intervals as usize + 1)
}

/// A `weights` channel played on the look: its track and the first of the
/// look's targets it sets.
struct Played<'a> {
    track: &'a WeightTrack,
    first: usize,
}

/// The `weights` channels of animation `name` that drive a mesh node with as
/// many morph targets as they have weights; the others are warned about.
fn played_weights<'a>(
    tracks: &'a [WeightTrack],
    nodes: &MorphNodes,
    name: &str,
    warnings: &mut Vec<Warning>,
) -> Vec<Played<'a>> {
    let mut played = Vec::new();
    for track in tracks {
        match nodes.iter().find(|(n, ..)| *n == track.node) {
            Some(&(_, first, count)) if count == track.targets => played.push(Played { track, first }),
            Some(&(_, _, count)) => warnings.push(Warning {
                line: None,
                message: format!(
                    "animation `{name}`: nodes[{}] has {count} morph targets but its weights channel sets {}; not played",
                    track.node, track.targets
                ),
            }),
            None => warnings.push(Warning {
                line: None,
                message: format!("animation `{name}`: nodes[{}] has no drawn mesh with morph targets; its weights are not played", track.node),
            }),
        }
    }
    played
}

/// The look's morph-target weights at each of `motion`'s frames (`rest` where
/// no played channel sets them): empty when no channel is played.
fn sample_weights(motion: &Motion, played: &[Played<'_>], rest: &[f32]) -> Vec<f32> {
    let (frames, targets) = (motion.frame_count(), rest.len());
    if played.is_empty() || targets == 0 || frames.saturating_mul(targets) > MAX_VALUES {
        return Vec::new();
    }
    let mut out = Vec::with_capacity(frames * targets);
    for _ in 0..frames {
        out.extend_from_slice(rest);
    }
    let mut scratch = Vec::new();
    for p in played {
        let mut cursor = 0;
        scratch.resize(p.track.targets, 0.0);
        for f in 0..frames {
            p.track.sample((f as f64 * motion.frame_time()) as f32, &mut cursor, &mut scratch);
            let row = f * targets + p.first;
            if let Some(slots) = out.get_mut(row..row + p.track.targets) {
                slots.copy_from_slice(&scratch);
            }
        }
    }
    out
}

/// Samples one animation (no tracks: the rest pose, one frame) into motion.
fn sample_take(
    graph: &Graph,
    layout: &Layout,
    skeleton: &Skeleton,
    tracks: &[Track],
    weights: &[Played<'_>],
    name: &str,
) -> Result<Motion, ParseError> {
    let (frame_time, frames) = frames_of(tracks, weights);
    let width = skeleton.channel_count();
    if frames.saturating_mul(width) > MAX_VALUES {
        return Err(ParseError::new(
            0,
            0,
            format!("animation `{name}`: {frames} frames × {width} channels is more than this reader holds"),
        ));
    }
    let mut by_joint: Vec<Vec<&Track>> = vec![Vec::new(); graph.joints.len()];
    for t in tracks {
        if let Some(j) = graph.joint_of.get(t.node).copied().flatten() {
            by_joint[j].push(t);
        }
    }
    let mut cursors: Vec<Vec<usize>> = by_joint.iter().map(|t| vec![0; t.len()]).collect();
    let on_grid: Vec<Vec<bool>> =
        by_joint.iter().map(|ts| ts.iter().map(|t| t.on_grid(frame_time, frames)).collect()).collect();
    let unrest: Vec<Quat> = skeleton.joints().iter().map(|j| j.rest_rotation.inverse()).collect();
    let mut data = Vec::with_capacity(frames * width);
    let mut previous: Vec<[f32; 3]> = vec![[0.0; 3]; graph.joints.len()];
    let take = TakeSampler { graph, layout, by_joint: &by_joint, on_grid: &on_grid, unrest: &unrest };
    for f in 0..frames {
        take.frame(f, (f as f64 * frame_time) as f32, &mut cursors, &mut previous, &mut data);
    }
    if let Some(k) = data.iter().position(|v| !v.is_finite()) {
        return Err(ParseError::new(0, 0, format!("animation `{name}`: frame {} is not finite", k / width.max(1))));
    }
    Motion::new(frame_time, width, frames, data)
        .ok_or_else(|| ParseError::new(0, 0, format!("animation `{name}`: the motion does not fit its channels")))
}

/// What [`sample_take`] samples each frame from: the joints' tracks, which
/// of them have a key on every frame ([`Track::on_grid`]: frame `f` is key
/// `f`), the node graph, the channel layout and the rest rotations' inverses.
struct TakeSampler<'a> {
    graph: &'a Graph,
    layout: &'a Layout,
    by_joint: &'a [Vec<&'a Track>],
    on_grid: &'a [Vec<bool>],
    unrest: &'a [Quat],
}

impl TakeSampler<'_> {
    /// Appends the channels of frame `f`, at `time`, to `data` (`cursors`:
    /// each track's key interval; `previous`: each joint's angles a frame
    /// before, for every frame after the first). A call per frame, not
    /// inlined: a browser's WebAssembly engine first runs code unoptimised and
    /// optimises a function after it is called often, so a loop over every
    /// frame in one call ran slowly throughout.
    #[inline(never)]
    fn frame(&self, f: usize, time: f32, cursors: &mut [Vec<usize>], previous: &mut [[f32; 3]], data: &mut Vec<f32>) {
        let graph = self.graph;
        let continues = f > 0;
        for (j, joint_tracks) in self.by_joint.iter().enumerate() {
            let n = graph.joints[j];
            let mut trs = graph.rest[n];
            let mut value = [0.0f32; 4];
            let Some(cursors) = cursors.get_mut(j) else { continue };
            let on_grid = self.on_grid.get(j).map_or(&[][..], Vec::as_slice);
            for (i, (track, cursor)) in joint_tracks.iter().zip(cursors.iter_mut()).enumerate() {
                if on_grid.get(i).copied().unwrap_or(false) {
                    track.key(f, &mut value);
                } else {
                    track.sample(time, cursor, &mut value);
                }
                match track.path {
                    Path::Translation => trs.t = Vec3::new(value[0], value[1], value[2]),
                    Path::Rotation => trs.r = Quat::from_array(value),
                    Path::Scale => trs.s = Vec3::new(value[0], value[1], value[2]),
                }
            }
            let local: Trs = trs.after(&graph.between[n]);
            if self.layout.translate[j] {
                data.extend(local.t.to_array());
            }
            let unrest_j = self.unrest.get(j).copied().unwrap_or(Quat::IDENTITY);
            let (z, x, y) = zxy((unrest_j * local.r).normalize());
            let before = previous.get(j).copied().unwrap_or_default();
            let angles = unwrap([z.to_degrees(), x.to_degrees(), y.to_degrees()], before, continues);
            if let Some(p) = previous.get_mut(j) {
                *p = angles;
            }
            data.extend(angles);
            if self.layout.scale[j] {
                data.extend(local.s.to_array());
            }
        }
    }
}

/// `q`'s ZXY Euler angles in radians, `(z, x, y)`: what
/// `q.to_euler(EulerRot::ZXY)` returns, to the bit (the same products as
/// glam's `Mat3::from_quat` for the five entries used, the same square root
/// and arc tangents), without building the matrix or choosing among the
/// orders at run time: that was a fifth of a glTF take's import.
fn zxy(q: Quat) -> (f32, f32, f32) {
    let (x2, y2, z2) = (q.x + q.x, q.y + q.y, q.z + q.z);
    let (xx, xy, xz) = (q.x * x2, q.x * y2, q.x * z2);
    let (yy, yz, zz) = (q.y * y2, q.y * z2, q.z * z2);
    let (wx, wy, wz) = (q.w * x2, q.w * y2, q.w * z2);
    // The matrix's columns: x's, y's and z's last entry.
    let col_x = Vec3::new(1.0 - (yy + zz), xy + wz, xz - wy);
    let col_y = Vec3::new(xy - wz, 1.0 - (xx + zz), yz + wx);
    let col_z_z = 1.0 - (xx + yy);
    let cy = (col_z_z * col_z_z + col_x.z * col_x.z).sqrt();
    let (a, b, c) = if cy > 16.0 * f32::EPSILON {
        (col_y.x.atan2(col_y.y), (-col_y.z).atan2(cy), col_x.z.atan2(col_z_z))
    } else {
        ((-col_x.y).atan2(col_x.x), (-col_y.z).atan2(cy), 0.0)
    };
    (-a, -b, -c)
}

/// Each angle moved by whole turns to the one nearest the previous frame's, so
/// that interpolating between frames never goes the long way round.
fn unwrap(angles: [f32; 3], previous: [f32; 3], has_previous: bool) -> [f32; 3] {
    if !has_previous {
        return angles;
    }
    let mut out = angles;
    for (a, p) in out.iter_mut().zip(previous) {
        let d = p - *a;
        // Under half a turn apart rounds to no turn: skip the rounding.
        if d.abs() >= 180.0 {
            *a += (d / 360.0).round() * 360.0;
        }
    }
    out
}

/// What the file holds, for `mocap info`.
fn summary(parsed: &document::Parsed<'_>, all: &[(String, Vec<Track>)]) -> Summary {
    let d = &parsed.document;
    let name = |n: Option<&str>, kind: &str, i: usize| n.map_or_else(|| format!("{kind} {i}"), str::to_owned);
    Summary {
        nodes: d.nodes().len(),
        scenes: d.scenes().len(),
        meshes: d
            .meshes()
            .map(|m| {
                let vertices =
                    m.primitives().filter_map(|p| p.get(&gltf::Semantic::Positions).map(|a| a.count())).sum::<usize>();
                (name(m.name(), "mesh", m.index()), m.primitives().len(), vertices)
            })
            .collect(),
        skins: d.skins().map(|s| (name(s.name(), "skin", s.index()), s.joints().len())).collect(),
        animations: all
            .iter()
            .map(|(n, t)| (n.clone(), t.iter().map(Track::end).fold(0.0f32, f32::max) as f64, t.len()))
            .collect(),
        extensions_used: d.extensions_used().map(str::to_owned).collect(),
        extensions_required: d.extensions_required().map(str::to_owned).collect(),
    }
}

#[cfg(test)]
mod zxy_tests {
    use super::zxy;
    use glam::{EulerRot, Quat};
    use proptest::prelude::*;

    fn same_bits(q: Quat) {
        let (a, b, c) = zxy(q);
        let (x, y, z) = q.to_euler(EulerRot::ZXY);
        assert_eq!([a.to_bits(), b.to_bits(), c.to_bits()], [x.to_bits(), y.to_bits(), z.to_bits()], "{q:?}");
    }

    #[test]
    fn gimbal_lock_and_identity_match_glam() {
        for (z, x, y) in [(0.0, 0.0, 0.0), (0.3, std::f32::consts::FRAC_PI_2, -0.7), (1.2, -std::f32::consts::FRAC_PI_2, 0.4)] {
            same_bits(Quat::from_euler(EulerRot::ZXY, z, x, y));
        }
        same_bits(Quat::from_xyzw(0.0, 0.0, 0.0, -1.0));
    }

    proptest! {
        #[test]
        fn matches_glam_to_the_bit(x in -1.0f32..1.0, y in -1.0f32..1.0, z in -1.0f32..1.0, w in -1.0f32..1.0) {
            let q = Quat::from_xyzw(x, y, z, w);
            prop_assume!(q.length() > 1e-3);
            same_bits(q.normalize());
        }
    }
}
