//! What a set of files becomes: a skeletal [`Clip`] or a vertex-animated [`Model`].
//! The stage, the viewer, the CLI and the JS API handle both through this one type.

use crate::model::clip::{Aabb, Clip, Units};
use crate::model::mesh::Model;
use crate::model::time::Timeline;
use serde::{Deserialize, Serialize};

/// A loaded asset. Its serde form (the [`crate::formats::store`] body) goes
/// through each part's checks when read.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum Asset {
    /// A skeleton and its motion (BVH, BVA, Acclaim).
    Clip(Clip),
    /// A mesh with vertex frames and maybe a skin (MD2).
    Model(Model),
}

impl From<Clip> for Asset {
    fn from(clip: Clip) -> Asset {
        Asset::Clip(clip)
    }
}

impl From<Model> for Asset {
    fn from(model: Model) -> Asset {
        Asset::Model(model)
    }
}

impl Asset {
    /// The clip, when it is one.
    pub fn clip(&self) -> Option<&Clip> {
        match self {
            Asset::Clip(c) => Some(c),
            Asset::Model(_) => None,
        }
    }

    /// The model, when it is one.
    pub fn model(&self) -> Option<&Model> {
        match self {
            Asset::Model(m) => Some(m),
            Asset::Clip(_) => None,
        }
    }

    /// The model, mutably (to choose its animation), when it is one.
    pub fn model_mut(&mut self) -> Option<&mut Model> {
        match self {
            Asset::Model(m) => Some(m),
            Asset::Clip(_) => None,
        }
    }

    /// Its frames and frame time: a clip's, or the frames of the model's animation.
    pub fn timeline(&self) -> Timeline {
        match self {
            Asset::Clip(c) => c.timeline(),
            Asset::Model(m) => m.timeline(),
        }
    }

    /// Frames on its timeline.
    pub fn frame_count(&self) -> usize {
        self.timeline().frames()
    }

    /// Time of its last frame in seconds.
    pub fn duration(&self) -> f64 {
        self.timeline().duration()
    }

    /// Guessed length unit (the same rule for clips and models: [`Units::guess`]).
    pub fn units(&self) -> Units {
        match self {
            Asset::Clip(c) => c.units(),
            Asset::Model(m) => m.mesh.units(),
        }
    }

    /// Bounds over the whole motion, or the key frames of the model's animation
    /// (file units).
    pub fn bounds(&self) -> Aabb {
        match self {
            Asset::Clip(c) => c.bounds(),
            Asset::Model(m) => m.bounds(),
        }
    }

    /// Size of the first pose or frame (file units).
    pub fn extent(&self) -> f32 {
        match self {
            Asset::Clip(c) => c.pose_extent(),
            Asset::Model(m) => m.mesh.extent(),
        }
    }
}
