//! Forward kinematics for many frames at once: the same arithmetic as
//! [`crate::runtime::pose::from_row`] followed by [`crate::runtime::fk::local_to_model`], but each
//! step works on `LANES` frames held side by side (structure of arrays), so the
//! compiler turns it into SIMD. Used for whole-clip passes (bounds, exports,
//! statistics). Skeletons with scale or length channels take the scalar path
//! frame by frame; a test checks both agree.

use crate::model::motion::Motion;
use crate::model::skeleton::{EulerConvention, Skeleton};
use crate::runtime::fastmath::sin_cos;
use crate::runtime::fk::{Transform, local_to_model};
use crate::runtime::pose::{LocalPose, from_row};
use glam::Vec3;

/// Frames processed together.
const LANES: usize = 8;
type Lanes = [f32; LANES];

/// One joint's world rotation (x, y, z, w) and translation for `LANES` frames.
#[derive(Clone, Copy)]
struct JointLanes {
    q: [Lanes; 4],
    t: [Lanes; 3],
}

/// `q · axis-rotation(angle)` lane by lane; `half` is half a radian per unit.
#[inline(always)]
fn rotate_about_axis(q: &mut [Lanes; 4], axis: usize, angles: &Lanes, half: f32) {
    let (s, c) = half_sin_cos(angles, half);
    // One fixed loop per axis (constant field indices vectorise; dynamic ones don't).
    let [x, y, z, w] = q;
    match axis {
        0 => rotate_lanes(w, x, y, z, &s, &c),
        1 => rotate_lanes(w, y, z, x, &s, &c),
        _ => rotate_lanes(w, z, x, y, &s, &c),
    }
}

/// Sine and cosine of `angle · half` lane by lane (the half-angle terms of an
/// axis rotation's quaternion).
#[inline(always)]
fn half_sin_cos(angles: &Lanes, half: f32) -> (Lanes, Lanes) {
    let mut s = [0.0; LANES];
    let mut c = [0.0; LANES];
    for l in 0..LANES {
        (s[l], c[l]) = sin_cos(angles[l] * half);
    }
    (s, c)
}

/// Rotation about axis `a` where `(a, b, d)` is a cyclic permutation of `(x, y, z)`:
/// `(a, b, d, w) ← (w·s + a·c, b·c + d·s, d·c − b·s, w·c − a·s)`.
#[inline(always)]
fn rotate_lanes(w: &mut Lanes, a: &mut Lanes, b: &mut Lanes, d: &mut Lanes, s: &Lanes, c: &Lanes) {
    for l in 0..LANES {
        let (wl, al, bl, dl) = (w[l], a[l], b[l], d[l]);
        a[l] = wl * s[l] + al * c[l];
        b[l] = bl * c[l] + dl * s[l];
        d[l] = dl * c[l] - bl * s[l];
        w[l] = wl * c[l] - al * s[l];
    }
}

/// `parent ∘ local` lane by lane.
#[inline(always)]
fn compose(parent: &JointLanes, local: &JointLanes) -> JointLanes {
    let [px, py, pz, pw] = parent.q;
    let [bx, by, bz, bw] = local.q;
    let mut q = [[0.0; LANES]; 4];
    for l in 0..LANES {
        q[0][l] = pw[l] * bx[l] + px[l] * bw[l] + py[l] * bz[l] - pz[l] * by[l];
        q[1][l] = pw[l] * by[l] - px[l] * bz[l] + py[l] * bw[l] + pz[l] * bx[l];
        q[2][l] = pw[l] * bz[l] + px[l] * by[l] - py[l] * bx[l] + pz[l] * bw[l];
        q[3][l] = pw[l] * bw[l] - px[l] * bx[l] - py[l] * by[l] - pz[l] * bz[l];
    }
    JointLanes { q, t: moved_by(parent, &local.t) }
}

/// `parent ∘ (identity, t)`: [`compose`] for a local transform without
/// rotation (the parent's rotation as it is).
#[inline(always)]
fn offset_from(parent: &JointLanes, t: &[Lanes; 3]) -> JointLanes {
    JointLanes { q: parent.q, t: moved_by(parent, t) }
}

/// The point `v` (in the parent's frame) in the world, lane by lane:
/// `parent.t + parent.q · v`.
#[inline(always)]
fn moved_by(parent: &JointLanes, v: &[Lanes; 3]) -> [Lanes; 3] {
    let [px, py, pz, pw] = parent.q;
    let [vx, vy, vz] = v;
    let mut out = [[0.0; LANES]; 3];
    for l in 0..LANES {
        let tx = 2.0 * (py[l] * vz[l] - pz[l] * vy[l]);
        let ty = 2.0 * (pz[l] * vx[l] - px[l] * vz[l]);
        let tz = 2.0 * (px[l] * vy[l] - py[l] * vx[l]);
        out[0][l] = parent.t[0][l] + vx[l] + pw[l] * tx + (py[l] * tz - pz[l] * ty);
        out[1][l] = parent.t[1][l] + vy[l] + pw[l] * ty + (pz[l] * tx - px[l] * tz);
        out[2][l] = parent.t[2][l] + vz[l] + pw[l] * tz + (px[l] * ty - py[l] * tx);
    }
    out
}

/// World transforms of every joint for `LANES` rows, compiled for the best SIMD
/// the CPU has (AVX2 when detected at run time; SSE2 otherwise). Both versions run
/// the same IEEE operations in the same order, so results are identical.
fn fk_block_dispatch(skeleton: &Skeleton, rows: &[&[f32]; LANES], half: f32, world: &mut [JointLanes]) {
    let extrinsic = skeleton.euler() == EulerConvention::Extrinsic;
    #[cfg(all(target_arch = "x86_64", not(target_feature = "avx2")))]
    if std::arch::is_x86_feature_detected!("avx2") {
        // SAFETY: the CPU supports AVX2, checked just above.
        unsafe {
            if extrinsic {
                fk_block_avx2::<true>(skeleton, rows, half, world);
            } else {
                fk_block_avx2::<false>(skeleton, rows, half, world);
            }
        }
        return;
    }
    if extrinsic {
        fk_block_with::<true>(skeleton, rows, half, world);
    } else {
        fk_block_with::<false>(skeleton, rows, half, world);
    }
}

/// [`fk_block_with`] compiled for AVX2 (both Euler conventions: Acclaim
/// skeletons are extrinsic).
#[cfg(all(target_arch = "x86_64", not(target_feature = "avx2")))]
#[target_feature(enable = "avx2")]
fn fk_block_avx2<const EXTRINSIC: bool>(
    skeleton: &Skeleton,
    rows: &[&[f32]; LANES],
    half: f32,
    world: &mut [JointLanes],
) {
    fk_block_with::<EXTRINSIC>(skeleton, rows, half, world);
}

/// One block of `LANES` frames: local transforms from the rows, then parent ∘ local.
/// Extrinsic rotations in file order are intrinsic ones in reverse
/// order (`rx ry rz` extrinsic is `Rz·Ry·Rx`), so `EXTRINSIC` walks the channels
/// backwards; translation channels do not depend on the order.
///
/// Three shortcuts give the same values as the plain steps (exactly, for finite
/// input): a rotation channel at zero in every lane is skipped (the identity);
/// the first rotation of a joint at rest is the axis rotation itself, not a
/// product with the identity; a joint left without rotation (an End Site, or
/// every rotation at zero, and no rest rotation) takes its parent's as it is.
#[inline(always)]
fn fk_block_with<const EXTRINSIC: bool>(
    skeleton: &Skeleton,
    rows: &[&[f32]; LANES],
    half: f32,
    world: &mut [JointLanes],
) {
    for (j, joint) in skeleton.joints().iter().enumerate() {
        let [rx, ry, rz, rw] = joint.rest_rotation.to_array();
        let mut local = JointLanes {
            q: [[rx; LANES], [ry; LANES], [rz; LANES], [rw; LANES]],
            t: [[joint.offset.x; LANES], [joint.offset.y; LANES], [joint.offset.z; LANES]],
        };
        let mut at_rest = joint.rest_rotation == glam::Quat::IDENTITY;
        let count = joint.channels.len();
        for step in 0..count {
            let k = if EXTRINSIC { count - 1 - step } else { step };
            let Some(channel) = joint.channels.get(k) else { continue };
            let column = joint.first_channel() + k;
            let values: Lanes = std::array::from_fn(|l| rows[l].get(column).copied().unwrap_or(0.0));
            if channel.is_rotation() {
                if values.iter().all(|&v| v == 0.0) {
                    continue;
                }
                if at_rest {
                    set_axis_rotation(&mut local.q, channel.axis(), &values, half);
                    at_rest = false;
                } else {
                    rotate_about_axis(&mut local.q, channel.axis(), &values, half);
                }
            } else if let Some(slot) = local.t.get_mut(channel.axis()) {
                *slot = values;
            }
        }
        let parent = joint.parent.filter(|&p| p < j).and_then(|p| world.get(p));
        let result = match parent {
            Some(parent) if at_rest => offset_from(parent, &local.t),
            Some(parent) => compose(parent, &local),
            None => local,
        };
        if let Some(slot) = world.get_mut(j) {
            *slot = result;
        }
    }
}

/// `q ← axis-rotation(angle)` lane by lane (what [`rotate_about_axis`] gives
/// from the identity).
#[inline(always)]
fn set_axis_rotation(q: &mut [Lanes; 4], axis: usize, angles: &Lanes, half: f32) {
    let (s, c) = half_sin_cos(angles, half);
    *q = [[0.0; LANES]; 4];
    if let Some(slot) = q.get_mut(axis) {
        *slot = s;
    }
    q[3] = c;
}

/// Calls `visit(frame, positions)` for every frame in order, with the world
/// position of every joint (End Sites included). `positions` is reused.
pub fn for_each_frame_positions(skeleton: &Skeleton, motion: &Motion, visit: impl FnMut(usize, &[Vec3])) {
    for_each_frame_positions_in(skeleton, motion, 0..motion.frame_count(), visit);
}

/// Fewest joint transforms worth a run (and a thread) of their own.
const PER_THREAD_MIN: usize = 1 << 16;

/// [`for_each_frame_positions`] on several threads: the frames are cut into
/// contiguous runs, a few per thread (threads as many as the machine has, at
/// most eight; one run on the web or for small clips), which the threads take
/// in turn, so faster cores take more; each run starts from `init()` and visits
/// its frames in order with `visit(&mut accumulator, frame, positions)`. Returns
/// the accumulators in frame order, for the caller to combine.
pub fn fold_frame_positions<A: Send>(
    skeleton: &Skeleton,
    motion: &Motion,
    init: impl Fn() -> A + Sync,
    visit: impl Fn(&mut A, usize, &[Vec3]) + Sync,
) -> Vec<A> {
    let frames = motion.frame_count();
    let work = frames.saturating_mul(skeleton.len().max(1)) / PER_THREAD_MIN;
    let threads = crate::runtime::parallel::max_threads();
    let runs = if threads <= 1 { 1 } else { (threads * 4).min(work).max(1) };
    // Runs of whole blocks of LANES frames.
    let per = (frames.div_ceil(runs).div_ceil(LANES) * LANES).max(LANES);
    let ranges: Vec<std::ops::Range<usize>> = (0..frames).step_by(per).map(|s| s..(s + per).min(frames)).collect();
    let run = |range: std::ops::Range<usize>| {
        let mut acc = init();
        for_each_frame_positions_in(skeleton, motion, range, |f, p| visit(&mut acc, f, p));
        acc
    };
    if ranges.is_empty() {
        return vec![init()];
    }
    // A run only fails by a panic in `visit`: pass it on.
    crate::runtime::parallel::map(ranges, run)
        .into_iter()
        .map(|r| r.unwrap_or_else(|| panic!("a frame-visiting thread panicked")))
        .collect()
}

/// [`for_each_frame_positions`] for the frames in `range` (clamped to the clip).
pub fn for_each_frame_positions_in(
    skeleton: &Skeleton,
    motion: &Motion,
    range: std::ops::Range<usize>,
    mut visit: impl FnMut(usize, &[Vec3]),
) {
    let frames = range.end.min(motion.frame_count());
    let first = range.start.min(frames);
    let joints = skeleton.len();
    let simple = !skeleton.has_scale_channels() && !skeleton.has_length_channels();
    if !simple {
        let (mut local, mut model, mut positions) = (LocalPose::default(), Vec::<Transform>::new(), Vec::new());
        for frame in first..frames {
            from_row(skeleton, motion.row(frame), motion.angle_unit(), &mut local);
            local_to_model(skeleton, &local, &mut model);
            positions.clear();
            positions.extend(model.iter().map(|t| t.translation));
            visit(frame, &positions);
        }
        return;
    }
    let half = motion.angle_unit().radians_per_unit() * 0.5;
    let mut world = vec![JointLanes { q: [[0.0; LANES]; 4], t: [[0.0; LANES]; 3] }; joints];
    let mut positions = vec![Vec3::ZERO; joints];
    let mut start = first;
    while start < frames {
        let count = (frames - start).min(LANES);
        // Pad a short last block by repeating its last frame.
        let rows: [&[f32]; LANES] = std::array::from_fn(|l| motion.row(start + l.min(count - 1)));
        fk_block_dispatch(skeleton, &rows, half, &mut world);
        for l in 0..count {
            for (p, w) in positions.iter_mut().zip(&world) {
                *p = Vec3::new(w.t[0][l], w.t[1][l], w.t[2][l]);
            }
            visit(start + l, &positions);
        }
        start += count;
    }
}

#[cfg(test)]
mod tests {
    use super::for_each_frame_positions;
    use crate::runtime::pose::axis_rotation;
    use crate::{AngleUnit, Channel, Clip, EulerConvention, Joint, Motion, Skeleton};
    use glam::Vec3;

    /// The batch path against the scalar one (`from_row` + `local_to_model`) on every frame.
    fn agrees_with_scalar(clip: &Clip) {
        let mut seen = 0;
        for_each_frame_positions(clip.skeleton(), clip.motion(), |frame, positions| {
            assert_eq!(frame, seen);
            seen += 1;
            let reference = clip.world_positions(frame);
            assert_eq!(positions.len(), reference.len());
            for (a, b) in positions.iter().zip(&reference) {
                assert!((*a - *b).abs().max_element() < 1e-4, "frame {frame}: {a} vs {b}");
            }
        });
        assert_eq!(seen, clip.frame_count());
    }

    #[test]
    fn threaded_runs_visit_every_frame_once_with_the_same_positions() {
        // Enough frames and joints for several threads where the machine has them.
        let clip = crate::formats::bvh::parse(include_bytes!("../../../../data/walk.bvh")).unwrap();
        let joints = clip.skeleton().len();
        let frames = clip.frame_count();
        let mut data = Vec::new();
        for r in 0..(super::PER_THREAD_MIN * 3 / joints / frames + 1) * frames {
            data.extend_from_slice(clip.motion().row(r % frames));
        }
        let motion =
            Motion::new(0.1, clip.motion().channel_count(), data.len() / clip.motion().channel_count(), data).unwrap();
        let big = Clip::new(clip.skeleton().clone(), motion).unwrap();
        let runs = super::fold_frame_positions(
            big.skeleton(),
            big.motion(),
            Vec::new,
            |acc: &mut Vec<(usize, Vec3)>, f, p| acc.push((f, p[joints - 1])),
        );
        let all: Vec<(usize, Vec3)> = runs.into_iter().flatten().collect();
        assert_eq!(all.len(), big.frame_count());
        for (i, (f, p)) in all.iter().enumerate() {
            assert_eq!(*f, i, "frames in order, each once");
            assert!((*p - big.world_positions(i)[joints - 1]).abs().max_element() < 1e-3);
        }
    }

    #[test]
    fn matches_per_frame_fk() {
        let src = "HIERARCHY\nROOT R\n{\nOFFSET 1 2 3\nCHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation\nJOINT C\n{\nOFFSET 0 1 0\nCHANNELS 4 Yrotation Xposition Xrotation Zrotation\nEnd Site\n{\nOFFSET 1 0.5 0\n}\n}\n}\nMOTION\nFrames: 11\nFrame Time: 0.1\n";
        let mut text = src.to_string();
        for f in 0..11 {
            let a = f as f32 * 37.0 - 180.0;
            text.push_str(&format!("{f} 1 -2 {a} {} {} {} 0.5 {} {}\n", a * 0.5, -a, a * 2.0, a + 10.0, 3.0 * a));
        }
        agrees_with_scalar(&crate::formats::bvh::parse(text.as_bytes()).unwrap());
    }

    #[test]
    fn channels_at_zero_in_some_lanes_and_end_sites_agree_with_scalar_fk() {
        // Blocks where a rotation is zero in every frame, in all but one frame,
        // and a joint whose first rotation is zero (so its second meets the rest
        // pose), with End Sites under rotated and unrotated joints.
        let src = "HIERARCHY\nROOT R\n{\nOFFSET 0 1 0\nCHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation\nJOINT C\n{\nOFFSET 0 1 0\nCHANNELS 3 Zrotation Xrotation Yrotation\nEnd Site\n{\nOFFSET 1 0.5 0\n}\n}\nJOINT D\n{\nOFFSET 0.5 0 0\nCHANNELS 3 Zrotation Xrotation Yrotation\nEnd Site\n{\nOFFSET 0 0 2\n}\n}\n}\nMOTION\nFrames: 24\nFrame Time: 0.1\n";
        let mut text = src.to_string();
        for f in 0..24u32 {
            let a = f as f32 * 13.0 - 90.0;
            // Root Z: zero in frames 0-7, only frame 11 in 8-15, all of 16-23.
            let root_z = if f == 11 || f >= 16 { a } else { 0.0 };
            // C: Z always zero, X from frame 8 on; D never rotates but in frame 20.
            let c_x = if f >= 8 { a * 0.5 } else { 0.0 };
            let d_y = if f == 20 { 30.0 } else { 0.0 };
            text.push_str(&format!("{f} 0 0 {root_z} 0 {} 0 {c_x} {} 0 0 {d_y}\n", a * 0.25, a * 2.0));
        }
        agrees_with_scalar(&crate::formats::bvh::parse(text.as_bytes()).unwrap());
    }

    fn general_clip(euler: EulerConvention, channels: Vec<Channel>) -> Clip {
        let width = channels.len();
        let root = Joint::new("r", None, Vec3::new(1.0, 0.0, 0.0), channels).with_rest_rotation(axis_rotation(
            2,
            35.0,
            AngleUnit::Degrees,
        ));
        let child = Joint::new("c", Some(0), Vec3::new(0.0, 2.0, 0.0), vec![Channel::Xrotation, Channel::Zrotation])
            .with_rest_rotation(axis_rotation(1, -60.0, AngleUnit::Degrees));
        let end = Joint::end_site("e", Some(1), Vec3::new(0.3, 1.0, 0.0));
        let skeleton = Skeleton::new(vec![root, child, end], euler).unwrap();
        let frames = 9;
        let data: Vec<f32> = (0..frames * (width + 2)).map(|i| ((i * 7919) % 23) as f32 * 0.2 - 1.5).collect();
        let motion = Motion::new(0.1, width + 2, frames, data).unwrap().with_angle_unit(AngleUnit::Radians);
        Clip::new(skeleton, motion).unwrap()
    }

    #[test]
    fn rest_rotations_radians_and_the_general_channels_agree_with_scalar_fk() {
        // Batch lanes (intrinsic, translation and rotation channels).
        agrees_with_scalar(&general_clip(
            EulerConvention::Intrinsic,
            vec![Channel::Yposition, Channel::Yrotation, Channel::Xrotation],
        ));
        // Batch lanes, extrinsic (Acclaim) with a translation among the rotations.
        agrees_with_scalar(&general_clip(
            EulerConvention::Extrinsic,
            vec![Channel::Zrotation, Channel::Xposition, Channel::Xrotation],
        ));
        // Scalar fallback (scale and length channels).
        agrees_with_scalar(&general_clip(
            EulerConvention::Extrinsic,
            vec![Channel::Yrotation, Channel::Xscale, Channel::Length],
        ));
    }
}
