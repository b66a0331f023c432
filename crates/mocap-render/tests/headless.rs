//! Draws a scene offscreen on any available adapter (lavapipe on a headless Linux
//! box) and reads the pixels back. No adapter is a failure (`cargo xtask test`
//! installs lavapipe); `MOCAP_SKIP_GPU_TESTS=1` opts out where there is none.

use mocap_render::glam::Vec3;
use mocap_render::{Camera, Capsule, Grid, Line, RenderTarget, Scene, SceneRenderer, Sphere};

const SIZE: u32 = 128;
const FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;

/// A device, a renderer and a `SIZE`² target with `samples` samples. Without an
/// adapter: a panic, or `None` when `MOCAP_SKIP_GPU_TESTS=1` opts out.
fn setup(samples: u32) -> Option<(wgpu::Device, wgpu::Queue, SceneRenderer, RenderTarget)> {
    let instance = wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle());
    let device = pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions::default()))
        .ok()
        .and_then(|adapter| pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor::default())).ok());
    let Some((device, queue)) = device else {
        if std::env::var("MOCAP_SKIP_GPU_TESTS").is_ok_and(|v| v == "1") {
            eprintln!("no wgpu adapter here; skipped (MOCAP_SKIP_GPU_TESTS=1)");
            return None;
        }
        panic!(
            "no wgpu adapter: install Mesa's lavapipe (apt-get install mesa-vulkan-drivers; `cargo xtask test` does) or opt out with MOCAP_SKIP_GPU_TESTS=1"
        );
    };
    let renderer = SceneRenderer::new(&device, FORMAT, samples);
    let target = RenderTarget::new(&device, FORMAT, samples, [SIZE, SIZE]);
    Some((device, queue, renderer, target))
}

fn read_pixels(device: &wgpu::Device, queue: &wgpu::Queue, target: &RenderTarget) -> Vec<u8> {
    assert_eq!(target.size(), [SIZE, SIZE]);
    read_pixels_of(device, queue, target)
}

/// The pixels of a target of any size, rows top to bottom.
fn read_pixels_of(device: &wgpu::Device, queue: &wgpu::Queue, target: &RenderTarget) -> Vec<u8> {
    let [width, height] = target.size();
    let row = width * 4;
    let padded = row.div_ceil(256) * 256;
    let buffer = device.create_buffer(&wgpu::BufferDescriptor {
        label: None,
        size: u64::from(padded * height),
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });
    let mut encoder = device.create_command_encoder(&Default::default());
    encoder.copy_texture_to_buffer(
        wgpu::TexelCopyTextureInfo {
            texture: &target.color,
            mip_level: 0,
            origin: wgpu::Origin3d::ZERO,
            aspect: wgpu::TextureAspect::All,
        },
        wgpu::TexelCopyBufferInfo {
            buffer: &buffer,
            layout: wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(padded),
                rows_per_image: Some(height),
            },
        },
        wgpu::Extent3d { width, height, depth_or_array_layers: 1 },
    );
    queue.submit([encoder.finish()]);
    buffer.map_async(wgpu::MapMode::Read, .., |r| r.expect("map"));
    device.poll(wgpu::PollType::wait_indefinitely()).expect("poll");
    let data = buffer.slice(..).get_mapped_range().expect("mapped");
    data.chunks(padded as usize).flat_map(|r| r[..row as usize].to_vec()).collect()
}

#[test]
fn draws_lines_spheres_and_grid_offscreen() {
    let Some((device, queue, mut renderer, target)) = setup(4) else { return };
    let background = [10, 20, 30, 255];
    let mut scene = Scene { background, ..Scene::default() };
    let camera = Camera::look_at(Vec3::new(0.0, 1.0, 4.0), Vec3::new(0.0, 1.0, 0.0), 0.8, 1.0);

    renderer.render(&device, &queue, &target, &scene, &camera);
    let empty = read_pixels(&device, &queue, &target);
    assert!(empty.chunks(4).all(|p| p == background), "an empty scene is just the background");

    scene.grid = Some(Grid::floor(Vec3::new(-1.0, 0.0, -1.0), Vec3::new(1.0, 0.0, 1.0), 0.5, 0.5));
    scene.lines.push(Line {
        a: Vec3::new(0.0, 0.5, 0.0),
        b: Vec3::new(0.0, 1.5, 0.0),
        color: [255, 0, 0, 255],
        width_px: 3.0,
    });
    scene.spheres.push(Sphere { center: Vec3::new(0.0, 1.5, 0.0), radius: 0.1, color: [0, 255, 0, 255] });
    renderer.render(&device, &queue, &target, &scene, &camera);
    let pixels = read_pixels(&device, &queue, &target);
    let count = |f: &dyn Fn(&[u8]) -> bool| pixels.chunks(4).filter(|p| f(p)).count();
    assert!(count(&|p| p[0] > 200 && p[1] < 60) > 10, "the red bone is drawn");
    assert!(count(&|p| p[1] > 100 && p[0] < 60) > 4, "the green joint is drawn");
    // Y up: the sphere (y = 1.5, eye height 1) lands in the upper half of the image.
    let green_rows: Vec<usize> =
        pixels.chunks(4).enumerate().filter(|(_, p)| p[1] > 100 && p[0] < 60).map(|(i, _)| i / SIZE as usize).collect();
    assert!(green_rows.iter().all(|&r| r < SIZE as usize / 2), "sphere above the centre: rows {green_rows:?}");
}

/// A camera looking straight down from `height` at a 4 m floor around the
/// origin, and a scene with that floor alone.
fn floor_from(height: f32) -> (Camera, Scene) {
    let camera = Camera::look_at(Vec3::new(0.0, height, 0.01), Vec3::ZERO, 0.8, 1.0);
    let scene = Scene { grid: Some(Grid::floor(Vec3::new(-2.0, 0.0, -2.0), Vec3::splat(2.0), 1.0, 10.0)), ..Scene::default() };
    (camera, scene)
}

/// For each pixel of `pixels`: where it is floor (grey, not a red caster)
/// darker than in `bare`, the ratio of its brightness to the bare floor's.
fn floor_shadow(bare: &[u8], pixels: &[u8]) -> Vec<Option<f32>> {
    let luma = |p: &[u8]| p[0] as f32 + p[1] as f32 + p[2] as f32;
    bare.chunks(4)
        .zip(pixels.chunks(4))
        .map(|(b, l)| (l[0] <= l[1] + 10 && luma(l) + 12.0 < luma(b)).then(|| luma(l) / luma(b).max(1.0)))
        .collect()
}

/// How many pixels of `pixels` are floor darker than in `bare` ([`floor_shadow`]).
fn shadowed_count(bare: &[u8], pixels: &[u8]) -> usize {
    floor_shadow(bare, pixels).iter().flatten().count()
}

#[test]
fn capsules_are_lit_and_cast_a_shadow_on_the_floor() {
    let Some((device, queue, mut renderer, target)) = setup(4) else { return };
    // Looking straight down at a floor with a pole standing at its centre.
    let (camera, mut scene) = floor_from(6.0);
    renderer.render(&device, &queue, &target, &scene, &camera);
    let bare = read_pixels(&device, &queue, &target);
    scene.capsules.push(Capsule {
        a: Vec3::new(0.0, 0.0, 0.0),
        b: Vec3::new(0.0, 2.5, 0.0),
        radius: 0.15,
        color: [200, 60, 60, 255],
    });
    renderer.render(&device, &queue, &target, &scene, &camera);
    assert_eq!(renderer.draw_calls(), 4, "shadow map, floor, floor shadow, capsules");
    let lit = read_pixels(&device, &queue, &target);
    let red = lit.chunks(4).filter(|p| p[0] > 100 && p[0] as u32 > 2 * p[1] as u32).count();
    assert!(red > 20, "the capsule is drawn: {red} red pixels");
    // The light is not straight overhead, so the pole's shadow is a streak on the
    // floor beside it (the pole itself covers only a disc from above).
    let darker = shadowed_count(&bare, &lit);
    assert!(darker > 20, "a shadow darkens the floor: {darker} pixels");
    // The fast look: the same capsule and its shadow.
    renderer.fast_look = true;
    renderer.render(&device, &queue, &target, &scene, &camera);
    let fast = read_pixels(&device, &queue, &target);
    renderer.fast_look = false;
    let fast_red = fast.chunks(4).filter(|p| p[0] > 100 && p[0] as u32 > 2 * p[1] as u32).count();
    assert!(
        fast_red.abs_diff(red) * 10 <= red,
        "fast look: the capsule covers about the same pixels ({fast_red} against {red})"
    );
    let fast_darker = shadowed_count(&bare, &fast);
    assert!(fast_darker > 20, "fast look: a shadow darkens the floor: {fast_darker} pixels");
    scene.shadows = false;
    renderer.render(&device, &queue, &target, &scene, &camera);
    let unshadowed = read_pixels(&device, &queue, &target);
    let darker = shadowed_count(&bare, &unshadowed);
    assert_eq!(darker, 0, "no shadow when shadows are off");
    // Shadows on again (their own pipelines, made before): the first picture.
    scene.shadows = true;
    renderer.render(&device, &queue, &target, &scene, &camera);
    assert!(read_pixels(&device, &queue, &target) == lit, "shadows on again draw the same picture as before");
    scene.shadows = false;

    // A line inside the pole's top is hidden; as an overlay line it shows.
    let green = |pixels: &[u8]| pixels.chunks(4).filter(|p| p[1] > 150 && p[0] < 100).count();
    let inside =
        Line { a: Vec3::new(-0.1, 2.5, 0.0), b: Vec3::new(0.1, 2.5, 0.0), color: [0, 255, 0, 255], width_px: 3.0 };
    scene.lines.push(inside);
    renderer.render(&device, &queue, &target, &scene, &camera);
    assert_eq!(green(&read_pixels(&device, &queue, &target)), 0, "a line inside a capsule is hidden");
    scene.lines.clear();
    scene.overlay_lines.push(inside);
    renderer.render(&device, &queue, &target, &scene, &camera);
    assert!(green(&read_pixels(&device, &queue, &target)) > 3, "an overlay line shows through");
}

#[test]
fn the_fast_look_darkens_the_floor_once_under_crossing_casters_where_the_map_does() {
    let Some((device, queue, mut renderer, target)) = setup(1) else { return };
    let (camera, mut scene) = floor_from(6.0);
    renderer.render(&device, &queue, &target, &scene, &camera);
    let bare = read_pixels(&device, &queue, &target);
    // Two bars crossing above the floor (their shadows overlap) and a pole.
    let bar = |a: Vec3, b: Vec3, radius: f32| Capsule { a, b, radius, color: [200, 60, 60, 255] };
    scene.capsules.push(bar(Vec3::new(-1.2, 1.0, -0.6), Vec3::new(1.2, 1.0, 0.6), 0.2));
    scene.capsules.push(bar(Vec3::new(-1.2, 1.2, 0.6), Vec3::new(1.2, 1.2, -0.6), 0.2));
    scene.capsules.push(bar(Vec3::new(0.8, 0.0, 0.8), Vec3::new(0.8, 1.5, 0.8), 0.15));
    // Floor pixels darkened (not the red capsules), as a ratio to the bare floor.
    let shadowed = |pixels: &[u8]| floor_shadow(&bare, pixels);
    renderer.render(&device, &queue, &target, &scene, &camera);
    let map = shadowed(&read_pixels(&device, &queue, &target));
    renderer.fast_look = true;
    renderer.render(&device, &queue, &target, &scene, &camera);
    let fast = shadowed(&read_pixels(&device, &queue, &target));
    let (in_map, in_fast) = (map.iter().flatten().count(), fast.iter().flatten().count());
    assert!(in_map > 500, "the casters shadow the floor: {in_map} pixels");
    // The footprints fall where the map's shadow does, edges aside (the full
    // quality's soft edge reaches a little farther than the hard one).
    let only_fast = map.iter().zip(&fast).filter(|(m, f)| m.is_none() && f.is_some()).count();
    let only_map = map.iter().zip(&fast).filter(|(m, f)| m.is_some() && f.is_none()).count();
    assert!(
        only_fast * 8 < in_map && only_map * 4 < in_map,
        "the same shadow: {in_fast} pixels against the map's {in_map}; {only_fast} only in the fast look, {only_map} only with the map"
    );
    // One darkness, where one caster's shadow falls and where two overlap.
    let mut ratios: Vec<f32> = fast.iter().flatten().copied().collect();
    ratios.sort_by(f32::total_cmp);
    let (darkest, middle) = (ratios[0], ratios[ratios.len() / 2]);
    assert!(middle - darkest < 0.06, "darkened once: the darkest {darkest}, the median {middle}");
    let full_strength = map.iter().flatten().copied().fold(f32::MAX, f32::min);
    assert!((middle - full_strength).abs() < 0.06, "as dark as the map's full shadow: {middle} against {full_strength}");
}

#[test]
fn a_shadow_falls_where_the_key_light_projects_its_caster() {
    let Some((device, queue, mut renderer, target)) = setup(1) else { return };
    let (camera, mut scene) = floor_from(8.0);
    // A ball in the air, and a small one off to a side so that the fitted shadow
    // map is not symmetric about the ball (a mirrored lookup would then miss it).
    let ball = Vec3::new(0.0, 1.5, 0.0);
    scene.capsules.push(Capsule { a: ball, b: ball, radius: 0.3, color: [255, 0, 0, 255] });
    let pebble = Vec3::new(-1.5, 0.05, 1.0);
    scene.capsules.push(Capsule { a: pebble, b: pebble, radius: 0.05, color: [255, 0, 0, 255] });
    // Full quality, then the fast look (a smaller map, one lookup per pixel).
    for fast in [false, true] {
        renderer.fast_look = fast;
        renderer.render(&device, &queue, &target, &scene, &camera);
        let pixels = read_pixels(&device, &queue, &target);
        // Dark grey (shadowed floor) pixels: their centroid on screen.
        let (mut sum, mut n) = ([0.0f32; 2], 0.0f32);
        for (i, p) in pixels.chunks(4).enumerate() {
            let luma = p[0] as u32 + p[1] as u32 + p[2] as u32;
            if luma < 125 && (p[0] as i32 - p[2] as i32).abs() < 30 {
                sum[0] += (i % SIZE as usize) as f32;
                sum[1] += (i / SIZE as usize) as f32;
                n += 1.0;
            }
        }
        assert!(n > 30.0, "fast {fast}: the ball casts a shadow ({n} pixels)");
        let light = mocap_render::key_light_direction();
        let on_floor = ball - light * (ball.y / light.y);
        let c = (camera.projection * camera.view).project_point3(on_floor);
        let expected = [(c.x * 0.5 + 0.5) * SIZE as f32, (0.5 - c.y * 0.5) * SIZE as f32];
        let found = [sum[0] / n, sum[1] / n];
        let off = ((found[0] - expected[0]).powi(2) + (found[1] - expected[1]).powi(2)).sqrt();
        assert!(off < 3.0, "fast {fast}: shadow centre at {found:?}, expected {expected:?}");
    }
}

#[test]
fn a_shadow_keeps_its_shape_on_a_map_longer_one_way() {
    // The shadow map holds only the casters, so a row of them makes it long
    // and narrow: a ball's shadow must stay as wide and as long (on screen,
    // from above) as with the ball alone.
    let Some((device, queue, mut renderer, target)) = setup(1) else { return };
    let camera = Camera::look_at(Vec3::new(0.0, 8.0, 0.01), Vec3::ZERO, 0.8, 1.0);
    let ball = Vec3::new(0.0, 1.0, 0.0);
    let light = mocap_render::key_light_direction();
    let on_floor = ball - light * (ball.y / light.y);
    let c = (camera.projection * camera.view).project_point3(on_floor);
    let centre = [(c.x * 0.5 + 0.5) * SIZE as f32, (0.5 - c.y * 0.5) * SIZE as f32];
    // Width and height (pixels) of the shadowed floor around the ball's shadow.
    let mut extent = |scene: &Scene| {
        renderer.render(&device, &queue, &target, scene, &camera);
        let (mut lo, mut hi) = ([f32::MAX; 2], [f32::MIN; 2]);
        for (i, p) in read_pixels(&device, &queue, &target).chunks(4).enumerate() {
            let at = [(i % SIZE as usize) as f32, (i / SIZE as usize) as f32];
            let near = (at[0] - centre[0]).hypot(at[1] - centre[1]) < 20.0;
            let luma = p[0] as u32 + p[1] as u32 + p[2] as u32;
            if near && luma < 125 && (p[0] as i32 - p[2] as i32).abs() < 30 {
                for k in 0..2 {
                    lo[k] = lo[k].min(at[k]);
                    hi[k] = hi[k].max(at[k]);
                }
            }
        }
        [hi[0] - lo[0] + 1.0, hi[1] - lo[1] + 1.0]
    };
    let floor = Grid::floor(Vec3::new(-4.0, 0.0, -4.0), Vec3::splat(4.0), 1.0, 10.0);
    let mut scene = Scene { grid: Some(floor), ..Scene::default() };
    scene.capsules.push(Capsule { a: ball, b: ball, radius: 0.3, color: [255, 0, 0, 255] });
    let alone = extent(&scene);
    assert!(alone[0] >= 8.0 && alone[1] >= 8.0, "the ball casts a shadow: {alone:?}");
    // Pebbles in a row far to one side.
    for k in 0..8 {
        let pebble = Vec3::new(1.0 + 0.4 * k as f32, 0.05, -3.0);
        scene.capsules.push(Capsule { a: pebble, b: pebble, radius: 0.05, color: [255, 0, 0, 255] });
    }
    let with_row = extent(&scene);
    for k in 0..2 {
        assert!(
            (with_row[k] - alone[k]).abs() <= 1.0,
            "the shadow keeps its size: {with_row:?} with the row, {alone:?} alone"
        );
    }
}

/// A square facing the camera (two triangles) at `x` for each frame, with a
/// texture whose left half is red and right half blue.
fn quad_mesh(xs: &[f32], skin: bool) -> std::sync::Arc<mocap_render::MorphMeshData> {
    use mocap_render::{MorphMeshData, MorphVertex, SkinImage};
    let corners =
        [(-0.3f32, 0.7f32, 0.0f32, 0.0f32), (0.3, 0.7, 1.0, 0.0), (0.3, 1.3, 1.0, 1.0), (-0.3, 1.3, 0.0, 1.0)];
    let vertices = xs
        .iter()
        .flat_map(|x| {
            corners
                .iter()
                .map(move |&(cx, cy, _, _)| MorphVertex { position: [x + cx, cy, 0.0], normal: [0.0, 0.0, 1.0] })
        })
        .collect();
    let uvs = corners.iter().map(|&(_, _, u, v)| [u, v]).collect();
    let half = |c: [u8; 4]| std::iter::repeat_n(c, 8).flatten();
    let skin = skin.then(|| SkinImage {
        width: 16,
        height: 1,
        pixels: half([230, 20, 20, 255]).chain(half([20, 20, 230, 255])).collect(),
    });
    std::sync::Arc::new(MorphMeshData::new(4, vertices, uvs, vec![0, 1, 2, 0, 2, 3], skin).expect("a valid mesh"))
}

/// Columns of the image where pixels pass `f`.
fn columns(pixels: &[u8], f: impl Fn(&[u8]) -> bool) -> Vec<usize> {
    let mut cols: Vec<usize> =
        pixels.chunks(4).enumerate().filter(|(_, p)| f(p)).map(|(i, _)| i % SIZE as usize).collect();
    cols.sort_unstable();
    cols.dedup();
    cols
}

#[test]
fn meshes_blend_two_frames_on_the_gpu_and_show_their_skin() {
    use mocap_render::glam::Mat4;
    use mocap_render::{MeshDraw, NEUTRAL_TINT};
    let Some((device, queue, mut renderer, target)) = setup(1) else { return };
    let background = [10, 20, 30, 255];
    let camera = Camera::look_at(Vec3::new(0.0, 1.0, 4.0), Vec3::new(0.0, 1.0, 0.0), 0.8, 1.0);
    let mesh = quad_mesh(&[-1.0, 1.0], true);
    let draw = |frames: [u32; 2], blend: f32| MeshDraw {
        mesh: mesh.clone(),
        frames,
        blend,
        transform: Mat4::IDENTITY,
        tint: [255; 4],
    };
    let mut scene = Scene { background, shadows: false, ..Scene::default() };
    let mut centre = |frames, blend, scene: &mut Scene| {
        scene.meshes = vec![draw(frames, blend)];
        renderer.render(&device, &queue, &target, scene, &camera);
        let px = read_pixels(&device, &queue, &target);
        let cols = columns(&px, |p| p != background);
        assert!(!cols.is_empty(), "frames {frames:?} at {blend}: the mesh is drawn");
        (cols[0] + cols[cols.len() - 1]) as f32 / 2.0 / SIZE as f32
    };
    let (a, b, half) =
        (centre([0, 0], 0.0, &mut scene), centre([1, 1], 0.0, &mut scene), centre([0, 1], 0.5, &mut scene));
    assert!(a < 0.4 && b > 0.6, "frame 0 on the left ({a}), frame 1 on the right ({b})");
    assert!((half - 0.5).abs() < 0.03, "halfway between the frames is the middle ({half})");
    let quarter = centre([0, 1], 0.25, &mut scene);
    assert!((quarter - (a + (b - a) * 0.25)).abs() < 0.03, "a quarter of the way ({quarter})");
    // The skin: red on the left half of the square, blue on the right.
    scene.meshes = vec![draw([0, 1], 0.5)];
    renderer.render(&device, &queue, &target, &scene, &camera);
    let px = read_pixels(&device, &queue, &target);
    let red = columns(&px, |p| p[0] > 120 && p[2] < 80);
    let blue = columns(&px, |p| p[2] > 120 && p[0] < 80);
    assert!(red.len() > 5 && blue.len() > 5 && red[red.len() - 1] < blue[0], "red left of blue: {red:?} {blue:?}");
    // Without a skin: the neutral tint, grey.
    scene.meshes = vec![MeshDraw {
        mesh: quad_mesh(&[0.0], false),
        frames: [0, 0],
        blend: 0.0,
        transform: Mat4::IDENTITY,
        tint: NEUTRAL_TINT,
    }];
    renderer.render(&device, &queue, &target, &scene, &camera);
    let px = read_pixels(&device, &queue, &target);
    let drawn: Vec<&[u8]> = px.chunks(4).filter(|p| *p != background).collect();
    assert!(drawn.len() > 100 && drawn.iter().all(|p| p[0].abs_diff(p[2]) < 50), "a grey square");
    assert_eq!(renderer.draw_calls(), 1, "one draw per mesh (no floor, no shadows)");
}

#[test]
fn a_mesh_casts_a_shadow_on_the_floor() {
    use mocap_render::MeshDraw;
    use mocap_render::glam::Mat4;
    let Some((device, queue, mut renderer, target)) = setup(1) else { return };
    let camera = Camera::look_at(Vec3::new(0.0, 3.0, 4.0), Vec3::new(0.0, 0.5, 0.0), 0.8, 1.0);
    let mesh = quad_mesh(&[0.0], false);
    // Turn the square to lie flat above the floor, so it shades a patch of it.
    let flat = Mat4::from_translation(Vec3::new(0.0, 0.3, 0.0))
        * Mat4::from_rotation_x(-std::f32::consts::FRAC_PI_2)
        * Mat4::from_translation(Vec3::new(0.0, -1.0, 0.0));
    let mut scene = Scene { background: [10, 20, 30, 255], ..Scene::default() };
    scene.grid = Some(Grid::floor(Vec3::new(-2.0, 0.0, -2.0), Vec3::new(2.0, 0.0, 2.0), 1.0, 0.5));
    scene.meshes = vec![MeshDraw { mesh, frames: [0, 0], blend: 0.0, transform: flat, tint: [255; 4] }];
    let mut shot = |shadows: bool| {
        scene.shadows = shadows;
        renderer.render(&device, &queue, &target, &scene, &camera);
        read_pixels(&device, &queue, &target)
    };
    let (lit, shadowed) = (shot(false), shot(true));
    let darker = lit
        .chunks(4)
        .zip(shadowed.chunks(4))
        .filter(|(a, b)| {
            u32::from(a[0]) + u32::from(a[1]) + u32::from(a[2])
                > u32::from(b[0]) + u32::from(b[1]) + u32::from(b[2]) + 20
        })
        .count();
    assert!(darker > 50, "the floor under the mesh is darker with shadows ({darker} pixels)");
}

/// GPU skinning against the same blend done on the CPU: a bent strip of quads
/// weighted between two joints, drawn skinned, then drawn from CPU-skinned
/// vertices as a static mesh; the pictures agree.
#[test]
fn gpu_skinning_matches_the_cpu_blend() {
    use mocap_render::glam::{Mat4, Quat};
    use mocap_render::{MeshDraw, MorphMeshData, MorphVertex, SkinnedDraw, SkinnedMeshData};
    let Some((device, queue, mut renderer, target)) = setup(1) else { return };
    // A strip along +Y from 0 to 2 facing +Z, 9 rows; weights move from joint 0 to joint 1 along it.
    let (mut positions, mut normals, mut joints, mut weights, mut uvs) =
        (Vec::new(), Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for row in 0..9 {
        let y = row as f32 * 0.25;
        let w1 = (y - 0.5).clamp(0.0, 1.0);
        for x in [-0.2f32, 0.2] {
            positions.push(Vec3::new(x, y, 0.0));
            normals.push(Vec3::Z);
            joints.push([0, 1, 0, 0]);
            weights.push([1.0 - w1, w1, 0.0, 0.0]);
            uvs.push([0.0, 0.0]);
        }
    }
    let mut indices = Vec::new();
    for row in 0..8u32 {
        let (a, b) = (row * 2, row * 2 + 2);
        indices.extend([a, a + 1, b + 1, a, b + 1, b]);
    }
    let mesh =
        std::sync::Arc::new(SkinnedMeshData::new(&positions, &normals, &joints, &weights, indices.clone(), 2).unwrap());
    // Joint 1 at y = 1 turns 60° about Z: its matrix is T(1)·R·T(-1) (bind → posed).
    let bend = Mat4::from_translation(Vec3::Y)
        * Mat4::from_quat(Quat::from_rotation_z(1.0))
        * Mat4::from_translation(-Vec3::Y);
    let matrices = vec![Mat4::IDENTITY, bend];
    let camera = Camera::look_at(Vec3::new(0.0, 1.0, 4.0), Vec3::new(0.0, 1.0, 0.0), 0.8, 1.0);
    let tint = [200, 180, 160, 255];
    let mut scene = Scene { shadows: false, ..Scene::default() };
    scene.skinned =
        vec![SkinnedDraw { mesh: mesh.clone(), coarse: None, matrices: matrices.clone(), tint, weights_view: false, shape: None }];
    renderer.render(&device, &queue, &target, &scene, &camera);
    let gpu = read_pixels(&device, &queue, &target);
    // The CPU blend: Σ wᵢ·Mᵢ applied to each vertex.
    let vertices: Vec<MorphVertex> = positions
        .iter()
        .zip(&normals)
        .zip(&weights)
        .map(|((p, n), w)| {
            let m = matrices[0] * w[0] + matrices[1] * w[1];
            MorphVertex {
                position: m.transform_point3(*p).to_array(),
                normal: m.transform_vector3(*n).normalize().to_array(),
            }
        })
        .collect();
    let cpu_mesh = std::sync::Arc::new(MorphMeshData::new(positions.len(), vertices, uvs, indices, None).unwrap());
    scene.skinned.clear();
    scene.meshes = vec![MeshDraw { mesh: cpu_mesh, frames: [0, 0], blend: 0.0, transform: Mat4::IDENTITY, tint }];
    renderer.render(&device, &queue, &target, &scene, &camera);
    let cpu = read_pixels(&device, &queue, &target);
    let background = Scene::default().background;
    let drawn = gpu.chunks(4).filter(|p| *p != background).count();
    let differ = gpu
        .chunks(4)
        .zip(cpu.chunks(4))
        .filter(|(a, b)| a.iter().zip(b.iter()).any(|(x, y)| x.abs_diff(*y) > 8))
        .count();
    assert!(drawn > 300, "the skinned strip is drawn ({drawn} pixels)");
    assert!(differ * 100 < drawn, "GPU and CPU skinning agree: {differ} of {drawn} pixels differ");
    // The bend is real: the top of the strip moved left of the bottom.
    let columns_of = |rows: std::ops::Range<usize>| {
        let cols: Vec<usize> = gpu
            .chunks(4)
            .enumerate()
            .filter(|(i, p)| *p != background && rows.contains(&(i / SIZE as usize)))
            .map(|(i, _)| i % SIZE as usize)
            .collect();
        cols.iter().sum::<usize>() as f32 / cols.len().max(1) as f32
    };
    assert!(columns_of(10..40) + 10.0 < columns_of(80..110), "bent toward -X at the top");
    // The weights view colours by joint, not by the tint.
    scene.meshes.clear();
    scene.skinned = vec![SkinnedDraw { mesh, coarse: None, matrices, tint, weights_view: true, shape: None }];
    renderer.render(&device, &queue, &target, &scene, &camera);
    let weights_view = read_pixels(&device, &queue, &target);
    let changed = gpu
        .chunks(4)
        .zip(weights_view.chunks(4))
        .filter(|(a, b)| a.iter().zip(b.iter()).any(|(x, y)| x.abs_diff(*y) > 30))
        .count();
    assert!(changed * 2 > drawn, "the weights view recolours the body ({changed} of {drawn})");
}

#[test]
fn a_multisampled_renderer_also_draws_into_a_single_sample_target_and_blit_copies_it() {
    let Some((device, queue, mut renderer, target)) = setup(4) else { return };
    let single = RenderTarget::new(&device, FORMAT, 1, [SIZE, SIZE]);
    let (camera, mut scene) = floor_from(6.0);
    scene.capsules.push(Capsule { a: Vec3::ZERO, b: Vec3::new(0.0, 2.5, 0.0), radius: 0.3, color: [200, 60, 60, 255] });
    // The same scene into both: the images differ only along edges.
    renderer.render(&device, &queue, &target, &scene, &camera);
    let smooth = read_pixels(&device, &queue, &target);
    renderer.render(&device, &queue, &single, &scene, &camera);
    let fast = read_pixels(&device, &queue, &single);
    let close = smooth
        .chunks(4)
        .zip(fast.chunks(4))
        .filter(|(a, b)| a.iter().zip(b.iter()).all(|(x, y)| x.abs_diff(*y) <= 8))
        .count();
    assert!(close as f32 > 0.9 * (SIZE * SIZE) as f32, "{close} of {} pixels alike", SIZE * SIZE);
    let red = |p: &[u8]| p.chunks(4).filter(|p| p[0] > 100 && p[0] as u32 > 2 * p[1] as u32).count();
    assert!(red(&fast) > 100, "the capsule is drawn with one sample");
    // And back: the multisampled target still draws as before.
    renderer.render(&device, &queue, &target, &scene, &camera);
    assert_eq!(read_pixels(&device, &queue, &target), smooth);

    // Blit: the frame copied onto another pass's viewport, texel for texel.
    let blit = mocap_render::Blit::new(&device, FORMAT);
    let source = blit.source(&device, &target);
    let copy = RenderTarget::new(&device, FORMAT, 1, [SIZE, SIZE]);
    let mut encoder = device.create_command_encoder(&Default::default());
    {
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: None,
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: &copy.color_view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations { load: wgpu::LoadOp::Clear(wgpu::Color::BLACK), store: wgpu::StoreOp::Store },
            })],
            depth_stencil_attachment: None,
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        blit.draw(&mut pass, &source);
    }
    queue.submit([encoder.finish()]);
    let copied = read_pixels(&device, &queue, &copy);
    let rgb = |p: &[u8]| p.chunks(4).flat_map(|p| p[..3].to_vec()).collect::<Vec<u8>>();
    assert_eq!(rgb(&copied), rgb(&smooth), "the copy is the frame, the right way up");
}

/// Renders `scene` into a new single-sampled `format` target and reads it back,
/// in the fast look or not.
fn render_in(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    format: wgpu::TextureFormat,
    scene: &Scene,
    camera: &Camera,
    fast_look: bool,
) -> Vec<u8> {
    let mut renderer = SceneRenderer::new(device, format, 1);
    renderer.fast_look = fast_look;
    let target = RenderTarget::new(device, format, 1, [SIZE, SIZE]);
    renderer.render(device, queue, &target, scene, camera);
    read_pixels(device, queue, &target)
}

#[test]
fn the_floor_has_its_colours_on_srgb_and_plain_targets() {
    // The floor's colours reach the shader as the target stores them (linear
    // for an sRGB target, encoded for a plain one, the web's): the stored bytes
    // of its middle, where lines are absent and it is opaque, are its sRGB colour
    // on both.
    let Some((device, queue, _, _)) = setup(1) else { return };
    let mut grid = Grid::floor(Vec3::new(-2.0, 0.0, -2.0), Vec3::new(2.0, 0.0, 2.0), 0.0, 10.0);
    grid.color[3] = 0;
    grid.major_color[3] = 0;
    let scene = Scene { background: [10, 20, 30, 255], grid: Some(grid), ..Scene::default() };
    let camera = Camera::look_at(Vec3::new(0.0, 3.0, 0.5), Vec3::ZERO, 0.8, 1.0);
    let middle = |pixels: &[u8]| {
        let at = ((SIZE / 2) * SIZE + SIZE / 2) as usize * 4;
        pixels[at..at + 4].to_vec()
    };
    for format in [wgpu::TextureFormat::Rgba8UnormSrgb, wgpu::TextureFormat::Rgba8Unorm] {
        let pixel = middle(&render_in(&device, &queue, format, &scene, &camera, false));
        let close = pixel.iter().zip(grid.floor_color).all(|(&p, c)| p.abs_diff(c) <= 1);
        assert!(close, "{format:?}: the floor's middle is {pixel:?}, its colour {:?}", grid.floor_color);
    }
    // With lines: a line crossing the middle is lighter than the floor on both.
    let lined =
        Scene { grid: Some(Grid::floor(Vec3::new(-2.0, 0.0, -2.0), Vec3::new(2.0, 0.0, 2.0), 0.0, 0.5)), ..scene };
    let camera = Camera::look_at(Vec3::new(0.0, 3.0, 0.001), Vec3::new(0.0, 0.0, 0.0), 0.8, 1.0);
    for format in [wgpu::TextureFormat::Rgba8UnormSrgb, wgpu::TextureFormat::Rgba8Unorm] {
        let pixels = render_in(&device, &queue, format, &lined, &camera, false);
        let row = &pixels[((SIZE / 2) * SIZE * 4) as usize..((SIZE / 2 + 1) * SIZE * 4) as usize];
        let brightest = row.chunks(4).map(|p| p[1]).max().unwrap_or(0);
        assert!(
            brightest > grid.floor_color[1] + 20,
            "{format:?}: no line across the middle row (brightest green {brightest})"
        );
    }
}

#[test]
fn lit_surfaces_store_the_same_colours_on_srgb_and_plain_targets() {
    // A plain unorm target (the web's) gets its sRGB encoding in the shader
    // (`to_target`); an sRGB target encodes in hardware. One sample per pixel
    // in the fast look (outlines not blended, which sRGB targets do in linear
    // space and plain ones in encoded), so both cover the same pixels.
    let Some((device, queue, _, _)) = setup(1) else { return };
    let camera = Camera::look_at(Vec3::new(0.0, 1.0, 3.0), Vec3::new(0.0, 1.0, 0.0), 0.8, 1.0);
    let mut scene = Scene { background: [0, 0, 0, 255], ..Scene::default() };
    for (k, color) in [[200, 60, 60, 255], [40, 160, 220, 255], [230, 230, 230, 255]].into_iter().enumerate() {
        let x = k as f32 * 0.5 - 0.5;
        scene.capsules.push(Capsule { a: Vec3::new(x, 0.3, 0.0), b: Vec3::new(x, 1.7, 0.0), radius: 0.2, color });
    }
    scene.spheres.push(Sphere { center: Vec3::new(0.0, 1.9, 0.5), radius: 0.15, color: [90, 200, 90, 255] });
    let exact = render_in(&device, &queue, wgpu::TextureFormat::Rgba8UnormSrgb, &scene, &camera, true);
    let shader = render_in(&device, &queue, wgpu::TextureFormat::Rgba8Unorm, &scene, &camera, true);
    let lit = exact.chunks(4).filter(|p| p[..3].iter().any(|&v| v > 40)).count();
    assert!(lit > 2000, "the figures are drawn ({lit} pixels)");
    let worst = exact.iter().zip(&shader).map(|(a, b)| a.abs_diff(*b)).max().unwrap_or(0);
    assert!(worst <= 2, "stored values differ by up to {worst} between the exact and the shader's encoding");
}

/// Where the ray from the eye through the centre of pixel (`x`, `y`) stands to
/// the capsule `a`–`b` of radius `r`: its distance outside the outline in
/// pixels (negative inside), and the view depth where it first meets the
/// surface, found by sphere tracing (`None` if it does not). In f64, written
/// apart from the shader.
fn ray_against_capsule(camera: &Camera, x: u32, y: u32, a: Vec3, b: Vec3, r: f32) -> (f64, Option<f64>) {
    use mocap_render::glam::{DMat4, DVec3, DVec4};
    let view = camera.view.as_dmat4();
    let inverse: DMat4 = (camera.projection.as_dmat4() * view).inverse();
    let ndc = [(x as f64 + 0.5) / SIZE as f64 * 2.0 - 1.0, 1.0 - (y as f64 + 0.5) / SIZE as f64 * 2.0];
    let unproject = |z: f64| {
        let p = inverse * DVec4::new(ndc[0], ndc[1], z, 1.0);
        p.truncate() / p.w
    };
    let eye = view.inverse().w_axis.truncate();
    let dir = (unproject(0.5) - eye).normalize();
    let (a, b, r) = (a.as_dvec3(), b.as_dvec3(), r as f64);
    let ab = b - a;
    let to_axis = |p: DVec3| {
        let s = if ab.length_squared() > 0.0 { ((p - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0) } else { 0.0 };
        (p - (a + ab * s)).length()
    };
    // The ray's least distance to the axis: the distance is convex along the
    // ray, so a golden-section search finds it.
    let (mut lo, mut hi) = (0.0f64, 1e3f64);
    for _ in 0..200 {
        let (m1, m2) = (lo + (hi - lo) * 0.382, lo + (hi - lo) * 0.618);
        if to_axis(eye + dir * m1) < to_axis(eye + dir * m2) { hi = m2 } else { lo = m1 }
    }
    let t_close = (lo + hi) * 0.5;
    let depth_of = |t: f64| -(view * (eye + dir * t).extend(1.0)).z;
    let pixel = 2.0 / (camera.projection.y_axis.y as f64 * SIZE as f64) * depth_of(t_close);
    let outside = (to_axis(eye + dir * t_close) - r) / pixel;
    let mut t = 0.0;
    for _ in 0..10_000 {
        let d = to_axis(eye + dir * t) - r;
        if d < 1e-9 {
            return (outside, Some(depth_of(t)));
        }
        t += d;
        if t > t_close + r * 4.0 + 1.0 {
            break;
        }
    }
    (outside, None)
}

#[test]
fn capsule_impostors_cover_exactly_what_their_rays_meet() {
    // One sample in the fast look: a pixel is drawn when its centre's ray
    // meets the capsule (full quality blends a fringe, tested below).
    let Some((device, queue, mut renderer, target)) = setup(1) else { return };
    renderer.fast_look = true;
    let background = [0, 0, 0, 255];
    let eye = Vec3::new(0.0, 0.0, 3.0);
    let camera = Camera::look_at(eye, Vec3::ZERO, 0.8, 1.0);
    let near = 3.0 * 0.01;
    let cases = [
        ("long, near and slanted", Vec3::new(-1.5, -0.5, -1.0), Vec3::new(1.2, 0.8, 0.5), 0.3),
        ("at the edge of the view", Vec3::new(1.1, 1.0, 0.0), Vec3::new(1.3, 0.2, -0.5), 0.25),
        ("pointing at the eye", Vec3::new(0.1, 0.0, 0.0), Vec3::new(0.1, 0.0, 1.5), 0.3),
        ("a ball", Vec3::new(-0.8, -0.8, 0.5), Vec3::new(-0.8, -0.8, 0.5), 0.4),
        ("filling the view", Vec3::new(-0.3, 0.0, 1.8), Vec3::new(0.3, 0.0, 1.8), 0.5),
        ("through the eye's plane", Vec3::new(0.5, 0.1, 4.0), Vec3::new(0.5, -0.1, -2.0), 0.2),
        ("thin and far", Vec3::new(-0.5, 0.3, -20.0), Vec3::new(0.6, -0.2, -22.0), 0.02),
    ];
    for (what, a, b, r) in cases {
        let scene = Scene {
            background,
            capsules: vec![Capsule { a, b, radius: r, color: [255, 255, 255, 255] }],
            shadows: false,
            ..Scene::default()
        };
        renderer.render(&device, &queue, &target, &scene, &camera);
        let pixels = read_pixels(&device, &queue, &target);
        let (mut drawn, mut wrong) = (0, Vec::new());
        for (i, p) in pixels.chunks(4).enumerate() {
            let (x, y) = ((i % SIZE as usize) as u32, (i / SIZE as usize) as u32);
            let (outside, hit) = ray_against_capsule(&camera, x, y, a, b, r);
            let is_drawn = p != background;
            drawn += is_drawn as usize;
            // Pixels within a third of a pixel of the outline, or whose hit is
            // at the near plane, may go either way.
            let meets = hit.filter(|&depth| depth >= near);
            let clear_cut = outside.abs() > 0.3 && hit.is_none_or(|depth| (depth - near).abs() > 1e-3);
            if clear_cut && is_drawn != meets.is_some() {
                wrong.push((x, y, outside, hit));
            }
        }
        assert!(drawn > 0, "{what}: drawn");
        assert!(
            wrong.is_empty(),
            "{what}: {} of {drawn} drawn pixels wrong, e.g. {:?}",
            wrong.len(),
            &wrong[..wrong.len().min(5)]
        );
    }
    // Beside and behind the eye, out of view: nothing drawn.
    for (a, b) in
        [(Vec3::new(1.0, 0.0, 3.2), Vec3::new(1.5, 0.0, 2.8)), (Vec3::new(0.0, 0.0, 3.5), Vec3::new(0.0, 0.3, 4.0))]
    {
        let scene = Scene {
            background,
            capsules: vec![Capsule { a, b, radius: 0.2, color: [255, 255, 255, 255] }],
            shadows: false,
            ..Scene::default()
        };
        renderer.render(&device, &queue, &target, &scene, &camera);
        assert!(
            read_pixels(&device, &queue, &target).chunks(4).all(|p| p == background),
            "a capsule out of view at {a}-{b} draws nothing"
        );
    }
}

#[test]
fn capsule_impostors_hide_each_other_by_their_true_depth() {
    let Some((device, queue, mut renderer, target)) = setup(1) else { return };
    let camera = Camera::look_at(Vec3::new(0.0, 0.0, 3.0), Vec3::ZERO, 0.8, 1.0);
    // Two capsules crossing, one leaning towards the eye: which one shows
    // changes along their overlap, where the nearer surface is.
    let red = (Vec3::new(-1.0, -0.2, 0.0), Vec3::new(1.0, 0.2, 0.0), 0.3);
    let blue = (Vec3::new(0.2, -1.0, -0.6), Vec3::new(-0.2, 1.0, 0.7), 0.25);
    let scene = Scene {
        background: [0, 0, 0, 255],
        capsules: vec![
            Capsule { a: red.0, b: red.1, radius: red.2, color: [255, 0, 0, 255] },
            Capsule { a: blue.0, b: blue.1, radius: blue.2, color: [0, 0, 255, 255] },
        ],
        shadows: false,
        ..Scene::default()
    };
    renderer.render(&device, &queue, &target, &scene, &camera);
    let pixels = read_pixels(&device, &queue, &target);
    let (mut checked, mut wrong) = (0, Vec::new());
    for (i, p) in pixels.chunks(4).enumerate() {
        let (x, y) = ((i % SIZE as usize) as u32, (i / SIZE as usize) as u32);
        let (red_out, red_hit) = ray_against_capsule(&camera, x, y, red.0, red.1, red.2);
        let (blue_out, blue_hit) = ray_against_capsule(&camera, x, y, blue.0, blue.1, blue.2);
        if let (Some(r), Some(b)) = (red_hit, blue_hit) {
            // Away from the nearer one's outline, whose fringe is a blend.
            let inside_nearer = if r < b { red_out } else { blue_out } < -0.6;
            if (r - b).abs() > 0.02 && inside_nearer {
                checked += 1;
                let shows_red = p[0] > p[2];
                if shows_red != (r < b) {
                    wrong.push((x, y, r, b));
                }
            }
        }
    }
    assert!(checked > 50, "the capsules overlap on screen: {checked} pixels");
    assert!(
        wrong.is_empty(),
        "{} of {checked} overlapping pixels show the farther capsule, e.g. {:?}",
        wrong.len(),
        &wrong[..wrong.len().min(5)]
    );
}

#[test]
fn capsule_outlines_are_smoothed_on_a_multisampled_target() {
    let Some((device, queue, mut renderer, target)) = setup(4) else { return };
    let camera = Camera::look_at(Vec3::new(0.0, 0.0, 3.0), Vec3::ZERO, 0.8, 1.0);
    let (a, b, r) = (Vec3::new(-1.0, -0.7, 0.0), Vec3::new(1.0, 0.4, 0.0), 0.3);
    let background = [0, 0, 0, 255];
    let scene = Scene {
        background,
        capsules: vec![Capsule { a, b, radius: r, color: [255, 255, 255, 255] }],
        shadows: false,
        ..Scene::default()
    };
    renderer.render(&device, &queue, &target, &scene, &camera);
    let pixels = read_pixels(&device, &queue, &target);
    // The same capsule half a pixel fatter on one sample: the colour fringe
    // pixels would have, fully covered.
    let single = RenderTarget::new(&device, FORMAT, 1, [SIZE, SIZE]);
    let pixel = 2.0 / (camera.projection.y_axis.y * SIZE as f32) * 3.0;
    let fat = Scene {
        capsules: vec![Capsule { a, b, radius: r + pixel * 0.6, color: [255, 255, 255, 255] }],
        ..scene.clone()
    };
    renderer.render(&device, &queue, &single, &fat, &camera);
    let full = read_pixels(&device, &queue, &single);
    let (mut fringe, mut fringe_blended) = (0, 0);
    for (i, p) in pixels.chunks(4).enumerate() {
        let (x, y) = ((i % SIZE as usize) as u32, (i / SIZE as usize) as u32);
        let (outside, _) = ray_against_capsule(&camera, x, y, a, b, r);
        if outside > 1.0 {
            assert_eq!(p, background, "({x}, {y}) is {outside} pixels outside the outline");
        } else if outside < -1.0 {
            assert_ne!(p, background, "({x}, {y}) is {} pixels inside the outline", -outside);
        } else if (0.1..0.4).contains(&outside) {
            // Centres just outside: one sample would leave them clear; here
            // the samples the outline covers take its colour.
            fringe += 1;
            let (v, whole) =
                (p[0].max(p[1]).max(p[2]) as u32, full[i * 4..i * 4 + 3].iter().copied().max().unwrap_or(0) as u32);
            fringe_blended += (p != background && v * 10 < whole * 8) as usize;
        }
        assert_eq!(p[3], 255, "the target keeps its alpha");
    }
    assert!(
        fringe > 10 && fringe_blended * 2 > fringe,
        "the outline is smoothed: {fringe_blended} of {fringe} pixels just outside it are blends"
    );
}

/// Largest difference of any colour channel between two RGBA pixels.
fn channel_diff(p: &[u8], q: &[u8]) -> u8 {
    p.iter().zip(q).take(3).map(|(a, b)| a.abs_diff(*b)).max().unwrap_or(0)
}

/// Full quality on one sample: capsule outlines are filtered by drawing the
/// partly covered pixels last, blended over what lies behind, so the picture
/// is the multisampled one (a red capsule's outline over a blue one behind it
/// blends red into blue, not into the background); the fast look keeps hard
/// outlines. And the rule callers draw with: such a scene takes one sample.
#[test]
fn capsule_outlines_are_blended_on_one_sample_as_on_a_multisampled_target() {
    let Some((device, queue, mut renderer, multisampled)) = setup(4) else { return };
    let single = RenderTarget::new(&device, FORMAT, 1, [SIZE, SIZE]);
    let camera = Camera::look_at(Vec3::new(0.0, 0.0, 3.0), Vec3::ZERO, 0.8, 1.0);
    // The red one in front and listed first, so its fringe is drawn before
    // the blue one's inside unless fringes come last.
    let scene = Scene {
        background: [0, 0, 0, 255],
        capsules: vec![
            Capsule {
                a: Vec3::new(-1.0, -0.6, 0.5),
                b: Vec3::new(0.9, 0.5, 0.5),
                radius: 0.25,
                color: [255, 0, 0, 255],
            },
            Capsule {
                a: Vec3::new(0.3, -1.2, -0.5),
                b: Vec3::new(-0.4, 1.1, -0.5),
                radius: 0.35,
                color: [0, 0, 255, 255],
            },
        ],
        grid: None,
        shadows: false,
        ..Scene::default()
    };
    assert!(scene.smooth_on_one_sample());
    assert_eq!(renderer.samples_for(&scene), 1, "capsules alone are drawn on one sample");
    renderer.render(&device, &queue, &multisampled, &scene, &camera);
    let reference = read_pixels(&device, &queue, &multisampled);
    renderer.render(&device, &queue, &single, &scene, &camera);
    let blended = read_pixels(&device, &queue, &single);
    assert_eq!(renderer.draw_calls(), 1, "one draw of the capsules");
    renderer.fast_look = true;
    assert_eq!(renderer.samples_for(&scene), 1);
    renderer.render(&device, &queue, &single, &scene, &camera);
    let hard = read_pixels(&device, &queue, &single);
    renderer.fast_look = false;
    // Multisampling turns coverage into whole samples (lavapipe rounds up, a
    // quarter of the contrast at most; other drivers dither, up to about
    // three eighths); a hard outline misses by up to all of it.
    let count = |pixels: &[u8], limit: u8| {
        pixels.chunks(4).zip(reference.chunks(4)).filter(|(p, q)| channel_diff(p, q) > limit).count()
    };
    let (blended_off, hard_off) = (count(&blended, 100), count(&hard, 100));
    // A pixel red in one picture and blue in the other.
    let hue = |p: &[u8]| (p[0] as i32 - p[2] as i32).signum() * ((p[0] as i32 - p[2] as i32).abs() > 40) as i32;
    let swapped =
        |pixels: &[u8]| pixels.chunks(4).zip(reference.chunks(4)).filter(|(p, q)| hue(p) * hue(q) < 0).count();
    eprintln!(
        "pixels more than 100 levels from the multisampled picture: blended {blended_off}, fast look {hard_off}; of the other hue {} / {}",
        swapped(&blended),
        swapped(&hard)
    );
    assert!(hard_off > 25, "the fast look's outlines are hard: {hard_off} pixels differ from the multisampled picture");
    // (Where two outlines cross in a pixel, the farther fringe is left out.)
    assert!(
        blended_off <= 2,
        "blended outlines match the multisampled picture: {blended_off} pixels differ (fast look {hard_off})"
    );
    assert_eq!(swapped(&blended), 0, "no pixel takes the other capsule's hue");
    assert!(blended.chunks(4).all(|p| p[3] == 255), "the target keeps its alpha");
    // Lines and spheres are filtered on one sample too; a mesh, drawn with
    // hard edges there, makes the scene multisampled.
    let sticks = Scene {
        spheres: vec![Sphere { center: Vec3::ZERO, radius: 0.1, color: [255; 4] }],
        lines: vec![Line { a: Vec3::ZERO, b: Vec3::Y, color: [255; 4], width_px: 3.0 }],
        ..scene.clone()
    };
    assert!(sticks.smooth_on_one_sample());
    assert_eq!(renderer.samples_for(&sticks), 1);
    let transform = mocap_render::glam::Mat4::IDENTITY;
    let mesh = mocap_render::MeshDraw {
        mesh: quad_mesh(&[0.0], false),
        frames: [0, 0],
        blend: 0.0,
        transform,
        tint: [255; 4],
    };
    let with_mesh = Scene { meshes: vec![mesh], ..sticks };
    assert!(!with_mesh.smooth_on_one_sample());
    assert_eq!(renderer.samples_for(&with_mesh), 4);
}

/// Sticks on one sample: lines and spheres filtered by their coverage and
/// blended (drawn farthest first, lines before spheres), against a reference
/// drawn on one sample with hard edges at four times the size and averaged
/// down (16 samples a pixel); the fast look keeps hard edges. The same lines
/// on a multisampled target are as they were.
#[test]
fn line_and_sphere_outlines_are_blended_on_one_sample() {
    let Some((device, queue, mut renderer, multisampled)) = setup(4) else { return };
    let single = RenderTarget::new(&device, FORMAT, 1, [SIZE, SIZE]);
    let big = RenderTarget::new(&device, FORMAT, 1, [SIZE * 4, SIZE * 4]);
    let camera = Camera::look_at(Vec3::new(0.0, 0.0, 3.0), Vec3::ZERO, 0.8, 1.0);
    let bone = |a: Vec3, b: Vec3| Line { a, b, color: [240, 240, 240, 255], width_px: 3.0 };
    let joint = |center: Vec3, color| Sphere { center, radius: 0.12, color };
    let (hip, knee, foot, other) =
        (Vec3::new(-0.6, 0.8, 0.0), Vec3::new(0.1, -0.1, 0.3), Vec3::new(0.7, -0.9, 0.0), Vec3::new(0.2, 0.7, -0.6));
    let scene = Scene {
        background: [0, 0, 0, 255],
        lines: vec![bone(hip, knee), bone(knee, foot), bone(knee, other)],
        spheres: vec![
            joint(knee, [255, 60, 60, 255]),
            joint(hip, [60, 60, 255, 255]),
            joint(foot, [60, 255, 60, 255]),
            joint(other, [60, 200, 255, 255]),
        ],
        grid: None,
        shadows: false,
        ..Scene::default()
    };
    let draw = |renderer: &mut SceneRenderer, target: &RenderTarget| {
        renderer.render(&device, &queue, target, &scene, &camera);
        read_pixels_of(&device, &queue, target)
    };
    let blended = draw(&mut renderer, &single);
    assert_eq!(renderer.draw_calls(), 2, "one draw of the lines, one of the spheres");
    renderer.fast_look = true;
    let hard = draw(&mut renderer, &single);
    // The reference: hard edges four times as fine, lines four times as wide.
    renderer.pixels_per_point = 4.0;
    let fine = draw(&mut renderer, &big);
    renderer.pixels_per_point = 1.0;
    renderer.fast_look = false;
    let fine = &fine;
    let reference: Vec<u8> = (0..SIZE * SIZE)
        .flat_map(|i| {
            let (x, y) = (i % SIZE, i / SIZE);
            let at = move |dx: u32, dy: u32, c: usize| {
                u32::from(fine[(((y * 4 + dy) * SIZE * 4 + x * 4 + dx) * 4) as usize + c])
            };
            (0..4).map(move |c| ((0..16).map(|k| at(k % 4, k / 4, c)).sum::<u32>() / 16) as u8)
        })
        .collect();
    let count = |pixels: &[u8], limit: u8| {
        pixels.chunks(4).zip(reference.chunks(4)).filter(|(p, q)| channel_diff(p, q) > limit).count()
    };
    let edge = reference.chunks(4).filter(|p| p[..3].iter().any(|&c| c > 20 && c < 200)).count();
    let (blended_off, hard_off) = (count(&blended, 64), count(&hard, 64));
    eprintln!(
        "{edge} partly covered pixels in the reference; more than 64 levels off: blended {blended_off}, fast look {hard_off}"
    );
    assert!(edge > 150, "the reference has smooth outlines ({edge} partly covered pixels)");
    assert!(hard_off > 60, "the fast look's outlines are hard: {hard_off} pixels differ from the reference");
    assert!(
        blended_off * 8 < hard_off,
        "blended outlines are close to the reference: {blended_off} pixels differ (fast look {hard_off})"
    );
    assert!(blended.chunks(4).all(|p| p[3] == 255), "the target keeps its alpha");
    // On a multisampled target the lines keep their hard quads (the samples
    // smooth them) and no fringe: the one-sample blended picture is no wider.
    renderer.render(&device, &queue, &multisampled, &scene, &camera);
    let msaa = read_pixels(&device, &queue, &multisampled);
    let lit = |pixels: &[u8]| pixels.chunks(4).filter(|p| p[..3] != [0, 0, 0]).count();
    assert!(
        lit(&msaa) <= lit(&blended) + lit(&blended) / 10,
        "multisampled {} against blended {} lit pixels",
        lit(&msaa),
        lit(&blended)
    );
}

#[test]
fn pipelines_are_made_for_the_sample_counts_and_looks_drawn_with() {
    // A multisampling renderer that draws only capsules (one sample) never
    // compiles its multisampled set: a page's first frame compiles one set.
    let Some((device, queue, mut renderer, multisampled)) = setup(4) else { return };
    assert_eq!(renderer.pipeline_sets(), 0);
    let single = RenderTarget::new(&device, FORMAT, 1, [SIZE, SIZE]);
    let camera = Camera::look_at(Vec3::new(0.0, 1.0, 3.0), Vec3::ZERO, 0.8, 1.0);
    let capsules = Scene {
        capsules: vec![Capsule { a: Vec3::ZERO, b: Vec3::Y, radius: 0.2, color: [200; 4] }],
        ..Scene::default()
    };
    renderer.render(&device, &queue, &single, &capsules, &camera);
    renderer.render(&device, &queue, &single, &capsules, &camera);
    assert_eq!(renderer.pipeline_sets(), 1, "one set for capsules on one sample");
    // That set was made without the meshes' pipelines; the first frame with a
    // mesh (beside the same capsule: the same shadows) adds them to it and
    // draws the mesh.
    let before = read_pixels(&device, &queue, &single);
    let mesh = Scene {
        meshes: vec![mocap_render::MeshDraw {
            mesh: quad_mesh(&[0.0], false),
            frames: [0, 0],
            blend: 0.0,
            transform: mocap_render::glam::Mat4::IDENTITY,
            tint: mocap_render::NEUTRAL_TINT,
        }],
        ..capsules.clone()
    };
    renderer.render(&device, &queue, &single, &mesh, &camera);
    let changed = read_pixels(&device, &queue, &single).chunks(4).zip(before.chunks(4)).filter(|(a, b)| a != b).count();
    assert!(changed > 100, "the mesh is drawn ({changed} pixels)");
    assert_eq!(renderer.pipeline_sets(), 1, "in the same set");
    // Nor with the spheres' and lines' pipelines: the first frame with them
    // adds them to it and draws them.
    let joints = Scene {
        spheres: vec![Sphere { center: Vec3::new(-0.6, 0.5, 0.0), radius: 0.1, color: [30, 30, 255, 255] }],
        lines: vec![Line { a: Vec3::new(0.5, -0.5, 0.0), b: Vec3::new(0.5, 0.8, 0.0), color: [255, 255, 0, 255], width_px: 3.0 }],
        ..capsules.clone()
    };
    renderer.render(&device, &queue, &single, &joints, &camera);
    let pixels = read_pixels(&device, &queue, &single);
    assert!(pixels.chunks(4).any(|p| p[2] > 150 && p[0] < 100), "the blue joint is drawn");
    assert!(pixels.chunks(4).any(|p| p[0] > 200 && p[1] > 200 && p[2] < 60), "the yellow line is drawn");
    assert_eq!(renderer.pipeline_sets(), 1, "in the same set");
    let sticks = Scene {
        spheres: vec![Sphere { center: Vec3::new(0.6, 0.5, 0.0), radius: 0.1, color: [30, 30, 255, 255] }],
        ..capsules.clone()
    };
    renderer.render(&device, &queue, &multisampled, &sticks, &camera);
    assert_eq!(renderer.pipeline_sets(), 2, "and one for multisampled frames");
    assert!(
        read_pixels(&device, &queue, &multisampled).chunks(4).any(|p| p[2] > 150 && p[0] < 100),
        "the blue ball is drawn"
    );
}

#[test]
fn a_still_camera_starts_each_frame_from_the_floor_drawn_before_with_the_same_pixels() {
    // Copying colour and depth; and as on OpenGL, the colour of single-sampled
    // frames only (the depth drawn), multisampled frames drawing their floor.
    for (samples, color_only) in [(1, false), (4, false), (1, true), (4, true)] {
        let Some((device, queue, renderer, target)) = setup(samples) else { return };
        let paths = mocap_render::TestPaths { floor_color_only: color_only, ..Default::default() };
        let mut renderer =
            if color_only { SceneRenderer::with_test_paths(&device, FORMAT, samples, paths) } else { renderer };
        let copies = !color_only || samples == 1;
        let samples_label = format!("{samples} samples{}", if color_only { ", colour only" } else { "" });
        // Each frame as a new renderer draws it (its first frame draws its floor).
        let fresh = |scene: &Scene, camera: &Camera| {
            let mut first = SceneRenderer::new(&device, FORMAT, samples);
            first.render(&device, &queue, &target, scene, camera);
            assert!(!first.floor_copied(), "a first frame draws its floor");
            read_pixels(&device, &queue, &target)
        };
        let differing = |a: &[u8], b: &[u8]| a.chunks(4).zip(b.chunks(4)).filter(|(p, q)| p != q).count();
        let grid = Grid::floor(Vec3::new(-1.5, 0.0, -1.5), Vec3::new(1.5, 0.0, 1.5), 0.25, 0.5);
        let mut scene = Scene { background: [20, 30, 40, 255], grid: Some(grid), ..Scene::default() };
        // A pole moving through the floor: the floor's depth hides its lower end.
        let pole = |k: f32| Capsule {
            a: Vec3::new(-0.4 + 0.2 * k, -0.6, 0.0),
            b: Vec3::new(0.3, 1.4, 0.1 * k),
            radius: 0.2,
            color: [200, 60, 60, 255],
        };
        let still = Camera::look_at(Vec3::new(1.0, 2.0, 4.0), Vec3::new(0.0, 0.4, 0.0), 0.8, 1.0);
        for frame in 0..4 {
            scene.capsules = vec![pole(frame as f32)];
            scene.shadows = frame != 2;
            renderer.render(&device, &queue, &target, &scene, &still);
            assert_eq!(
                renderer.floor_copied(),
                copies && frame > 0,
                "{samples_label}, frame {frame}: the floor is copied from the second frame of a still camera on"
            );
            let pixels = read_pixels(&device, &queue, &target);
            let expected = fresh(&scene, &still);
            assert_eq!(
                differing(&pixels, &expected),
                0,
                "{samples_label}, frame {frame}: the pixels of drawing the floor"
            );
            let red = pixels.chunks(4).filter(|p| p[0] > 100 && p[0] as u32 > 2 * p[1] as u32).count();
            let floor = pixels.chunks(4).filter(|p| p[..3] != scene.background[..3]).count();
            assert!(
                red > 50 && floor > red + 1000,
                "{samples_label}, frame {frame}: the pole ({red}) on the floor ({floor})"
            );
        }
        // The camera moves: that frame draws its floor, the next reuses the new one.
        let moved = Camera::look_at(Vec3::new(-1.5, 2.5, 3.5), Vec3::new(0.0, 0.4, 0.0), 0.8, 1.0);
        for frame in 0..2 {
            renderer.render(&device, &queue, &target, &scene, &moved);
            assert_eq!(renderer.floor_copied(), copies && frame == 1, "{samples_label}: after a move, frame {frame}");
            assert_eq!(
                differing(&read_pixels(&device, &queue, &target), &fresh(&scene, &moved)),
                0,
                "{samples_label}: moved, frame {frame}"
            );
        }
        // A frame without a floor, then the floor again: drawn, then copied.
        let bare = Scene { grid: None, ..scene.clone() };
        renderer.render(&device, &queue, &target, &bare, &moved);
        assert!(!renderer.floor_copied());
        assert_eq!(
            differing(&read_pixels(&device, &queue, &target), &fresh(&bare, &moved)),
            0,
            "{samples_label}: no floor"
        );
        for frame in 0..2 {
            renderer.render(&device, &queue, &target, &scene, &moved);
            assert_eq!(renderer.floor_copied(), copies && frame == 1, "{samples_label}: the floor back, frame {frame}");
            assert_eq!(
                differing(&read_pixels(&device, &queue, &target), &fresh(&scene, &moved)),
                0,
                "{samples_label}: the floor back, frame {frame}"
            );
        }
    }
}

#[test]
fn a_still_camera_redraws_only_around_the_figures_with_the_pixels_of_a_full_frame() {
    // Single-sampled and multisampled, copying everything and, as on OpenGL,
    // the colour of single-sampled frames only.
    for (samples, color_only) in [(1, false), (4, false), (1, true)] {
        let Some((device, queue, _, target)) = setup(samples) else { return };
        let paths = mocap_render::TestPaths { floor_color_only: color_only, ..Default::default() };
        let mut renderer = SceneRenderer::with_test_paths(&device, FORMAT, samples, paths);
        let label = format!("{samples} samples{}", if color_only { ", colour only" } else { "" });
        // Each frame drawn whole by a new renderer, into a target of its own.
        let whole = RenderTarget::new(&device, FORMAT, samples, [SIZE, SIZE]);
        let fresh = |scene: &Scene, camera: &Camera| {
            SceneRenderer::new(&device, FORMAT, samples).render(&device, &queue, &whole, scene, camera);
            read_pixels(&device, &queue, &whole)
        };
        let differing = |a: &[u8], b: &[u8]| a.chunks(4).zip(b.chunks(4)).filter(|(p, q)| p != q).count();
        let grid = Grid::floor(Vec3::new(-1.5, 0.0, -1.5), Vec3::new(1.5, 0.0, 1.5), 0.25, 0.5);
        let camera = Camera::look_at(Vec3::new(1.0, 2.0, 4.0), Vec3::new(0.0, 0.4, 0.0), 0.8, 1.0);
        // A small figure walking across, with a bone line, a joint, a raised
        // arm (its shadow long and thin across the floor: the redrawn rect
        // follows each caster's shadow) and their shadows; one frame it jumps
        // to the other side, one frame it is gone.
        let figure = |x: f32| Scene {
            background: [20, 30, 40, 255],
            grid: Some(grid.clone()),
            capsules: vec![
                Capsule { a: Vec3::new(x, 0.1, 0.0), b: Vec3::new(x + 0.1, 0.6, 0.1), radius: 0.08, color: [200, 60, 60, 255] },
                Capsule { a: Vec3::new(x + 0.1, 0.6, 0.1), b: Vec3::new(x - 0.1, 1.1, -0.1), radius: 0.03, color: [60, 200, 60, 255] },
            ],
            spheres: vec![Sphere { center: Vec3::new(x + 0.1, 0.7, 0.1), radius: 0.06, color: [60, 60, 220, 255] }],
            lines: vec![Line {
                a: Vec3::new(x, 0.6, 0.0),
                b: Vec3::new(x + 0.3, 0.9, 0.0),
                color: [250, 250, 120, 255],
                width_px: 2.0,
            }],
            shadows: true,
            ..Scene::default()
        };
        let xs = [-1.0, -0.9, -0.8, -0.7, 0.9, 0.8];
        for (frame, &x) in xs.iter().enumerate() {
            let scene = if frame == 5 { Scene { capsules: vec![], spheres: vec![], lines: vec![], ..figure(x) } } else { figure(x) };
            renderer.render(&device, &queue, &target, &scene, &camera);
            let pixels = read_pixels(&device, &queue, &target);
            assert_eq!(differing(&pixels, &fresh(&scene, &camera)), 0, "{label}, frame {frame}: the pixels of a whole frame");
            let copies = !color_only || samples == 1;
            match renderer.changed_rect() {
                Some([x, y, w, h]) => {
                    assert!(copies && frame >= 2, "{label}, frame {frame}: only from the third frame of a still camera");
                    // The same as two rects, the figures' and their shadow's (a shadow every frame here).
                    let [a, b] = renderer.changed_rects().expect("rects with the rect");
                    assert!(a[2] * a[3] > 0 && b[2] * b[3] > 0, "{label}, frame {frame}: {a:?} {b:?}");
                    let around = [a[0].min(b[0]), a[1].min(b[1]), (a[0] + a[2]).max(b[0] + b[2]), (a[1] + a[3]).max(b[1] + b[3])];
                    assert_eq!(around, [x, y, x + w, y + h], "{label}, frame {frame}: the rect around both");
                    assert!(w > 0 && h > 0, "{label}, frame {frame}: the figure moved");
                    if frame != 4 {
                        assert!(w * h < SIZE * SIZE / 2, "{label}, frame {frame}: a small figure's rect ({w}x{h})");
                    }
                }
                None => assert!(!copies || frame < 2, "{label}, frame {frame}: the figures' rect is found"),
            }
        }
        // Nothing moves: the figure's rect alone is redrawn, to the same pixels.
        let scene = figure(0.8);
        for _ in 0..2 {
            renderer.render(&device, &queue, &target, &scene, &camera);
        }
        if !color_only || samples == 1 {
            let area = renderer.changed_rect().map(|r| r[2] * r[3]);
            assert!(area.is_some_and(|a| a > 0 && a < SIZE * SIZE / 4), "{label}: the still figure's rect ({area:?})");
        }
        assert_eq!(differing(&read_pixels(&device, &queue, &target), &fresh(&scene, &camera)), 0, "{label}: still");
    }
}

#[test]
fn the_fast_look_leaves_out_capsules_under_two_pixels() {
    let Some((device, queue, mut renderer, target)) = setup(1) else { return };
    let camera = Camera::look_at(Vec3::new(0.0, 0.0, 3.0), Vec3::ZERO, 0.8, 1.0);
    // Pixels per world unit one unit from the eye, and half a pixel there.
    let scale = camera.projection.y_axis.y * 0.5 * SIZE as f32;
    let half_pixel = 0.5 / scale * 3.0;
    // A ball about 1.6 pixels across, centred on a pixel's centre; a limb.
    let centre = Vec3::new(half_pixel, half_pixel, 0.0);
    let ball = Capsule { a: centre, b: centre, radius: 0.016, color: [0, 255, 0, 255] };
    let limb =
        Capsule { a: Vec3::new(-0.8, -0.5, 0.0), b: Vec3::new(-0.2, -0.6, 0.0), radius: 0.05, color: [255, 0, 0, 255] };
    let scene = Scene { background: [0, 0, 0, 255], capsules: vec![ball, limb], shadows: false, ..Scene::default() };
    let count = |pixels: &[u8], f: &dyn Fn(&[u8]) -> bool| pixels.chunks(4).filter(|p| f(p)).count();
    let green = |p: &[u8]| p[1] > 60 && p[0] < 30;
    let red = |p: &[u8]| p[0] > 60 && p[1] < 30;
    renderer.render(&device, &queue, &target, &scene, &camera);
    let full = read_pixels(&device, &queue, &target);
    assert!(
        count(&full, &green) >= 1 && count(&full, &red) > 20,
        "full quality draws both ({} green, {} red)",
        count(&full, &green),
        count(&full, &red)
    );
    renderer.fast_look = true;
    renderer.render(&device, &queue, &target, &scene, &camera);
    let fast = read_pixels(&device, &queue, &target);
    assert_eq!(count(&fast, &green), 0, "the fast look leaves the 1.6-pixel ball out");
    // and keeps the limb: its pixels are red at full quality too, which
    // adds at most its blended fringe.
    let both_red = fast.chunks(4).zip(full.chunks(4)).filter(|(f, g)| red(f) && red(g)).count();
    assert!(
        count(&fast, &red) > 20 && both_red == count(&fast, &red),
        "and keeps the limb ({} red pixels, {both_red} red at full quality)",
        count(&fast, &red)
    );
    assert!(count(&full, &red) < count(&fast, &red) * 2, "the fringe is about a pixel wide");
    // Nearer, the same ball spans more than two pixels and is drawn.
    let near = Camera::look_at(Vec3::new(0.0, 0.0, 1.0), Vec3::ZERO, 0.8, 1.0);
    renderer.render(&device, &queue, &target, &scene, &near);
    assert!(count(&read_pixels(&device, &queue, &target), &green) > 2, "a nearer ball is drawn in the fast look");
}

#[test]
fn in_the_fast_look_a_body_casts_its_shadow_from_its_bones_capsules() {
    use mocap_render::SkinnedDraw;
    use mocap_render::glam::Mat4;
    let Some((device, queue, mut renderer, target)) = setup(1) else { return };
    let mesh = pillar(0.0);
    let body = SkinnedDraw {
        mesh,
        coarse: None,
        matrices: vec![Mat4::IDENTITY],
        tint: [200, 60, 60, 255],
        weights_view: false,
        shape: None,
    };
    let (camera, mut scene) = floor_from(6.0);
    renderer.render(&device, &queue, &target, &scene, &camera);
    let bare = read_pixels(&device, &queue, &target);
    // The floor pixels (grey, not the red pillar) darker than the bare floor.
    let shadowed = |pixels: &[u8]| -> Vec<usize> {
        floor_shadow(&bare, pixels).iter().enumerate().filter(|(_, r)| r.is_some()).map(|(i, _)| i).collect()
    };
    let shared = |a: &[usize], b: &[usize]| a.iter().filter(|i| b.contains(i)).count();
    let frame = |renderer: &mut SceneRenderer, scene: &Scene| {
        renderer.render(&device, &queue, &target, scene, &camera);
        read_pixels(&device, &queue, &target)
    };
    scene.skinned.push(body);
    let full = frame(&mut renderer, &scene);
    let mesh_shadow = shadowed(&full);
    assert!(mesh_shadow.len() > 20, "the body's mesh casts a shadow: {} pixels", mesh_shadow.len());
    // A stand-in capsule set well to the side, so its shadow tells which cast:
    // unused at full quality.
    scene.body_casters.push(Capsule {
        a: Vec3::new(1.2, 0.0, 1.2),
        b: Vec3::new(1.2, 2.5, 1.2),
        radius: 0.15,
        color: [200, 60, 60, 255],
    });
    assert!(frame(&mut renderer, &scene) == full, "body casters are unused at full quality");
    // The fast look: the capsule casts instead of the mesh.
    renderer.fast_look = true;
    let capsule_shadow = shadowed(&frame(&mut renderer, &scene));
    assert!(capsule_shadow.len() > 20, "fast look: the stand-in capsule casts: {} pixels", capsule_shadow.len());
    assert!(
        shared(&capsule_shadow, &mesh_shadow) * 4 < mesh_shadow.len(),
        "fast look: the mesh casts no shadow of its own"
    );
    // Without body casters the mesh casts in the fast look too.
    scene.body_casters.clear();
    let fast_mesh_shadow = shadowed(&frame(&mut renderer, &scene));
    assert!(
        shared(&fast_mesh_shadow, &mesh_shadow) * 2 > mesh_shadow.len(),
        "fast look without body casters: the mesh's shadow"
    );
}

/// A square pillar 0.3 wide from the floor to y = 2.5 at (`x`, 0), bound to one joint.
fn pillar(x: f32) -> std::sync::Arc<mocap_render::SkinnedMeshData> {
    let (mut positions, mut normals) = (Vec::new(), Vec::new());
    for (n, u) in [(Vec3::X, Vec3::Z), (Vec3::Z, -Vec3::X), (-Vec3::X, -Vec3::Z), (-Vec3::Z, Vec3::X)] {
        for (s, y) in [(-1.0, 0.0), (1.0, 0.0), (1.0, 2.5), (-1.0, 2.5)] {
            positions.push(Vec3::X * x + n * 0.15 + u * 0.15 * s + Vec3::Y * y);
            normals.push(n);
        }
    }
    // Counter-clockwise seen from outside, as bodies are (only front faces are drawn).
    let indices: Vec<u32> = (0..4u32).flat_map(|f| [0, 2, 1, 0, 3, 2].map(|i| f * 4 + i)).collect();
    let n = positions.len();
    std::sync::Arc::new(
        mocap_render::SkinnedMeshData::new(
            &positions,
            &normals,
            &vec![[0; 4]; n],
            &vec![[1.0, 0.0, 0.0, 0.0]; n],
            indices,
            1,
        )
        .unwrap(),
    )
}

#[test]
fn the_fast_look_draws_a_small_body_with_its_coarse_mesh_and_a_near_one_with_its_own() {
    use mocap_render::SkinnedDraw;
    use mocap_render::glam::Mat4;
    let Some((device, queue, mut renderer, target)) = setup(1) else { return };
    // The "coarse" mesh is set apart (at x = 1) so the picture tells which is drawn.
    let body = SkinnedDraw {
        mesh: pillar(0.0),
        coarse: Some(pillar(1.0)),
        matrices: vec![Mat4::IDENTITY],
        tint: [200, 60, 60, 255],
        weights_view: false,
        shape: None,
    };
    let scene = Scene { skinned: vec![body], shadows: false, ..Scene::default() };
    let red_columns = |renderer: &mut SceneRenderer, camera: &Camera| {
        renderer.render(&device, &queue, &target, &scene, camera);
        let pixels = read_pixels(&device, &queue, &target);
        let columns: Vec<usize> = pixels
            .chunks(4)
            .enumerate()
            .filter(|(_, p)| p[0] > 60 && p[0] as u32 > 2 * p[1] as u32)
            .map(|(i, _)| i % SIZE as usize)
            .collect();
        (columns.len(), columns.iter().sum::<usize>() as f32 / columns.len().max(1) as f32)
    };
    // Far (the body spans about 40 pixels): the fast look draws the coarse mesh, to the right.
    let far = Camera::look_at(Vec3::new(0.0, 1.25, 6.0), Vec3::new(0.5, 1.25, 0.0), 0.8, 1.0);
    let (full_count, full_x) = red_columns(&mut renderer, &far);
    renderer.fast_look = true;
    let (fast_count, fast_x) = red_columns(&mut renderer, &far);
    assert!(full_count > 50 && fast_count > 50, "drawn: {full_count}, {fast_count} pixels");
    assert!(
        fast_x > full_x + 10.0,
        "fast look, far: the coarse mesh (x = 1) is drawn, not the mesh: columns {fast_x} vs {full_x}"
    );
    // Near (far more than COARSE_BODY_SPAN_PX): the body's own mesh, in both looks.
    let near = Camera::look_at(Vec3::new(0.0, 1.25, 0.8), Vec3::new(0.0, 1.25, 0.0), 0.8, 1.0);
    let (near_fast, _) = red_columns(&mut renderer, &near);
    renderer.fast_look = false;
    let (near_full, _) = red_columns(&mut renderer, &near);
    assert!(
        near_fast * 10 > near_full * 9 && near_full > 1000,
        "near: the mesh fills the view in both looks ({near_fast} vs {near_full} pixels)"
    );
}

#[test]
fn bodies_are_drawn_from_outside_and_seen_through_from_inside() {
    // Bodies wind counter-clockwise seen from outside and only their front
    // faces are drawn: from outside the pillar shows; from inside its walls
    // (whose back faces the eye sees) are not drawn, in either look.
    use mocap_render::SkinnedDraw;
    use mocap_render::glam::Mat4;
    let Some((device, queue, mut renderer, target)) = setup(4) else { return };
    let body = SkinnedDraw {
        mesh: pillar(0.0),
        coarse: None,
        matrices: vec![Mat4::IDENTITY],
        tint: [200, 60, 60, 255],
        weights_view: false,
        shape: None,
    };
    let scene = Scene { skinned: vec![body], shadows: false, ..Scene::default() };
    let background = Scene::default().background;
    for fast in [false, true] {
        renderer.fast_look = fast;
        let mut drawn = |camera: &Camera| {
            renderer.render(&device, &queue, &target, &scene, camera);
            read_pixels(&device, &queue, &target).chunks(4).filter(|p| *p != background).count()
        };
        let outside = drawn(&Camera::look_at(Vec3::new(0.3, 1.25, 3.0), Vec3::new(0.0, 1.25, 0.0), 0.8, 1.0));
        assert!(outside > 1500, "fast look {fast}: from outside the pillar covers {outside} pixels");
        let inside = drawn(&Camera::look_at(Vec3::new(0.0, 1.25, 0.0), Vec3::new(0.05, 1.25, -1.0), 0.8, 1.0));
        assert_eq!(inside, 0, "fast look {fast}: from inside, {inside} pixels of the walls are drawn");
    }
}

#[test]
fn capsules_given_as_their_triangle_alone_draw_the_same_pixels() {
    // Capsules small in every pass are given as their one triangle (three
    // corners); the same scene with every capsule given four corners, the
    // shader choosing the shape, must give the same pixels.
    let Some((device, queue, mut renderer, target)) = setup(1) else { return };
    let eye = Vec3::new(0.4, 2.5, 6.0);
    let camera = Camera::look_at(eye, Vec3::new(0.0, 0.4, 0.0), 0.8, 1.0);
    let mut scene =
        Scene { grid: Some(Grid::floor(Vec3::new(-2.0, 0.0, -2.0), Vec3::splat(2.0), 0.5, 4.0)), ..Scene::default() };
    // A crowd of small capsules in all directions (one along the view, some
    // balls), a large one near the eye, and shadow-only casters.
    for i in 0..48 {
        let t = i as f32;
        let a = Vec3::new((t * 0.37).sin() * 1.6, 0.1 + (t * 0.23).cos().abs() * 1.2, (t * 0.61).cos() * 1.6);
        let dir = Vec3::new((t * 1.3).cos(), (t * 0.7).sin(), (t * 2.1).sin()) * (0.05 + (i % 5) as f32 * 0.06);
        let b = if i % 7 == 0 { a } else { a + dir };
        let color = [(40 + i * 4) as u8, 200, (250 - i * 3) as u8, 255];
        scene.capsules.push(Capsule { a, b, radius: 0.03 + (i % 3) as f32 * 0.02, color });
    }
    let along = Vec3::new(0.2, 0.8, 0.5);
    scene.capsules.push(Capsule {
        a: along,
        b: along + (along - eye).normalize() * 0.3,
        radius: 0.05,
        color: [250, 250, 40, 255],
    });
    scene.capsules.push(Capsule {
        a: Vec3::new(-0.3, 1.6, 4.0),
        b: Vec3::new(0.3, 1.9, 4.2),
        radius: 0.25,
        color: [250, 60, 60, 255],
    });
    scene.shadow_casters.push(Capsule {
        a: Vec3::new(1.0, 1.5, -1.0),
        b: Vec3::new(1.4, 1.7, -1.0),
        radius: 0.05,
        color: [0; 4],
    });
    scene.shadow_casters.push(Capsule {
        a: Vec3::new(-1.0, 1.0, 1.0),
        b: Vec3::new(-1.0, 2.0, 1.0),
        radius: 0.4,
        color: [0; 4],
    });
    renderer.render(&device, &queue, &target, &scene, &camera);
    let alone = read_pixels(&device, &queue, &target);
    let paths = mocap_render::TestPaths { four_corners_always: true, ..Default::default() };
    let mut renderer = SceneRenderer::with_test_paths(&device, FORMAT, 1, paths);
    renderer.render(&device, &queue, &target, &scene, &camera);
    let four = read_pixels(&device, &queue, &target);
    let differ = alone.chunks(4).zip(four.chunks(4)).filter(|(a, b)| a != b).count();
    assert_eq!(differ, 0, "pixels differ between the triangle alone and four corners");
    // The picture has the capsules and their shadows.
    let bright = alone.chunks(4).filter(|p| p[1] > 150).count();
    assert!(bright > 200, "the capsules are drawn: {bright} pixels");

    // A view of nearly 180 degrees, with a small capsule at its edge (about 85
    // degrees off the axis, where the shader has no outline bound and covers the
    // whole view): the same pixels too.
    let wide = Camera::look_at(Vec3::new(0.0, 1.0, 0.0), Vec3::new(0.0, 1.0, -1.0), 3.0, 1.0);
    let edge = Vec3::new(-(85f32.to_radians().sin()), 0.0, -(85f32.to_radians().cos())) * 10.0 + Vec3::Y;
    let scene = Scene {
        capsules: vec![Capsule { a: edge, b: edge + Vec3::Y * 0.2, radius: 0.1, color: [255, 255, 255, 255] }],
        shadows: false,
        ..Scene::default()
    };
    let frame = |renderer: &mut SceneRenderer| {
        renderer.render(&device, &queue, &target, &scene, &wide);
        read_pixels(&device, &queue, &target)
    };
    let four = frame(&mut renderer);
    let mut fresh = SceneRenderer::new(&device, FORMAT, 1);
    let alone = frame(&mut fresh);
    assert!(alone == four, "a capsule at the edge of a wide view: the same pixels");
    assert!(alone.chunks(4).any(|p| p[0] > 60), "the capsule at the edge is drawn");
}

#[test]
fn every_pixel_an_outline_reaches_is_drawn_across_a_wide_view() {
    // An impostor's shape must hold its capsule's outline and the edge
    // filter's fringe: coverage falls to 0 half a pixel outside, measured
    // across the pixel's ray, which in the image grows away from the view's
    // axis. Small capsules over the whole of a wide view (up to about 60
    // degrees off its axis in the corners), each pixel's coverage computed
    // here from its ray as the shader does: every pixel with some must be drawn.
    let Some((device, queue, mut renderer, target)) = setup(1) else { return };
    let fov = 1.9_f32;
    let camera = Camera::look_at(Vec3::ZERO, Vec3::NEG_Z, fov, 1.0);
    let mut scene = Scene { background: [0, 0, 0, 255], shadows: false, ..Scene::default() };
    let tan = (fov * 0.5).tan();
    for i in 0..11 {
        for j in 0..11 {
            // Directions spread over the view, a few pixels from its edges.
            let (x, y) = ((i as f32 - 5.0) / 5.4 * tan, (j as f32 - 5.0) / 5.4 * tan);
            let a = Vec3::new(x, y, -1.0) * 10.0;
            let k = (i * 11 + j) as f32;
            let along = Vec3::new((k * 1.3).cos(), (k * 0.7).sin(), (k * 2.1).sin()) * 0.3;
            let b = if (i + j) % 4 == 0 { a } else { a + along };
            scene.capsules.push(Capsule {
                a,
                b,
                radius: 0.04 + (i + j) as f32 % 3.0 * 0.03,
                color: [255, 255, 255, 255],
            });
        }
    }
    renderer.render(&device, &queue, &target, &scene, &camera);
    let pixels = read_pixels(&device, &queue, &target);
    // One pixel's size at unit depth.
    let pixel_at_unit = 2.0 * tan / SIZE as f32;
    let coverage = |px: u32, py: u32| -> f32 {
        let ray = Vec3::new(
            ((px as f32 + 0.5) / SIZE as f32 * 2.0 - 1.0) * tan,
            (1.0 - (py as f32 + 0.5) / SIZE as f32 * 2.0) * tan,
            -1.0,
        );
        let d = ray.normalize();
        let best = scene.capsules.iter().map(|c| {
            let ab = c.b - c.a;
            let across = c.a - d * c.a.dot(d);
            let slope = ab - d * ab.dot(d);
            let s = if slope.length_squared() > 1e-12 * ab.length_squared() {
                (-across.dot(slope) / slope.length_squared()).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let miss = (across + slope * s).length();
            // The ray's point nearest the capsule, and its depth.
            let depth = -(d * (c.a + ab * s).dot(d)).z;
            if depth <= 0.0 {
                return 0.0;
            }
            (0.5 - (miss - c.radius) / (pixel_at_unit * depth)).clamp(0.0, 1.0)
        });
        best.fold(0.0, f32::max)
    };
    let mut reached = 0;
    let mut missed = Vec::new();
    for py in 0..SIZE {
        for px in 0..SIZE {
            if coverage(px, py) > 0.05 {
                reached += 1;
                let i = ((py * SIZE + px) * 4) as usize;
                if pixels[i..i + 3] == [0, 0, 0] {
                    missed.push((px, py));
                }
            }
        }
    }
    assert!(reached > 400, "the capsules cover pixels: {reached}");
    assert!(
        missed.is_empty(),
        "{} of {reached} pixels the outlines reach are not drawn: {:?}",
        missed.len(),
        &missed[..missed.len().min(20)]
    );
}

/// A square of two triangles bound to one joint: corners (x, y) at z = 0 with
/// texture coordinates (u, v), v down.
fn skinned_square() -> mocap_render::SkinnedMeshData {
    let corners = [(-0.5f32, 0.5f32), (0.5, 0.5), (0.5, 1.5), (-0.5, 1.5)];
    let positions: Vec<Vec3> = corners.iter().map(|&(x, y)| Vec3::new(x, y, 0.0)).collect();
    mocap_render::SkinnedMeshData::new(
        &positions,
        &[Vec3::Z; 4],
        &[[0, 0, 0, 0]; 4],
        &[[1.0, 0.0, 0.0, 0.0]; 4],
        vec![0, 1, 2, 0, 2, 3],
        1,
    )
    .expect("a valid mesh")
}

#[test]
fn a_skinned_mesh_draws_its_texture_per_pixel() {
    use mocap_render::glam::Mat4;
    use mocap_render::{SkinImage, SkinnedDraw, SkinnedTexture};
    let Some((device, queue, mut renderer, target)) = setup(1) else { return };
    let background = [10, 20, 30, 255];
    let camera = Camera::look_at(Vec3::new(0.0, 1.0, 3.0), Vec3::new(0.0, 1.0, 0.0), 0.8, 1.0);
    // 64 texels wide: red on the left half, blue on the right; the square's left
    // corners sample u = 0, its right u = 1.
    let half = |c: [u8; 4]| std::iter::repeat_n(c, 32).flatten();
    let image =
        SkinImage { width: 64, height: 1, pixels: half([230, 20, 20, 255]).chain(half([20, 20, 230, 255])).collect() };
    let texture = SkinnedTexture { image, wrap: [wgpu::AddressMode::ClampToEdge; 2] };
    let uvs = [Some([0.0, 1.0]), Some([1.0, 1.0]), Some([1.0, 0.0]), Some([0.0, 0.0])];
    let mut mesh = skinned_square();
    mesh.set_texture(texture.clone(), &uvs, &[[255; 4]; 4]).expect("a valid texture");
    let draw = |mesh: mocap_render::SkinnedMeshData| SkinnedDraw {
        mesh: std::sync::Arc::new(mesh),
        coarse: None,
        matrices: vec![Mat4::IDENTITY],
        tint: [255; 4],
        weights_view: false,
        shape: None,
    };
    let mut scene = Scene { background, shadows: false, ..Scene::default() };
    scene.skinned = vec![draw(mesh)];
    renderer.render(&device, &queue, &target, &scene, &camera);
    let px = read_pixels(&device, &queue, &target);
    let red = columns(&px, |p| p[0] > 100 && p[2] < 60);
    let blue = columns(&px, |p| p[2] > 100 && p[0] < 60);
    assert!(red.len() > 10 && blue.len() > 10, "both halves drawn: {} red, {} blue columns", red.len(), blue.len());
    assert!(red[red.len() - 1] < blue[0], "red left of blue, per pixel: {red:?} {blue:?}");
    // A vertex without a coordinate takes its own colour: the same square all green.
    let mut plain = skinned_square();
    plain.set_texture(texture.clone(), &[None; 4], &[[20, 200, 20, 255]; 4]).expect("valid");
    scene.skinned = vec![draw(plain)];
    renderer.render(&device, &queue, &target, &scene, &camera);
    let px = read_pixels(&device, &queue, &target);
    let drawn: Vec<&[u8]> = px.chunks(4).filter(|p| *p != background).collect();
    assert!(drawn.len() > 100 && drawn.iter().all(|p| p[1] > p[0] && p[1] > p[2]), "green, no texture");
    // Refused: a coordinate per vertex is needed, and finite ones; the mesh stays as it was.
    let mut bad = skinned_square();
    assert!(bad.set_texture(texture.clone(), &uvs[..3], &[[255; 4]; 3]).is_err());
    assert!(bad.set_texture(texture, &[Some([f32::NAN, 0.0]); 4], &[[255; 4]; 4]).is_err());
}
