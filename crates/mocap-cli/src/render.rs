//! `mocap render`: headless rendering of clips and models to PNG through wgpu
//! (Vulkan; Mesa's lavapipe on a machine without a GPU), for stills, frame
//! sequences and contact sheets. The scene is built from world positions and mesh
//! frames; the renderer knows no formats.

use mocap::stage::{Actor, Layout, PoseScratch, Stage};
use mocap::{Asset, Interpolation, Timeline};
use mocap_render::{Camera, DrawMode, Readback, RenderTarget, Scene, SceneRenderer, wgpu};
use mocap_scene::{ActorDraw, Drawable, OrbitCamera, SceneStyle};
use std::path::Path;

/// Colour format of the offscreen target (sRGB, read back as RGBA8).
const FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8UnormSrgb;
/// Multisampling for anti-aliasing, for scenes that need it
/// (`SceneRenderer::samples_for`: scenes without meshes or bodies are smooth on
/// one sample).
const SAMPLES: u32 = 4;

/// Where the camera is: orbit angles in degrees and a distance in file units.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Orbit {
    /// Rotation about the vertical axis, degrees (0 looks along -Z).
    pub yaw: f32,
    /// Elevation, degrees (positive looks down).
    pub pitch: f32,
    /// Distance from the target in metres; `None` frames the whole motion.
    pub distance: Option<f32>,
}

impl Default for Orbit {
    /// The page's default view ([`OrbitCamera::default`]'s angles), framing the whole motion.
    fn default() -> Orbit {
        let c = OrbitCamera::default();
        Orbit { yaw: c.yaw.to_degrees(), pitch: c.pitch.to_degrees(), distance: None }
    }
}

/// Parses `yaw,pitch[,distance]`.
pub fn parse_orbit(text: &str) -> Result<Orbit, String> {
    let parts: Vec<&str> = text.split(',').map(str::trim).collect();
    let number = |s: &str| {
        s.parse::<f32>().ok().filter(|v| v.is_finite()).ok_or_else(|| format!("--camera: `{s}` is not a number"))
    };
    match parts.as_slice() {
        [yaw, pitch] => Ok(Orbit { yaw: number(yaw)?, pitch: number(pitch)?, distance: None }),
        [yaw, pitch, distance] => {
            let d = number(distance)?;
            if d <= 0.0 {
                return Err("--camera: distance must be positive".into());
            }
            Ok(Orbit { yaw: number(yaw)?, pitch: number(pitch)?, distance: Some(d) })
        }
        _ => Err("--camera takes yaw,pitch[,distance] (degrees, degrees, metres)".into()),
    }
}

/// Parses `WIDTHxHEIGHT`, each 16..=8192.
pub fn parse_size(text: &str) -> Result<[u32; 2], String> {
    let (w, h) = text.split_once(['x', 'X']).ok_or_else(|| format!("--size: expected WIDTHxHEIGHT, found `{text}`"))?;
    let parse = |s: &str| s.trim().parse::<u32>().ok().filter(|v| (16..=8192).contains(v));
    match (parse(w), parse(h)) {
        (Some(w), Some(h)) => Ok([w, h]),
        _ => Err(format!("--size: `{text}`: width and height must be 16 to 8192 pixels")),
    }
}

/// A wgpu device for offscreen work.
pub struct Gpu {
    device: wgpu::Device,
    queue: wgpu::Queue,
    adapter: String,
    /// Why the device is unusable (lost, or the first error it reported), once it is.
    failed: std::sync::Arc<std::sync::Mutex<Option<String>>>,
}

/// How long a frame's pixels may take to come back before the device is taken for hung.
const READBACK_LIMIT: std::time::Duration = std::time::Duration::from_secs(120);

impl Gpu {
    /// The device (for callers drawing with it themselves).
    pub fn device(&self) -> &wgpu::Device {
        &self.device
    }

    /// An error when the device was lost or reported an error: every frame after
    /// is refused with it, instead of waiting for a device that will not answer.
    pub fn check(&self) -> Result<(), String> {
        match self.failed.lock().ok().and_then(|f| f.clone()) {
            Some(reason) => Err(reason),
            None => Ok(()),
        }
    }

    /// Records why the device failed, keeping the first reason.
    fn watch(device: &wgpu::Device) -> std::sync::Arc<std::sync::Mutex<Option<String>>> {
        let failed = std::sync::Arc::new(std::sync::Mutex::new(None::<String>));
        let record = |failed: &std::sync::Arc<std::sync::Mutex<Option<String>>>, reason: String| {
            if let Ok(mut slot) = failed.lock() {
                slot.get_or_insert(reason);
            }
        };
        let lost = failed.clone();
        device.set_device_lost_callback(move |reason, message| {
            record(&lost, format!("the GPU device was lost ({reason:?}: {message}); nothing more can be drawn"));
        });
        let errors = failed.clone();
        device.on_uncaptured_error(std::sync::Arc::new(move |error| {
            record(&errors, format!("GPU error: {error}"));
        }));
        failed
    }

    /// The adapter's name (e.g. "llvmpipe (LLVM 15.0.6, 256 bits)").
    pub fn adapter_name(&self) -> &str {
        &self.adapter
    }

    /// Opens the first native adapter (Vulkan); a software one (lavapipe) is fine.
    pub fn new() -> Result<Gpu, String> {
        let instance = wgpu::Instance::new(wgpu::InstanceDescriptor {
            backends: wgpu::Backends::VULKAN,
            ..wgpu::InstanceDescriptor::new_without_display_handle()
        });
        let options = wgpu::RequestAdapterOptions {
            power_preference: wgpu::PowerPreference::HighPerformance,
            force_fallback_adapter: false,
            compatible_surface: None,
            apply_limit_buckets: false,
        };
        let adapter = pollster::block_on(instance.request_adapter(&options)).map_err(|e| {
            format!("no Vulkan adapter ({e}); on Debian install Mesa's software renderer: apt-get install mesa-vulkan-drivers")
        })?;
        let info = adapter.get_info();
        let name = info.name;
        if info.device_type == wgpu::DeviceType::Cpu {
            keep_freed_memory();
        }
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("mocap render"),
            required_limits: wgpu::Limits::downlevel_defaults().using_resolution(adapter.limits()),
            ..Default::default()
        }))
        .map_err(|e| format!("cannot open the Vulkan device {name}: {e}"))?;
        let failed = Gpu::watch(&device);
        Ok(Gpu { device, queue, adapter: name, failed })
    }
}

/// Keeps memory freed at the top of the heap for reuse instead of handing it
/// back to the kernel (glibc: a trim threshold of 1 GiB instead of 128 KiB).
/// Mesa's lavapipe frees and allocates megabytes of per-frame data (the
/// rasteriser's bins, the placed vertices), so with glibc's default every frame
/// faulted those pages in again: about 3,000 page faults a frame at 64
/// characters, none with this (64 characters, one sample: 46-54 → 36-41 ms a
/// frame; 4× MSAA: 70-76 → 67-70). Elsewhere nothing changes.
fn keep_freed_memory() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    // SAFETY: mallopt only sets an allocator parameter; any value is valid for
    // M_TRIM_THRESHOLD.
    unsafe {
        libc::mallopt(libc::M_TRIM_THRESHOLD, 1 << 30);
    }
}

/// Draws scenes into an offscreen target and reads the pixels back.
pub struct Offscreen {
    renderer: SceneRenderer,
    /// A target of the renderer's sample count.
    target: RenderTarget,
    /// One sample beside a multisampled `target`, made when first drawn into
    /// (`SceneRenderer::samples_for`).
    single: Option<RenderTarget>,
    /// Samples per pixel of the last frame.
    last_samples: u32,
    readback: Readback,
}

impl Offscreen {
    /// A target of `size` pixels.
    pub fn new(gpu: &Gpu, size: [u32; 2]) -> Offscreen {
        Offscreen::with_samples(gpu, size, SAMPLES)
    }

    /// A target of `size` pixels with `samples` samples per pixel (1 or 4).
    pub fn with_samples(gpu: &Gpu, size: [u32; 2], samples: u32) -> Offscreen {
        let renderer = SceneRenderer::new(&gpu.device, FORMAT, samples);
        let target = RenderTarget::new(&gpu.device, FORMAT, samples, size);
        let readback = Readback::new(&gpu.device, target.size());
        Offscreen { renderer, target, single: None, last_samples: samples, readback }
    }

    /// Size in pixels.
    pub fn size(&self) -> [u32; 2] {
        self.target.size()
    }

    /// Draws in the renderer's fast look (`SceneRenderer::fast_look`: one
    /// lookup into a shadow map of texels twice as large), what a
    /// window draws while playing once frames are slow. Not for final images:
    /// `mocap render` never sets it. Takes effect from the next frame.
    pub fn set_fast_look(&mut self, fast: bool) {
        self.renderer.fast_look = fast;
    }

    /// Draw calls of the last frame.
    pub fn draw_calls(&self) -> u32 {
        self.renderer.draw_calls()
    }

    /// Samples per pixel of the last frame's target.
    pub fn samples(&self) -> u32 {
        self.last_samples
    }

    /// Makes the target a frame of `scene` is drawn into: of the sample count
    /// the renderer asks for it ([`SceneRenderer::samples_for`]); returns
    /// whether it is the single-sampled one beside a multisampled `target`.
    fn choose_target(&mut self, gpu: &Gpu, scene: &Scene) -> bool {
        let samples = self.renderer.samples_for(scene);
        self.last_samples = samples;
        let single = samples != self.target.sample_count();
        if single && self.single.is_none() {
            self.single = Some(RenderTarget::new(&gpu.device, FORMAT, 1, self.target.size()));
        }
        single
    }

    /// Renders and waits for the GPU to finish, without reading pixels back (what a
    /// frame costs in a window).
    pub fn render(&mut self, gpu: &Gpu, scene: &Scene, camera: &Camera) -> Result<(), String> {
        gpu.check()?;
        let single = self.choose_target(gpu, scene);
        self.renderer.render(&gpu.device, &gpu.queue, pick(&self.target, &self.single, single), scene, camera);
        gpu.device.poll(wgpu::PollType::wait_indefinitely()).map_err(|e| format!("GPU wait failed: {e}"))?;
        gpu.check()
    }

    /// Renders and returns tightly packed RGBA8 (sRGB) rows.
    pub fn draw(&mut self, gpu: &Gpu, scene: &Scene, camera: &Camera) -> Result<Vec<u8>, String> {
        gpu.check()?;
        let single = self.choose_target(gpu, scene);
        let target = pick(&self.target, &self.single, single);
        let mut encoder =
            gpu.device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("mocap render") });
        self.renderer.encode(&gpu.device, &gpu.queue, &mut encoder, target, scene, camera);
        self.readback.copy(&mut encoder, &target.color);
        gpu.queue.submit([encoder.finish()]);
        let slice = self.readback.buffer().slice(..);
        let (sender, receiver) = std::sync::mpsc::channel();
        slice.map_async(wgpu::MapMode::Read, move |result| {
            let _ = sender.send(result);
        });
        let waited = gpu.device.poll(wgpu::PollType::wait_indefinitely());
        gpu.check()?;
        waited.map_err(|e| format!("GPU wait failed: {e}"))?;
        let mapped = receiver.recv_timeout(READBACK_LIMIT).map_err(|e| match e {
            std::sync::mpsc::RecvTimeoutError::Timeout => {
                format!(
                    "the GPU did not return the frame in {} s: the device is hung or lost",
                    READBACK_LIMIT.as_secs()
                )
            }
            std::sync::mpsc::RecvTimeoutError::Disconnected => {
                "GPU readback was dropped: the device is lost".to_owned()
            }
        })?;
        gpu.check()?;
        mapped.map_err(|e| format!("GPU readback failed: {e}"))?;
        self.readback.read()
    }
}

/// `single` if `use_single` (and made), else `target`.
fn pick<'a>(target: &'a RenderTarget, single: &'a Option<RenderTarget>, use_single: bool) -> &'a RenderTarget {
    single.as_ref().filter(|_| use_single).unwrap_or(target)
}

/// How `mocap render` draws the shared [`Stage`] (the one the viewer uses: clips
/// and models in metres by their guessed units, side by side in lanes, one
/// timeline over all).
pub struct StageView {
    stage: Stage<Drawable>,
    mode: DrawMode,
    /// How poses between frames are sampled (default linear).
    interpolation: Interpolation,
    /// The joint whose path over the whole clip is drawn (`--trail`).
    trail: Option<String>,
    scratch: std::cell::RefCell<(PoseScratch, Vec<mocap::Transform>)>,
}

impl StageView {
    /// Places `assets` (name, clip or model) in lanes.
    pub fn new(assets: Vec<(String, Asset)>) -> StageView {
        let actors = assets.into_iter().map(|(name, asset)| {
            let mut actor = Actor::new(&name, asset, Drawable::default());
            actor.extra = Drawable::of(&actor.asset, actor.extent);
            actor
        });
        StageView {
            stage: Stage::new(actors.collect(), Layout::Spread),
            mode: DrawMode::default(),
            interpolation: Interpolation::Linear,
            trail: None,
            scratch: Default::default(),
        }
    }

    /// Plays animation `name` on every model that has it; false when none has.
    pub fn set_animation(&mut self, name: &str) -> bool {
        let mut found = false;
        for i in 0..self.stage.actors.len() {
            found |= self.stage.set_animation(i, name);
        }
        found
    }

    /// Stands every clip up along its file's `up` axis (instead of the guess).
    pub fn set_up_axis(&mut self, up: mocap::UpAxis) {
        for i in 0..self.stage.actors.len() {
            self.stage.set_up_axis(i, up);
        }
    }

    /// Draws joint `name`'s path over each clip that has it (the root's on the
    /// floor), a tick each second and the current point; false when no clip has it.
    pub fn set_trail(&mut self, name: &str) -> bool {
        let found = self.stage.actors.iter().any(|a| a.asset.clip().is_some_and(|c| c.skeleton().find(name).is_some()));
        self.trail = found.then(|| name.to_string());
        found
    }

    /// Samples between frames by `interpolation` (nearest, linear or cubic).
    pub fn set_interpolation(&mut self, interpolation: Interpolation) {
        self.interpolation = interpolation;
    }

    /// The same stage drawn in `mode` (body mode builds the bodies).
    pub fn with_mode(mut self, mode: DrawMode) -> StageView {
        self.mode = mode;
        if mode == DrawMode::Body {
            for actor in &mut self.stage.actors {
                actor.extra.ensure_body(actor.asset.clip(), actor.extent);
            }
        }
        self
    }

    /// The longest clip's duration.
    pub fn duration(&self) -> f64 {
        self.stage.duration()
    }

    /// The shared timeline, in the first clip's frame time (frames on the command line count in it).
    pub fn timeline(&self) -> Timeline {
        self.stage.timeline(0).unwrap_or(Timeline::new(mocap::model::time::DEFAULT_FRAME_TIME, 0))
    }

    /// Fills `scene` with the floor and every actor posed at `time` seconds,
    /// through the scene builder the viewer uses ([`mocap_scene::push_actor`]).
    pub fn scene_at(&self, time: f64, scene: &mut Scene) {
        scene.clear();
        scene.grid = Some(mocap_scene::floor_grid(&self.stage));
        let style = SceneStyle { mode: self.mode, ..SceneStyle::default() };
        let mut scratch = self.scratch.borrow_mut();
        let (pose_scratch, pose) = &mut *scratch;
        for (n, actor) in self.stage.visible() {
            let morph = actor.morph_at(time, self.interpolation);
            pose.clear();
            if actor.asset.clip().is_some() {
                actor.pose_at(time, self.interpolation, pose_scratch, pose);
            }
            let shape = actor.asset.clip().and_then(|clip| mocap_scene::MorphShape::default().at(clip, time));
            let draw = ActorDraw {
                drawable: &actor.extra,
                pose,
                morph,
                world_matrix: actor.world_matrix(),
                color: mocap_render::PALETTE[n % mocap_render::PALETTE.len()],
                extent: actor.world_extent(),
                selected: None,
                ghost: &[],
                shape: shape.as_ref(),
            };
            mocap_scene::push_actor(scene, &draw, &style);
        }
        drop(scratch);
        self.push_trails(time, scene);
    }

    /// The `--trail` joint's path on every clip that has it.
    fn push_trails(&self, time: f64, scene: &mut Scene) {
        let Some(name) = &self.trail else { return };
        let floor = self.stage.floor_height() + 0.003;
        let mut scratch = Default::default();
        for (n, actor) in self.stage.visible() {
            let Some(clip) = actor.asset.clip() else { continue };
            let Some(joint) = clip.skeleton().find(name) else { continue };
            let on_floor = clip.skeleton().joints().get(joint).is_some_and(|j| j.parent.is_none()).then_some(floor);
            let step = clip.frame_time().max(1.0 / 30.0);
            let (path, ticks) = mocap_scene::joint_path(actor, joint, (0.0, clip.duration()), step, on_floor, &mut scratch);
            let (now, _) = mocap_scene::joint_path(actor, joint, (time, time), 1.0, on_floor, &mut scratch);
            let [r, g, b, _] = mocap_render::PALETTE[n % mocap_render::PALETTE.len()];
            mocap_scene::push_trail(scene, &path, &ticks, now.first().copied(), [r, g, b, 230], actor.world_extent());
        }
    }

    /// A camera orbiting the stage's centre, framed by the viewer's rule
    /// ([`OrbitCamera::frame`]) for a view of `size` pixels unless `orbit` sets
    /// the distance.
    pub fn camera(&self, orbit: Orbit, size: [u32; 2]) -> Camera {
        self.orbit_camera(orbit, size).to_camera(size[0] as f32 / size[1].max(1) as f32)
    }

    /// The orbit camera [`StageView::camera`] draws with.
    pub fn orbit_camera(&self, orbit: Orbit, size: [u32; 2]) -> OrbitCamera {
        let mut camera = OrbitCamera { aspect: size[0] as f32 / size[1].max(1) as f32, ..OrbitCamera::default() };
        camera.set_angles(orbit.yaw.to_radians(), orbit.pitch.to_radians());
        camera.frame(self.stage.bounds());
        if let Some(distance) = orbit.distance {
            camera.distance = distance;
        }
        camera
    }
}

/// Writes RGBA8 pixels as a PNG.
pub fn write_png(path: &Path, size: [u32; 2], rgba: &[u8]) -> Result<(), String> {
    let file = std::fs::File::create(path).map_err(|e| format!("{}: cannot write: {e}", path.display()))?;
    let mut encoder = png::Encoder::new(std::io::BufWriter::new(file), size[0], size[1]);
    encoder.set_color(png::ColorType::Rgba);
    encoder.set_depth(png::BitDepth::Eight);
    encoder.set_source_srgb(png::SrgbRenderingIntent::Perceptual);
    let mut writer = encoder.write_header().map_err(|e| format!("{}: {e}", path.display()))?;
    writer.write_image_data(rgba).map_err(|e| format!("{}: {e}", path.display()))
}

/// Copies a `size` tile into a sheet `sheet_width` pixels wide at `(x, y)`.
pub fn blit(sheet: &mut [u8], sheet_width: u32, tile: &[u8], size: [u32; 2], x: u32, y: u32) {
    let row_bytes = (size[0] * 4) as usize;
    for (r, row) in tile.chunks(row_bytes).enumerate() {
        let start = (((y as usize + r) * sheet_width as usize) + x as usize) * 4;
        if let Some(dst) = sheet.get_mut(start..start + row_bytes) {
            dst.copy_from_slice(row);
        }
    }
}
