//! The per-frame stages, each over flat arrays in parent-before-child order:
//! [`sample`] a clip at a time into a local pose ([`pose`]), forward kinematics
//! ([`fk`], and [`batch`] for every frame at once), [`skin`]ning matrices and
//! vertices, and inverse kinematics ([`ik`]).

pub mod batch;
pub(crate) mod fastmath;
pub mod fk;
pub mod ik;
pub(crate) mod parallel;
pub mod pose;
pub mod sample;
pub mod skin;
