//! The object JavaScript holds: `state()`, `load()`, `add()`, `setVisible()`,
//! `remove()`, `setLayout()`, `seek()`, `play()`, `pause()`, ...

use eframe::egui;
use mocap_viewer::{Command, OpenMode, Viewer};
use std::cell::RefCell;
use std::rc::Rc;
use wasm_bindgen::prelude::*;

/// Handle to the running viewer, exported to JavaScript.
#[wasm_bindgen]
pub struct MocapViewer {
    pub(crate) viewer: Rc<RefCell<Viewer>>,
    /// The last file the viewer asked to save (`HostRequest::Save`), until the page takes it.
    pub(crate) saved: Rc<RefCell<Option<(String, Vec<u8>)>>>,
    pub(crate) ctx: Rc<RefCell<Option<egui::Context>>>,
    /// What the runner was started with and the runner itself (see `crate::gpu`).
    pub(crate) shared: crate::start::Shared,
}

#[wasm_bindgen]
impl MocapViewer {
    /// `{clips:[{name, frames, frameTime, joints, jointNames, visible, color, offset,
    /// animation, animations, modelFrame, frameName, skin}],
    /// frame, time, playing, speed, selectedJoint, selectedCharacter, layout, error,
    /// treeLabels, framesRendered, view, embed, backend, quality, reduced, samples, viewPixels,
    /// floorCopied}`
    /// (`floorCopied`: the last frame started from the floor drawn for an earlier
    /// one, under a still camera). `color` is `#rrggbb`,
    /// `offset` `[x, y, z]` in metres (layout plus hand-set), `selectedCharacter` an
    /// index into `clips` (or `null`), `frame` counts in the frame time of that
    /// character, else the first.
    pub fn state(&self) -> JsValue {
        match self.viewer.try_borrow() {
            Ok(v) => crate::js_state::to_js(&v.snapshot()),
            Err(_) => JsValue::NULL,
        }
    }

    /// Reads a file (BVH, BVA, ASF; an AMC with the last skeleton opened) and opens it in place of everything open; returns the error text
    /// (and shows it) when it cannot, keeping what was open. Returns `undefined` on success.
    pub fn load(&self, file_name: &str, bytes: &[u8]) -> Option<String> {
        self.with_viewer(|v| v.load(file_name, bytes)).map_or_else(|| Some("viewer busy".to_owned()), Result::err)
    }

    /// Parses a file and adds it as one more character; returns the error text (and
    /// shows it) when it cannot, keeping what was open. Returns `undefined` on success.
    pub fn add(&self, file_name: &str, bytes: &[u8]) -> Option<String> {
        self.with_viewer(|v| v.add(file_name, bytes)).map_or_else(|| Some("viewer busy".to_owned()), Result::err)
    }

    /// Opens a set of files together (`names[i]` names `contents[i]`, a
    /// `Uint8Array`): the core detects each format from its content and pairs an
    /// Acclaim `.asf` with its `.amc` motions (one character per motion; a motion
    /// alone uses the last skeleton opened). With `add` they join what is open, else
    /// they replace it (when none opens, what was open stays). Returns every error
    /// message (also shown in the banner); empty when all opened.
    #[wasm_bindgen(js_name = openFiles)]
    pub fn open_files(&self, names: Vec<String>, contents: Vec<js_sys::Uint8Array>, add: bool) -> Vec<String> {
        let bytes: Vec<Vec<u8>> = contents.iter().map(js_sys::Uint8Array::to_vec).collect();
        let files: Vec<(&str, &[u8])> = names.iter().map(String::as_str).zip(bytes.iter().map(Vec::as_slice)).collect();
        let mode = if add { mocap_viewer::OpenMode::Add } else { mocap_viewer::OpenMode::Replace };
        self.with_viewer(|v| v.open_files(&files, mode)).unwrap_or_else(|| vec!["viewer busy".to_owned()])
    }

    /// Opens the files of `set` (see `FileSet`) together, like `openFiles`,
    /// leaving `set` empty. Returns every error message; empty when all opened.
    #[wasm_bindgen(js_name = openFileSet)]
    pub fn open_file_set(&self, set: &mut crate::FileSet, add: bool) -> Vec<String> {
        let mode = if add { mocap_viewer::OpenMode::Add } else { mocap_viewer::OpenMode::Replace };
        let opened = match set.take() {
            Ok(crate::file_set::Taken::Clips(clips)) => self.with_viewer(|v| v.open_clips(clips, mode)),
            Ok(crate::file_set::Taken::Files(files)) => {
                let files: Vec<(&str, &[u8])> =
                    files.iter().map(|(name, bytes)| (name.as_str(), bytes.as_slice())).collect();
                self.with_viewer(|v| v.open_files(&files, mode))
            }
            Err(message) => {
                self.show_error(&message, None);
                return vec![message];
            }
        };
        opened.unwrap_or_else(|| vec!["viewer busy".to_owned()])
    }

    /// Holds playback while the page reads files it is about to open (`true`),
    /// or lets it go on (`false`, which also asks for a frame): held, the
    /// playhead stays and a playing view draws no frames, so a software
    /// rasteriser's drawing does not slow the read and the open down.
    #[wasm_bindgen(js_name = holdFrames)]
    pub fn hold_frames(&self, on: bool) {
        if let Ok(mut v) = self.viewer.try_borrow_mut() {
            v.hold(on);
        }
        // Not even a frame already asked for is drawn while held.
        eframe::web::hold_paints(on);
        if !on && let Some(ctx) = self.ctx.borrow().as_ref() {
            ctx.request_repaint();
        }
    }

    /// Position `[x, y, z]` of joint `name` of character `character` (0-based) at the
    /// frame shown, in the clip's own units and model space (no layout offset, no
    /// scale to metres), as `mocap pose` prints it; `undefined` when there is none.
    #[wasm_bindgen(js_name = jointPosition)]
    pub fn joint_position(&self, character: u32, name: &str) -> Option<Vec<f32>> {
        let v = self.viewer.try_borrow().ok()?;
        let c = v.state().stage.actors.get(character as usize)?;
        let clip = c.clip()?;
        let joint = clip.skeleton().find(name)?;
        let frame = c.frame_at(v.state().playback.time);
        clip.world_positions(frame).get(joint).map(|p| p.to_array().to_vec())
    }

    /// Opens a clip from `parseMotion` (copying it; `clip` stays usable) under
    /// `file_name`, in place of everything open.
    #[wasm_bindgen(js_name = loadClip)]
    pub fn load_clip(&self, clip: &crate::MotionClip, file_name: &str) {
        let clip = clip.clip().clone();
        self.with_viewer(|v| v.open_assets(vec![(file_name.to_owned(), mocap::Asset::Clip(clip))]));
    }

    /// Adds a clip from `parseMotion` (copying it) as one more character named `file_name`.
    #[wasm_bindgen(js_name = addClip)]
    pub fn add_clip(&self, clip: &crate::MotionClip, file_name: &str) {
        let clip = clip.clip().clone();
        self.with_viewer(|v| v.add_asset(file_name, clip));
    }

    /// Edit mode: moves joint `name` of character `character` (0-based) to world
    /// position `x, y, z` (metres, as drawn) at the frame shown, by IK; the clip's
    /// own pose shows as a ghost. Returns whether the target was reached (`false`
    /// also when there is no such joint).
    #[wasm_bindgen(js_name = dragJoint)]
    pub fn drag_joint(&self, character: u32, name: &str, x: f32, y: f32, z: f32) -> bool {
        self.with_viewer(|v| {
            let joint = v.state().stage.actors.get(character as usize)?.clip()?.skeleton().find(name)?;
            v.drag_joint(character as usize, joint, mocap::glam::Vec3::new(x, y, z)).map(|s| s.reached)
        })
        .flatten()
        .unwrap_or(false)
    }

    /// Opens a demo in place of everything open: `'tentacle'` (the bendy
    /// tentacle, `bones` bones, 2 by default). Returns false for an unknown name.
    #[wasm_bindgen(js_name = openDemo)]
    pub fn open_demo(&self, name: &str, bones: Option<u32>) -> bool {
        if name != "tentacle" {
            return false;
        }
        self.with_viewer(|v| v.apply(Command::OpenTentacle(bones.unwrap_or(2) as usize))).is_some()
    }

    /// Sets the tentacle demo: its target (world, metres), whether the tip follows
    /// it, the solver (`'two-bone'`, `'ccd'`, `'fabrik'`) and soft or rigid skin.
    /// Returns false when the demo is not open or the solver is unknown.
    #[wasm_bindgen(js_name = setDemo)]
    pub fn set_demo(
        &self,
        target: Option<Vec<f32>>,
        follow: Option<bool>,
        solver: Option<String>,
        soft: Option<bool>,
    ) -> bool {
        self.with_viewer(|v| {
            let Some(mut t) = v.state().tentacle.clone() else { return false };
            if let Some([x, y, z]) = target.as_deref().and_then(|p| <[f32; 3]>::try_from(p).ok()) {
                t.target = mocap::glam::Vec3::new(x, y, z);
            }
            if let Some(f) = follow {
                t.follow = f;
            }
            if let Some(s) = solver {
                match mocap_viewer::tentacle::Solver::from_name(&s) {
                    Some(s) => t.solver = s,
                    None => return false,
                }
            }
            if let Some(s) = soft {
                t.soft = s;
            }
            v.try_apply(Command::SetTentacle(t)).is_ok()
        })
        .unwrap_or(false)
    }

    /// Where the tentacle demo's target sphere was last drawn, in CSS pixels
    /// (`[x, y]`), or `undefined`.
    #[wasm_bindgen(js_name = demoTargetScreenPosition)]
    pub fn demo_target_screen_position(&self) -> Option<Vec<f32>> {
        let v = self.viewer.try_borrow().ok()?;
        let target = v.state().tentacle.as_ref()?.target;
        let p = v.screen_position(target)?;
        Some(vec![p.x, p.y])
    }

    /// Character `index` (the current one by default) as a BVH file, every edit
    /// baked in: `[fileName, text]` (`walk-edited.bvh` when edited), or
    /// `undefined` for a model.
    #[wasm_bindgen(js_name = saveBvh)]
    pub fn save_bvh(&self, index: Option<u32>) -> Option<Vec<String>> {
        let (index, saved) = {
            let v = self.viewer.try_borrow().ok()?;
            let index = index.map_or(v.state().current(), |i| i as usize);
            (index, v.save_bvh(index)?)
        };
        // The page downloads what it asked for: the work is saved.
        self.with_viewer(|v| v.apply(Command::MarkSaved(index)));
        Some(vec![saved.0, saved.1])
    }

    /// The file the viewer asked to save with its last `mocap-save` event (Save
    /// as BVH, Save as glTF, Save rig): `[fileName, bytes]` (a `Uint8Array`),
    /// taken (asked once), or `undefined`.
    #[wasm_bindgen(js_name = takeDownload)]
    pub fn take_download(&self) -> Option<js_sys::Array> {
        let (name, bytes) = self.saved.try_borrow_mut().ok()?.take()?;
        Some(js_sys::Array::of2(&name.into(), &js_sys::Uint8Array::from(bytes.as_slice())))
    }

    /// Makes the glTF writer's and reader's code ready before their first use:
    /// writes the current character's first 60 frames as a GLB in memory and
    /// reads it back, keeping nothing (see `Viewer::warm_up_gltf`). The browser
    /// compiles WebAssembly a function at a time when first called; the page
    /// calls this once, when idle after its first frames, so that the first
    /// glTF file opened or saved does not wait for that. Returns whether it ran
    /// (`false` for a model, with nothing open, or while the viewer is busy).
    #[wasm_bindgen(js_name = warmUp)]
    pub fn warm_up(&self) -> bool {
        self.viewer.try_borrow().is_ok_and(|v| v.warm_up_gltf())
    }

    /// Character `index` (the current one by default) as a binary glTF (`.glb`):
    /// skeleton, skin, a generated body and the animation, every edit baked in,
    /// metres and Y up. Returns the bytes; throws the reason for a model.
    #[wasm_bindgen(js_name = saveGltf)]
    pub fn save_gltf(&self, index: Option<u32>) -> Result<Vec<u8>, JsError> {
        let v = self.viewer.try_borrow().map_err(|_| JsError::new("viewer busy"))?;
        let index = index.map_or(v.state().current(), |i| i as usize);
        v.save_gltf(index).map(|(_, bytes)| bytes).map_err(|e| JsError::new(&e))
    }

    /// Character `index` (the current one by default) as a binary glTF file, as
    /// `saveGltf` makes it: `[fileName, bytes]` (`walk-edited.glb` when edited);
    /// throws the reason for a model.
    #[wasm_bindgen(js_name = saveGltfFile)]
    pub fn save_gltf_file(&self, index: Option<u32>) -> Result<js_sys::Array, JsError> {
        let (index, (name, bytes)) = {
            let v = self.viewer.try_borrow().map_err(|_| JsError::new("viewer busy"))?;
            let index = index.map_or(v.state().current(), |i| i as usize);
            (index, v.save_gltf(index).map_err(|e| JsError::new(&e))?)
        };
        self.with_viewer(|v| v.apply(Command::MarkSaved(index)));
        Ok(js_sys::Array::of2(&name.into(), &js_sys::Uint8Array::from(bytes.as_slice())))
    }

    /// Captures the skeletal motion of model `index` (an MD2): with the rig given
    /// by `useRig` if it fits, else an automatic fit. It runs a little per drawn
    /// frame (see `captureProgress`); with `now` true it finishes before returning.
    /// The captured clip joins the stage beside the model, in overlay. Returns the
    /// error message, or `undefined` when started.
    pub fn capture(&self, index: u32, now: Option<bool>) -> Option<String> {
        self.with_viewer(|v| {
            let started = v.try_apply(Command::StartCapture(index as usize));
            if started.is_ok() && now.unwrap_or(false) {
                let _ = v.apply(Command::FinishCapture);
            }
            started.err()
        })
        .flatten()
    }

    /// Starts setting up a capture rig on model `index` (Fit skeleton): a humanoid,
    /// or the skeleton of clip character `template`, fitted in its first frame.
    /// Returns the error message, or `undefined`.
    #[wasm_bindgen(js_name = fitSkeleton)]
    pub fn fit_skeleton(&self, index: u32, template: Option<u32>) -> Option<String> {
        self.with_viewer(|v| {
            v.try_apply(Command::FitRig { model: index as usize, template: template.map(|t| t as usize) }).err()
        })
        .flatten()
    }

    /// Where rig joint `name` (of the rig being set up) is on the page (`[x, y]`,
    /// CSS pixels), or `undefined`.
    #[wasm_bindgen(js_name = rigJointScreenPosition)]
    pub fn rig_joint_screen_position(&self, name: &str) -> Option<Vec<f32>> {
        let v = self.viewer.try_borrow().ok()?;
        let e = v.state().rig_edit.as_ref()?;
        let j = e.rig.joints.iter().position(|j| j.name == name)?;
        let world = v
            .state()
            .stage
            .actors
            .get(e.model)?
            .world_matrix()
            .transform_point3(mocap::glam::Vec3::from_array(e.rig.joints[j].position));
        let p = v.screen_position(world)?;
        Some(vec![p.x, p.y])
    }

    /// The rig being set up (else the one kept for the next capture) as JSON, or `undefined`.
    #[wasm_bindgen(js_name = rigJson)]
    pub fn rig_json(&self) -> Option<String> {
        let v = self.viewer.try_borrow().ok()?;
        v.state().rig_edit.as_ref().map(|e| &e.rig).or(v.state().capture_rig.as_ref()).map(|r| r.to_json())
    }

    /// Binds every vertex of the rig being set up to its nearest bone.
    #[wasm_bindgen(js_name = bindRig)]
    pub fn bind_rig(&self) {
        self.with_viewer(|v| v.apply(Command::BindRig));
    }

    /// Ends the rig set-up, keeping the rig for the next capture.
    #[wasm_bindgen(js_name = finishRig)]
    pub fn finish_rig(&self) {
        self.with_viewer(|v| v.apply(Command::FinishRigEdit));
    }

    /// `[stepsDone, stepsInAll]` while a capture runs, else `undefined`.
    #[wasm_bindgen(js_name = captureProgress)]
    pub fn capture_progress(&self) -> Option<Vec<u32>> {
        let v = self.viewer.try_borrow().ok()?;
        v.state().capture_progress().map(|(a, b)| vec![a as u32, b as u32])
    }

    /// The last capture's per-joint report (text), or `undefined`.
    #[wasm_bindgen(js_name = captureReport)]
    pub fn capture_report(&self) -> Option<String> {
        let v = self.viewer.try_borrow().ok()?;
        v.state().capture_result.as_ref().map(|r| r.report.text())
    }

    /// Keeps a capture rig (JSON text, as `mocap capture --save-rig` or Save rig
    /// writes it) for the next capture; returns the error message, or `undefined`.
    #[wasm_bindgen(js_name = useRig)]
    pub fn use_rig(&self, name: &str, text: &str) -> Option<String> {
        self.with_viewer(|v| v.open_files(&[(name, text.as_bytes())], OpenMode::Add).into_iter().next()).flatten()
    }

    /// Applies a clip edit to character `index`, one undoable step, written as
    /// the CLI's specs are (one grammar, `mocap::ops::edit::EditSpec`):
    /// `'reverse'`, `'ping-pong'`, `'in-place'`, `'in-place-turning'`, `'up:z'`
    /// (`'up-z'`), `'trim:A:B'`, `'fps:N'`, `'knit:N'`, `'scale:F'`, `'units:cm'`,
    /// `'rename:OLD:NEW'`, `'remove:JOINT'`, `'drop:JOINT'`,
    /// `'add:PARENT:NAME:x,y,z'`, `'offset:NAME:x,y,z'`,
    /// `'channels:NAME:ZXY[:position]'`, `'correct:FRAME:WINDOW:POSE'`,
    /// `'key:FRAME:KEYS:POSE'`. Returns the error message, or `undefined` when done.
    pub fn edit(&self, index: u32, spec: &str) -> Option<String> {
        // The one edit grammar (`mocap::ops::edit::EditSpec`), as the CLI reads it.
        let read = spec.parse::<mocap::ops::edit::EditSpec>();
        self.with_viewer(|v| {
            let character = index as usize;
            let clip = v.state().stage.actors.get(character).and_then(|c| c.clip());
            let edit = match (read, clip) {
                (Err(e), _) => return Some(e.to_string()),
                (Ok(spec), Some(clip)) => spec.resolve(clip),
                (Ok(mocap::ops::edit::EditSpec::Edit(edit)), None) => edit,
                (Ok(_), None) => return Some(format!("{spec}: character {} is not a clip", character + 1)),
            };
            v.try_apply(Command::Edit { character, edit, label: spec.to_owned() }).err()
        })
        .flatten()
    }

    /// Layers character `source`'s clip on the subtree of joint `subtree` of
    /// character `index` (override, or `additive`), one undoable step; returns
    /// the error message, or `undefined` when done. `map` lists explicit joint
    /// matches as `"Base=Layer,Base2=Layer2"` (an empty layer name leaves that
    /// base joint out); other joints are matched by name.
    #[wasm_bindgen(js_name = addLayer)]
    pub fn add_layer(
        &self,
        index: u32,
        source: u32,
        subtree: &str,
        weight: Option<f32>,
        additive: Option<bool>,
        map: Option<String>,
    ) -> Option<String> {
        let blend = if additive.unwrap_or(false) {
            mocap::ops::layer::Blend::Additive
        } else {
            mocap::ops::layer::Blend::Override
        };
        let mut pairs = Vec::new();
        for item in map.as_deref().unwrap_or("").split(',').filter(|s| !s.trim().is_empty()) {
            let Some((b, l)) = item.split_once('=') else { return Some(format!("{item}: a map entry is Base=Layer")) };
            pairs.push((b.trim().to_owned(), l.trim().to_owned()));
        }
        let layer = mocap::ops::layer::Layer {
            weight: weight.unwrap_or(1.0),
            blend,
            map: pairs,
            ..mocap::ops::layer::Layer::on(subtree)
        };
        self.with_viewer(|v| {
            v.try_apply(Command::AddLayer { character: index as usize, source: source as usize, layer }).err()
        })
        .flatten()
    }

    /// Puts character `source`'s motion on character `target`'s skeleton (and
    /// look, for a glTF character): every mapped bone points where its source
    /// bone points, the hips' path scaled by the legs. The result opens as a new
    /// character (the last index). `map` lists explicit pairs as
    /// `"Target=Source,Target2=Source2"` (an empty source leaves that target joint
    /// out); other joints are matched by name across conventions. `reference` is
    /// `"first-frame"` (default) or `"rest"`. Returns the error message, or
    /// `undefined` when done.
    pub fn retarget(&self, source: u32, target: u32, map: Option<String>, reference: Option<String>) -> Option<String> {
        let mut pairs = Vec::new();
        for item in map.as_deref().unwrap_or("").split(',').filter(|s| !s.trim().is_empty()) {
            let Some((t, s)) = item.split_once('=') else {
                return Some(format!("{item}: a map entry is Target=Source"));
            };
            pairs.push((t.trim().to_owned(), s.trim().to_owned()));
        }
        let reference = match reference.as_deref() {
            None | Some("first-frame") => mocap::ops::retarget::Reference::FirstFrame,
            Some("rest") => mocap::ops::retarget::Reference::Rest,
            Some(other) => return Some(format!("reference {other}: expected first-frame or rest")),
        };
        let options = mocap::ops::retarget::Options { map: pairs, reference };
        self.with_viewer(|v| {
            v.try_apply(Command::Retarget { source: source as usize, target: target as usize, options }).err()
        })
        .flatten()
    }

    /// Keys the poses corrected by dragging (Edit mode) at their frames: fading over
    /// `window` frames on each side (3 by default), or with `between` true
    /// interpolated from key to key (key-frame animation; the creator's default);
    /// returns the error message, or `undefined` when done.
    #[wasm_bindgen(js_name = setKey)]
    pub fn set_key(&self, window: Option<u32>, between: Option<bool>) -> Option<String> {
        self.with_viewer(|v| {
            let mut settings = v.state().settings.clone();
            if let Some(w) = window {
                settings.key_window = w as usize;
                settings.key_between = false;
            }
            if let Some(b) = between {
                settings.key_between = b;
            }
            v.try_apply(Command::SetSettings(settings)).and_then(|()| v.try_apply(Command::SetKey)).err()
        })
        .flatten()
    }

    /// Starts a new character for the creator (a root joint, 60 frames) in place of
    /// everything open, in Edit mode.
    #[wasm_bindgen(js_name = newCharacter)]
    pub fn new_character(&self) {
        self.with_viewer(|v| v.apply(Command::NewCharacter));
    }

    /// Deletes the key at `frame` of the current character (later edits are made
    /// again); returns the error message, or `undefined` when done.
    #[wasm_bindgen(js_name = deleteKey)]
    pub fn delete_key(&self, frame: u32) -> Option<String> {
        self.with_viewer(|v| v.try_apply(Command::DeleteKey(frame as usize)).err()).flatten()
    }

    /// Moves the key at `from` of the current character to frame `to`.
    #[wasm_bindgen(js_name = moveKey)]
    pub fn move_key(&self, from: u32, to: u32) -> Option<String> {
        self.with_viewer(|v| v.try_apply(Command::MoveKey { from: from as usize, to: to as usize }).err()).flatten()
    }

    /// Takes back the last clip edit; returns its label (`undefined` when none).
    pub fn undo(&self) -> Option<String> {
        self.with_viewer(|v| {
            let label = v.state().history.next_undo().map(str::to_owned);
            v.try_apply(Command::Undo).ok().and(label)
        })
        .flatten()
    }

    /// Makes the last undone edit again; returns its label.
    pub fn redo(&self) -> Option<String> {
        self.with_viewer(|v| {
            let label = v.state().history.next_redo().map(str::to_owned);
            v.try_apply(Command::Redo).ok().and(label)
        })
        .flatten()
    }

    /// Edit mode by typing: sets joint `name` of character `character` to the local
    /// rotation Z, X, Y degrees (intrinsic) at the frame shown; Set key keeps it.
    /// Returns whether there is such a joint.
    #[wasm_bindgen(js_name = rotateJoint)]
    pub fn rotate_joint(&self, character: u32, name: &str, z: f32, x: f32, y: f32) -> bool {
        use mocap::glam::{EulerRot, Quat};
        self.with_viewer(|v| {
            let joint = v.state().stage.actors.get(character as usize)?.clip()?.skeleton().find(name)?;
            let q = Quat::from_euler(EulerRot::ZXY, z.to_radians(), x.to_radians(), y.to_radians());
            Some(v.try_apply(Command::RotateJoint { character: character as usize, joint, rotation: q }).is_ok())
        })
        .flatten()
        .unwrap_or(false)
    }

    /// Forgets every pose corrected by dragging.
    #[wasm_bindgen(js_name = resetPose)]
    pub fn reset_pose(&self) {
        self.with_viewer(|v| v.apply(Command::ResetPose));
    }

    /// Where joint `name` of character `character` was last drawn, in CSS pixels
    /// of the page (`[x, y]`), or `undefined` when it is not on screen.
    #[wasm_bindgen(js_name = jointScreenPosition)]
    pub fn joint_screen_position(&self, character: u32, name: &str) -> Option<Vec<f32>> {
        let v = self.viewer.try_borrow().ok()?;
        let joint = v.state().stage.actors.get(character as usize)?.clip()?.skeleton().find(name)?;
        let p = v.joint_on_screen(character as usize, joint)?;
        Some(vec![p.x, p.y])
    }

    /// World position (metres, as drawn) of joint `name` of character `character`
    /// at the last frame drawn, or `undefined`.
    #[wasm_bindgen(js_name = jointWorldPosition)]
    pub fn joint_world_position(&self, character: u32, name: &str) -> Option<Vec<f32>> {
        let v = self.viewer.try_borrow().ok()?;
        let c = v.state().stage.actors.get(character as usize)?;
        let joint = c.clip()?.skeleton().find(name)?;
        c.extra.pose.get(joint).map(|t| t.translation.to_array().to_vec())
    }

    /// Plays animation `name` (`'all'` for every frame in file order) on the model
    /// that is character `index` (0-based); returns whether that model has it.
    #[wasm_bindgen(js_name = setAnimation)]
    pub fn set_animation(&self, index: u32, name: &str) -> bool {
        self.with_viewer(|v| v.try_apply(Command::SetAnimation(index as usize, name.to_owned())).is_ok())
            .unwrap_or(false)
    }

    /// Stands clip `index` (0-based) up along its file's `'y'` or `'z'` axis (the
    /// viewer guesses it when the clip opens); returns whether that clip exists
    /// and the axis is one of those.
    #[wasm_bindgen(js_name = setUpAxis)]
    pub fn set_up_axis(&self, index: u32, up: &str) -> bool {
        let Some(up) = mocap::UpAxis::from_name(up) else { return false };
        self.with_viewer(|v| v.try_apply(Command::SetUpAxis(index as usize, up)).is_ok()).unwrap_or(false)
    }

    /// Shows or hides character `index` (0-based, as in `state().clips`); returns whether it exists.
    #[wasm_bindgen(js_name = setVisible)]
    pub fn set_visible(&self, index: u32, visible: bool) -> bool {
        self.with_viewer(|v| v.try_apply(Command::SetVisible(index as usize, visible)).is_ok()).unwrap_or(false)
    }

    /// Closes character `index` (0-based); returns whether it existed.
    pub fn remove(&self, index: u32) -> bool {
        self.with_viewer(|v| v.try_apply(Command::CloseNow(index as usize)).is_ok()).unwrap_or(false)
    }

    /// Places the characters `'spread'` (side by side) or `'overlay'` (on top of each
    /// other); returns false for any other name.
    #[wasm_bindgen(js_name = setLayout)]
    pub fn set_layout(&self, #[wasm_bindgen(unchecked_param_type = "'spread' | 'overlay'")] layout: &str) -> bool {
        let Some(layout) = mocap_viewer::Layout::parse(layout) else { return false };
        self.with_viewer(|v| v.apply(Command::SetLayout(layout))).is_some()
    }

    /// Moves to a frame (clamped).
    pub fn seek(&self, frame: u32) {
        self.with_viewer(|v| v.apply(Command::Seek(frame as usize)));
    }

    /// Starts playback.
    pub fn play(&self) {
        self.with_viewer(|v| v.apply(Command::SetPlaying(true)));
    }

    /// Pauses playback (on an exact frame).
    pub fn pause(&self) {
        self.with_viewer(|v| v.apply(Command::SetPlaying(false)));
    }

    /// How a playing view samples between frames (View ▸ Between frames), and
    /// how Edit ▸ Resample makes in-betweens: `nearest`, `linear` or `cubic`
    /// (Catmull-Rom positions, squad rotations). The URL fragment keeps it.
    /// Returns an error message for any other name (nothing changes).
    #[wasm_bindgen(js_name = setInterpolation)]
    pub fn set_interpolation(&self, name: &str) -> Option<String> {
        let Some(mut settings) = self.viewer.try_borrow().ok().map(|v| v.state().settings.clone()) else {
            return Some("the viewer is busy".to_owned());
        };
        if !settings.set_between(name) {
            return Some(format!("unknown interpolation `{name}`: expected nearest, linear or cubic"));
        }
        self.with_viewer(|v| v.apply(Command::SetSettings(settings)));
        None
    }

    /// The view state as a URL fragment (no leading `#`): time, play state, speed,
    /// loop range, camera, selection, draw flags and panels.
    #[wasm_bindgen(js_name = viewState)]
    pub fn view_state(&self) -> String {
        self.viewer.try_borrow().map(|v| v.state().view_fragment()).unwrap_or_default()
    }

    /// Restores a view state written by [`MocapViewer::view_state`] (a `#` is optional).
    #[wasm_bindgen(js_name = applyViewState)]
    pub fn apply_view_state(&self, fragment: &str) {
        self.with_viewer(|v| v.apply_fragment(fragment));
    }

    /// Shows a message about files that could not be opened in the viewer's error
    /// banner. `opened` says whether other files given with them did open (the
    /// banner then says so); when it is false or omitted the banner says that what
    /// was open is still open.
    #[wasm_bindgen(js_name = showError)]
    pub fn show_error(&self, message: &str, opened: Option<bool>) {
        let notice = mocap_viewer::Notice::open_failed(message.to_owned(), opened.unwrap_or(false));
        self.with_viewer(|v| v.apply(Command::Notify(notice)));
    }

    /// Switches the embed layout (3D view and a minimal timeline) on or off.
    #[wasm_bindgen(js_name = setEmbed)]
    pub fn set_embed(&self, embed: bool) {
        self.with_viewer(|v| {
            let panels = mocap_viewer::Panels { embed, ..v.state().panels.clone() };
            let _ = v.apply(Command::SetPanels(panels));
        });
    }

    /// Closes every character (the view shows a drop hint).
    pub fn clear(&self) {
        self.with_viewer(|v| v.apply(Command::CloseAll));
    }

    /// Selects a joint by name in character `character` (0-based; the first when
    /// omitted); returns whether it exists.
    #[wasm_bindgen(js_name = selectJoint)]
    pub fn select_joint(&self, name: &str, character: Option<u32>) -> bool {
        self.with_viewer(|v| {
            v.try_apply(Command::SelectNamed { character: character.unwrap_or(0) as usize, name: name.to_owned() })
                .is_ok()
        })
        .unwrap_or(false)
    }

    /// Runs `f` on the viewer and asks for a repaint.
    pub(crate) fn with_viewer<R>(&self, f: impl FnOnce(&mut Viewer) -> R) -> Option<R> {
        let result = self.viewer.try_borrow_mut().ok().map(|mut v| f(&mut v));
        if let Some(ctx) = self.ctx.borrow().as_ref() {
            ctx.request_repaint();
        }
        result
    }
}
