//! Bottom panel: transport buttons, scrub bar, loop, speed and loop range, over
//! the longest clip, counted in frames of the current character.

use crate::character::Character;
use crate::command::{Command, button, button_with};
use crate::playback::{Playback, SPEED_RANGE, Timing};
use crate::settings::ViewSettings;

/// What the timeline shows.
pub struct TimelineView<'a> {
    /// The playhead, speed, loop and loop range.
    pub playback: &'a Playback,
    /// The shared timeline, when a clip is open.
    pub timing: Option<Timing>,
    /// The view settings (key mode, foot lock).
    pub settings: &'a ViewSettings,
    /// The current character: frames are counted in its frame time; its foot contacts.
    pub character: Option<&'a Character>,
    /// The current character's keyed frames.
    pub keys: Vec<usize>,
    /// Whether a pose corrected by dragging waits to be keyed.
    pub corrections: bool,
    /// The embed layout's minimal timeline.
    pub embed: bool,
    /// Compare ▸ with: the error per frame, drawn under the scrub bar.
    pub comparison: Option<(&'a crate::comparison::Comparison, f64)>,
}

/// Shows the timeline panel; what the user does comes back as commands in `out`.
pub fn show(ui: &mut egui::Ui, view: &TimelineView, out: &mut Vec<Command>) {
    egui::Panel::bottom("timeline").show(ui, |ui| {
        ui.add_space(4.0);
        let Some(timing) = view.timing else {
            ui.label("No clip open");
            return;
        };
        let frame = view.playback.frame(timing);
        let play = if view.playback.playing { "Pause" } else { "Play" };
        if view.embed {
            minimal(ui, play, frame, timing, out);
            return;
        }
        let mut settings = view.settings.clone();
        ui.horizontal(|ui| {
            button(ui, Command::First, out);
            button(ui, Command::Step(-1), out);
            button_with(ui, play, Command::TogglePlay, out);
            button(ui, Command::Step(1), out);
            button(ui, Command::Last, out);
            if view.corrections {
                // Keying sits here, on the timeline's row, so the view above never moves.
                ui.separator();
                button(ui, Command::SetKey, out);
                key_mode(ui, &mut settings);
                button(ui, Command::ResetPose, out);
            }
            if !view.keys.is_empty() {
                ui.separator();
                if ui.button("◀ key").on_hover_text("Previous keyed frame").clicked() {
                    out.push(Command::StepKey(false));
                }
                if ui.button("key ▶").on_hover_text("Next keyed frame").clicked() {
                    out.push(Command::StepKey(true));
                }
                let here = frame;
                if view.keys.contains(&here) {
                    if ui.button("← move").on_hover_text("Move this key one frame earlier").clicked() && here > 0 {
                        out.push(Command::MoveKey { from: here, to: here - 1 });
                    }
                    if ui.button("move →").on_hover_text("Move this key one frame later").clicked() && here < timing.last() {
                        out.push(Command::MoveKey { from: here, to: here + 1 });
                    }
                    if ui.button("× key").on_hover_text("Delete this key (later edits are made again)").clicked() {
                        out.push(Command::DeleteKey(here));
                    }
                }
            }
        });
        if settings != *view.settings {
            out.push(Command::SetSettings(settings));
        }
        ui.horizontal(|ui| {
            let counted_in = view.character.map_or(String::new(), |d| format!("Frames of {} ({:.2} fps)", d.name, 1.0 / d.asset.timeline().frame_time()));
            ui.monospace(format!("frame {frame:>5} / {}   {:>8.3} s", timing.last(), view.playback.time))
                .on_hover_text(format!("{counted_in}: the selected joint's character, else the first. The timeline spans the longest clip; shorter ones hold their last pose."));
            ui.separator();
            let mut looping = view.playback.looping;
            if ui.checkbox(&mut looping, "Loop").changed() {
                out.push(Command::SetLooping(looping));
            }
            let mut speed = view.playback.speed;
            let slider = egui::Slider::new(&mut speed, SPEED_RANGE)
                .logarithmic(true)
                .text("speed")
                .suffix("×")
                .max_decimals(2);
            if ui.add(slider).changed() {
                out.push(Command::SetSpeed(speed));
            }
        });
        ui.horizontal(|ui| {
            let mut f = frame;
            ui.spacing_mut().slider_width = (ui.available_width() - 60.0).max(100.0);
            let slider = frame_slider(ui, &mut f, timing.last());
            if slider.changed() {
                out.push(Command::Seek(f));
            }
            if view.settings.foot_lock {
                contact_marks(ui, view, &slider, timing);
            }
            key_marks(ui, view, &slider, timing, out);
        });
        ui.horizontal(|ui| {
            let mut on = view.playback.range.is_some();
            if ui.checkbox(&mut on, "Loop range").changed() {
                out.push(Command::SetRange(on.then_some((frame, timing.last()))));
            }
            if let Some((mut a, mut b)) = view.playback.range {
                let from = ui.add(egui::DragValue::new(&mut a).range(0..=timing.last()).prefix("from "));
                let to = ui.add(egui::DragValue::new(&mut b).range(0..=timing.last()).prefix("to "));
                if from.changed() || to.changed() {
                    out.push(Command::SetRange(Some((a, b))));
                }
            }
        });
        if let Some((comparison, dt)) = view.comparison {
            error_curve(ui, comparison, dt, view.playback.time, out);
        }
        ui.add_space(2.0);
    });
}

/// Foot contacts of the current character under the scrub bar: one row of marks
/// per foot at the frames where it rests on the floor.
fn contact_marks(ui: &egui::Ui, view: &TimelineView, slider: &egui::Response, timing: Timing) {
    let Some(c) = view.character else { return };
    let (Some(lock), Some(clip)) = (&c.extra.foot_lock, c.clip()) else { return };
    // The slider's rail: its width less the value box.
    let rail =
        egui::Rect::from_min_max(slider.rect.left_top(), egui::pos2(slider.rect.right() - 60.0, slider.rect.bottom()));
    let span = timing.duration().max(1e-9);
    let colors = [egui::Color32::from_rgb(90, 200, 255), egui::Color32::from_rgb(255, 150, 80)];
    for (row, contacts) in lock.contacts().enumerate() {
        let y = rail.bottom() + 1.0 + row as f32 * 3.0;
        let color = colors[row % colors.len()];
        for (f, _) in contacts.iter().enumerate().filter(|(_, c)| **c) {
            let x = rail.left() + (clip.timeline().time_of(f) / span) as f32 * rail.width();
            if x <= rail.right() {
                ui.painter().line_segment([egui::pos2(x, y), egui::pos2(x + 2.0, y)], egui::Stroke::new(2.0, color));
            }
        }
    }
}

/// The current character's keyed frames as small diamonds on the scrub bar. A
/// diamond can be dragged along the bar: a ghost follows the pointer, snapped to
/// frames, and the key moves there (one undoable step) where it is let go.
fn key_marks(ui: &egui::Ui, view: &TimelineView, slider: &egui::Response, timing: Timing, out: &mut Vec<Command>) {
    let keys = &view.keys;
    if keys.is_empty() {
        return;
    }
    let Some(timeline) = view.character.map(|c| c.asset.timeline()) else { return };
    let rail =
        egui::Rect::from_min_max(slider.rect.left_top(), egui::pos2(slider.rect.right() - 60.0, slider.rect.bottom()));
    let span = timing.duration().max(1e-9);
    let x_of = |frame: usize| rail.left() + (timeline.time_of(frame) / span) as f32 * rail.width();
    let y = rail.center().y;
    let mut moved = None;
    for &k in keys {
        let x = x_of(k);
        if x > rail.right() {
            continue;
        }
        let hit = ui.interact(
            egui::Rect::from_center_size(egui::pos2(x, y), egui::vec2(12.0, 14.0)),
            ui.scope_id().with(("key", k)),
            egui::Sense::drag(),
        );
        let hover = hit.hovered() || hit.dragged();
        diamond(ui, x, y, if hover { 6.5 } else { 5.0 }, egui::Color32::from_rgb(255, 200, 40));
        let hit = hit.on_hover_text(format!("Key at frame {k}: drag along the bar to move it"));
        if let Some(p) = hit.interact_pointer_pos().filter(|_| hit.dragged() || hit.drag_stopped()) {
            let time = (((p.x - rail.left()) / rail.width().max(1.0)) as f64 * span).clamp(0.0, timeline.duration());
            let to = timeline.nearest(time).min(timeline.last());
            diamond(ui, x_of(to), y, 5.0, egui::Color32::from_rgba_unmultiplied(255, 230, 120, 150));
            ui.painter().text(
                egui::pos2(x_of(to), rail.top() - 2.0),
                egui::Align2::CENTER_BOTTOM,
                to.to_string(),
                egui::FontId::monospace(11.0),
                ui.visuals().strong_text_color(),
            );
            if hit.drag_stopped() && to != k {
                moved = Some((k, to));
            }
        }
    }
    if let Some((from, to)) = moved {
        out.push(Command::MoveKey { from, to });
    }
}

/// A key diamond of half-size `d` at (`x`, `y`).
fn diamond(ui: &egui::Ui, x: f32, y: f32, d: f32, fill: egui::Color32) {
    let points = vec![egui::pos2(x, y - d), egui::pos2(x + d, y), egui::pos2(x, y + d), egui::pos2(x - d, y)];
    ui.painter().add(egui::Shape::convex_polygon(points, fill, egui::Stroke::new(1.0, egui::Color32::BLACK)));
}

/// The embed layout's timeline: play/pause and the scrub bar on one row.
fn minimal(ui: &mut egui::Ui, play: &str, frame: usize, timing: crate::playback::Timing, out: &mut Vec<Command>) {
    ui.horizontal(|ui| {
        button_with(ui, play, Command::TogglePlay, out);
        let mut f = frame;
        ui.spacing_mut().slider_width = (ui.available_width() - 60.0).max(100.0);
        if frame_slider(ui, &mut f, timing.last()).changed() {
            out.push(Command::Seek(f));
        }
    });
    ui.add_space(2.0);
}

/// How a key spreads: fading over ± N frames (fixing a dense take) or
/// interpolated between keys (key-frame animation).
fn key_mode(ui: &mut egui::Ui, settings: &mut crate::settings::ViewSettings) {
    ui.selectable_value(&mut settings.key_between, true, "between keys").on_hover_text("Key-frame animation: the pose goes smoothly (slerp) from key to key and holds before the first and after the last");
    ui.selectable_value(&mut settings.key_between, false, "fade")
        .on_hover_text("A correction of a dense take: it fades in and out over the frames set beside");
    if !settings.key_between {
        ui.add(egui::DragValue::new(&mut settings.key_window).range(0..=60).prefix("± ").suffix(" frames"))
            .on_hover_text("Frames on each side over which the key fades in and out");
    }
}

/// The playhead's slider over frames `0..=last`. A clip of one frame has nothing
/// to scrub: its slider is shown at the start and disabled (egui would put the
/// handle of an empty range half-way along).
fn frame_slider(ui: &mut egui::Ui, frame: &mut usize, last: usize) -> egui::Response {
    let slider = egui::Slider::new(frame, 0..=last.max(1)).show_value(true).trailing_fill(true);
    ui.add_enabled(last > 0, slider)
}

/// The comparison's error per frame (its frame time `dt`), the playhead, and
/// the worst frame one click away.
fn error_curve(ui: &mut egui::Ui, comparison: &crate::comparison::Comparison, dt: f64, time: f64, out: &mut Vec<Command>) {
    let r = &comparison.report;
    ui.horizontal(|ui| {
        ui.label(format!("Error: MPJPE {:.2} {} ({:.3} m)", r.mpjpe, comparison.units, r.mpjpe_m));
        if ui
            .button(format!("Worst frame ({})", r.worst_frame))
            .on_hover_text("Go to the frame where the takes differ most")
            .clicked()
        {
            out.push(Command::SetTime(r.worst_frame as f64 * dt));
        }
        if ui.button("Stop comparing").clicked() {
            out.push(Command::Compare(None));
        }
    });
    let points: egui_plot::PlotPoints = r.frames.iter().enumerate().map(|(k, e)| [k as f64 * dt, f64::from(*e)]).collect();
    egui_plot::Plot::new("comparison error")
        .height(70.0)
        .allow_scroll(false)
        .allow_zoom(false)
        .allow_drag(false)
        .show_axes([false, true])
        .show(ui, |plot| {
            plot.line(egui_plot::Line::new("error", points).color(egui::Color32::from_rgb(235, 120, 80)));
            plot.vline(egui_plot::VLine::new("playhead", time).color(egui::Color32::YELLOW));
        });
}
