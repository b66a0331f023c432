//! Draws a scene offscreen on any available adapter (lavapipe on a headless Linux
//! box) and reads the pixels back. Skips, with a note, when no adapter exists.

use mocap_render::glam::Vec3;
use mocap_render::{Camera, Grid, Line, RenderTarget, Scene, SceneRenderer, Sphere};

const SIZE: u32 = 64;
const FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;

fn device() -> Option<(wgpu::Device, wgpu::Queue)> {
    let instance = wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle());
    let adapter = pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions::default())).ok()?;
    pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor::default())).ok()
}

fn read_pixels(device: &wgpu::Device, queue: &wgpu::Queue, target: &RenderTarget) -> Vec<u8> {
    let row = SIZE * 4;
    let padded = row.div_ceil(256) * 256;
    let buffer = device.create_buffer(&wgpu::BufferDescriptor {
        label: None,
        size: u64::from(padded * SIZE),
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });
    let mut encoder = device.create_command_encoder(&Default::default());
    encoder.copy_texture_to_buffer(
        wgpu::TexelCopyTextureInfo { texture: &target.color, mip_level: 0, origin: wgpu::Origin3d::ZERO, aspect: wgpu::TextureAspect::All },
        wgpu::TexelCopyBufferInfo {
            buffer: &buffer,
            layout: wgpu::TexelCopyBufferLayout { offset: 0, bytes_per_row: Some(padded), rows_per_image: Some(SIZE) },
        },
        wgpu::Extent3d { width: SIZE, height: SIZE, depth_or_array_layers: 1 },
    );
    queue.submit([encoder.finish()]);
    buffer.map_async(wgpu::MapMode::Read, .., |r| r.expect("map"));
    device.poll(wgpu::PollType::wait_indefinitely()).expect("poll");
    let data = buffer.slice(..).get_mapped_range().expect("mapped");
    data.chunks(padded as usize).flat_map(|r| r[..row as usize].to_vec()).collect()
}

#[test]
fn draws_lines_spheres_and_grid_offscreen() {
    let Some((device, queue)) = device() else {
        eprintln!("no wgpu adapter here (install mesa-vulkan-drivers for lavapipe); skipping");
        return;
    };
    let mut renderer = SceneRenderer::new(&device, FORMAT, 4);
    let target = RenderTarget::new(&device, FORMAT, 4, [SIZE, SIZE]);
    let background = [10, 20, 30, 255];
    let mut scene = Scene { background, ..Scene::default() };
    let camera = Camera::look_at(Vec3::new(0.0, 1.0, 4.0), Vec3::new(0.0, 1.0, 0.0), 0.8, 1.0);

    renderer.render(&device, &queue, &target, &scene, &camera);
    let empty = read_pixels(&device, &queue, &target);
    assert!(empty.chunks(4).all(|p| p == background), "an empty scene is just the background");

    scene.grid = Some(Grid { center: Vec3::ZERO, cell: 0.5, half_cells: 4, major_every: 2, color: [90; 4], major_color: [120; 4] });
    scene.lines.push(Line { a: Vec3::new(0.0, 0.5, 0.0), b: Vec3::new(0.0, 1.5, 0.0), color: [255, 0, 0, 255], width_px: 3.0 });
    scene.spheres.push(Sphere { center: Vec3::new(0.0, 1.5, 0.0), radius: 0.1, color: [0, 255, 0, 255] });
    renderer.render(&device, &queue, &target, &scene, &camera);
    let pixels = read_pixels(&device, &queue, &target);
    let count = |f: &dyn Fn(&[u8]) -> bool| pixels.chunks(4).filter(|p| f(p)).count();
    assert!(count(&|p| p[0] > 200 && p[1] < 60) > 10, "the red bone is drawn");
    assert!(count(&|p| p[1] > 100 && p[0] < 60) > 4, "the green joint is drawn");
    // Y up: the sphere (y = 1.5, eye height 1) lands in the upper half of the image.
    let green_rows: Vec<usize> = pixels.chunks(4).enumerate().filter(|(_, p)| p[1] > 100 && p[0] < 60).map(|(i, _)| i / SIZE as usize).collect();
    assert!(green_rows.iter().all(|&r| r < SIZE as usize / 2), "sphere above the centre: rows {green_rows:?}");
}
