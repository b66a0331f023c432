//! A small wgpu renderer for motion-capture scenes.
//!
//! It knows nothing of file formats or UI: callers hand it a [`Scene`] made of
//! primitives (lit [`Capsule`]s, screen-space-wide [`Line`]s, shaded [`Sphere`]
//! impostors, textured vertex-animated meshes ([`MeshDraw`]) and a floor [`Grid`]
//! that receives a soft shadow from a key light)
//! plus a [`Camera`], and it draws them into a [`RenderTarget`] with any wgpu
//! `Device`/`Queue` (WebGPU, WebGL2, Vulkan, lavapipe, ...). [`push_figure`] turns
//! a posed skeleton (parents and world positions) into primitives in a
//! [`DrawMode`]. Everything is instanced: a frame takes a handful of draw calls
//! whatever the number of figures.
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

mod blit;
mod bounds;
mod buffer;
mod camera;
mod capsule;
mod color;
mod damage;
mod figure;
mod floor_cache;
mod grid;
mod lines;
mod mesh;
#[cfg(test)]
mod first_frame_glsl;
#[cfg(test)]
mod glsl_ahead;
mod pipeline;
mod pipeline_set;
mod placed;
mod radius;
mod readback;
mod renderer;
mod scene;
mod shader_source;
mod shader_text;
mod shadow;
mod skinned;
mod spheres;
mod target;
mod texture;
mod uniforms;

pub use blit::{Blit, BlitSource};
pub use camera::Camera;
pub use color::srgb_to_linear;
pub use figure::{
    DrawMode, FigureJoint, FigureStyle, HIGHLIGHT_COLOR, JOINT_COLOR, MAX_FIGURE_BONES, PALETTE, figure, push_figure,
};
pub use glam;
pub use grid::Grid;
pub use mesh::{MeshDraw, MorphMeshData, MorphVertex, NEUTRAL_TINT};
pub use radius::{BODY_THICKNESS, HELPER_BONE, MAX_CARRIED, body_radii, bone_radii, bone_radius, size_figure};
pub use readback::Readback;
pub use renderer::SceneRenderer;
#[cfg(feature = "test-support")]
pub use renderer::TestPaths;
pub use scene::{Capsule, Line, Scene, Sphere};
pub use shadow::key_light_direction;
pub use skinned::{COARSE_BODY_SPAN_PX, SkinnedDraw, SkinnedMeshData, SkinnedTexture, SkinnedVertex};
pub use target::RenderTarget;
pub use texture::SkinImage;
pub use wgpu;

/// Depth format used by every pipeline and [`RenderTarget`]: 32-bit float,
/// which (unlike `Depth24Plus`) can be copied, so a frame can start from the
/// floor's depth drawn before (floor_cache.rs).
pub const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;
