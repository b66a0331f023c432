//! glTF 2.0, in and out. [`read`] turns a `.glb` or `.gltf` (with its `.bin`
//! and images) into a clip carrying a character (skinned look, every animation
//! as a take), through [`document`] (bytes → checked document and buffers),
//! [`graph`] (nodes → joints), [`animation`] (channels → sampled tracks),
//! [`accessor`] (bounds-checked data) and [`look`] (meshes → one skinned mesh).
//! [`write`] turns a clip into a `.glb` or `.gltf` (skeleton, skin, body or the
//! character's own mesh, and animation; metres, Y up).

pub mod accessor;
pub mod animation;
pub mod document;
pub mod graph;
pub mod look;
pub mod read;
pub mod write;

pub use document::{Resources, SUPPORTED_EXTENSIONS, sniff};
pub use read::parse;
pub use write::{Options, WriteError, to_glb, to_gltf};
