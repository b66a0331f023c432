//! Seeing motion, not just the frame: onion skin (poses before and after the
//! frame, fading with distance) and trails (a joint's path, or the root's path
//! on the floor with a tick each second and the current point). Inputs are
//! posed world transforms (metres, placed); output is lines and spheres added to
//! a [`Scene`], drawn by the same renderer in the viewer and `mocap render`.

use mocap::Transform;
use mocap::glam::Vec3;
use mocap::runtime::sample::Interpolation;
use mocap::stage::{Actor, PoseScratch};
use mocap_render::{FigureJoint, Line, Scene, Sphere};

/// Onion skin: `count` poses each side of the frame, `step` seconds apart.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Onion {
    /// Poses before and after (each side).
    pub count: usize,
    /// Seconds between them.
    pub step: f64,
}

/// Pushes `actor`'s onion skin around `time` (bones as lines in its `color`,
/// fading with distance from the frame; earlier poses cooler, later warmer).
pub fn push_onion<E>(
    scene: &mut Scene,
    actor: &Actor<E>,
    figure: &[FigureJoint],
    time: f64,
    onion: Onion,
    scratch: &mut (PoseScratch, Vec<Transform>),
) {
    if actor.asset.clip().is_none() || onion.count == 0 || !(onion.step > 0.0) {
        return;
    }
    let duration = actor.asset.duration();
    for k in 1..=onion.count.min(16) {
        let fade = 1.0 - k as f32 / (onion.count + 1) as f32;
        for (sign, tint) in [(-1.0, [120, 170, 255]), (1.0, [255, 170, 110])] {
            let t = time + sign * k as f64 * onion.step;
            if !(0.0..=duration).contains(&t) {
                continue;
            }
            let (ps, pose) = scratch;
            actor.pose_at(t, Interpolation::Linear, ps, pose);
            let color = [tint[0], tint[1], tint[2], (40.0 + 150.0 * fade) as u8];
            // Bones under 3% of the figure (fingers, helpers) are left out: on a
            // software rasteriser every line costs, and they do not show the pose.
            let shortest = actor.world_extent() * 0.03;
            for (joint, tr) in figure.iter().zip(pose.iter()) {
                if let Some(parent) = joint.parent.and_then(|p| pose.get(p)) {
                    if parent.translation.distance(tr.translation) >= shortest {
                        scene.lines.push(Line { a: parent.translation, b: tr.translation, color, width_px: 1.0 + fade });
                    }
                }
            }
        }
    }
}

/// A trail: `points` joined as a line, the `current` point as a sphere, and a
/// small cross at each of `ticks`.
pub fn push_trail(scene: &mut Scene, points: &[Vec3], ticks: &[Vec3], current: Option<Vec3>, color: [u8; 4], size: f32) {
    for pair in points.windows(2) {
        scene.overlay_lines.push(Line { a: pair[0], b: pair[1], color, width_px: 2.0 });
    }
    let r = size * 0.015;
    for &p in ticks {
        for d in [Vec3::X, Vec3::Z] {
            scene.overlay_lines.push(Line { a: p - d * r * 2.0, b: p + d * r * 2.0, color, width_px: 2.0 });
        }
    }
    if let Some(c) = current {
        scene.spheres.push(Sphere { center: c, radius: r * 1.5, color: [255, 220, 90, 255] });
    }
}

/// `actor`'s joint `joint` over `[from, to]` seconds sampled every `step`
/// (world metres), the same dropped to `floor` (when given), and the points at
/// whole seconds (ticks).
pub fn joint_path<E>(
    actor: &Actor<E>,
    joint: usize,
    (from, to): (f64, f64),
    step: f64,
    floor: Option<f32>,
    scratch: &mut (PoseScratch, Vec<Transform>),
) -> (Vec<Vec3>, Vec<Vec3>) {
    let (mut points, mut ticks) = (Vec::new(), Vec::new());
    if actor.asset.clip().is_none() || !(step > 0.0) || !(to >= from) {
        return (points, ticks);
    }
    let count = (((to - from) / step).ceil() as usize).min(20_000);
    let (ps, pose) = scratch;
    let mut at = |t: f64| -> Option<Vec3> {
        actor.pose_at(t, Interpolation::Linear, ps, pose);
        pose.get(joint).map(|tr| match floor {
            Some(y) => Vec3::new(tr.translation.x, y, tr.translation.z),
            None => tr.translation,
        })
    };
    for i in 0..=count {
        points.extend(at((from + i as f64 * step).min(to)));
    }
    let mut second = from.ceil();
    while second <= to && ticks.len() < 10_000 {
        ticks.extend(at(second));
        second += 1.0;
    }
    (points, ticks)
}
