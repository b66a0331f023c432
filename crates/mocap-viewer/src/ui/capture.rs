//! The model panel's capture section: the rig set-up (Fit skeleton, Bind, paint
//! the binding, Done), Capture skeleton (with a progress bar while it runs), what
//! the last capture gave (joints tracked, residuals, joints without vertices, the
//! animations as frame ranges), and Save rig.

use crate::capture::CaptureResult;
use crate::character::Character;
use crate::command::Command;
use crate::rig_edit::RigEdit;

/// What the capture section shows.
pub struct CaptureView<'a> {
    /// The open characters (a clip's skeleton can be fitted instead of the humanoid).
    pub characters: &'a [Character],
    /// The capture's progress (steps done, steps in all), while one runs.
    pub progress: Option<(usize, usize)>,
    /// A rig being set up on a model.
    pub rig_edit: Option<&'a RigEdit>,
    /// A rig dropped or set up for the next capture.
    pub capture_rig: Option<&'a mocap::capture::Rig>,
    /// What the last capture gave.
    pub result: Option<&'a CaptureResult>,
}

/// Shows the capture section for model `index`; what the user does comes back
/// as commands in `out`.
pub fn show(ui: &mut egui::Ui, view: &CaptureView, index: usize, out: &mut Vec<Command>) {
    ui.separator();
    ui.heading("Skeleton capture");
    if let Some((done, total)) = view.progress {
        let share = done as f32 / total.max(1) as f32;
        ui.add(egui::ProgressBar::new(share).show_percentage().text(format!("capturing: step {done} of {total}")));
        return;
    }
    rig_setup(ui, view, index, out);
    let rig_note = if view.rig_edit.is_some_and(|e| e.model == index) {
        Some("with the rig being set up".to_owned())
    } else {
        view.capture_rig.map(|r| format!("with the rig set up or dropped ({} joints)", r.joints.len()))
    };
    let hint = "Turn the model's vertex animation into skeletal motion: a humanoid fitted in its first frame (or a rig dropped as JSON), four tracked vertices per joint";
    if ui.button("Capture skeleton").on_hover_text(hint).clicked() {
        out.push(Command::StartCapture(index));
    }
    ui.label(
        egui::RichText::new(rig_note.unwrap_or_else(|| "automatic fit (drop a rig .json to use yours)".to_owned()))
            .weak(),
    );
    let Some(result) = view.result else { return };
    last_capture(ui, result);
    if ui
        .button("Save rig")
        .on_hover_text("Download the rig used (JSON); drop it back with the model to capture with it")
        .clicked()
    {
        out.push(Command::SaveRig);
    }
}

/// Fit skeleton, and while a rig is set up on this model: Bind, painting, the
/// binding view, Save rig and Done.
fn rig_setup(ui: &mut egui::Ui, view: &CaptureView, index: usize, out: &mut Vec<Command>) {
    let editing = view.rig_edit.is_some_and(|e| e.model == index);
    if !editing {
        let clips: Vec<(usize, String)> = view
            .characters
            .iter()
            .enumerate()
            .filter(|(_, c)| c.clip().is_some())
            .map(|(i, c)| (i, c.name.clone()))
            .collect();
        ui.horizontal(|ui| {
            let hint = "Place a skeleton in the model's first frame to adjust by hand: drag its joints and spin handles, bind, paint";
            if ui.button("Fit skeleton").on_hover_text(hint).clicked() {
                out.push(Command::FitRig { model: index, template: None });
            }
            for (i, name) in clips {
                if ui.small_button(format!("fit {name}")).on_hover_text("Fit this clip's skeleton (its first pose) instead of the humanoid").clicked() {
                    out.push(Command::FitRig { model: index, template: Some(i) });
                }
            }
        });
        return;
    }
    let Some(e) = view.rig_edit else { return };
    let (mut show_binding, mut painting) = (e.show_binding, e.painting);
    let selected = e.selected.and_then(|j| e.rig.joints.get(j)).map(|j| j.name.clone());
    ui.label(egui::RichText::new("Drag the crosses (joints) to where they belong and the cyan handles to turn each bone's up; the model shows its set-up frame.").weak());
    ui.label(format!("Selected: {}", selected.as_deref().unwrap_or("none (press a joint)")));
    ui.horizontal(|ui| {
        ui.checkbox(&mut show_binding, "Show binding");
        ui.add_enabled(selected.is_some(), egui::Checkbox::new(&mut painting, "Paint"))
            .on_hover_text("Drag over the model: the vertices under the pointer go to the selected joint's bone (the one ending at it)");
    });
    let mut bind = false;
    let mut done = false;
    let mut save = false;
    ui.horizontal(|ui| {
        bind = ui.button("Bind").on_hover_text("Bind every vertex to its nearest bone").clicked();
        save = ui.button("Save rig").on_hover_text("Download the rig (JSON)").clicked();
        done = ui.button("Done").on_hover_text("Keep the rig for the next capture and stop editing").clicked();
    });
    if (show_binding, painting) != (e.show_binding, e.painting) {
        out.push(Command::SetRigView { show_binding, painting });
    }
    if bind {
        out.push(Command::BindRig);
    }
    if save {
        out.push(Command::SaveRig);
    }
    if done {
        out.push(Command::FinishRigEdit);
    }
}

/// What the last capture gave: joints tracked, residual, joints without vertices,
/// the animations as frame ranges.
fn last_capture(ui: &mut egui::Ui, result: &crate::capture::CaptureResult) {
    let joints = &result.report.joints;
    let tracked = joints.iter().filter(|j| j.tracked.is_ok()).count();
    let worst = joints.iter().map(|j| j.max_residual).fold(0.0, f64::max);
    let failed: usize = joints.iter().map(|j| j.failures.len()).sum();
    egui::Grid::new("capture").num_columns(2).striped(true).show(ui, |ui| {
        let mut row = |k: &str, v: String| {
            ui.label(k);
            ui.label(v);
            ui.end_row();
        };
        row("Captured", format!("{} → {}", result.model, result.clip));
        row("Joints", format!("{tracked} of {} tracked", joints.len()));
        row(
            "Residual",
            format!("≤ {worst:.3} ({:.2} % of the height)", worst / f64::from(result.report.height.max(1e-6)) * 100.0),
        );
        row("Not converged", format!("{failed} joint-frames"));
    });
    for j in joints.iter().filter(|j| j.tracked.is_err()) {
        ui.label(egui::RichText::new(format!("{}: follows its bones' vertices (no rigid four)", j.name)).weak());
    }
    ui.collapsing("Animations (frame ranges)", |ui| {
        for (name, first, last) in &result.animations {
            ui.label(format!("{name}: {first}–{last}"));
        }
    });
}
