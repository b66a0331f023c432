//! [`Viewer::apply`]: the one place commands change the viewer.

use super::Viewer;
use crate::command::{Command, HostRequest};
use crate::selection::Selection;

impl Viewer {
    /// Requests for the page made outside [`Viewer::ui`] (by commands applied
    /// from the JS API), taken.
    pub fn take_requests(&mut self) -> Vec<HostRequest> {
        std::mem::take(&mut self.requests)
    }

    /// Applies one command (see [`crate::command`]): the one way the state
    /// changes. A refused one shows its reason in the banner, changes nothing
    /// and gives the reason back.
    pub fn apply(&mut self, command: Command) -> Result<(), String> {
        self.try_apply(command).inspect_err(|message| self.refuse(message.clone()))
    }

    /// Applies one command as [`Viewer::apply`] does, but a refusal is only
    /// returned, not shown (the JS API gives it to its caller).
    pub fn try_apply(&mut self, command: Command) -> Result<(), String> {
        let timing = self.state.timing();
        match (command, timing) {
            (Command::TogglePlay, _) => self.set_playing(!self.state.playback.playing),
            (Command::SetPlaying(on), _) => self.set_playing(on),
            (Command::SetTime(time), Some(t)) => {
                if time.is_finite() {
                    self.state.playback.time = time.clamp(0.0, t.duration());
                }
            }
            (Command::SetTime(_), None) => {}
            (Command::Step(d), Some(t)) => self.state.playback.step(d, t),
            (Command::First, Some(t)) => {
                let (a, _) = self.state.playback.frame_range(t);
                self.state.playback.seek(a, t);
            }
            (Command::Last, Some(t)) => {
                let (_, b) = self.state.playback.frame_range(t);
                self.state.playback.playing = false;
                self.state.playback.seek(b, t);
            }
            (Command::Seek(frame), _) => self.seek(frame),
            (Command::SetLooping(on), _) => self.state.playback.looping = on,
            (Command::SetSpeed(speed), _) => {
                if speed.is_finite() && speed > 0.0 {
                    self.state.playback.speed = speed;
                }
            }
            (Command::SetRange(range), _) => self.state.playback.range = range,
            (Command::Zoom(f), _) => self.state.camera.zoom(f),
            (Command::Orbit(px), _) if px > 0.0 && self.state.settings.pose_mode && self.state.has_corrections() => {
                // In Edit mode with a correction, k sets the key instead of orbiting.
                self.set_key()?;
            }
            (Command::Orbit(px), _) => self.state.camera.orbit(px, 0.0),
            (Command::Waypoint(w), _) => self.state.camera.waypoint(w),
            (Command::ToggleFollow, _) => self.state.settings.follow_root = !self.state.settings.follow_root,
            (Command::ToggleAxes, _) => self.state.settings.show_axes = !self.state.settings.show_axes,
            (Command::ToggleDrawMode, _) => self.state.settings.mode = self.state.settings.mode.next(),
            (Command::SetSettings(settings), _) => self.state.settings = settings,
            (Command::SetPanels(panels), _) => self.state.panels = panels,
            (Command::SetLayout(layout), _) => self.set_layout(layout),
            (Command::ResetCamera, _) => self.reset_camera(),
            (Command::SetCamera(camera), _) => self.state.camera = camera,
            (Command::ApplyFragment(fragment), _) => {
                self.apply_view(&crate::view_state::ViewState::parse(&fragment));
            }
            (Command::SelectNamed { character, name }, _) => {
                if !self.select_named(character, &name) {
                    return Err(format!("no joint `{name}` in character {}", character + 1));
                }
            }
            (Command::CloseAll, _) => self.clear(),
            (Command::Select { character, joint }, _) => self.select_in(character, joint),
            (Command::Fold { character, joint, folded }, _) => self.state.folds.set(character, joint, folded),
            (Command::SetVisible(index, on), _) => {
                if !self.set_visible(index, on) {
                    return Err(no_character(index));
                }
            }
            (Command::SetAnimation(index, name), _) => {
                if !self.set_animation(index, &name) {
                    return Err(format!("no animation `{name}`"));
                }
            }
            (Command::SetUpAxis(index, up), _) => {
                if !self.set_up_axis(index, up) {
                    return Err(format!("character {} is not a clip", index + 1));
                }
            }
            (Command::Close(index), _) => {
                if self.state.history.edited(index) {
                    self.state.pending_close = Some(index);
                } else {
                    self.remove(index);
                }
            }
            (Command::CloseNow(index), _) => {
                self.state.pending_close = None;
                if !self.remove(index) {
                    return Err(no_character(index));
                }
            }
            (Command::KeepOpen, _) => self.state.pending_close = None,
            (Command::SetKey, _) => {
                self.set_key()?;
            }
            (Command::ResetPose, _) => self.reset_pose(),
            (Command::StepKey(forward), _) => {
                self.step_key(forward);
            }
            (Command::MoveKey { from, to }, _) => {
                self.move_key(from, to)?;
                self.set_playing(false);
                self.seek(to);
            }
            (Command::DeleteKey(frame), _) => self.delete_key(frame)?,
            (Command::Undo, _) => {
                self.undo();
            }
            (Command::Redo, _) => {
                self.redo();
            }
            (Command::Edit { character, edit, label }, _) => self.edit(character, &edit, &label)?,
            (Command::AddLayer { character, source, layer }, _) => {
                self.add_layer(character, source, &layer)?;
                self.state.layer_dialog = None;
            }
            (Command::RotateJoint { character, joint, rotation }, _) => {
                if !self.rotate_joint(character, joint, rotation) {
                    return Err(format!("character {} has no joint {joint} to turn", character + 1));
                }
            }
            (Command::NewCharacter, _) => self.new_character(),
            (Command::GrowBone(name), _) => {
                if !self.grow_bone(&name) {
                    return Err("select a joint of a clip to grow a bone from".into());
                }
            }
            (Command::RefreshTentacleSkin, _) => self.refresh_tentacle_skin(),
            (Command::SetTentacle(demo), _) => {
                let Some(old) = &self.state.tentacle else { return Err("the tentacle demo is not open".into()) };
                if demo.bones != old.bones {
                    return Err("resize the tentacle with its bones control".into());
                }
                let soft_changed = demo.soft != old.soft;
                self.state.tentacle = Some(demo);
                if soft_changed {
                    self.refresh_tentacle_skin();
                }
            }
            (Command::ResizeTentacle(bones), _) => {
                if let Some(demo) = self.state.tentacle.clone() {
                    self.open_tentacle(bones);
                    if let Some(t) = &mut self.state.tentacle {
                        (t.follow, t.solver, t.soft, t.target) = (demo.follow, demo.solver, demo.soft, demo.target);
                    }
                    self.refresh_tentacle_skin();
                }
            }
            (Command::CloseTentacle, _) => {
                self.state.tentacle = None;
                self.reset_pose();
            }
            (Command::SetOffset(index, offset), _) => {
                if let Some(c) = self.state.stage.actors.get_mut(index)
                    && offset.is_finite()
                {
                    c.offset = offset;
                }
            }
            (Command::ShowWeights(on), _) => self.state.settings.show_weights = on,
            (Command::OpenLayerDialog { character, joint }, _) => {
                self.state.layer_dialog = Some(crate::layer_dialog::LayerDialog::new(character, &joint));
            }
            (Command::SetLayerDialog(dialog), _) => self.state.layer_dialog = Some(dialog),
            (Command::CloseLayerDialog, _) => self.state.layer_dialog = None,
            (Command::Retarget { source, target, options }, _) => {
                self.retarget(source, target, &options)?;
                self.state.retarget_dialog = None;
            }
            (Command::OpenRetargetDialog(source), _) => {
                if self.state.stage.actors.get(source).and_then(|c| c.clip()).is_none() {
                    return Err(format!("character {} has no motion to retarget", source + 1));
                }
                self.state.retarget_dialog = Some(crate::retarget_dialog::RetargetDialog::new(source));
            }
            (Command::SetRetargetDialog(dialog), _) => self.state.retarget_dialog = Some(dialog),
            (Command::CloseRetargetDialog, _) => self.state.retarget_dialog = None,
            (Command::StartCapture(index), _) => self.start_capture(index)?,
            (Command::FinishCapture, _) => self.finish_capture_now(),
            (Command::FitRig { model, template }, _) => self.start_rig_edit(model, template)?,
            (Command::SetRigView { show_binding, painting }, _) => {
                if let Some(e) = &mut self.state.rig_edit {
                    (e.show_binding, e.painting) = (show_binding, painting);
                }
            }
            (Command::BindRig, _) => self.bind_rig(),
            (Command::FinishRigEdit, _) => self.finish_rig_edit(),
            (Command::OpenTentacle(bones), _) => self.open_tentacle(bones),
            (Command::Open(mode), _) => self.requests.push(HostRequest::PickFiles(mode)),
            (Command::Share, _) => self.requests.push(HostRequest::Share),
            (Command::SaveBvh, _) => {
                self.request_save(self.state.current())?;
                self.state.history.mark_saved(self.state.current());
            }
            (Command::SaveCharacter(index), _) => {
                // Saving saves the current character: make it this one.
                if self.state.current() != index {
                    self.state.selected = Some(Selection { character: index, joint: 0 });
                }
                self.request_save(index)?;
                self.state.history.mark_saved(index);
            }
            (Command::SaveGltf, _) => {
                let (name, bytes) = self.save_gltf(self.state.current())?;
                self.requests.push(HostRequest::Save { name, bytes });
                self.state.history.mark_saved(self.state.current());
            }
            (Command::SaveRig, _) => {
                let (name, text) = self.rig_download().ok_or("no capture rig to save")?;
                self.requests.push(HostRequest::Save { name, bytes: text.into_bytes() });
            }
            (Command::DismissNotice, _) => self.state.notice = None,
            (Command::Restore(restored), _) => self.restore(*restored),
            (Command::MarkSaved(index), _) => self.state.history.mark_saved(index),
            (Command::SetPreviousSession(held), _) => self.state.previous_session = held,
            (Command::RestorePrevious, _) => self.requests.push(HostRequest::RestorePrevious),
            (Command::SetVideoExport(can), _) => self.state.video_export = can,
            (Command::ExportVideo, _) => self.requests.push(HostRequest::ExportVideo),
            (Command::Compare(None), _) => self.state.comparison = None,
            (Command::Compare(Some((a, b))), _) => {
                if let Err(e) = self.compare(a, b) {
                    self.state.comparison = None;
                    return Err(e);
                }
            }
            (Command::Notify(notice), _) => self.state.notice = Some(notice),
            (Command::Step(_) | Command::First | Command::Last, None) => {}
        }
        Ok(())
    }

    /// Asks the page to save character `index` as BVH ([`Viewer::save_bvh`]).
    fn request_save(&mut self, index: usize) -> Result<(), String> {
        let (name, text) = self.save_bvh(index).ok_or("a model has no motion to save as BVH")?;
        self.requests.push(HostRequest::Save { name, bytes: text.into_bytes() });
        Ok(())
    }
}

/// The refusal for a character index that is not open.
fn no_character(index: usize) -> String {
    format!("no character {}", index + 1)
}
