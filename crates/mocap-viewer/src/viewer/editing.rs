//! Clip edits as undoable steps: edits, keys (set, moved, deleted), layers,
//! undo and redo, and saving the result as BVH.

use super::Viewer;
use crate::character::{self, Character};

impl Viewer {
    /// Applies a clip edit ([`mocap::ops::edit`]) to character `character`, as one step
    /// that [`Viewer::undo`] takes back. Returns why not when it cannot be made.
    pub(crate) fn edit(&mut self, character: usize, edit: &mocap::ops::edit::Edit, label: &str) -> Result<(), String> {
        let c = self.state.stage.actors.get(character).ok_or_else(|| format!("no character {}", character + 1))?;
        let clip = c.clip().ok_or_else(|| format!("{}: a model has no motion to edit", c.name))?;
        let edited = mocap::ops::edit::apply(clip, edit).map_err(|e| format!("{}: {e}", c.name))?;
        use mocap::ops::edit::Edit;
        let key = edit.key_frame();
        let retimes = matches!(edit, Edit::Trim { .. } | Edit::Resample { .. } | Edit::ResampleCubic { .. } | Edit::Reverse | Edit::PingPong);
        self.commit(character, edited, label, key, retimes, Some(edit.clone()), None);
        Ok(())
    }

    /// Deletes the key at `frame` of the current character (not only the last one):
    /// the clip is rebuilt from before that key with every later edit made again,
    /// as one undoable step.
    pub(crate) fn delete_key(&mut self, frame: usize) -> Result<(), String> {
        self.rekey(frame, None)
    }

    /// Moves the key at `from` of the current character to frame `to` (the same
    /// pose, at another time), as one undoable step.
    pub(crate) fn move_key(&mut self, from: usize, to: usize) -> Result<(), String> {
        self.rekey(from, Some(to))
    }

    fn rekey(&mut self, frame: usize, to: Option<usize>) -> Result<(), String> {
        let character = self.state.current();
        if !self.state.history.keys(character).contains(&frame) {
            return Err(format!("no key at frame {frame}"));
        }
        let (base, mut edits) =
            self.state.history.effective(character).ok_or_else(|| format!("no key at frame {frame}"))?;
        let at = edits
            .iter()
            .rposition(|e| e.key_frame() == Some(frame))
            .ok_or_else(|| format!("the key at frame {frame} was made before a layer: it cannot be changed now"))?;
        let removed = edits.remove(at);
        let moved = to.and_then(|to| removed.at_frame(to));
        // Keys interpolated between keys follow the one deleted or moved.
        for e in &mut edits {
            e.follow_key(frame, to);
        }
        if let Some(m) = &moved {
            // In the same place in the sequence (later renames still apply after it).
            edits.insert(at, m.clone());
        }
        let mut clip = base.clip().cloned().ok_or("not a clip")?;
        for edit in &edits {
            clip = mocap::ops::edit::apply(&clip, edit).map_err(|e| e.to_string())?;
        }
        let label = match to {
            Some(to) => format!("Move key {frame} → {to}"),
            None => format!("Delete key at frame {frame}"),
        };
        // The key list follows: the old frame goes, a moved key's new frame comes.
        self.commit(character, clip, &label, to, false, moved, Some(frame));
        Ok(())
    }

    /// Moves the playhead to the next (`forward`) or previous keyed frame of the
    /// current character; returns the frame, if there is one that way.
    pub(crate) fn step_key(&mut self, forward: bool) -> Option<usize> {
        let keys = self.state.history.keys(self.state.current());
        let now = self.state.frame();
        let next =
            if forward { keys.into_iter().find(|&k| k > now) } else { keys.into_iter().rev().find(|&k| k < now) }?;
        self.set_playing(false);
        self.seek(next);
        Some(next)
    }

    /// Layers character `source`'s clip on the subtree of `layer.subtree` in
    /// character `character` ([`mocap::ops::layer::apply`]), as one undoable step.
    /// Puts character `source`'s motion on character `target` and opens the
    /// result as a new character named `SOURCE on TARGET` (it wears the target's
    /// look when it has one).
    pub(crate) fn retarget(
        &mut self,
        source: usize,
        target: usize,
        options: &mocap::ops::retarget::Options,
    ) -> Result<(), String> {
        let actors = &self.state.stage.actors;
        let clip = |i: usize| actors.get(i).and_then(|c| c.clip()).ok_or_else(|| format!("no clip {}", i + 1));
        let (from, onto) = (clip(source)?, clip(target)?);
        let (out, _) = mocap::ops::retarget::retarget(from, onto, options).map_err(|e| e.to_string())?;
        let name = |i: usize| actors.get(i).map_or(String::new(), |c| c.name.clone());
        let title = format!("{} on {}", name(source), name(target));
        self.add_asset(&title, out);
        Ok(())
    }

    pub(crate) fn add_layer(
        &mut self,
        character: usize,
        source: usize,
        layer: &mocap::ops::layer::Layer,
    ) -> Result<(), String> {
        let base = self
            .state
            .stage
            .actors
            .get(character)
            .and_then(|c| c.clip())
            .ok_or_else(|| format!("no clip {}", character + 1))?;
        let other = self
            .state
            .stage
            .actors
            .get(source)
            .and_then(|c| c.clip())
            .ok_or_else(|| format!("no clip {}", source + 1))?;
        let name = self.state.stage.actors.get(source).map_or(String::new(), |c| c.name.clone());
        let out = mocap::ops::layer::apply(base, other, layer).map_err(|e| e.to_string())?;
        self.commit(character, out, &format!("Layer {name} on {}", layer.subtree), None, false, None, None);
        Ok(())
    }

    /// Records and shows an edited clip of character `character`.
    #[allow(clippy::too_many_arguments)]
    fn commit(
        &mut self,
        character: usize,
        edited: mocap::Clip,
        label: &str,
        key: Option<usize>,
        retimes: bool,
        edit: Option<mocap::ops::edit::Edit>,
        unkey: Option<usize>,
    ) {
        let Some(before) = self.state.stage.actors.get(character).map(|c| c.asset.clone()) else { return };
        let after = mocap::Asset::Clip(edited);
        self.state.history.push(crate::history::Change {
            character,
            label: label.to_owned(),
            before,
            after: after.clone(),
            key,
            retimes,
            unkey,
            edit,
        });
        self.replace_asset(character, after);
    }

    /// Takes back the last edit; returns its label.
    pub(crate) fn undo(&mut self) -> Option<String> {
        let change = self.state.history.undo()?.clone();
        self.replace_asset(change.character, change.before);
        Some(change.label)
    }

    /// Makes the last undone edit again; returns its label.
    pub(crate) fn redo(&mut self) -> Option<String> {
        let change = self.state.history.redo()?.clone();
        self.replace_asset(change.character, change.after);
        Some(change.label)
    }

    /// Puts `asset` in character `index`'s place, keeping its name, colour,
    /// visibility and placement; the timeline and the selection follow.
    fn replace_asset(&mut self, index: usize, asset: mocap::Asset) {
        let Some(old) = self.state.stage.actors.get(index) else { return };
        let others: Vec<Character> = Vec::new();
        let mut c = character::new_character(&old.name, asset, &others);
        c.extra.color = old.extra.color;
        c.visible = old.visible;
        c.offset = old.offset;
        // An up axis set by hand stays; a guessed one is guessed again (an edit
        // turning the file to Y-up changes the guess).
        if old.clip().is_some_and(|clip| clip.up_axis() != old.up) {
            c.set_up(old.up);
        }
        // The character stays where it stands (an edit does not move it to a new
        // lane centre; changing the layout arranges again).
        c.layout_offset = old.layout_offset;
        if let Some(slot) = self.state.stage.actors.get_mut(index) {
            *slot = c;
        }
        if let Some(s) = self.state.selected.filter(|s| s.character == index) {
            let joints = self.state.stage.actors.get(index).and_then(|c| c.clip()).map_or(0, |c| c.skeleton().len());
            if s.joint >= joints {
                self.state.selected = None;
            }
        }
        self.state.playback.range = None;
        if let Some(t) = self.state.timing() {
            self.state.playback.time = self.state.playback.time.min(t.duration());
        }
    }

    /// Character `index` as a BVH file: (file name, text), every edit baked in;
    /// an edited clip's name says so (`walk-edited.bvh`). `None` for a model.
    pub fn save_bvh(&self, index: usize) -> Option<(String, String)> {
        let clip = self.state.stage.actors.get(index)?.clip()?;
        Some((self.save_name(index, "bvh"), mocap::formats::bvh::write(clip)))
    }

    /// Character `index` as a binary glTF ([`mocap::formats::gltf`]): its file
    /// name and bytes, every edit baked in (a model: its key frames as morph
    /// targets, every animation); why not for a clip that cannot be written.
    pub fn save_gltf(&self, index: usize) -> Result<(String, Vec<u8>), String> {
        let c = self.state.stage.actors.get(index).ok_or_else(|| format!("no character {}", index + 1))?;
        let name = self.save_name(index, "glb");
        if let Some(model) = c.model() {
            // Its key frames as morph targets and every animation.
            let bytes = mocap::formats::gltf::model_to_glb(model, name.trim_end_matches(".glb"));
            return Ok((name, bytes.map_err(|e| e.to_string())?));
        }
        let clip = c.clip().ok_or("nothing to save as glTF")?;
        let options = mocap::formats::gltf::Options { name: name.trim_end_matches(".glb").to_owned(), body: true };
        let bytes = mocap::formats::gltf::to_glb(clip, &options).map_err(|e| e.to_string())?;
        Ok((name, bytes))
    }

    /// The file name character `index` saves under: its stem, `-edited` when
    /// edited, and `extension`.
    fn save_name(&self, index: usize, extension: &str) -> String {
        let name = self.state.stage.actors.get(index).map_or("motion", |c| c.name.as_str());
        let stem = character::file_stem(name);
        let stem = stem.strip_suffix("-edited").unwrap_or(stem);
        if self.state.history.edited(index) {
            format!("{stem}-edited.{extension}")
        } else {
            format!("{stem}.{extension}")
        }
    }

    /// Turns the pose corrections made by dragging into keys: each character's
    /// correction becomes one undoable edit at its frame: a correction fading over
    /// [`crate::settings::ViewSettings::key_window`] frames on each side
    /// ([`mocap::ops::edit::Edit::Correct`]), or with
    /// [`crate::settings::ViewSettings::key_between`] a key of key-frame animation
    /// interpolated to and from the character's other keys ([`mocap::ops::edit::Edit::Key`]).
    /// Returns how many characters were keyed.
    pub(crate) fn set_key(&mut self) -> Result<usize, String> {
        let window = self.state.settings.key_window;
        let mut keyed = 0;
        for index in 0..self.state.stage.actors.len() {
            let Some(c) = self.state.stage.actors.get(index) else { continue };
            let Some(correction) = c.extra.correction.clone().filter(|k| k.ghost) else { continue };
            let Some(clip) = c.clip() else { continue };
            let name = |j: usize| clip.skeleton().joints().get(j).map(|x| x.name.clone());
            let rotations = correction.rotations.iter().filter_map(|&(j, q)| Some((name(j)?, q))).collect();
            let translations = correction.translations.iter().filter_map(|&(j, t)| Some((name(j)?, t))).collect();
            let frame = correction.frame;
            let edit = if self.state.settings.key_between {
                let keys = self.state.history.keys(index).into_iter().filter(|k| *k != frame).collect();
                mocap::ops::edit::Edit::Key { frame, rotations, translations, keys }
            } else {
                mocap::ops::edit::Edit::Correct { frame, rotations, translations, window }
            };
            self.edit(index, &edit, &format!("Key at frame {}", correction.frame))?;
            keyed += 1;
        }
        Ok(keyed)
    }
}
