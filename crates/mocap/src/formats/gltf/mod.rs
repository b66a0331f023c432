//! glTF 2.0, in and out. [`read`] turns a `.glb` or `.gltf` (with its `.bin`
//! and images) into a clip carrying a character (skinned look, every animation
//! as a take), through [`document`] (bytes → checked document and buffers),
//! [`graph`] (nodes → joints), [`animation`] (channels → sampled tracks),
//! [`accessor`] (bounds-checked data) and [`look`] (meshes → one skinned mesh);
//! a mesh that moves by morph targets alone reads as a model ([`morph`]).
//! [`write`] turns a clip into a `.glb` or `.gltf` (skeleton, skin, body or the
//! character's own mesh, and animation; metres, Y up); [`model`] an MD2 model
//! (morph targets, a `weights` animation per named animation, its skin).

pub mod accessor;
pub mod animation;
mod buffer;
pub mod document;
pub mod graph;
pub mod look;
pub mod model;
pub mod morph;
pub mod read;
pub mod write;

pub use document::{Resources, SUPPORTED_EXTENSIONS, sniff};
pub use model::{model_to_glb, model_to_gltf};
pub use read::{parse, parse_asset};
pub use write::{Options, WriteError, to_glb, to_gltf};
