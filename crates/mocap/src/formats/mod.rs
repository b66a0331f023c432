//! One folder per file format, each with a pure `parse(bytes)` into the
//! [`model`](crate::model) and, where it writes, `write`: [`bvh`], [`bva`],
//! [`acclaim`] (ASF/AMC), [`md2`] (Quake 2 models), [`gltf`] (written) and [`image`] (skins: PCX,
//! BMP, PNG, JPEG). [`load`] picks the reader for a set of named files. [`store`]
//! keeps any asset losslessly in a binary file of this crate's own (the page's
//! autosave). Formats depend on the model, never the reverse.

pub mod acclaim;
pub mod bva;
pub mod bvh;
mod decimal;
pub mod gltf;
pub mod image;
pub mod load;
pub mod md2;
pub mod store;
mod text;
