//! `FileSet`: files the page reads chunk by chunk straight into the module's
//! memory, to open together with `MocapViewer.openFileSet`. Reading a `File`'s
//! stream this way skips the whole-file `ArrayBuffer` and its copy into the
//! module (`openFiles`), and a BVH file's motion rows are parsed while the rest
//! of it is still being read (`mocap::formats::bvh::Stream`).

use mocap::formats::bvh::Stream;
use wasm_bindgen::prelude::*;

/// Bytes copied out of JavaScript's memory at a time.
const PIECE: usize = 1 << 20;

/// Named files being read (`begin`, then `push` every chunk), in order.
#[wasm_bindgen]
#[derive(Default)]
pub struct FileSet {
    files: Vec<(String, Stream)>,
    /// The first file that could not be held in memory (its name).
    too_large: Option<String>,
}

#[wasm_bindgen]
impl FileSet {
    /// An empty set.
    #[wasm_bindgen(constructor)]
    pub fn new() -> FileSet {
        FileSet::default()
    }

    /// Starts the next file, `name`, of `size` bytes (room is reserved for them,
    /// up to 256 MB; what arrives decides the length).
    pub fn begin(&mut self, name: String, size: f64) {
        let size = if size.is_finite() && size > 0.0 { size as usize } else { 0 };
        self.files.push((name, Stream::with_capacity(size)));
    }

    /// Appends `chunk` to the file begun last (nothing before a `begin`).
    pub fn push(&mut self, chunk: &js_sys::Uint8Array) {
        let Some((name, stream)) = self.files.last_mut() else { return };
        if self.too_large.is_some() {
            return;
        }
        // Room is asked for first: a failed allocation in the push would abort.
        let len = chunk.length() as usize;
        if stream.try_reserve(len).is_err() {
            self.too_large = Some(name.clone());
            return;
        }
        // Copied out of JavaScript's memory a megabyte at a time into a
        // buffer of its own, then appended: as fast as copying into room
        // zeroed at the end of the stream first (measured on a 27 MB drop),
        // and the stream then needs no way to be filled from outside.
        let mut at = 0;
        while at < len {
            let end = (at + PIECE).min(len);
            stream.push(&chunk.subarray(at as u32, end as u32).to_vec());
            at = end;
        }
    }

    /// Bytes held so far, every file together.
    #[wasm_bindgen(getter)]
    pub fn size(&self) -> f64 {
        self.files.iter().map(|(_, s)| s.bytes().len() as f64).sum()
    }
}

/// What a [`FileSet`] holds, ready to open.
pub(crate) enum Taken {
    /// Every file is BVH: the clips (or their errors), read as they arrived.
    Clips(Vec<(String, Result<mocap::Clip, mocap::ParseError>)>),
    /// Anything else: the bytes, for the viewer's loader (it pairs Acclaim
    /// skeletons with their motions, models with their skins).
    Files(Vec<(String, Vec<u8>)>),
}

impl FileSet {
    /// The files, or the message for one that did not fit in memory.
    pub(crate) fn take(&mut self) -> Result<Taken, String> {
        if let Some(name) = self.too_large.take() {
            self.files.clear();
            return Err(format!("{name}: too large to hold in this page's memory"));
        }
        let files = std::mem::take(&mut self.files);
        if files.iter().all(|(_, s)| s.is_bvh()) {
            Ok(Taken::Clips(files.into_iter().map(|(name, s)| (name, s.finish())).collect()))
        } else {
            Ok(Taken::Files(files.into_iter().map(|(name, s)| (name, s.into_bytes())).collect()))
        }
    }
}
