//! [`Viewer::apply`]: the one place commands change the viewer.

use super::Viewer;
use crate::command::{Command, HostRequest};
use crate::selection::Selection;
use crate::ui;

impl Viewer {
    /// Requests for the page made outside [`Viewer::ui`] (by commands applied
    /// from the JS API), taken.
    pub fn take_requests(&mut self) -> Vec<HostRequest> {
        std::mem::take(&mut self.requests)
    }

    /// Applies one command (see [`crate::command`]). A refused one shows its
    /// reason in the banner and changes nothing.
    pub fn apply(&mut self, command: Command) {
        if let Err(message) = self.run(command) {
            self.refuse(message);
        }
    }

    /// Executes `command`; `Err` when it was refused.
    fn run(&mut self, command: Command) -> Result<(), String> {
        let timing = self.timing();
        match (command, timing) {
            (Command::TogglePlay, _) => self.set_playing(!self.playback.playing),
            (Command::Step(d), Some(t)) => self.playback.step(d, t),
            (Command::First, Some(t)) => {
                let (a, _) = self.playback.frame_range(t);
                self.playback.seek(a, t);
            }
            (Command::Last, Some(t)) => {
                let (_, b) = self.playback.frame_range(t);
                self.playback.playing = false;
                self.playback.seek(b, t);
            }
            (Command::Seek(frame), _) => self.seek(frame),
            (Command::SetLooping(on), _) => self.playback.looping = on,
            (Command::SetSpeed(speed), _) => {
                if speed.is_finite() && speed > 0.0 {
                    self.playback.speed = speed;
                }
            }
            (Command::SetRange(range), _) => self.playback.range = range,
            (Command::Zoom(f), _) => self.camera.zoom(f),
            (Command::Orbit(px), _) if px > 0.0 && self.settings.pose_mode && self.has_corrections() => {
                // In Edit mode with a correction, k sets the key instead of orbiting.
                self.set_key()?;
            }
            (Command::Orbit(px), _) => self.camera.orbit(px, 0.0),
            (Command::Waypoint(w), _) => self.camera.waypoint(w),
            (Command::ToggleFollow, _) => self.settings.follow_root = !self.settings.follow_root,
            (Command::ToggleAxes, _) => self.settings.show_axes = !self.settings.show_axes,
            (Command::ToggleDrawMode, _) => self.settings.mode = self.settings.mode.next(),
            (Command::SetSettings(settings), _) => self.settings = settings,
            (Command::SetPanels(panels), _) => self.panels = panels,
            (Command::SetLayout(layout), _) => self.set_layout(layout),
            (Command::ResetCamera, _) => self.reset_camera(),
            (Command::Select { character, joint }, _) => self.select_in(character, joint),
            (Command::SetVisible(index, on), _) => {
                self.set_visible(index, on);
            }
            (Command::SetAnimation(index, name), _) => {
                if !self.set_animation(index, &name) {
                    return Err(format!("no animation `{name}`"));
                }
            }
            (Command::SetUpAxis(index, up), _) => {
                self.set_up_axis(index, up);
            }
            (Command::Close(index), _) => {
                if self.history.edited(index) {
                    self.pending_close = Some(index);
                } else {
                    self.remove(index);
                }
            }
            (Command::CloseNow(index), _) => {
                self.pending_close = None;
                self.remove(index);
            }
            (Command::KeepOpen, _) => self.pending_close = None,
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
                self.layer_dialog = None;
            }
            (Command::RotateJoint { character, joint, rotation }, _) => {
                self.rotate_joint(character, joint, rotation);
            }
            (Command::NewCharacter, _) => self.new_character(),
            (Command::GrowBone(name), _) => {
                if !self.grow_bone(&name) {
                    return Err("select a joint of a clip to grow a bone from".into());
                }
            }
            (Command::RefreshTentacleSkin, _) => self.refresh_tentacle_skin(),
            (Command::ResizeTentacle(bones), _) => {
                if let Some(demo) = self.tentacle.clone() {
                    self.open_tentacle(bones);
                    if let Some(t) = &mut self.tentacle {
                        (t.follow, t.solver, t.soft, t.target) = (demo.follow, demo.solver, demo.soft, demo.target);
                    }
                    self.refresh_tentacle_skin();
                }
            }
            (Command::CloseTentacle, _) => {
                self.tentacle = None;
                self.reset_pose();
            }
            (Command::SetOffset(index, offset), _) => {
                if let Some(c) = self.stage.actors.get_mut(index)
                    && offset.is_finite()
                {
                    c.offset = offset;
                }
            }
            (Command::ShowWeights(on), _) => self.settings.show_weights = on,
            (Command::OpenLayerDialog { character, joint }, _) => {
                self.layer_dialog = Some(ui::layer_window::LayerDialog::new(character, &joint));
            }
            (Command::CloseLayerDialog, _) => self.layer_dialog = None,
            (Command::StartCapture(index), _) => self.start_capture(index)?,
            (Command::FitRig { model, template }, _) => self.start_rig_edit(model, template)?,
            (Command::SetRigView { show_binding, painting }, _) => {
                if let Some(e) = &mut self.rig_edit {
                    (e.show_binding, e.painting) = (show_binding, painting);
                }
            }
            (Command::BindRig, _) => self.bind_rig(),
            (Command::FinishRigEdit, _) => self.finish_rig_edit(),
            (Command::OpenTentacle(bones), _) => self.open_tentacle(bones),
            (Command::Open(mode), _) => self.requests.push(HostRequest::PickFiles(mode)),
            (Command::Share, _) => self.requests.push(HostRequest::Share),
            (Command::SaveBvh, _) => self.request_save(self.current())?,
            (Command::SaveCharacter(index), _) => {
                // Saving saves the current character: make it this one.
                if self.current() != index {
                    self.selected = Some(Selection { character: index, joint: 0 });
                }
                self.request_save(index)?;
            }
            (Command::SaveRig, _) => {
                let (name, text) = self.rig_download().ok_or("no capture rig to save")?;
                self.requests.push(HostRequest::Save { name, text });
            }
            (Command::DismissNotice, _) => self.error = None,
            (Command::Notify(notice), _) => self.error = Some(notice),
            (Command::Step(_) | Command::First | Command::Last, None) => {}
        }
        Ok(())
    }

    /// Asks the page to save character `index` as BVH ([`Viewer::save_bvh`]).
    fn request_save(&mut self, index: usize) -> Result<(), String> {
        let (name, text) = self.save_bvh(index).ok_or("a model has no motion to save as BVH")?;
        self.requests.push(HostRequest::Save { name, text });
        Ok(())
    }
}
