//! The bendy-tentacle demo's window: bones, a bend and a swing slider per bone
//! (forward kinematics), following the target by IK with a chosen solver, soft or
//! rigid skin, and the weights view.

use crate::command::Command;
use crate::tentacle::{Solver, Tentacle};

/// Shows the demo window for `shown`; what it changes comes back in `out`.
pub fn show(ui: &mut egui::Ui, shown: &Tentacle, show_weights: bool, out: &mut Vec<Command>) {
    let mut demo = shown.clone();
    let mut weights = show_weights;
    let mut open = true;
    let mut rebuild = None;
    egui::Window::new("Bendy tentacle").open(&mut open).default_pos(egui::pos2(260.0, 60.0)).resizable(false).show(
        ui.ctx(),
        |ui| {
            let mut bones = demo.bones;
            ui.add(egui::Slider::new(&mut bones, mocap::build::demo::BONES).text("bones"));
            if bones != demo.bones {
                rebuild = Some(bones);
            }
            ui.checkbox(&mut demo.follow, "Follow the target (IK)")
                .on_hover_text("Drag the red sphere in the view; the tip follows");
            ui.horizontal(|ui| {
                ui.label("solver");
                for s in Solver::ALL {
                    ui.selectable_value(&mut demo.solver, s, s.name());
                }
            });
            ui.horizontal(|ui| {
                ui.selectable_value(&mut demo.soft, true, "Soft skin")
                    .on_hover_text("Vertices blended across each joint: a smooth bend");
                ui.selectable_value(&mut demo.soft, false, "Rigid skin")
                    .on_hover_text("Each vertex on one bone: a crease at each joint");
                ui.checkbox(&mut weights, "Weights");
            });
            ui.separator();
            ui.label(if demo.follow { "Bones (the pose IK starts from):" } else { "Bones (forward kinematics):" });
            egui::Grid::new("tentacle-angles").num_columns(3).show(ui, |ui| {
                for (b, [bend, swing]) in demo.angles.iter_mut().enumerate() {
                    ui.label(format!("bone {b}"));
                    ui.add(egui::Slider::new(bend, -120.0..=120.0).suffix("°").text("bend"));
                    ui.add(egui::Slider::new(swing, -120.0..=120.0).suffix("°").text("swing"));
                    ui.end_row();
                }
            });
            let reach = demo.tip.distance(demo.target);
            ui.label(format!("tip to target: {reach:.3} m"));
        },
    );
    match rebuild {
        Some(bones) => out.push(Command::ResizeTentacle(bones)),
        None if demo != *shown => out.push(Command::SetTentacle(demo)),
        None => {}
    }
    if weights != show_weights {
        out.push(Command::ShowWeights(weights));
    }
    if !open {
        out.push(Command::CloseTentacle);
    }
}
