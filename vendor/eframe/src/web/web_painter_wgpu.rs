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
        })
    }
}

impl WebPainter for WebPainterWgpu {
    fn canvas(&self) -> &HtmlCanvasElement {
        &self.canvas
    }

    fn max_texture_side(&self) -> usize {
        self.render_state.as_ref().map_or(0, |state| {
            state.device.limits().max_texture_dimension_2d as _
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
        let frame_and_capture_buffer = if is_zero_sized_surface {
            None
        } else {
            if size_in_pixels[0] != self.surface_configuration.width
                || size_in_pixels[1] != self.surface_configuration.height
            {
                self.surface_configuration.width = size_in_pixels[0];
                self.surface_configuration.height = size_in_pixels[1];
                self.surface
                    .configure(&render_state.device, &self.surface_configuration);
                self.depth_texture_view = self.generate_depth_texture_view(
                    render_state,
                    size_in_pixels[0],
                    size_in_pixels[1],
                );
            }

            if self.needs_reconfigure {
                self.surface
                    .configure(&render_state.device, &self.surface_configuration);
                self.needs_reconfigure = false;
            }

            let output_frame = match self.surface.get_current_texture() {
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
            };

            {
                let renderer = render_state.renderer.read();

                let target_texture = if capture {
                    let size = output_frame.texture.size();
                    let format = output_frame.texture.format();
                    let capture_state = self.screen_capture_state.get_or_insert_with(|| {
                        CaptureState::new(&render_state.device, size, format)
                    });
                    capture_state.update(&render_state.device, size);

                    &capture_state.texture
                } else {
                    &output_frame.texture
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
                        self.surface_configuration.usage,
                    )
                };
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

            let capture_buffer =
                if capture && let Some(capture_state) = &mut self.screen_capture_state {
                    Some(capture_state.copy_textures(
                        &render_state.device,
                        Some(&output_frame),
                        &mut encoder,
                    ))
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

            render_state.queue.present(frame);
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
    let [width, height] = screen.size_in_pixels.map(|v| v as i32);
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
        let info = egui::PaintCallbackInfo {
            viewport: callback.rect,
            clip_rect: primitive.clip_rect,
            pixels_per_point: screen.pixels_per_point,
            screen_size_px: screen.size_in_pixels,
        };
        let (view, clip) = (info.viewport_in_pixels(), info.clip_rect_in_pixels());
        let fits = source.format().remove_srgb_suffix() == format
            && source.sample_count() == 1
            && source.usage().contains(wgpu::TextureUsages::COPY_SRC)
            && source.width() as i32 == view.width_px
            && source.height() as i32 == view.height_px;
        if !fits {
            continue;
        }
        let x0 = view.left_px.max(clip.left_px).max(0);
        let y0 = view.top_px.max(clip.top_px).max(0);
        let x1 = (view.left_px + view.width_px).min(clip.left_px + clip.width_px).min(width);
        let y1 = (view.top_px + view.height_px).min(clip.top_px + clip.height_px).min(height);
        if x1 <= x0 || y1 <= y0 {
            continue;
        }
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
