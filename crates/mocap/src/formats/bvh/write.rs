//! Writes a clip as standard BVH: tab indentation, LF line endings, one row per
//! frame, and shortest round-trip float formatting (so parse → write → parse gives
//! bit-identical f32 values).

use crate::formats::text::push_f32;

use crate::model::clip::Clip;
use crate::model::skeleton::Skeleton;
use std::fmt::Write as _;

/// Deeper levels are not indented further, so output stays linear in the input
/// even for absurdly deep hierarchies.
const MAX_INDENT: usize = 64;

fn indent(out: &mut String, depth: usize) {
    out.extend(std::iter::repeat_n('\t', depth.min(MAX_INDENT)));
}

/// Channel columns in the order a reader will assign them: joints in depth-first
/// file order (the order the hierarchy is written in), which may permute the clip's.
fn column_order(skeleton: &Skeleton, written: &[usize]) -> Vec<usize> {
    written.iter().filter_map(|&j| skeleton.joints().get(j)).flat_map(|j| j.columns()).collect()
}

/// Serialises a clip as BVH text. A clip BVH cannot hold as it is (rest rotations,
/// extrinsic rotations, radians, scale or length channels) is first baked by
/// [`crate::ops::bake::to_bvh`], which keeps every joint's model position.
pub fn write(clip: &Clip) -> String {
    if crate::ops::bake::is_bvh_ready(clip) {
        write_ready(clip)
    } else {
        // Baked once, never again: what baking cannot make plain is written as it is.
        write_ready(&crate::ops::bake::to_bvh(clip).0)
    }
}

/// Writes a clip whose skeleton and units BVH holds as they are.
fn write_ready(clip: &Clip) -> String {
    let skeleton = clip.skeleton();
    let kids = skeleton.children();
    let mut written = Vec::with_capacity(skeleton.len());
    let mut out = String::with_capacity(64 * skeleton.len() + clip.motion().data().len() * 10);
    let mut buffer = ryu::Buffer::new();
    out.push_str("HIERARCHY\n");
    // Depth-first, iterative: (joint, depth, closing?)
    let mut stack: Vec<(usize, usize, bool)> = skeleton.roots().map(|r| (r, 0, false)).collect();
    stack.reverse();
    while let Some((j, depth, closing)) = stack.pop() {
        let Some(joint) = skeleton.joints().get(j) else { continue };
        if closing {
            indent(&mut out, depth);
            out.push_str("}\n");
            continue;
        }
        written.push(j);
        indent(&mut out, depth);
        if joint.is_end_site() {
            out.push_str("End Site\n");
        } else {
            out.push_str(if joint.parent.is_none() { "ROOT " } else { "JOINT " });
            let name: String =
                joint.name.chars().map(|c| if c.is_control() || c == '{' || c == '}' { '_' } else { c }).collect();
            // A joint without a name (a damaged store, a hand-built clip) still reads back.
            if name.trim().is_empty() {
                out.push_str(&format!("joint{j}"));
            } else {
                out.push_str(&name);
            }
            out.push('\n');
        }
        indent(&mut out, depth);
        out.push_str("{\n");
        indent(&mut out, depth + 1);
        out.push_str("OFFSET");
        for v in joint.offset.to_array() {
            out.push(' ');
            push_f32(&mut out, &mut buffer, v);
        }
        out.push('\n');
        if !joint.is_end_site() {
            indent(&mut out, depth + 1);
            let _ = write!(out, "CHANNELS {}", joint.channels.len());
            for c in &joint.channels {
                out.push(' ');
                out.push_str(c.name());
            }
            out.push('\n');
        }
        stack.push((j, depth, true));
        if let Some(list) = kids.get(j) {
            stack.extend(list.iter().rev().map(|&c| (c, depth + 1, false)));
        }
    }
    let motion = clip.motion();
    let _ = write!(
        out,
        "MOTION\nFrames: {}\nFrame Time: {}\n",
        motion.frame_count(),
        ryu::Buffer::new().format(motion.frame_time())
    );
    let order = column_order(skeleton, &written);
    for frame in 0..motion.frame_count() {
        let row = motion.row(frame);
        for (n, &col) in order.iter().enumerate() {
            if n > 0 {
                out.push(' ');
            }
            push_f32(&mut out, &mut buffer, row.get(col).copied().unwrap_or(0.0));
        }
        out.push('\n');
    }
    out
}
