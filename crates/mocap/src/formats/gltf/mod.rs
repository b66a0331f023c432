//! glTF 2.0: [`write`] turns a clip into a `.glb` or `.gltf` (skeleton, skin,
//! generated body and animation; metres, Y up).

pub mod write;

pub use write::{Options, WriteError, to_glb, to_gltf};
