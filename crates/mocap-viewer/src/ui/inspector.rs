//! The selected joint: offset, channels with current values, and a plot of its
//! channels over the whole clip with the playhead.

use crate::character::Character;

/// Most points per plotted channel (longer clips are decimated for drawing).
const MAX_PLOT_POINTS: usize = 4000;

/// Shows the inspector section for joint `index` of `doc` (the selection), at the
/// clip's own `frame` and the playhead `time`.
pub fn show(ui: &mut egui::Ui, selected: Option<(&Character, usize)>, frame: usize, time: f64) {
    ui.heading("Joint");
    let Some((doc, index)) = selected else {
        ui.label("Click a joint in the hierarchy to inspect it.");
        return;
    };
    let Some(clip) = doc.clip() else { return };
    let Some(joint) = clip.skeleton().joints().get(index) else { return };
    let values = clip.channel_values(frame);
    egui::Grid::new("joint").num_columns(2).striped(true).show(ui, |ui| {
        ui.label("Name");
        ui.strong(&joint.name);
        ui.end_row();
        ui.label("Clip");
        ui.label(&doc.name);
        ui.end_row();
        ui.label("Parent");
        let parent = joint.parent.and_then(|p| clip.skeleton().joints().get(p)).map_or("—", |p| p.name.as_str());
        ui.label(parent);
        ui.end_row();
        ui.label("Offset");
        ui.monospace(format!("{:.3} {:.3} {:.3}", joint.offset.x, joint.offset.y, joint.offset.z));
        ui.end_row();
        if joint.rest_rotation != mocap::glam::Quat::IDENTITY {
            let (x, y, z) = joint.rest_rotation.to_euler(mocap::glam::EulerRot::XYZ);
            ui.label("Rest rotation").on_hover_text("Relative to the parent (Acclaim axis), XYZ degrees");
            ui.monospace(format!("{:.2} {:.2} {:.2}", x.to_degrees(), y.to_degrees(), z.to_degrees()));
            ui.end_row();
        }
        for (k, channel) in joint.channels.iter().enumerate() {
            let label = ui.label(channel.to_string());
            if let Some(limit) = joint.limits.get(k) {
                label.on_hover_text(format!("limits {} … {}", limit.min, limit.max));
            }
            match values.get(joint.first_channel() + k) {
                Some(v) => ui.monospace(format!("{v:10.4}")),
                None => ui.weak("rest pose (no frames)"),
            };
            ui.end_row();
        }
        if !joint.limits.is_empty() {
            ui.label("Limits");
            let text: Vec<String> = joint.limits.iter().map(|l| format!("[{}, {}]", l.min, l.max)).collect();
            ui.monospace(text.join(" "));
            ui.end_row();
        }
    });
    if !joint.channels.is_empty() && clip.frame_count() > 0 {
        plot(ui, clip, joint, time);
    }
}

fn plot(ui: &mut egui::Ui, clip: &mocap::Clip, joint: &mocap::Joint, time: f64) {
    let frames = clip.frame_count();
    let step = frames.div_ceil(MAX_PLOT_POINTS).max(1);
    egui_plot::Plot::new("channels").height(180.0).legend(egui_plot::Legend::default()).allow_scroll(false).show(
        ui,
        |plot_ui| {
            for (k, channel) in joint.channels.iter().enumerate() {
                let c = joint.first_channel() + k;
                let points: Vec<[f64; 2]> = (0..frames)
                    .step_by(step)
                    .map(|f| [clip.timeline().time_of(f), f64::from(clip.motion().value(f, c))])
                    .collect();
                plot_ui.line(egui_plot::Line::new(channel.to_string(), points));
            }
            plot_ui.vline(egui_plot::VLine::new("playhead", time).color(egui::Color32::YELLOW));
        },
    );
}
