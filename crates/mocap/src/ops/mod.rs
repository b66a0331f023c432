//! Offline operations on whole clips: [`edit`]s (trim, retime, keys, rig
//! changes), animation [`layer`]s, [`bake`] (a pose stream back to channels)
//! foot [`contact`]s (foot lock), [`retarget`] (a motion on another skeleton)
//! and [`compare`] (two takes: position and angle errors).

pub mod bake;
pub mod compare;
pub mod contact;
pub mod edit;
pub mod layer;
pub mod retarget;
