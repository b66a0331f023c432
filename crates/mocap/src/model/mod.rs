//! The data model every format reads into and every stage works on: the
//! [`skeleton`] (joints in parent-before-child order), its [`channel`]s, the
//! [`motion`] table, a [`clip`] (skeleton + motion + units), [`time`], the
//! [`up`] axis, the format-free [`mesh`] model (vertex frames and skins), and
//! an [`asset`] (a clip or a model), and a clip's [`character`] (a glTF look and takes). Nothing here depends on a file format.

pub mod asset;
pub mod channel;
pub mod character;
pub mod clip;
pub mod mesh;
pub mod motion;
pub mod skeleton;
pub mod time;
pub mod up;
