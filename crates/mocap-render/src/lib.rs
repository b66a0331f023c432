//! A small wgpu renderer for motion-capture scenes.
//!
//! It knows nothing of file formats or UI: callers hand it a [`Scene`] made of
//! primitives (screen-space-wide line segments, shaded sphere impostors and a floor
//! [`Grid`]) plus a [`Camera`], and it draws them into a [`RenderTarget`] with any
//! wgpu `Device`/`Queue` (WebGPU, WebGL2, Vulkan, lavapipe, ...).
//!
//! ```no_run
//! # fn demo(device: &wgpu::Device, queue: &wgpu::Queue) {
//! use mocap_render::{Camera, RenderTarget, Scene, SceneRenderer};
//! let format = wgpu::TextureFormat::Rgba8UnormSrgb;
//! let mut renderer = SceneRenderer::new(device, format, 4);
//! let target = RenderTarget::new(device, format, 4, [640, 480]);
//! let scene = Scene::default();
//! let camera = Camera::look_at(glam::Vec3::new(0.0, 2.0, 5.0), glam::Vec3::ZERO, 0.8, 640.0 / 480.0);
//! renderer.render(device, queue, &target, &scene, &camera);
//! # }
//! ```

#![warn(missing_docs)]

mod buffer;
mod camera;
mod color;
mod grid;
mod lines;
mod pipeline;
mod scene;
mod spheres;
mod target;
mod uniforms;
mod renderer;

pub use camera::Camera;
pub use color::srgb_to_linear;
pub use grid::Grid;
pub use renderer::SceneRenderer;
pub use scene::{Line, Scene, Sphere};
pub use target::RenderTarget;
pub use glam;
pub use wgpu;

/// Depth format used by every pipeline and [`RenderTarget`].
pub const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth24Plus;
