//! The key light's shadow map: a depth texture rendered from the light with an
//! orthographic projection fitted to the shadow casters, sampled with a comparison
//! sampler (soft edges from a small filter in the shader).
//!
//! The texel size is that of a square map of [`SIZE`] texels holding the
//! casters and the floor their shadows fall on, or that of a screen pixel where
//! the nearest of them is seen if that is larger: texels finer than the pixels
//! they are seen through do not show, yet cost their clearing, filling and
//! lookups (a figure filling a 1280×720 view needed a 1024×1792 map, about 3.5
//! texels a pixel; it now takes 512×768). The texture itself holds only
//! the casters (seen from the light, the floor in shadow lies behind them; a
//! lookup outside the map is lit), on the same lattice of texels, so it is the
//! same picture from fewer texels to clear and fill every frame: about half at
//! 64 characters (a software rasteriser's cost).

use glam::{Mat4, Vec2, Vec3};

/// Texels across the square the texel size is fitted to (unless a screen
/// pixel is larger, see [`fit_light`]); the largest map.
pub(crate) const SIZE: u32 = 2048;
/// The fast look's [`SIZE`]: a quarter of the texels to clear and draw every
/// frame (a software rasteriser's cost), softer shadow edges; where screen
/// pixels are larger than its texels both looks' texels are the pixels'.
pub(crate) const FAST_SIZE: u32 = 1024;
/// Map sizes are whole steps of this many texels (so a moving crowd seldom
/// needs a new texture).
const STEP: u32 = 256;
/// Texels of empty map kept around the casters (the lookups' filter reads up
/// to two texels out).
const BORDER: f32 = 4.0;
/// Depth format of the shadow map.
pub(crate) const FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

/// Unit vector towards the key light: high and from the left of the default
/// camera, so figures are lit from the front and their shadows fall to the right
/// where the camera sees them.
pub fn key_light_direction() -> Vec3 {
    Vec3::new(-0.6, 1.0, 0.35).normalize()
}

/// The layout the lit pipelines sample a [`ShadowMap`] through.
pub(crate) fn layout(device: &wgpu::Device) -> wgpu::BindGroupLayout {
    crate::pipeline::texture_layout(
        device,
        "mocap shadow",
        wgpu::TextureSampleType::Depth,
        wgpu::SamplerBindingType::Comparison,
    )
}

/// The shadow map texture and the bind group (of [`layout`]) the lit pipelines
/// sample it through.
pub(crate) struct ShadowMap {
    pub view: wgpu::TextureView,
    pub bind_group: wgpu::BindGroup,
    /// Texels across and down.
    pub size: [u32; 2],
}

impl ShadowMap {
    /// A map of `size` texels (at most the device's texture limit).
    pub fn new(device: &wgpu::Device, size: [u32; 2], layout: &wgpu::BindGroupLayout) -> ShadowMap {
        let limit = device.limits().max_texture_dimension_2d;
        let size = size.map(|s| s.clamp(1, limit));
        let texture = device.create_texture(&wgpu::TextureDescriptor {
            label: Some("mocap shadow map"),
            size: wgpu::Extent3d { width: size[0], height: size[1], depth_or_array_layers: 1 },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: FORMAT,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING,
            view_formats: &[],
        });
        let view = texture.create_view(&Default::default());
        let sampler = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("mocap shadow"),
            address_mode_u: wgpu::AddressMode::ClampToEdge,
            address_mode_v: wgpu::AddressMode::ClampToEdge,
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            compare: Some(wgpu::CompareFunction::LessEqual),
            ..Default::default()
        });
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("mocap shadow"),
            layout,
            entries: &[
                wgpu::BindGroupEntry { binding: 0, resource: wgpu::BindingResource::TextureView(&view) },
                wgpu::BindGroupEntry { binding: 1, resource: wgpu::BindingResource::Sampler(&sampler) },
            ],
        });
        ShadowMap { view, bind_group, size }
    }

    /// A map of one [`STEP`] square, to be fitted to casters ([`ShadowMap::fit`]).
    pub fn small(device: &wgpu::Device, layout: &wgpu::BindGroupLayout) -> ShadowMap {
        ShadowMap::new(device, [STEP; 2], layout)
    }

    /// Makes this a map for casters that need `needed` texels (see
    /// [`new_size`]): kept, or made anew.
    pub fn fit(&mut self, device: &wgpu::Device, needed: [u32; 2], layout: &wgpu::BindGroupLayout) {
        if let Some(size) = new_size(Some(self.size), needed) {
            *self = ShadowMap::new(device, size, layout);
        }
    }
}

/// The size of a new map for casters that need `needed` texels, or `None` to
/// keep the map of size `current`: kept while it holds them and is less than
/// two [`STEP`]s larger on each side, else made in whole steps.
fn new_size(current: Option<[u32; 2]>, needed: [u32; 2]) -> Option<[u32; 2]> {
    let keep = current.is_some_and(|size| (0..2).all(|i| needed[i] <= size[i] && size[i] < needed[i] + 2 * STEP));
    (!keep).then(|| needed.map(|n| n.div_ceil(STEP).max(1) * STEP))
}

/// How the key light sees the casters this frame, before the map's size is
/// chosen ([`LightView::on_map`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct LightView {
    /// World to the light's view space.
    view: Mat4,
    /// The casters' middle in the light's view (x, y), on a texel corner.
    center: Vec2,
    /// Near and far distances of the casters and the floor in shadow.
    near: f32,
    far: f32,
    /// Size of one shadow-map texel in world units.
    pub texel: f32,
    /// Texels across and down the casters need (with a border), at most the
    /// map size fitted to; even.
    pub texels: [u32; 2],
    /// Where on the floor the shadows fall, with a margin (what the map is
    /// fitted to): min x, min z, max x, max z.
    pub floor_rect: [f32; 4],
    /// The part of the floor the floor's shadow is drawn over
    /// ([`floor_shadow_rect`]).
    pub floor_shadow: [f32; 4],
}

impl LightView {
    /// The projection onto a map of `size` texels (even, each at least
    /// [`LightView::texels`]) centred on the casters.
    pub fn on_map(&self, size: [u32; 2]) -> LightFit {
        let half = Vec2::new(size[0] as f32, size[1] as f32) * 0.5 * self.texel;
        let (lo, hi) = (self.center - half, self.center + half);
        let projection = glam::camera::rh::proj::directx::orthographic(lo.x, hi.x, lo.y, hi.y, self.near, self.far);
        LightFit { view_proj: projection * self.view, texel: self.texel, floor_shadow: self.floor_shadow }
    }
}

/// How the key light's shadow map is laid over the scene this frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct LightFit {
    /// World to the shadow map's clip space.
    pub view_proj: Mat4,
    /// Size of one shadow-map texel in world units.
    pub texel: f32,
    /// The part of the floor the floor's shadow is drawn over: min x, min z,
    /// max x, max z.
    pub floor_shadow: [f32; 4],
}

/// The eight corners of the box `min..max`.
fn corners(min: Vec3, max: Vec3) -> [Vec3; 8] {
    std::array::from_fn(|i| {
        let pick = |bit: usize, a: f32, b: f32| if i & bit == 0 { a } else { b };
        Vec3::new(pick(1, min.x, max.x), pick(2, min.y, max.y), pick(4, min.z, max.z))
    })
}

/// The rectangle (min x, min z, max x, max z) on the floor holding `shadows`
/// ([`shadows_on_floor`]), with a margin for soft edges: what the map is
/// fitted to (the floor's shadow is drawn over [`floor_shadow_rect`]).
fn floor_rect(shadows: [f32; 4]) -> [f32; 4] {
    grown(shadows, (shadows[2] - shadows[0]).max(shadows[3] - shadows[1]) * 0.05)
}

/// The rectangle on the floor at `floor_y` holding the shadows of casters
/// inside `min..max`: the box's corners carried along the key light down to
/// the floor ([`on_floor`]).
pub(crate) fn shadows_on_floor(min: Vec3, max: Vec3, floor_y: f32) -> [f32; 4] {
    let (mut lo, mut hi) = (Vec2::splat(f32::INFINITY), Vec2::splat(f32::NEG_INFINITY));
    for p in corners(min, max) {
        let q = on_floor(p, floor_y);
        lo = lo.min(q);
        hi = hi.max(q);
    }
    [lo.x, lo.y, hi.x, hi.y]
}

/// Where `p`'s shadow falls on the floor at `floor_y` (x, z): `p` carried
/// along the key light down to it (a point below the floor stays where it is).
pub(crate) fn on_floor(p: Vec3, floor_y: f32) -> Vec2 {
    let l = key_light_direction();
    let q = p - l * ((p.y - floor_y).max(0.0) / l.y);
    Vec2::new(q.x, q.z)
}

/// How far on the floor, from a caster's shadow, a map of `texel`-unit
/// texels can still darken it: [`FLOOR_LOOKUP_REACH`] texels in the light's
/// view are up to 1 / y of the light's direction as long on the floor.
pub(crate) fn floor_lookup_reach(texel: f32) -> f32 {
    FLOOR_LOOKUP_REACH * texel / key_light_direction().y
}

/// `rect` grown by `by` on every side.
fn grown(rect: [f32; 4], by: f32) -> [f32; 4] {
    [rect[0] - by, rect[1] - by, rect[2] + by, rect[3] + by]
}

/// Texels, in the light's view, from the casters to the farthest floor point
/// whose shadow-map lookups can find them: the lookup point is raised three
/// texels along the floor's normal (lighting.wgsl) and its four filtered taps
/// read up to 1.75 texels beyond it; with room.
const FLOOR_LOOKUP_REACH: f32 = 6.0;

/// The part of the floor the floor's shadow is drawn over (floor.wgsl's
/// `vs_shadow`), for casters whose shadows fall in `shadows`
/// ([`shadows_on_floor`]) and a map of `texel`-unit texels: `shadows` grown
/// by as far as the lookups reach (a distance in the light's view is up to
/// 1 / y of the light's direction as long on the floor), within `fitted` (the
/// rectangle the map was fitted to). Every floor point outside it is lit, so drawing it there changed
/// nothing, and on a software rasteriser each such pixel cost four lookups: the
/// rectangle the map is fitted to has a margin of a twentieth of its size
/// on each side (about a fifth more floor at 64 characters).
fn floor_shadow_rect(shadows: [f32; 4], texel: f32, fitted: [f32; 4]) -> [f32; 4] {
    let [x0, z0, x1, z1] = grown(shadows, floor_lookup_reach(texel));
    [x0.max(fitted[0]), z0.max(fitted[1]), x1.min(fitted[2]), z1.min(fitted[3])]
}

/// How large a screen pixel is, in world units, at each distance from the eye:
/// what a shadow-map texel is never made smaller than (see [`fit_light`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum ScreenPixel {
    /// A perspective view from `eye`: `per_distance` world units per pixel
    /// per world unit of distance.
    Perspective { eye: Vec3, per_distance: f32 },
    /// An orthographic view: the same size everywhere.
    Orthographic(f32),
}

impl ScreenPixel {
    /// The pixels of `camera` on a target `height_px` pixels tall (`None` for
    /// a degenerate projection).
    pub fn of(camera: &crate::Camera, height_px: u32) -> Option<ScreenPixel> {
        let per = 1.0 / camera.pixels_per_unit(height_px.max(1) as f32);
        if !per.is_finite() || per <= 0.0 {
            return None;
        }
        if camera.is_perspective() {
            let eye = camera.eye();
            eye.is_finite().then_some(ScreenPixel::Perspective { eye, per_distance: per })
        } else {
            Some(ScreenPixel::Orthographic(per))
        }
    }

    /// The size of a pixel at the point of `min..max` nearest the eye (0 when
    /// the eye is inside the box).
    fn nearest_in(self, min: Vec3, max: Vec3) -> f32 {
        match self {
            ScreenPixel::Perspective { eye, per_distance } => {
                (min - eye).max(eye - max).max(Vec3::ZERO).length() * per_distance
            }
            ScreenPixel::Orthographic(size) => size,
        }
    }
}

/// Fits the light's view to casters inside `min..max` (world space) and a floor
/// at height `floor_y` (the box's bottom without one): an orthographic view
/// along the light whose depth range holds the box and the floor under the far
/// end of its shadows, and the floor rectangle the shadows fall in. The texel
/// size is that of a square of `size` texels holding the box and that floor,
/// but never smaller than a screen `pixel` where the nearest of them is seen
/// (finer texels would not show: a crowd seen from afar, or a figure that
/// fills a small view, needs a far smaller map to clear, fill and look up),
/// quantised (in steps of 25%), and the view is centred on the casters on
/// whole texels, so that shadows do not shimmer as the figures move. `None`
/// for an empty or non-finite box.
pub(crate) fn fit_light(
    min: Vec3,
    max: Vec3,
    floor_y: Option<f32>,
    size: u32,
    pixel: Option<ScreenPixel>,
) -> Option<LightView> {
    let floor_y = floor_y.filter(|y| y.is_finite()).unwrap_or(min.y);
    let lo = Vec3::new(min.x, min.y.min(floor_y), min.z);
    if !(lo.is_finite() && max.is_finite() && (max - lo).min_element() >= 0.0) {
        return None;
    }
    let l = key_light_direction();
    let center = (lo + max) * 0.5;
    let radius = ((max - lo).length() * 0.5).max(1e-3);
    let view = glam::camera::rh::view::look_at_mat4(center + l * radius * 2.0, center, Vec3::Y);
    // The box's corners and, on the floor, the far end of the shadows they cast:
    // floor points there lie farther from the light than the box.
    let shadows = shadows_on_floor(min, max, floor_y);
    let floor_rect = floor_rect(shadows);
    let [x0, z0, x1, z1] = floor_rect;
    let floor = [
        Vec3::new(x0, floor_y, z0),
        Vec3::new(x1, floor_y, z0),
        Vec3::new(x0, floor_y, z1),
        Vec3::new(x1, floor_y, z1),
    ];
    let bounds = |points: &mut dyn Iterator<Item = Vec3>| {
        points
            .map(|p| view.transform_point3(p))
            .fold((Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)), |(a, b), c| (a.min(c), b.max(c)))
    };
    let (a, b) = bounds(&mut corners(lo, max).into_iter().chain(floor));
    // Square extent, grown to the next step of 1.25^k, with a margin for the filter.
    let size = size.max(2) & !1;
    // Where shadows are seen: the casters and the floor they fall on.
    let seen = (lo.min(Vec3::new(x0, floor_y, z0)), max.max(Vec3::new(x1, floor_y, z1)));
    // (A pixel too large to be a number sets no limit.)
    let least = pixel.map_or(0.0, |p| p.nearest_in(seen.0, seen.1)) * size as f32 * 0.5;
    let least = if least.is_finite() { least } else { 0.0 };
    let half = ((b.x - a.x).max(b.y - a.y) * 0.5 * 1.05).max(least).max(1e-3);
    let half = 1.25f32.powf(half.log(1.25).ceil());
    let texel = 2.0 * half / size as f32;
    // The casters alone: the floor in their shadow lies behind them.
    let (ca, cb) = bounds(&mut corners(min, max).into_iter());
    let snap = |v: f32| (v / texel).round() * texel;
    let center = Vec2::new(snap((ca.x + cb.x) * 0.5), snap((ca.y + cb.y) * 0.5));
    // Texels from the centre to the far side of the casters, and a border.
    let reach = |lo: f32, hi: f32, c: f32| ((hi - c).max(c - lo) / texel + BORDER).ceil();
    let texels = [reach(ca.x, cb.x, center.x), reach(ca.y, cb.y, center.y)]
        .map(|r| if r.is_finite() { (2.0 * r).min(size as f32) as u32 } else { size });
    // View space looks down -Z: depths are -z.
    let depth = b.z - a.z;
    let (near, far) = (-b.z - depth * 0.05 - 1e-3, -a.z + depth * 0.05 + 1e-3);
    let floor_shadow = floor_shadow_rect(shadows, texel, floor_rect);
    Some(LightView { view, center, near, far, texel, texels, floor_rect, floor_shadow })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fitted_casters_land_inside_the_map_and_the_floor_in_its_depth_range() {
        let (min, max) = (Vec3::new(-1.0, 0.0, -0.5), Vec3::new(1.0, 1.8, 0.5));
        let view = fit_light(min, max, Some(-0.1), SIZE, None).unwrap();
        let texel = view.texel;
        assert!(texel > 0.0 && texel < 0.01);
        assert!(view.texels.iter().all(|&t| t % 2 == 0 && t <= SIZE), "{:?}", view.texels);
        let m = view.on_map(view.texels).view_proj;
        // The casters, with a border of empty texels around them.
        for p in corners(min, max) {
            let c = m.project_point3(p);
            let inside = |v: f32, texels: u32| v.abs() <= 1.0 - 2.0 * BORDER / texels as f32 + 1e-4;
            assert!(
                inside(c.x, view.texels[0]) && inside(c.y, view.texels[1]) && (0.0..=1.0).contains(&c.z),
                "{p} -> {c}"
            );
        }
        // The fast map has texels twice as large.
        let fast = fit_light(min, max, Some(-0.1), FAST_SIZE, None).unwrap();
        assert!((fast.texel - texel * (SIZE / FAST_SIZE) as f32).abs() < texel * 1e-3, "{} vs {texel}", fast.texel);
        // The floor under the far end of the shadow of the box's top lies in
        // the depth range, behind that top, on the same texel.
        let rect = view.floor_rect;
        assert_eq!(rect, floor_rect(shadows_on_floor(min, max, -0.1)));
        let l = key_light_direction();
        for top in corners(min, max).into_iter().filter(|p| p.y == max.y) {
            let shadow = top - l * ((top.y + 0.1) / l.y);
            let (t, f) = (m.project_point3(top), m.project_point3(shadow));
            assert!((t.truncate() - f.truncate()).length() < 1e-4, "{t} vs {f}");
            assert!(t.z < f.z && (0.0..=1.0).contains(&f.z), "{t} vs {f}");
            assert!(shadow.x >= rect[0] && shadow.x <= rect[2] && shadow.z >= rect[1] && shadow.z <= rect[3]);
        }
        // Higher points are closer to the light.
        assert!(m.project_point3(Vec3::new(0.0, 1.8, 0.0)).z < m.project_point3(Vec3::new(0.0, 0.0, 0.0)).z);
    }

    #[test]
    fn the_floors_shadow_is_drawn_wherever_a_lookup_can_find_a_caster() {
        // A crowd on a floor a little below its feet, and a small box high up.
        for (min, max, floor_y) in [
            (Vec3::new(-10.6, 0.0, -8.3), Vec3::new(10.9, 1.6, 8.0), -0.05),
            (Vec3::new(0.2, 2.0, -0.3), Vec3::new(0.5, 2.2, 0.1), 0.0),
        ] {
            let view = fit_light(min, max, Some(floor_y), SIZE, None).unwrap();
            let (texel, drawn, fitted) = (view.texel, view.floor_shadow, view.floor_rect);
            assert!(
                drawn[0] >= fitted[0] && drawn[1] >= fitted[1] && drawn[2] <= fitted[2] && drawn[3] <= fitted[3],
                "{drawn:?} in {fitted:?}"
            );
            // Smaller than the fitted rectangle, which has a margin of a twentieth.
            let area = |r: [f32; 4]| (r[2] - r[0]) * (r[3] - r[1]);
            assert!(area(drawn) < area(fitted) * 0.9, "{drawn:?} vs {fitted:?}");
            // The casters' box in the light's view (x, y): the convex hull of
            // its corners there, anticlockwise.
            let to_light = |p: Vec3| view.view.transform_point3(p).truncate();
            let hull = convex_hull(corners(min, max).map(to_light));
            // Floor points on a fine grid around the fitted rectangle: each
            // whose lookup (raised three texels, as lighting.wgsl) may read a
            // caster's texel lies where the shadow is drawn.
            let mut reached = 0;
            for i in 0..=400 {
                for j in 0..=400 {
                    let x = fitted[0] - 1.0 + (fitted[2] - fitted[0] + 2.0) * i as f32 / 400.0;
                    let z = fitted[1] - 1.0 + (fitted[3] - fitted[1] + 2.0) * j as f32 / 400.0;
                    let q = to_light(Vec3::new(x, floor_y, z) + Vec3::Y * texel * 3.0);
                    // How far a lookup reads around its point: the taps 0.75
                    // texel out and their bilinear texel.
                    if distance_to_polygon(q, &hull) <= 1.75 * texel {
                        reached += 1;
                        assert!(
                            x >= drawn[0] && x <= drawn[2] && z >= drawn[1] && z <= drawn[3],
                            "({x}, {z}) reaches a caster outside {drawn:?}"
                        );
                    }
                }
            }
            assert!(reached > 1000, "{reached}");
        }
    }

    /// The convex hull of `points`, anticlockwise (gift wrapping).
    fn convex_hull(points: [Vec2; 8]) -> Vec<Vec2> {
        let start = points.iter().copied().fold(points[0], |a, p| if (p.x, p.y) < (a.x, a.y) { p } else { a });
        let mut hull = vec![start];
        loop {
            let last = hull[hull.len() - 1];
            // The next corner: every point lies left of last -> next.
            let next = points.iter().copied().filter(|&p| p != last).fold(None, |best: Option<Vec2>, p| match best {
                Some(b) if (b - last).perp_dot(p - last) >= 0.0 => Some(b),
                _ => Some(p),
            });
            match next {
                Some(n) if n != start && hull.len() < 9 => hull.push(n),
                _ => return hull,
            }
        }
    }

    /// The distance from `q` to the convex polygon `hull` (anticlockwise); 0 inside.
    fn distance_to_polygon(q: Vec2, hull: &[Vec2]) -> f32 {
        let edges = hull.iter().zip(hull.iter().cycle().skip(1));
        if edges.clone().all(|(&a, &b)| (b - a).perp_dot(q - a) >= 0.0) {
            return 0.0;
        }
        edges
            .map(|(&a, &b)| {
                let t = ((q - a).dot(b - a) / (b - a).length_squared().max(1e-12)).clamp(0.0, 1.0);
                q.distance(a + (b - a) * t)
            })
            .fold(f32::INFINITY, f32::min)
    }

    #[test]
    fn a_map_trimmed_to_the_casters_keeps_the_texels_of_the_whole_square() {
        // A crowd: wide and flat, its shadows reaching well past it.
        let (min, max) = (Vec3::new(-10.6, 0.0, -8.3), Vec3::new(10.9, 1.6, 8.0));
        let view = fit_light(min, max, Some(0.0), SIZE, None).unwrap();
        let texels = view.texels[0] as u64 * view.texels[1] as u64;
        assert!(texels * 10 < (SIZE as u64).pow(2) * 7, "{:?} of {SIZE}²", view.texels);
        let (trimmed, whole) = (view.on_map(view.texels).view_proj, view.on_map([SIZE, SIZE]).view_proj);
        for p in [Vec3::new(0.3, 1.0, 0.2), Vec3::new(-10.0, 0.1, 7.5), Vec3::new(10.5, 1.5, -8.0)] {
            // Texel coordinates on each map differ by whole texels.
            let at = |m: Mat4, size: u32| (m.project_point3(p).truncate() * 0.5 + 0.5) * size as f32;
            let shift = at(trimmed, view.texels[0]).x - at(whole, SIZE).x;
            assert!((shift - shift.round()).abs() < 1e-2, "{p}: {shift}");
            let shift = at(trimmed, view.texels[1]).y - at(whole, SIZE).y;
            assert!((shift - shift.round()).abs() < 1e-2, "{p}: {shift}");
            assert_eq!(trimmed.project_point3(p).z, whole.project_point3(p).z);
        }
    }

    #[test]
    fn texels_are_never_finer_than_the_pixels_they_are_seen_through() {
        let (min, max) = (Vec3::new(-10.6, 0.0, -8.3), Vec3::new(10.9, 1.6, 8.0));
        let alone = fit_light(min, max, Some(0.0), SIZE, None).unwrap();
        // Seen from about 30 units beyond the crowd's near side on a
        // 720-pixel-tall target with a 45° field of view. Nearest: where the
        // box (or the floor its shadows fall on) comes closest to the eye.
        let eye = Vec3::new(0.0, 12.0, 38.0);
        let camera = crate::Camera::look_at(eye, Vec3::ZERO, 45f32.to_radians(), 16.0 / 9.0);
        let pixel = ScreenPixel::of(&camera, 720).unwrap();
        let [_, _, x1, z1] = alone.floor_rect;
        let nearest = eye.distance(Vec3::new(0.0, 1.6, z1.max(max.z)));
        assert!(x1 > 0.0 && nearest < eye.distance(Vec3::new(0.0, 1.6, max.z)) + 1e-3);
        let expected = 2.0 * nearest * (22.5f32.to_radians()).tan() / 720.0;
        let ScreenPixel::Perspective { per_distance, .. } = pixel else { panic!("{pixel:?}") };
        assert!(
            (per_distance * nearest - expected).abs() < expected * 1e-3,
            "{} vs {expected}",
            per_distance * nearest
        );
        let far = fit_light(min, max, Some(0.0), SIZE, Some(pixel)).unwrap();
        assert!(
            far.texel >= expected * 0.999 && far.texel < expected * 1.25 * 1.001,
            "{} for pixels of {expected}",
            far.texel
        );
        assert!(far.texel > alone.texel * 1.5, "{} vs {}", far.texel, alone.texel);
        // On the same lattice of steps: the square of `SIZE` texels is 1.25^k.
        let k = (far.texel * SIZE as f32 * 0.5).log(1.25);
        assert!((k - k.round()).abs() < 1e-3, "{k}");
        // Fewer texels to clear and fill, with the casters still inside.
        assert!(
            far.texels.iter().zip(alone.texels).all(|(&f, a)| f * 3 < a * 2),
            "{:?} vs {:?}",
            far.texels,
            alone.texels
        );
        let m = far.on_map(far.texels).view_proj;
        assert!(corners(min, max).iter().all(|&p| m.project_point3(p).truncate().abs().max_element() < 1.0));
        // Up close (or with the eye among the casters) the pixels are finer
        // than the square's texels: nothing changes.
        let close = crate::Camera::look_at(Vec3::new(0.0, 1.0, 9.0), Vec3::ZERO, 45f32.to_radians(), 16.0 / 9.0);
        assert_eq!(fit_light(min, max, Some(0.0), SIZE, ScreenPixel::of(&close, 720)), Some(alone));
        let inside = crate::Camera::look_at(Vec3::new(0.0, 1.0, 0.0), Vec3::X, 45f32.to_radians(), 16.0 / 9.0);
        assert_eq!(fit_light(min, max, Some(0.0), SIZE, ScreenPixel::of(&inside, 720)), Some(alone));
        // An orthographic view: its pixel everywhere.
        let flat = fit_light(min, max, Some(0.0), SIZE, Some(ScreenPixel::Orthographic(0.05))).unwrap();
        assert!(flat.texel >= 0.05 && flat.texel < 0.05 * 1.25 * 1.001, "{}", flat.texel);
        // The fast look's square has texels twice as large, which win where
        // they are larger than the pixels.
        let fast = fit_light(min, max, Some(0.0), FAST_SIZE, Some(pixel)).unwrap();
        let least = (2.0 * alone.texel).max(expected);
        assert!(fast.texel >= least * 0.999 && fast.texel < least * 1.25 * 1.001, "{} for {least}", fast.texel);
        // A broken camera sets no limit, nor does a pixel too large to be a number.
        let broken = crate::Camera { view: glam::Mat4::IDENTITY, projection: glam::Mat4::ZERO };
        assert_eq!(ScreenPixel::of(&broken, 720), None);
        let huge = ScreenPixel::Perspective { eye: Vec3::splat(1e30), per_distance: 1e30 };
        assert_eq!(fit_light(min, max, Some(0.0), SIZE, Some(huge)), Some(alone));
    }

    #[test]
    fn maps_are_made_in_steps_and_kept_while_they_fit() {
        assert_eq!(new_size(None, [1000, 300]), Some([1024, 512]));
        assert_eq!(new_size(None, [0, 0]), Some([STEP, STEP]));
        // Kept while it holds the casters and is not two steps too large.
        assert_eq!(new_size(Some([1024, 512]), [1000, 300]), None);
        assert_eq!(new_size(Some([1024, 512]), [800, 300]), None);
        assert_eq!(new_size(Some([1024, 512]), [1010, 512]), None);
        // Grown, or shrunk.
        assert_eq!(new_size(Some([1024, 512]), [1030, 300]), Some([1280, 512]));
        assert_eq!(new_size(Some([1024, 512]), [512, 300]), Some([512, 512]));
    }

    #[test]
    fn empty_or_broken_boxes_give_none() {
        assert!(fit_light(Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY), None, SIZE, None).is_none());
        assert!(fit_light(Vec3::ZERO, Vec3::splat(f32::NAN), Some(0.0), SIZE, None).is_none());
    }
}
