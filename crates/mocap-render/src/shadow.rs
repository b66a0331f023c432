//! The key light's shadow map: a depth texture rendered from the light with an
//! orthographic projection fitted to the shadow casters, sampled with a comparison
//! sampler (soft edges from a small filter in the shader).

use glam::{Mat4, Vec3};

/// Shadow map resolution (square).
pub(crate) const SIZE: u32 = 2048;
/// The fast look's shadow map resolution: a quarter of the texels to clear and
/// draw every frame (a software rasteriser's cost), softer shadow edges.
pub(crate) const FAST_SIZE: u32 = 1024;
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
    crate::pipeline::texture_layout(device, "mocap shadow", wgpu::TextureSampleType::Depth, wgpu::SamplerBindingType::Comparison)
}

/// The shadow map texture and the bind group (of [`layout`]) the lit pipelines
/// sample it through.
pub(crate) struct ShadowMap {
    pub view: wgpu::TextureView,
    pub bind_group: wgpu::BindGroup,
    /// Texels per side.
    pub size: u32,
}

impl ShadowMap {
    /// A map of `size`² texels (at most the device's texture limit).
    pub fn new(device: &wgpu::Device, size: u32, layout: &wgpu::BindGroupLayout) -> ShadowMap {
        let size = size.min(device.limits().max_texture_dimension_2d);
        let texture = device.create_texture(&wgpu::TextureDescriptor {
            label: Some("mocap shadow map"),
            size: wgpu::Extent3d { width: size, height: size, depth_or_array_layers: 1 },
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
}

/// How the key light's shadow map is laid over the scene this frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct LightFit {
    /// World to the shadow map's clip space.
    pub view_proj: Mat4,
    /// Size of one shadow-map texel in world units.
    pub texel: f32,
    /// Where on the floor the shadows fall: min x, min z, max x, max z.
    pub floor_rect: [f32; 4],
}

/// The eight corners of the box `min..max`.
fn corners(min: Vec3, max: Vec3) -> [Vec3; 8] {
    std::array::from_fn(|i| {
        let pick = |bit: usize, a: f32, b: f32| if i & bit == 0 { a } else { b };
        Vec3::new(pick(1, min.x, max.x), pick(2, min.y, max.y), pick(4, min.z, max.z))
    })
}

/// The rectangle (min x, min z, max x, max z) on the floor at `floor_y` where the
/// shadows of casters inside `min..max` fall, with a margin for soft edges.
fn floor_shadow_rect(min: Vec3, max: Vec3, floor_y: f32) -> [f32; 4] {
    let l = key_light_direction();
    let (mut lo, mut hi) = (glam::Vec2::splat(f32::INFINITY), glam::Vec2::splat(f32::NEG_INFINITY));
    for p in corners(min, max) {
        // Along the light down to the floor (points below it stay where they are).
        let q = p - l * ((p.y - floor_y).max(0.0) / l.y);
        let q = glam::Vec2::new(q.x, q.z);
        lo = lo.min(q);
        hi = hi.max(q);
    }
    let margin = (hi - lo).max_element() * 0.05;
    [lo.x - margin, lo.y - margin, hi.x + margin, hi.y + margin]
}

/// Fits the shadow map to casters inside `min..max` (world space) and a floor at
/// height `floor_y` (the box's bottom without one): an orthographic view along the
/// light holding the box and the floor under the far end of its shadows (so the
/// floor lies inside the depth range), and the floor rectangle the shadows fall
/// in. The fitted square is quantised (size in steps of 25%, centre on whole
/// texels of a map `size` texels across) so that shadows do not shimmer as the
/// figures move. `None` for an empty or non-finite box.
pub(crate) fn fit_light(min: Vec3, max: Vec3, floor_y: Option<f32>, size: u32) -> Option<LightFit> {
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
    let floor_rect = floor_shadow_rect(min, max, floor_y);
    let [x0, z0, x1, z1] = floor_rect;
    let floor = [Vec3::new(x0, floor_y, z0), Vec3::new(x1, floor_y, z0), Vec3::new(x0, floor_y, z1), Vec3::new(x1, floor_y, z1)];
    let (mut a, mut b) = (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY));
    for p in corners(lo, max).into_iter().chain(floor) {
        let c = view.transform_point3(p);
        a = a.min(c);
        b = b.max(c);
    }
    // Square extent, grown to the next step of 1.25^k, with a margin for the filter.
    let half = ((b.x - a.x).max(b.y - a.y) * 0.5 * 1.05).max(1e-3);
    let half = 1.25f32.powf(half.log(1.25).ceil());
    let texel = 2.0 * half / size.max(1) as f32;
    let snap = |v: f32| (v / texel).round() * texel;
    let (cx, cy) = (snap((a.x + b.x) * 0.5), snap((a.y + b.y) * 0.5));
    // View space looks down -Z: depths are -z.
    let depth = b.z - a.z;
    let (near, far) = (-b.z - depth * 0.05 - 1e-3, -a.z + depth * 0.05 + 1e-3);
    let projection = glam::camera::rh::proj::directx::orthographic(cx - half, cx + half, cy - half, cy + half, near, far);
    Some(LightFit { view_proj: projection * view, texel, floor_rect })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fitted_box_and_floor_land_inside_the_map() {
        let fit = fit_light(Vec3::new(-1.0, 0.0, -0.5), Vec3::new(1.0, 1.8, 0.5), Some(-0.1), SIZE).unwrap();
        let (m, texel) = (fit.view_proj, fit.texel);
        assert!(texel > 0.0 && texel < 0.01);
        // The fast map covers the same square with texels twice as large.
        let fast = fit_light(Vec3::new(-1.0, 0.0, -0.5), Vec3::new(1.0, 1.8, 0.5), Some(-0.1), FAST_SIZE).unwrap();
        assert!((fast.texel - texel * (SIZE / FAST_SIZE) as f32).abs() < texel * 1e-3, "{} vs {texel}", fast.texel);
        for p in [Vec3::new(-1.0, -0.1, -0.5), Vec3::new(1.0, 1.8, 0.5), Vec3::new(0.0, 0.9, 0.0)] {
            let c = m.project_point3(p);
            assert!(c.x.abs() <= 1.0 && c.y.abs() <= 1.0 && (0.0..=1.0).contains(&c.z), "{p} -> {c}");
        }
        // So does the floor under the far end of the shadow of the box's top.
        let rect = fit.floor_rect;
        assert_eq!(rect, floor_shadow_rect(Vec3::new(-1.0, 0.0, -0.5), Vec3::new(1.0, 1.8, 0.5), -0.1));
        for corner in [Vec3::new(rect[0], -0.1, rect[1]), Vec3::new(rect[2], -0.1, rect[3])] {
            let c = m.project_point3(corner);
            assert!(c.x.abs() <= 1.0 && c.y.abs() <= 1.0 && (0.0..=1.0).contains(&c.z), "{corner} -> {c}");
        }
        // Higher points are closer to the light.
        assert!(m.project_point3(Vec3::new(0.0, 1.8, 0.0)).z < m.project_point3(Vec3::new(0.0, 0.0, 0.0)).z);
    }

    #[test]
    fn empty_or_broken_boxes_give_none() {
        assert!(fit_light(Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY), None, SIZE).is_none());
        assert!(fit_light(Vec3::ZERO, Vec3::splat(f32::NAN), Some(0.0), SIZE).is_none());
    }
}
