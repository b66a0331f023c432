//! What a drag in the 3D view keeps between frames while the pointer is held:
//! each gesture's own state (a rotation ring, a joint grab, a bone being grown).
//! The viewer forgets them when the pointer lets go.

/// The gestures in progress.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Gestures {
    /// A rotation ring being turned.
    pub ring: Option<RingDrag>,
    /// A joint being grabbed.
    pub grab: Option<Grab>,
    /// The creator's "drag out a new bone" from a joint, while it is armed or held.
    pub grow: Option<Grow>,
}

impl Gestures {
    /// The pointer let go: the ring and the grab end (a grown bone is finished
    /// by the viewer, which takes [`Gestures::grow`]).
    pub fn release(&mut self) {
        self.ring = None;
        self.grab = None;
    }
}

/// The press of a joint grab, and whether it only switched the character being
/// edited (a press on another character's joint selects it; Edit mode acts on
/// one character at a time).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Grab {
    /// Where the press was (points).
    pub press: egui::Pos2,
    /// The press only switched characters.
    pub switching: bool,
}

/// A rotation ring being dragged: the joint, the ring's axis and centre, where the
/// press was (as a vector in the ring's plane and its angle), and the joint's world
/// rotation then.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RingDrag {
    pub(crate) character: usize,
    pub(crate) joint: usize,
    pub(crate) axis: mocap::glam::Vec3,
    pub(crate) center: mocap::glam::Vec3,
    pub(crate) from: mocap::glam::Vec3,
    pub(crate) start: f32,
    pub(crate) world: mocap::glam::Quat,
}

/// A new bone being dragged out of a joint (the creator): its parent, and where
/// its end is (world) while the pointer holds it.
#[derive(Clone, Debug, PartialEq)]
pub struct Grow {
    pub(crate) character: usize,
    pub(crate) parent: usize,
    pub(crate) name: String,
    pub(crate) end: Option<mocap::glam::Vec3>,
}
