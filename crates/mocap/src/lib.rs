//! Motion-capture data: readers and writers for the classic formats (Biovision
//! BVH and BVA, Acclaim ASF/AMC, Quake 2 MD2 models and their skins), one animation
//! model for all of them, sampling and forward kinematics.
//!
//! Data flows one way: bytes → [`Asset`] ([`load`]: a [`Clip`], skeleton + motion, or
//! a [`Model`], mesh + vertex frames + skin) → for clips, a sampled
//! [`LocalPose`] ([`sample`]) → [later stages: layers, IK, edits] → model
//! transforms ([`local_to_model`]). This crate touches no file system, GPU or browser: it takes
//! bytes and returns data.
//!
//! ```
//! let bvh = b"HIERARCHY\nROOT Hips\n{\n OFFSET 0 0 0\n CHANNELS 3 Xposition Yposition Zposition\n End Site\n {\n  OFFSET 0 1 0\n }\n}\nMOTION\nFrames: 1\nFrame Time: 0.5\n1 2 3\n";
//! let clip = mocap::bvh::parse(bvh).unwrap();
//! let positions = clip.world_positions(0);
//! assert_eq!(positions[1], mocap::glam::Vec3::new(1.0, 3.0, 3.0));
//! ```

#![warn(missing_docs)]

pub mod acclaim;
pub mod arrange;
pub mod asset;
pub mod bake;
pub mod batch;
pub mod body;
pub mod bva;
pub mod bvh;
pub mod capture;
pub mod channel;
pub mod clip;
pub mod contact;
mod decimal;
pub mod demo;
pub mod edit;
pub mod error;
mod fastmath;
pub mod fk;
pub mod ik;
pub mod image;
pub mod layer;
pub mod load;
pub mod md2;
pub mod morph;
pub mod motion;
mod parallel;
pub mod pose;
pub mod sample;
pub mod skeleton;
pub mod skin;
pub mod stage;
mod text;
pub mod time;
pub mod up;

pub use asset::Asset;
pub use channel::{AngleUnit, Channel, ChannelKind};
pub use clip::{Aabb, Clip, ClipError, Units};
pub use error::{LoadError, ParseError, Warning};
pub use fk::{Transform, local_to_model};
pub use glam;
pub use morph::{Model, MorphMesh};
pub use motion::Motion;
pub use pose::LocalPose;
pub use sample::{Interpolation, SampleScratch};
pub use skeleton::{EulerConvention, Joint, Limit, Skeleton};
pub use time::Timeline;
pub use up::UpAxis;

pub use load::{Format, Input, Loaded, Loader, load, load_one};
