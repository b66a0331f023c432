//! The part of a target a frame has to redraw when it starts from the last
//! frame's pixels: where this frame's and the last frame's figures are.
//!
//! Under a still camera (the floor copied from the floor cache, see
//! floor_cache.rs) every pixel outside the figures (capsules, spheres, lines,
//! meshes and the floor's shadow) is the floor's or the background's, the same
//! as in the last frame. So a frame that starts from the last frame's pixels
//! redraws only the screen rect around this frame's figures and the last
//! frame's; on a software rasteriser (where every pixel of a pass costs) a
//! clip playing under a still camera then costs about its figures' pixels
//! rather than the view's.
//!
//! Input: the scene, the frame's uniforms (camera, viewport, the floor's
//! shadow rect) and the pixels per point of line widths. Output: a rect of
//! the target in pixels, or `None` where one cannot be found (a figure
//! behind the eye): the whole target is redrawn.

use crate::bounds;
use crate::shadow;
use crate::scene::Scene;
use crate::uniforms::FrameUniforms;
use glam::{Mat4, Vec3, Vec4};

/// Pixels around the figures' projected boxes: capsules' and spheres'
/// outlines and edges, and rounding.
const MARGIN_PX: f32 = 4.0;

/// A rect of a target in pixels: min x, min y, max x, max y (max exclusive).
pub(crate) type PxRect = [u32; 4];

/// Where a frame draws besides the floor and the background, as two screen
/// rects of a target of `size` pixels: its figures', and the floor's shadow
/// of `casters` when `shadows` (see [`Casters`]; empty without). Two, because
/// a long shadow across the floor and a tall figure share a corner: one rect
/// around both holds mostly floor that did not change. Empty rects for a
/// scene without figures; `None` when they cannot be bounded on screen.
pub(crate) fn figures_rect(
    scene: &Scene,
    uniforms: &FrameUniforms,
    shadows: Option<Casters<'_>>,
    pixels_per_point: f32,
    size: [u32; 2],
) -> Option<[PxRect; 2]> {
    let grow = |p: Vec3, r: f32| Some((p - Vec3::splat(r), p + Vec3::splat(r)));
    let mut world: Option<(Vec3, Vec3)> = None;
    for c in &scene.capsules {
        world = bounds::union(world, bounds::union(grow(c.a, c.radius), grow(c.b, c.radius)));
    }
    for s in &scene.spheres {
        world = bounds::union(world, grow(s.center, s.radius));
    }
    let mut line_px: f32 = 0.0;
    for l in scene.lines.iter().chain(&scene.overlay_lines) {
        world = bounds::union(world, bounds::union(grow(l.a, 0.0), grow(l.b, 0.0)));
        line_px = line_px.max(l.width_px * pixels_per_point);
    }
    for b in scene.meshes.iter().filter_map(|m| m.world_bounds()) {
        world = bounds::union(world, Some(b));
    }
    for b in scene.skinned.iter().filter_map(|s| s.world_bounds()) {
        world = bounds::union(world, Some(b));
    }
    let view_proj = Mat4::from_cols_array_2d(&uniforms.projection) * Mat4::from_cols_array_2d(&uniforms.view);
    let figures = world.map(|(lo, hi)| screen_box(&view_proj, corners(lo, hi), size)).unwrap_or(Some(EMPTY))?;
    let shadow = match shadows.filter(|_| scene.grid.is_some()) {
        Some(casters) => shadow_box(&casters, uniforms, &view_proj, size)?,
        None => EMPTY,
    };
    Some([grown(figures, MARGIN_PX + line_px, size), grown(shadow, MARGIN_PX, size)])
}

/// What casts the floor's shadow this frame: capsules (their ends and
/// radius; spheres have both ends at the centre) and boxes around meshes.
pub(crate) struct Casters<'a> {
    /// Capsules and spheres that cast.
    pub capsules: &'a [(Vec3, Vec3, f32)],
    /// World boxes of casting meshes.
    pub boxes: &'a [(Vec3, Vec3)],
}

/// The screen box (floating pixels) of the floor's shadow of `casters`: each
/// caster's shadow on the floor (its ends carried along the key light down
/// to the floor, `shadow::on_floor`, grown by its radius and by how far the
/// shadow map's lookups reach, `shadow::floor_lookup_reach`) within the
/// rect the floor's shadow is drawn over (`uniforms.shadow_rect`), projected
/// on screen one caster at a time. Much tighter than the screen box of the
/// whole drawn rect, whose corners lie far from a long shadow falling across
/// the view; `None` when one cannot be bounded on screen.
fn shadow_box(casters: &Casters<'_>, uniforms: &FrameUniforms, view_proj: &Mat4, size: [u32; 2]) -> Option<[f32; 4]> {
    let drawn = uniforms.shadow_rect;
    if drawn[0] > drawn[2] || drawn[1] > drawn[3] {
        return Some(EMPTY);
    }
    let floor_y = uniforms.floor_center[1];
    let reach = shadow::floor_lookup_reach(uniforms.light_dir[3]);
    // A sphere's shadow reaches its radius over the light's y from its centre's.
    let per_radius = 1.0 / shadow::key_light_direction().y;
    let mut rect = EMPTY;
    let mut add = |lo: glam::Vec2, hi: glam::Vec2, grow: f32| -> Option<()> {
        let (lo, hi) = (lo - glam::Vec2::splat(grow), hi + glam::Vec2::splat(grow));
        let (x0, z0) = (lo.x.max(drawn[0]), lo.y.max(drawn[1]));
        let (x1, z1) = (hi.x.min(drawn[2]), hi.y.min(drawn[3]));
        if x0 > x1 || z0 > z1 {
            return Some(());
        }
        let y = floor_y;
        let floor = [Vec3::new(x0, y, z0), Vec3::new(x1, y, z0), Vec3::new(x0, y, z1), Vec3::new(x1, y, z1)];
        rect = join(rect, screen_box(view_proj, floor, size)?);
        Some(())
    };
    for &(a, b, radius) in casters.capsules {
        let (qa, qb) = (shadow::on_floor(a, floor_y), shadow::on_floor(b, floor_y));
        add(qa.min(qb), qa.max(qb), radius * per_radius + reach)?;
    }
    for &(lo, hi) in casters.boxes {
        let [x0, z0, x1, z1] = shadow::shadows_on_floor(lo, hi, floor_y);
        add(glam::Vec2::new(x0, z0), glam::Vec2::new(x1, z1), reach)?;
    }
    Some(rect)
}

/// A rect holding nothing.
pub(crate) const EMPTY: [f32; 4] = [f32::INFINITY, f32::INFINITY, f32::NEG_INFINITY, f32::NEG_INFINITY];

/// The pixel rect holding `rect` (floating pixels) grown by `by` pixels,
/// within a target of `size`; empty (`[0; 4]`) for an empty rect.
fn grown(rect: [f32; 4], by: f32, size: [u32; 2]) -> PxRect {
    if rect[0] > rect[2] || rect[1] > rect[3] {
        return [0; 4];
    }
    let clamp = |v: f32, max: u32| v.clamp(0.0, max as f32) as u32;
    let (x0, y0) = (clamp((rect[0] - by).floor(), size[0]), clamp((rect[1] - by).floor(), size[1]));
    let (x1, y1) = (clamp((rect[2] + by).ceil(), size[0]), clamp((rect[3] + by).ceil(), size[1]));
    if x1 <= x0 || y1 <= y0 { [0; 4] } else { [x0, y0, x1, y1] }
}

/// Both rects together (floating pixels).
fn join(a: [f32; 4], b: [f32; 4]) -> [f32; 4] {
    [a[0].min(b[0]), a[1].min(b[1]), a[2].max(b[2]), a[3].max(b[3])]
}

/// The rect in pixels (y down) around `points` projected by `view_proj`;
/// `None` if one is at or behind the eye's plane (or not finite).
fn screen_box<const N: usize>(view_proj: &Mat4, points: [Vec3; N], size: [u32; 2]) -> Option<[f32; 4]> {
    let mut rect = EMPTY;
    for p in points {
        let clip: Vec4 = *view_proj * p.extend(1.0);
        if !(clip.w > 1e-6) || !clip.is_finite() {
            return None;
        }
        let x = (clip.x / clip.w * 0.5 + 0.5) * size[0] as f32;
        let y = (0.5 - clip.y / clip.w * 0.5) * size[1] as f32;
        rect = join(rect, [x, y, x, y]);
    }
    Some(rect)
}

/// The eight corners of the box `lo`–`hi`.
fn corners(lo: Vec3, hi: Vec3) -> [Vec3; 8] {
    std::array::from_fn(|i| {
        Vec3::new(
            if i & 1 == 0 { lo.x } else { hi.x },
            if i & 2 == 0 { lo.y } else { hi.y },
            if i & 4 == 0 { lo.z } else { hi.z },
        )
    })
}

/// Where a frame draws the floor's shadow (with `shadows`): where it falls
/// this frame (`figures`' second rect, see [`figures_rect`]) within the
/// rect the frame redraws (`within`); `None` where that is empty or there
/// are no shadows. The floor drawn or copied under it holds no shadow, and
/// on a software rasteriser every pixel of the pass is a lookup and a blend.
pub(crate) fn shadow_area(shadows: bool, figures: Option<[PxRect; 2]>, within: PxRect) -> Option<PxRect> {
    let area = figures.map_or(within, |[_, fallen]| intersection(fallen, within));
    (shadows && area[2] > area[0] && area[3] > area[1]).then_some(area)
}

/// The pixels both `a` and `b` hold (an empty rect where none).
pub(crate) fn intersection(a: PxRect, b: PxRect) -> PxRect {
    let (x0, y0) = (a[0].max(b[0]), a[1].max(b[1]));
    [x0, y0, a[2].min(b[2]).max(x0), a[3].min(b[3]).max(y0)]
}

/// Both pixel rects together; an empty one adds nothing.
pub(crate) fn union(a: PxRect, b: PxRect) -> PxRect {
    let empty = |r: PxRect| r[2] <= r[0] || r[3] <= r[1];
    match (empty(a), empty(b)) {
        (true, _) => b,
        (_, true) => a,
        _ => [a[0].min(b[0]), a[1].min(b[1]), a[2].max(b[2]), a[3].max(b[3])],
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_floor_shadow_is_drawn_where_it_falls_within_the_redrawn_rect() {
        let whole = [0, 0, 100, 100];
        let figures = Some([[10, 10, 30, 60], [20, 50, 90, 70]]);
        assert_eq!(shadow_area(true, figures, whole), Some([20, 50, 90, 70]));
        assert_eq!(shadow_area(true, figures, [0, 0, 60, 60]), Some([20, 50, 60, 60]));
        assert_eq!(shadow_area(true, None, [0, 0, 60, 60]), Some([0, 0, 60, 60]));
        assert_eq!(shadow_area(true, None, whole), Some(whole));
        assert_eq!(shadow_area(false, figures, whole), None);
        assert_eq!(shadow_area(true, Some([[10, 10, 30, 60], [0; 4]]), whole), None);
    }

    #[test]
    fn intersection_is_what_both_hold() {
        assert_eq!(intersection([0, 0, 10, 10], [5, 2, 20, 8]), [5, 2, 10, 8]);
        let apart = intersection([0, 0, 10, 10], [20, 20, 30, 30]);
        assert!(apart[2] <= apart[0] && apart[3] <= apart[1], "{apart:?}");
    }

    #[test]
    fn union_ignores_empty_rects() {
        assert_eq!(union([0; 4], [1, 2, 3, 4]), [1, 2, 3, 4]);
        assert_eq!(union([1, 2, 3, 4], [0; 4]), [1, 2, 3, 4]);
        assert_eq!(union([1, 2, 3, 4], [0, 5, 2, 6]), [0, 2, 3, 6]);
    }

    #[test]
    fn a_shadow_falling_across_the_floor_is_bounded_by_its_casters_shadows() {
        // Two thin posts at opposite corners of a wide drawn rect: the
        // shadows' box is each post's shadow, not the whole rect.
        let camera = crate::Camera::look_at(Vec3::new(0.0, 6.0, 8.0), Vec3::ZERO, 0.8, 1.0);
        let view_proj = camera.projection * camera.view;
        let mut uniforms = <FrameUniforms as bytemuck::Zeroable>::zeroed();
        uniforms.shadow_rect = [-4.0, -4.0, 4.0, 4.0];
        uniforms.light_dir = crate::shadow::key_light_direction().extend(0.01).to_array();
        let size = [400, 400];
        let posts = [(Vec3::new(-1.0, 0.0, -1.0), Vec3::new(-1.0, 0.2, -1.0), 0.05)];
        let boxed = shadow_box(&Casters { capsules: &posts, boxes: &[] }, &uniforms, &view_proj, size).unwrap();
        let y = 0.0;
        let [x0, z0, x1, z1] = uniforms.shadow_rect;
        let floor = [Vec3::new(x0, y, z0), Vec3::new(x1, y, z0), Vec3::new(x0, y, z1), Vec3::new(x1, y, z1)];
        let whole = screen_box(&view_proj, floor, size).unwrap();
        let area = |r: [f32; 4]| (r[2] - r[0]).max(0.0) * (r[3] - r[1]).max(0.0);
        assert!(area(boxed) > 0.0 && area(boxed) < area(whole) / 20.0, "{boxed:?} within {whole:?}");
        // The post's foot and the end of its shadow (carried along the light) are inside.
        let light = crate::shadow::key_light_direction();
        let tip = posts[0].1 - light * (posts[0].1.y / light.y);
        for p in [posts[0].0, tip] {
            let s = screen_box(&view_proj, [p], size).unwrap();
            assert!(s[0] >= boxed[0] && s[2] <= boxed[2] && s[1] >= boxed[1] && s[3] <= boxed[3], "{p} at {s:?} in {boxed:?}");
        }
        // Outside the drawn rect nothing is shadowed.
        uniforms.shadow_rect = [2.0, 2.0, 3.0, 3.0];
        let none = shadow_box(&Casters { capsules: &posts, boxes: &[] }, &uniforms, &view_proj, size).unwrap();
        assert_eq!(none, EMPTY);
    }

    #[test]
    fn points_behind_the_eye_have_no_rect() {
        let view_proj = glam::camera::rh::proj::directx::perspective(1.0, 1.0, 0.1, 100.0);
        let ahead = screen_box(&view_proj, [Vec3::new(0.0, 0.0, -5.0)], [100, 100]).unwrap();
        assert!((ahead[0] - 50.0).abs() < 1e-3 && (ahead[1] - 50.0).abs() < 1e-3);
        assert!(screen_box(&view_proj, [Vec3::new(0.0, 0.0, 5.0)], [100, 100]).is_none());
    }
}
