//! Code made ready before its first use: the glTF writer and reader run once on
//! a few frames of the open character, with nothing kept.
//!
//! Why: a browser's WebAssembly engine (V8's) compiles each function the first
//! time it is called, on the page's own thread. The first glTF file a person
//! opens or saves would pay for compiling the whole reader or writer (a fifth
//! to a quarter of a 5 MB GLB's drop to its first frame, measured in
//! `docs/performance.md`). The page asks for this once, when idle after its
//! first frames; natively it is only a small, useless round trip.

use super::Viewer;

/// The open character's frames the round trip writes and reads: enough for
/// every path of the two, little enough to take a few milliseconds.
pub const FRAMES: usize = 60;

/// A skeleton with more joints than this is not written (a 200,000-joint file
/// is valid): the code is as ready after a smaller one.
pub const MAX_JOINTS: usize = 256;

impl Viewer {
    /// Writes the current character's first [`FRAMES`] frames (skeleton, a
    /// generated body, the motion) as a GLB in memory and reads it back through
    /// the loader a dropped file goes through; nothing is kept and nothing the
    /// user sees changes. Returns whether both ran without an error (`false`
    /// for a model, a skeleton over [`MAX_JOINTS`] joints, or with nothing
    /// open).
    pub fn warm_up_gltf(&self) -> bool {
        let Some(clip) = self.state.current_character().and_then(|c| c.clip()) else {
            return false;
        };
        if clip.skeleton().len() > MAX_JOINTS {
            return false;
        }
        let motion = clip.motion();
        let frames = motion.frame_count().min(FRAMES);
        let width = motion.channel_count();
        let Some(data) = motion.data().get(..frames * width) else {
            return false;
        };
        let Some(part) = mocap::Motion::new(motion.frame_time(), width, frames, data.to_vec())
            .and_then(|m| mocap::Clip::new(clip.skeleton().clone(), m).ok())
        else {
            return false;
        };
        let options = mocap::formats::gltf::Options { name: "warm-up".into(), body: true };
        let Ok(bytes) = mocap::formats::gltf::to_glb(&part, &options) else {
            return false;
        };
        let read = mocap::load(&[mocap::Input { name: "warm-up.glb", bytes: &bytes }]);
        read.iter().all(Result::is_ok) && !read.is_empty()
    }
}
