//! Motion-capture data: readers and writers for the classic formats, skeletons,
//! motion matrices, sampling and forward kinematics.
//!
//! Data flows one way: bytes → [`Clip`] (skeleton + motion) → sampled pose →
//! world transforms. This crate touches no file system, GPU or browser: it takes
//! bytes and returns data.
//!
//! ```
//! let bvh = b"HIERARCHY\nROOT Hips\n{\n OFFSET 0 0 0\n CHANNELS 3 Xposition Yposition Zposition\n End Site\n {\n  OFFSET 0 1 0\n }\n}\nMOTION\nFrames: 1\nFrame Time: 0.5\n1 2 3\n";
//! let clip = mocap::bvh::parse(bvh).unwrap();
//! let positions = clip.world_positions(0);
//! assert_eq!(positions[1], mocap::glam::Vec3::new(1.0, 3.0, 3.0));
//! ```

pub mod acclaim;
pub mod arrange;
pub mod batch;
pub mod bvh;
pub mod channel;
pub mod clip;
pub mod error;
mod fastmath;
pub mod fk;
pub mod motion;
pub mod sample;
pub mod skeleton;

pub use channel::Channel;
pub use clip::{Aabb, Clip, Units};
pub use error::{LoadError, ParseError, Warning};
pub use fk::Transform;
pub use glam;
pub use motion::Motion;
pub use sample::Interpolation;
pub use skeleton::{Joint, Skeleton};

/// The formats [`load`] recognises.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// Biovision hierarchy (`.bvh`).
    Bvh,
}

impl Format {
    /// Picks a format from the file name's extension, then from the content.
    pub fn detect(file_name: &str, bytes: &[u8]) -> Option<Format> {
        let ext = file_name.rsplit_once('.').map(|(_, e)| e.to_ascii_lowercase());
        match ext.as_deref() {
            Some("bvh") => Some(Format::Bvh),
            _ if bvh::sniff(bytes) => Some(Format::Bvh),
            _ => None,
        }
    }
}

/// Reads a motion file of any supported format; `file_name` picks the format and
/// names the file in errors (`file:line:col: message`).
pub fn load(file_name: &str, bytes: &[u8]) -> Result<Clip, LoadError> {
    match Format::detect(file_name, bytes) {
        Some(Format::Bvh) => bvh::parse(bytes).map_err(|error| LoadError::Parse { file: file_name.to_owned(), error }),
        None => Err(LoadError::UnknownFormat { file: file_name.to_owned() }),
    }
}
