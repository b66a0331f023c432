use std::sync::Arc;

use egui::ScreenshotCallback;
use egui_wgpu::{RenderState, SurfaceErrorAction, capture::CaptureState};
use wasm_bindgen::JsValue;
use web_sys::HtmlCanvasElement;

use super::web_painter::WebPainter;

pub(crate) struct WebPainterWgpu {
    canvas: HtmlCanvasElement,
    instance: wgpu::Instance,
    surface: wgpu::Surface<'static>,
    surface_configuration: wgpu::SurfaceConfiguration,
    render_state: Option<RenderState>,
    on_surface_status: Arc<dyn Fn(&wgpu::CurrentSurfaceTexture) -> SurfaceErrorAction>,
    depth_stencil_format: Option<wgpu::TextureFormat>,
    depth_texture_view: Option<wgpu::TextureView>,
    screen_capture_state: Option<CaptureState>,
    ctx: egui::Context,
    needs_reconfigure: bool,
    needs_recreate: bool,
    /// Vendored change: what the last frames drew, where the window keeps its
    /// pixels between frames (WebGL2: wgpu draws straight into the canvas,
    /// whose drawing buffer is preserved); see `damage.rs`.
    damage: Option<super::damage::Damage>,
    /// Vendored change: the background of a region redrawn alone.
    fill: egui_wgpu::FillQuad,
    /// Vendored change: where the window keeps its pixels, the canvas's
    /// drawing buffer as a texture (`canvas_texture`), drawn into instead of
    /// the surface's textures.
    canvas_texture: Option<wgpu::Texture>,
}

/// Owned web display handle that is `Send + Sync`.
///
/// `DisplayHandle` from `raw-window-handle` is `!Send`/`!Sync` because the enum
/// contains platform variants with raw pointers. On web the handle is always empty,
/// so this wrapper is safe.
#[cfg(target_arch = "wasm32")]
#[derive(Clone, Debug)]
struct WebDisplay;

#[cfg(target_arch = "wasm32")]
impl egui_wgpu::wgpu::rwh::HasDisplayHandle for WebDisplay {
    fn display_handle(
        &self,
    ) -> Result<egui_wgpu::wgpu::rwh::DisplayHandle<'_>, egui_wgpu::wgpu::rwh::HandleError> {
        Ok(egui_wgpu::wgpu::rwh::DisplayHandle::web())
    }
}

impl WebPainterWgpu {
    pub fn render_state(&self) -> Option<RenderState> {
        self.render_state.clone()
    }

    pub fn generate_depth_texture_view(
        &self,
        render_state: &RenderState,
        width_in_pixels: u32,
        height_in_pixels: u32,
    ) -> Option<wgpu::TextureView> {
        let device = &render_state.device;
        self.depth_stencil_format.map(|depth_stencil_format| {
            device
                .create_texture(&wgpu::TextureDescriptor {
                    label: Some("egui_depth_texture"),
                    size: wgpu::Extent3d {
                        width: width_in_pixels,
                        height: height_in_pixels,
                        depth_or_array_layers: 1,
                    },
                    mip_level_count: 1,
                    sample_count: 1,
                    dimension: wgpu::TextureDimension::D2,
                    format: depth_stencil_format,
                    usage: wgpu::TextureUsages::RENDER_ATTACHMENT,
                    view_formats: &[depth_stencil_format],
                })
                .create_view(&wgpu::TextureViewDescriptor::default())
        })
    }

    pub async fn new(
        ctx: egui::Context,
        canvas: web_sys::HtmlCanvasElement,
        options: &crate::WebOptions,
    ) -> Result<Self, String> {
        log::debug!("Creating wgpu painter");

        // Inject the display handle into the wgpu setup so that wgpu can create surfaces on WebGL.
        let mut wgpu_options = options.wgpu_options.clone();
        if let egui_wgpu::WgpuSetup::CreateNew(ref mut create_new) = wgpu_options.wgpu_setup
            && create_new.display_handle.is_none()
        {
            // Force WebGL, useful for quick & dirty testing:
            // create_new.instance_descriptor.backends = wgpu::Backends::GL;
            create_new.display_handle = Some(Box::new(WebDisplay));
        }
        // Vendored change: the page's early WebGPU adapter request (see
        // `WebOptions::webgpu_probe`) found none: straight to WebGL.
        if let Some(probe) = &options.webgpu_probe
            && !has_webgpu(probe).await
            && let egui_wgpu::WgpuSetup::CreateNew(ref mut create_new) = wgpu_options.wgpu_setup
        {
            create_new
                .instance_descriptor
                .backends
                .remove(wgpu::Backends::BROWSER_WEBGPU);
        }

        let instance = wgpu_options.wgpu_setup.new_instance().await;
        let surface = instance
            .create_surface(wgpu::SurfaceTarget::Canvas(canvas.clone()))
            .map_err(|err| format!("failed to create wgpu surface: {err}"))?;

        let depth_stencil_format = egui_wgpu::depth_format_from_bits(options.depth_buffer, 0);

        let render_state = RenderState::create(
            &wgpu_options,
            &instance,
            Some(&surface),
            egui_wgpu::RendererOptions {
                dithering: options.dithering,
                depth_stencil_format,
                ..Default::default()
            },
        )
        .await
        .map_err(|err| err.to_string())?;

        let default_configuration = surface
            .get_default_config(&render_state.adapter, 0, 0) // Width/height is set later.
            .ok_or("The surface isn't supported by this adapter")?;

        // Vendored change: the window's texture is a copy destination where the
        // surface allows it, for paint callbacks shown by a copy (see
        // `egui_wgpu::CallbackTrait::copy_source`).
        let copy_dst = surface
            .get_capabilities(&render_state.adapter)
            .usages
            .intersection(wgpu::TextureUsages::COPY_DST);
        // Vendored change: on WebGL2 wgpu draws straight into the canvas, whose
        // drawing buffer is preserved between frames (see wgpu-hal's
        // `VENDORED.md`): a frame redraws only what changed (`damage.rs`).
        let keeps_pixels = render_state.adapter.get_info().backend == wgpu::Backend::Gl;
        let fill = egui_wgpu::FillQuad::new(&render_state.device);
        let surface_configuration = wgpu::SurfaceConfiguration {
            format: render_state.target_format,
            present_mode: wgpu_options.surface.present_mode,
            view_formats: vec![render_state.target_format],
            usage: default_configuration.usage | copy_dst,
            ..default_configuration
        };

        log::debug!("wgpu painter initialized.");

        Ok(Self {
            canvas,
            instance,
            render_state: Some(render_state),
            surface,
            surface_configuration,
            depth_stencil_format,
            depth_texture_view: None,
            on_surface_status: Arc::clone(&wgpu_options.on_surface_status) as _,
            screen_capture_state: None,
            ctx,
            needs_reconfigure: false,
            needs_recreate: false,
            damage: keeps_pixels.then(Default::default),
            fill,
            canvas_texture: None,
        })
    }
}

impl WebPainter for WebPainterWgpu {
    fn canvas(&self) -> &HtmlCanvasElement {
        &self.canvas
    }

    fn max_texture_side(&self) -> usize {
        // Vendored change: at most the side egui's first pass was laid out
        // with (see `FIRST_PASS_TEXTURE_SIDE`).
        self.render_state.as_ref().map_or(0, |state| {
            (state.device.limits().max_texture_dimension_2d as usize)
                .min(super::FIRST_PASS_TEXTURE_SIDE)
        })
    }

    fn paint_and_update_textures(
        &mut self,
        clear_color: [f32; 4],
        clipped_primitives: &[egui::ClippedPrimitive],
        pixels_per_point: f32,
        textures_delta: &mut egui::TexturesDelta,
        capture_data: Vec<ScreenshotCallback>,
    ) -> Result<(), JsValue> {
        let capture = !capture_data.is_empty();

        let size_in_pixels = [self.canvas.width(), self.canvas.height()];

        let Some(render_state) = &self.render_state else {
            return Err(JsValue::from_str(
                "Can't paint, wgpu renderer was already disposed",
            ));
        };

        // If the previous frame produced `CurrentSurfaceTexture::Lost`, drop and recreate the
        // surface from the canvas before re-borrowing `self.render_state` for the rest of paint.
        if self.needs_recreate {
            self.needs_recreate = false;
            match self
                .instance
                .create_surface(wgpu::SurfaceTarget::Canvas(self.canvas.clone()))
            {
                Ok(new_surface) => {
                    new_surface.configure(&render_state.device, &self.surface_configuration);
                    self.surface = new_surface;
                }
                Err(err) => {
                    log::error!("Failed to recreate wgpu surface for canvas: {err}");
                }
            }
        }

        let mut encoder =
            render_state
                .device
                .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                    label: Some("egui_webpainter_paint_and_update_textures"),
                });

        // Upload all resources for the GPU.
        let screen_descriptor = egui_wgpu::ScreenDescriptor {
            size_in_pixels,
            pixels_per_point,
        };

        // Vendored change: a texture replaced or freed (or any but the font
        // atlas changed) may change pixels whose paint jobs did not change.
        let textures_changed = !textures_delta.free.is_empty()
            || textures_delta.set.iter().any(|(id, deltas)| {
                *id != egui::TextureId::default() || deltas.iter().any(|d| d.pos.is_none())
            });
        let user_cmd_bufs = {
            let mut renderer = render_state.renderer.write();
            #[expect(clippy::iter_over_hash_type)] // Order doesn't matter here
            for (id, image_deltas) in textures_delta.set.drain() {
                for image_delta in image_deltas {
                    renderer.update_texture(
                        &render_state.device,
                        &render_state.queue,
                        id,
                        &image_delta,
                    );
                }
            }

            renderer.update_buffers(
                &render_state.device,
                &render_state.queue,
                &mut encoder,
                clipped_primitives,
                &screen_descriptor,
            )
        };

        // Resize surface if needed
        let is_zero_sized_surface = size_in_pixels[0] == 0 || size_in_pixels[1] == 0;
        let mut reconfigured = self.needs_reconfigure;
        let frame_and_capture_buffer = if is_zero_sized_surface {
            None
        } else {
            let keeps_pixels = self.damage.is_some();
            if size_in_pixels[0] != self.surface_configuration.width
                || size_in_pixels[1] != self.surface_configuration.height
                || (keeps_pixels && self.canvas_texture.is_none())
            {
                reconfigured = true;
                self.surface_configuration.width = size_in_pixels[0];
                self.surface_configuration.height = size_in_pixels[1];
                if keeps_pixels {
                    self.canvas_texture = Some(canvas_texture(
                        &render_state.device,
                        &self.canvas,
                        &self.surface_configuration,
                    ));
                } else {
                    self.surface
                        .configure(&render_state.device, &self.surface_configuration);
                }
                self.depth_texture_view = self.generate_depth_texture_view(
                    render_state,
                    size_in_pixels[0],
                    size_in_pixels[1],
                );
            }

            if self.needs_reconfigure && !keeps_pixels {
                self.surface
                    .configure(&render_state.device, &self.surface_configuration);
                self.needs_reconfigure = false;
            }

            let output_frame = match self.canvas_texture.as_ref().filter(|_| keeps_pixels) {
                Some(_) => None,
                None => Some(match self.surface.get_current_texture() {
                wgpu::CurrentSurfaceTexture::Success(frame) => frame,
                wgpu::CurrentSurfaceTexture::Suboptimal(frame) => {
                    self.needs_reconfigure = true;
                    frame
                }
                other => {
                    match (*self.on_surface_status)(&other) {
                        SurfaceErrorAction::Reconfigure => {
                            self.surface
                                .configure(&render_state.device, &self.surface_configuration);
                        }
                        SurfaceErrorAction::RecreateSurface => {
                            // Full recovery needs `&mut self`, which conflicts with the live
                            // `render_state` / `self.surface` borrows here. Defer to the top
                            // of the next paint via the `needs_recreate` flag, and request a
                            // repaint so the next frame actually invokes `paint` to consume it.
                            self.needs_recreate = true;
                            self.ctx.request_repaint();
                        }
                        SurfaceErrorAction::SkipFrame => {}
                    }
                    return Ok(());
                }
            }),
            };
            let window_texture = match (&output_frame, &self.canvas_texture) {
                (Some(frame), _) => &frame.texture,
                (None, Some(texture)) => texture,
                (None, None) => return Ok(()),
            };

            {
                let renderer = render_state.renderer.read();

                let target_texture = if capture {
                    let size = window_texture.size();
                    let format = window_texture.format();
                    let capture_state = self.screen_capture_state.get_or_insert_with(|| {
                        CaptureState::new(&render_state.device, size, format)
                    });
                    capture_state.update(&render_state.device, size);

                    &capture_state.texture
                } else {
                    window_texture
                };
                let target_view =
                    target_texture.create_view(&wgpu::TextureViewDescriptor::default());

                // Vendored change: paint callbacks with a copy source are copied
                // onto their rect between two passes (see `copies`).
                let copies = if capture || self.depth_texture_view.is_some() {
                    Vec::new()
                } else {
                    copies(
                        &renderer,
                        clipped_primitives,
                        &screen_descriptor,
                        target_texture,
                        target_texture.usage(),
                    )
                };
                // Vendored change: where the window keeps its pixels, only
                // the regions that changed are redrawn (`damage.rs`).
                let regions = match &mut self.damage {
                    Some(damage) if !capture && self.depth_texture_view.is_none() => {
                        if textures_changed || reconfigured || clear_color[3] < 1.0 {
                            damage.forget();
                        }
                        damage.regions(clipped_primitives, size_in_pixels, pixels_per_point, |index| {
                            callback_change(&renderer, clipped_primitives, index)
                        })
                    }
                    Some(damage) => {
                        damage.forget();
                        None
                    }
                    None => None,
                };
                if let (Some(regions), Some(damage)) = (regions, self.damage.as_ref()) {
                    if !regions.is_empty() {
                        let color = egui::Color32::from_rgba_premultiplied(
                            (clear_color[0] * 255.0).round() as u8,
                            (clear_color[1] * 255.0).round() as u8,
                            (clear_color[2] * 255.0).round() as u8,
                            255,
                        );
                        self.fill.set(&render_state.queue, &screen_descriptor, color);
                    }
                    let covered = covered(&renderer, clipped_primitives, &screen_descriptor, &copies);
                    redraw_regions(
                        &renderer,
                        &mut encoder,
                        &target_view,
                        target_texture,
                        clipped_primitives,
                        &copies,
                        &covered,
                        &screen_descriptor,
                        &self.fill,
                        &regions,
                        damage,
                    );
                } else {
                let mut start = 0;
                for (index, copy) in copies.iter().enumerate() {
                    let load = if index == 0 { clear_to(clear_color) } else { wgpu::LoadOp::Load };
                    let mut pass = begin_pass(&mut encoder, &target_view, load, None).forget_lifetime();
                    renderer.render_range(&mut pass, clipped_primitives, start..copy.primitive, &screen_descriptor);
                    drop(pass);
                    encoder.copy_texture_to_texture(
                        wgpu::TexelCopyTextureInfo {
                            texture: copy.source,
                            mip_level: 0,
                            origin: copy.from,
                            aspect: wgpu::TextureAspect::All,
                        },
                        wgpu::TexelCopyTextureInfo {
                            texture: target_texture,
                            mip_level: 0,
                            origin: copy.to,
                            aspect: wgpu::TextureAspect::All,
                        },
                        copy.size,
                    );
                    start = copy.primitive + 1;
                }
                let load = if copies.is_empty() { clear_to(clear_color) } else { wgpu::LoadOp::Load };
                let depth = self.depth_texture_view.as_ref().map(|view| (view, self.depth_stencil_format));
                let render_pass = begin_pass(&mut encoder, &target_view, load, depth);

                // Forgetting the pass' lifetime means that we are no longer compile-time protected from
                // runtime errors caused by accessing the parent encoder before the render pass is dropped.
                // Since we don't pass it on to the renderer, we should be perfectly safe against this mistake here!
                renderer.render_range(
                    &mut render_pass.forget_lifetime(),
                    clipped_primitives,
                    start..clipped_primitives.len(),
                    &screen_descriptor,
                );
                }
            }

            let capture_buffer =
                if capture && let Some(capture_state) = &mut self.screen_capture_state {
                    let buffer = capture_state.copy_textures(
                        &render_state.device,
                        output_frame.as_ref(),
                        &mut encoder,
                    );
                    // Vendored change: the canvas's texture gets the captured
                    // frame as the surface's does above.
                    if output_frame.is_none() {
                        encoder.copy_texture_to_texture(
                            capture_state.texture.as_image_copy(),
                            window_texture.as_image_copy(),
                            window_texture.size(),
                        );
                    }
                    Some(buffer)
                } else {
                    None
                };

            Some((output_frame, capture_buffer))
        };

        // Submit the commands: both the main buffer and user-defined ones.
        render_state
            .queue
            .submit(core::iter::chain(user_cmd_bufs, [encoder.finish()]));

        if let Some((frame, capture_buffer)) = frame_and_capture_buffer {
            if let Some(capture_buffer) = capture_buffer
                && let Some(capture_state) = &self.screen_capture_state
            {
                capture_state.read_screen_rgba(capture_buffer, capture_data);
            }

            if let Some(frame) = frame {
                render_state.queue.present(frame);
            }
        }

        // Free textures marked for destruction **after** queue submit since they might still be used in the current frame.
        // Calling `wgpu::Texture::destroy` on a texture that is still in use would invalidate the command buffer(s) it is used in.
        // However, once we called `wgpu::Queue::submit`, it is up for wgpu to determine how long the underlying gpu resource has to live.
        {
            let mut renderer = render_state.renderer.write();
            #[expect(clippy::iter_over_hash_type)] // Order doesn't matter here
            for id in textures_delta.free.drain() {
                renderer.free_texture(&id);
            }
        }

        Ok(())
    }

    fn destroy(&mut self) {
        self.render_state = None;
    }
}

/// Vendored change: a paint callback shown by copying its texture onto the
/// window's (see `egui_wgpu::CallbackTrait::copy_source`).
struct Copy<'a> {
    /// Its index in the frame's primitives.
    primitive: usize,
    source: &'a wgpu::Texture,
    /// Where the visible part starts in `source`, and in the window.
    from: wgpu::Origin3d,
    to: wgpu::Origin3d,
    size: wgpu::Extent3d,
}

/// The paint callbacks of `primitives` that can be copied into `target`
/// instead of painted: with a copy source of the target's format (sRGB or not)
/// and of their rect's size in pixels, where the target is a copy destination
/// (`usage`). On a software rasteriser (SwiftShader, in virtual machines and
/// headless browsers) a copy is a small part of the cost of a textured draw.
fn copies<'a>(
    renderer: &'a egui_wgpu::Renderer,
    primitives: &[egui::ClippedPrimitive],
    screen: &egui_wgpu::ScreenDescriptor,
    target: &wgpu::Texture,
    usage: wgpu::TextureUsages,
) -> Vec<Copy<'a>> {
    if !usage.contains(wgpu::TextureUsages::COPY_DST) {
        return Vec::new();
    }
    let format = target.format().remove_srgb_suffix();
    let mut out = Vec::new();
    for (index, primitive) in primitives.iter().enumerate() {
        let egui::epaint::Primitive::Callback(callback) = &primitive.primitive else { continue };
        let Some(source) = callback
            .callback
            .downcast_ref::<egui_wgpu::Callback>()
            .and_then(|c| c.copy_source(&renderer.callback_resources))
        else {
            continue;
        };
        let view = callback_info(primitive, callback, screen).viewport_in_pixels();
        let fits = source.format().remove_srgb_suffix() == format
            && source.sample_count() == 1
            && source.usage().contains(wgpu::TextureUsages::COPY_SRC)
            && source.width() as i32 == view.width_px
            && source.height() as i32 == view.height_px;
        if !fits {
            continue;
        }
        let Some([x0, y0, x1, y1]) = callback_pixels(primitive, callback, screen, 0) else { continue };
        out.push(Copy {
            primitive: index,
            source,
            from: wgpu::Origin3d { x: (x0 - view.left_px) as u32, y: (y0 - view.top_px) as u32, z: 0 },
            to: wgpu::Origin3d { x: x0 as u32, y: y0 as u32, z: 0 },
            size: wgpu::Extent3d { width: (x1 - x0) as u32, height: (y1 - y0) as u32, depth_or_array_layers: 1 },
        });
    }
    out
}

/// Vendored change: the paint information of `callback`, the primitive of `job`.
fn callback_info(
    job: &egui::ClippedPrimitive,
    callback: &egui::PaintCallback,
    screen: &egui_wgpu::ScreenDescriptor,
) -> egui::PaintCallbackInfo {
    egui::PaintCallbackInfo {
        viewport: callback.rect,
        clip_rect: job.clip_rect,
        pixels_per_point: screen.pixels_per_point,
        screen_size_px: screen.size_in_pixels,
    }
}

/// Vendored change: the pixels `callback` (the primitive of `job`) paints,
/// its rect within its clip rect and the window, as `[x0, y0, x1, y1]`, less
/// `inset` pixels each side; `None` where that is empty.
fn callback_pixels(
    job: &egui::ClippedPrimitive,
    callback: &egui::PaintCallback,
    screen: &egui_wgpu::ScreenDescriptor,
    inset: i32,
) -> Option<[i32; 4]> {
    let info = callback_info(job, callback, screen);
    let (view, clip) = (info.viewport_in_pixels(), info.clip_rect_in_pixels());
    let [width, height] = screen.size_in_pixels.map(|v| v as i32);
    let x0 = view.left_px.max(clip.left_px).max(0) + inset;
    let y0 = view.top_px.max(clip.top_px).max(0) + inset;
    let x1 = (view.left_px + view.width_px).min(clip.left_px + clip.width_px).min(width) - inset;
    let y1 = (view.top_px + view.height_px).min(clip.top_px + clip.height_px).min(height) - inset;
    (x1 > x0 && y1 > y0).then_some([x0, y0, x1, y1])
}

/// Vendored change: the rects (`[x, y, width, height]` in pixels) whose
/// pixels `copies` or paint callbacks that cover their rect
/// ([`egui_wgpu::CallbackTrait::covers`]) write whatever lies under them:
/// a redrawn region needs no background there. A painted callback's rect is
/// taken a pixel in from each side (the painter's scissor may round its
/// edges otherwise).
fn covered(
    renderer: &egui_wgpu::Renderer,
    jobs: &[egui::ClippedPrimitive],
    screen: &egui_wgpu::ScreenDescriptor,
    copies: &[Copy<'_>],
) -> Vec<[u32; 4]> {
    let copied = copies.iter().map(|c| [c.to.x, c.to.y, c.size.width, c.size.height]);
    let painted = jobs.iter().enumerate().filter_map(|(index, job)| {
        let egui::epaint::Primitive::Callback(callback) = &job.primitive else { return None };
        if copies.iter().any(|c| c.primitive == index) {
            return None;
        }
        let covers = callback
            .callback
            .downcast_ref::<egui_wgpu::Callback>()
            .is_some_and(|c| c.covers(&renderer.callback_resources));
        let [x0, y0, x1, y1] = callback_pixels(job, callback, screen, 1).filter(|_| covers)?;
        Some([x0 as u32, y0 as u32, (x1 - x0) as u32, (y1 - y0) as u32])
    });
    copied.chain(painted).collect()
}

/// Vendored change: the drawing buffer of `canvas` (WebGL2's default
/// framebuffer) as a texture of `config`'s size and format, with `canvas`
/// mirrored back by its style: wgpu's GL backend draws the first row at the
/// top of memory, which WebGL shows at the bottom (its own present flips
/// it); the browser's compositor applies the style's `scaleY(-1)` at no cost,
/// and pointer positions are the page's, so input is unaffected.
#[expect(unsafe_code)]
fn canvas_texture(
    device: &wgpu::Device,
    canvas: &HtmlCanvasElement,
    config: &wgpu::SurfaceConfiguration,
) -> wgpu::Texture {
    if let Err(err) = canvas.style().set_property("transform", "scaleY(-1)") {
        log::warn!("could not mirror the canvas: {err:?}");
    }
    let hal = wgpu::hal::gles::Texture::default_framebuffer(config.format);
    let desc = wgpu::TextureDescriptor {
        label: Some("egui_canvas"),
        size: wgpu::Extent3d { width: config.width, height: config.height, depth_or_array_layers: 1 },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: config.format,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_DST,
        view_formats: &[],
    };
    // SAFETY: the default framebuffer belongs to the device's WebGL2 context
    // (the one the surface made), has the canvas's size (set just before)
    // and is initialised (the first frame drawn into it is a full one).
    unsafe { device.create_texture_from_hal::<wgpu::hal::api::Gles>(hal, &desc, wgpu::TextureUses::UNINITIALIZED) }
}

/// Vendored change: what changed in the copy source of the paint callback
/// at `index` of `jobs` (see `egui_wgpu::CallbackTrait::copy_changed`).
fn callback_change(
    renderer: &egui_wgpu::Renderer,
    jobs: &[egui::ClippedPrimitive],
    index: usize,
) -> egui_wgpu::CopyChange {
    match jobs.get(index).map(|job| &job.primitive) {
        Some(egui::epaint::Primitive::Callback(callback)) => callback
            .callback
            .downcast_ref::<egui_wgpu::Callback>()
            .map_or(egui_wgpu::CopyChange::All, |c| c.copy_changed(&renderer.callback_resources)),
        _ => egui_wgpu::CopyChange::All,
    }
}

/// Vendored change: redraws `regions` (`[x, y, width, height]` in pixels,
/// apart from each other) of the window's texture: in each, `fill` (the
/// clear colour), then every job inside it, with the copies (see `copies`)
/// cut to it; of each mesh only the triangles `damage` (which made the
/// regions) says may reach it ([`super::damage::Damage::index_runs`]). All
/// regions are drawn in one pass before each copy and one after the last,
/// each job in every region before the next job (its state set once):
/// regions apart from each other can be drawn in any order, and a pass
/// costs some thirty WebGL calls.
#[expect(clippy::too_many_arguments)]
fn redraw_regions(
    renderer: &egui_wgpu::Renderer,
    encoder: &mut wgpu::CommandEncoder,
    view: &wgpu::TextureView,
    texture: &wgpu::Texture,
    jobs: &[egui::ClippedPrimitive],
    copies: &[Copy<'_>],
    covered: &[[u32; 4]],
    screen: &egui_wgpu::ScreenDescriptor,
    fill: &egui_wgpu::FillQuad,
    regions: &[[u32; 4]],
    damage: &super::damage::Damage,
) {
    if regions.is_empty() {
        return;
    }
    let index_runs = |job, region, runs: &mut Vec<std::ops::Range<u32>>| damage.index_runs(job, region, runs);
    // A pass before each copy, then one after the last; the first draws the
    // background where nothing covers the regions.
    let mut start = 0;
    for (index, copy) in copies.iter().map(Some).chain([None]).enumerate() {
        let end = copy.map_or(jobs.len(), |c| c.primitive);
        let mut pass = begin_pass(encoder, view, wgpu::LoadOp::Load, None).forget_lifetime();
        if index == 0 {
            let bands: Vec<[u32; 4]> = regions.iter().flat_map(|&region| super::damage::uncovered(region, covered)).collect();
            renderer.render_fill(&mut pass, fill, screen, &bands);
        }
        renderer.render_range_within(&mut pass, jobs, start..end, screen, Some(regions), &index_runs);
        drop(pass);
        if let Some(copy) = copy {
            start = copy.primitive + 1;
            for &region in regions {
                copy_within(encoder, copy, texture, region);
            }
        }
    }
}

/// Vendored change: the part of `copy` inside `region` (`[x, y, width,
/// height]` in pixels) copied into `texture`.
fn copy_within(encoder: &mut wgpu::CommandEncoder, copy: &Copy<'_>, texture: &wgpu::Texture, region: [u32; 4]) {
    let [rx, ry, rw, rh] = region;
    let x0 = copy.to.x.max(rx);
    let y0 = copy.to.y.max(ry);
    let x1 = (copy.to.x + copy.size.width).min(rx + rw);
    let y1 = (copy.to.y + copy.size.height).min(ry + rh);
    if x1 <= x0 || y1 <= y0 {
        return;
    }
    encoder.copy_texture_to_texture(
        wgpu::TexelCopyTextureInfo {
            texture: copy.source,
            mip_level: 0,
            origin: wgpu::Origin3d { x: copy.from.x + x0 - copy.to.x, y: copy.from.y + y0 - copy.to.y, z: 0 },
            aspect: wgpu::TextureAspect::All,
        },
        wgpu::TexelCopyTextureInfo {
            texture,
            mip_level: 0,
            origin: wgpu::Origin3d { x: x0, y: y0, z: 0 },
            aspect: wgpu::TextureAspect::All,
        },
        wgpu::Extent3d { width: x1 - x0, height: y1 - y0, depth_or_array_layers: 1 },
    );
}

/// The clear of the window to `color`.
fn clear_to(color: [f32; 4]) -> wgpu::LoadOp<wgpu::Color> {
    let [r, g, b, a] = color.map(f64::from);
    wgpu::LoadOp::Clear(wgpu::Color { r, g, b, a })
}

/// egui's pass into `view`, loaded by `load`, with the depth buffer when there is one.
fn begin_pass<'e>(
    encoder: &'e mut wgpu::CommandEncoder,
    view: &wgpu::TextureView,
    load: wgpu::LoadOp<wgpu::Color>,
    depth: Option<(&wgpu::TextureView, Option<wgpu::TextureFormat>)>,
) -> wgpu::RenderPass<'e> {
    encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
        color_attachments: &[Some(wgpu::RenderPassColorAttachment {
            view,
            resolve_target: None,
            ops: wgpu::Operations { load, store: wgpu::StoreOp::Store },
            depth_slice: None,
        })],
        depth_stencil_attachment: depth.map(|(view, format)| wgpu::RenderPassDepthStencilAttachment {
            view,
            depth_ops: format.is_some_and(|f| f.has_depth_aspect()).then_some(wgpu::Operations {
                load: wgpu::LoadOp::Clear(1.0),
                // It is very unlikely that the depth buffer is needed after egui finished rendering
                // so no need to store it. (this can improve performance on tiling GPUs like mobile chips or Apple Silicon)
                store: wgpu::StoreOp::Discard,
            }),
            stencil_ops: format.is_some_and(|f| f.has_stencil_aspect()).then_some(wgpu::Operations {
                load: wgpu::LoadOp::Clear(0),
                store: wgpu::StoreOp::Discard,
            }),
        }),
        label: Some("egui_render"),
        occlusion_query_set: None,
        timestamp_writes: None,
        multiview_mask: None,
    })
}

/// Vendored change: whether the page's early WebGPU adapter request (see
/// `WebOptions::webgpu_probe`) found an adapter.
async fn has_webgpu(probe: &js_sys::Promise) -> bool {
    js_sys::futures::JsFuture::from(probe.clone())
        .await
        .is_ok_and(|adapter| !adapter.is_null() && !adapter.is_undefined())
}
