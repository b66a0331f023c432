//! Offline operations on whole clips: [`edit`]s (trim, retime, keys, rig
//! changes), animation [`layer`]s, [`bake`] (a pose stream back to channels)
//! and foot [`contact`]s (foot lock).

pub mod bake;
pub mod contact;
pub mod edit;
pub mod layer;
