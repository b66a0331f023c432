//! The work open in the viewer as the page stores it to bring it back after the
//! tab is closed (autosave): every character (its asset as it is now, with its
//! edits, and how it is shown), the edit history (undo and redo), which edits are
//! saved, and the view (camera, playhead, layout, settings and panels: the URL
//! fragment of [`crate::view_state`]).
//!
//! A session is a small JSON manifest naming assets by key, and the assets
//! themselves ([`mocap::formats::store`], bytes keyed by a hash of their content):
//! an asset the page has already stored under its key is not stored again, so a
//! large file is written once however often the manifest changes. [`parse`]
//! checks the manifest and every asset (the store's own checks) before anything
//! open changes; a damaged session is refused whole with a message.

use crate::history::{Change, History};
use mocap::Asset;
use serde::{Deserialize, Serialize};
use std::collections::HashMap;

/// Version of the manifest's layout.
const VERSION: u32 = 1;

/// A session ready to store: the manifest (JSON) and every asset it names, by key.
pub struct Stored {
    /// The manifest, JSON.
    pub manifest: String,
    /// The assets the manifest names: (key, [`mocap::formats::store`] bytes), each once.
    pub assets: Vec<(String, Vec<u8>)>,
    /// Whether some character has edits not saved since they were made.
    pub unsaved: bool,
}

/// A session read back, to open with [`crate::Command::Restore`].
#[derive(Clone, Debug, PartialEq)]
pub struct Restored {
    /// The characters: file name, asset and how each is shown.
    pub characters: Vec<(String, Asset, Shown)>,
    /// The edit history.
    pub history: History,
    /// The view (a URL fragment).
    pub view: String,
    /// Whether the work had unsaved edits.
    pub unsaved: bool,
}

/// How a character is shown, beside its asset.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Shown {
    /// Which file axis points up.
    pub up: mocap::UpAxis,
    /// Whether it is drawn.
    pub visible: bool,
    /// Offset set by hand, metres.
    pub offset: [f32; 3],
    /// Bone colour (sRGB).
    pub color: [u8; 4],
    /// Whether its edits are saved.
    pub saved: bool,
}

#[derive(Serialize, Deserialize)]
struct Manifest {
    version: u32,
    characters: Vec<CharacterRecord>,
    done: Vec<ChangeRecord>,
    undone: Vec<ChangeRecord>,
    view: String,
    unsaved: bool,
}

#[derive(Serialize, Deserialize)]
struct CharacterRecord {
    name: String,
    asset: String,
    shown: Shown,
}

#[derive(Serialize, Deserialize)]
struct ChangeRecord {
    character: usize,
    label: String,
    before: String,
    after: String,
    key: Option<usize>,
    retimes: bool,
    unkey: Option<usize>,
    edit: Option<mocap::ops::edit::Edit>,
}

/// The assets of a session being written, each once by key.
#[derive(Default)]
struct Pool {
    assets: Vec<(String, Vec<u8>)>,
    index: HashMap<String, usize>,
    /// The last asset stored and its key: an edit's "after" is usually the next
    /// one's "before", so equal neighbours are written once without serialising again.
    last: Option<(Asset, String)>,
}

impl Pool {
    fn key_of(&mut self, asset: &Asset) -> String {
        if let Some((last, key)) = &self.last
            && last == asset
        {
            return key.clone();
        }
        let bytes = mocap::formats::store::write(asset);
        let key = content_key(&bytes);
        if !self.index.contains_key(&key) {
            self.index.insert(key.clone(), self.assets.len());
            self.assets.push((key.clone(), bytes));
        }
        self.last = Some((asset.clone(), key.clone()));
        key
    }
}

/// A key for stored bytes: their length and a 64-bit FNV-1a hash.
fn content_key(bytes: &[u8]) -> String {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for &b in bytes {
        h ^= u64::from(b);
        h = h.wrapping_mul(0x0000_0100_0000_01b3);
    }
    format!("{:x}-{h:016x}", bytes.len())
}

/// The session of `characters` (name, asset, how shown), `history` and `view`.
pub fn store(characters: &[(&str, &Asset, Shown)], history: &History, view: String) -> Stored {
    let mut pool = Pool::default();
    let (done, undone) = history.changes();
    let record = |c: &Change, pool: &mut Pool| ChangeRecord {
        character: c.character,
        label: c.label.clone(),
        before: pool.key_of(&c.before),
        after: pool.key_of(&c.after),
        key: c.key,
        retimes: c.retimes,
        unkey: c.unkey,
        edit: c.edit.clone(),
    };
    let done: Vec<ChangeRecord> = done.iter().map(|c| record(c, &mut pool)).collect();
    let undone: Vec<ChangeRecord> = undone.iter().map(|c| record(c, &mut pool)).collect();
    let characters: Vec<CharacterRecord> = characters
        .iter()
        .map(|(name, asset, shown)| CharacterRecord {
            name: (*name).to_owned(),
            asset: pool.key_of(asset),
            shown: shown.clone(),
        })
        .collect();
    let unsaved = characters.iter().any(|c| !c.shown.saved);
    let manifest = Manifest { version: VERSION, characters, done, undone, view, unsaved };
    // Plain data with string keys: serialising cannot fail.
    let manifest = serde_json::to_string(&manifest).unwrap_or_default();
    Stored { manifest, assets: pool.assets, unsaved }
}

/// Reads a session back: the manifest and the assets it names (`asset(key)` gives
/// the stored bytes). Every asset is checked; a missing or damaged one, or a
/// manifest that does not hold together, is an error and nothing is restored.
pub fn parse(manifest: &str, asset: &dyn Fn(&str) -> Option<Vec<u8>>) -> Result<Restored, String> {
    let m: Manifest = serde_json::from_str(manifest).map_err(|e| format!("the saved session is damaged: {e}"))?;
    if m.version != VERSION {
        return Err(format!("the saved session is of version {}; this viewer reads version {VERSION}", m.version));
    }
    let mut read: HashMap<String, Asset> = HashMap::new();
    let mut get = |key: &str| -> Result<Asset, String> {
        if let Some(a) = read.get(key) {
            return Ok(a.clone());
        }
        let bytes = asset(key).ok_or_else(|| format!("the saved session lacks its file {key}"))?;
        let a = mocap::formats::store::parse(&bytes).map_err(|e| format!("the saved file {key} is damaged: {e}"))?;
        read.insert(key.to_owned(), a.clone());
        Ok(a)
    };
    let count = m.characters.len();
    let mut change = |r: ChangeRecord| -> Result<Change, String> {
        if r.character >= count {
            return Err(format!("the saved session edits character {} of {count}", r.character + 1));
        }
        Ok(Change {
            character: r.character,
            label: r.label,
            before: get(&r.before)?,
            after: get(&r.after)?,
            key: r.key,
            retimes: r.retimes,
            unkey: r.unkey,
            edit: r.edit,
        })
    };
    let done = m.done.into_iter().map(&mut change).collect::<Result<Vec<_>, _>>()?;
    let undone = m.undone.into_iter().map(&mut change).collect::<Result<Vec<_>, _>>()?;
    let characters =
        m.characters.into_iter().map(|c| Ok((c.name, get(&c.asset)?, c.shown))).collect::<Result<Vec<_>, String>>()?;
    Ok(Restored { characters, history: History::from_changes(done, undone), view: m.view, unsaved: m.unsaved })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn content_keys_differ_with_the_bytes() {
        assert_ne!(content_key(b"abc"), content_key(b"abd"));
        assert_ne!(content_key(b"abc"), content_key(b"abcd"));
        assert_eq!(content_key(b"abc"), content_key(b"abc"));
    }
}
