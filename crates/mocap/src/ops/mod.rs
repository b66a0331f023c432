//! Offline operations on whole clips: [`edit`]s (trim, retime, keys, rig
//! changes), animation [`layer`]s, [`bake`] (a pose stream back to channels)
//! foot [`contact`]s (foot lock) and [`retarget`] (a motion on another skeleton).

pub mod bake;
pub mod contact;
pub mod edit;
pub mod layer;
pub mod retarget;
