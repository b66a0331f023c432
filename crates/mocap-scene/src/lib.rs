//! The one scene builder, shared by the viewer, `mocap render` and the benches:
//! what each actor of a [`mocap::stage::Stage`] is drawn with ([`Drawable`]: its
//! figure, its generated body, a model's mesh), how one posed actor becomes
//! renderer primitives ([`push_actor`], [`floor_grid`]), and the one rule that
//! frames a stage ([`OrbitCamera::frame`]). A clip drawn by `mocap render` and by
//! the page at the same size is built by the same code and framed the same way.
//!
//! Data flow: posed actor (world transforms in metres, or a model's key frames)
//! → [`push_actor`] → [`mocap_render::Scene`] → `mocap_render::SceneRenderer`.

#![warn(missing_docs)]

mod build;
mod camera;
mod drawable;
mod morph_shape;
mod motion_marks;

pub use build::{ActorDraw, SceneStyle, floor_grid, push_actor};
pub use morph_shape::MorphShape;
pub use motion_marks::{Onion, joint_path, push_onion, push_trail};
pub use camera::{OrbitCamera, Waypoint, fit_distance};
pub use drawable::{Body, Drawable, body_skin, mesh_data};
