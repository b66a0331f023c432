//! Motion-capture data: readers and writers for the classic formats (Biovision
//! BVH and BVA, Acclaim ASF/AMC, Quake 2 MD2 models and their skins), one animation
//! model for all of them, sampling, forward kinematics and the operations on clips.
//!
//! The crate is organised by concept:
//! - [`model`]: the data (skeleton, channels, motion, clip, time, up axis, units,
//!   the mesh model, assets). It depends on nothing else here.
//! - [`formats`]: one folder per file format, each a pure `parse(bytes)` into the
//!   model and, where it writes, `write`; [`load`] picks the reader.
//! - [`runtime`]: the per-frame stages (sample, pose, FK, skinning, IK).
//! - [`ops`]: offline operations on clips (edits, layers, bake, foot contacts).
//! - [`build`]: what is made in code (the generated body, the demo characters).
//! - [`stage`]: several assets placed on one floor with one timeline.
//! - [`capture`]: a skeleton and its motion captured from an animated model.
//!
//! Data flows one way: bytes → [`Asset`] ([`load`]: a [`Clip`], skeleton + motion, or
//! a [`Model`], mesh + vertex frames + skin) → for clips, a sampled
//! [`LocalPose`] ([`runtime::sample`]) → [`ops`] (layers, IK, edits) → model
//! transforms ([`local_to_model`]). This crate touches no file system, GPU or browser:
//! it takes bytes and returns data.
//!
//! ```
//! let bvh = b"HIERARCHY\nROOT Hips\n{\n OFFSET 0 0 0\n CHANNELS 3 Xposition Yposition Zposition\n End Site\n {\n  OFFSET 0 1 0\n }\n}\nMOTION\nFrames: 1\nFrame Time: 0.5\n1 2 3\n";
//! let clip = mocap::formats::bvh::parse(bvh).unwrap();
//! let positions = clip.world_positions(0);
//! assert_eq!(positions[1], mocap::glam::Vec3::new(1.0, 3.0, 3.0));
//! ```

#![warn(missing_docs)]

pub mod build;
pub mod capture;
pub mod error;
pub mod formats;
pub mod model;
pub mod ops;
pub mod runtime;
pub mod stage;

pub use error::{LoadError, ParseError, Warning};
pub use glam;
pub use model::asset::Asset;
pub use model::channel::{AngleUnit, Channel, ChannelKind};
pub use model::clip::{Aabb, Clip, ClipError, Units};
pub use model::mesh::{Model, MorphMesh};
pub use model::motion::Motion;
pub use model::skeleton::{EulerConvention, Joint, Limit, Skeleton};
pub use model::time::Timeline;
pub use model::up::UpAxis;
pub use runtime::fk::{Transform, local_to_model};
pub use runtime::pose::LocalPose;
pub use runtime::sample::{Interpolation, SampleScratch};

pub use formats::load::{Format, Input, Loaded, Loader, load, load_one};
