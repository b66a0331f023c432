//! `FileSet`: files the page reads chunk by chunk straight into the module's
//! memory, to open together with `MocapViewer.openFileSet`. Reading a `File`'s
//! stream this way skips the whole-file `ArrayBuffer` and its copy into the
//! module (`openFiles`), which took about a third of a large drop's time.

use wasm_bindgen::prelude::*;

/// Bytes reserved up front for one file at most, whatever size the page gives:
/// a larger file grows as its chunks arrive.
const MAX_RESERVE: usize = 256 * 1024 * 1024;

/// Named files being read (`begin`, then `push` every chunk), in order.
#[wasm_bindgen]
#[derive(Default)]
pub struct FileSet {
    files: Vec<(String, Vec<u8>)>,
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
        let mut bytes = Vec::new();
        let want = if size.is_finite() && size > 0.0 { (size as usize).min(MAX_RESERVE) } else { 0 };
        if bytes.try_reserve_exact(want).is_err() {
            self.too_large.get_or_insert_with(|| name.clone());
        }
        self.files.push((name, bytes));
    }

    /// Appends `chunk` to the file begun last (nothing before a `begin`).
    pub fn push(&mut self, chunk: &js_sys::Uint8Array) {
        let Some((name, bytes)) = self.files.last_mut() else { return };
        let len = chunk.length() as usize;
        if bytes.try_reserve(len).is_err() {
            self.too_large.get_or_insert_with(|| name.clone());
            return;
        }
        let start = bytes.len();
        bytes.resize(start + len, 0);
        chunk.copy_to(&mut bytes[start..]);
    }

    /// Bytes held so far, every file together.
    #[wasm_bindgen(getter)]
    pub fn size(&self) -> f64 {
        self.files.iter().map(|(_, b)| b.len() as f64).sum()
    }
}

impl FileSet {
    /// The files, or the message for one that did not fit in memory.
    pub(crate) fn take(&mut self) -> Result<Vec<(String, Vec<u8>)>, String> {
        match self.too_large.take() {
            Some(name) => Err(format!("{name}: too large to hold in this page's memory")),
            None => Ok(std::mem::take(&mut self.files)),
        }
    }
}
