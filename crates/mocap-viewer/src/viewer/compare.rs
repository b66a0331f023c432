//! Compare ▸ with: the comparison made, kept current, and drawn (see
//! [`crate::comparison`]).

use super::Viewer;
use crate::comparison::{Comparison, color};
use mocap::glam::Vec3;

impl Viewer {
    /// Compares character `b` against character `a` and keeps it on.
    pub(crate) fn compare(&mut self, a: usize, b: usize) -> Result<(), String> {
        let actors = &self.state.stage.actors;
        let clip = |i: usize| {
            actors.get(i).and_then(|c| c.clip()).ok_or_else(|| format!("character {} has no motion to compare", i + 1))
        };
        if a == b {
            return Err("compare a character with another one".into());
        }
        let report = mocap::ops::compare::compare(clip(a)?, clip(b)?, mocap::ops::compare::Align::None, &[])
            .map_err(|e| format!("{} against {}: {e}", actors[b].name, actors[a].name))?;
        let units = actors[a].units.name();
        self.state.comparison = Some(Comparison { a, b, report, units, mark: self.history_mark() });
        Ok(())
    }

    /// The history's next undo and redo: what changes with every edit.
    fn history_mark(&self) -> (Option<String>, Option<String>) {
        (self.state.history.next_undo().map(str::to_owned), self.state.history.next_redo().map(str::to_owned))
    }

    /// Makes the comparison again after an edit, and ends it when a character
    /// it measured is gone.
    pub(crate) fn refresh_comparison(&mut self) {
        let Some(c) = &self.state.comparison else { return };
        let (a, b) = (c.a, c.b);
        let gone = [a, b].iter().any(|&i| self.state.stage.actors.get(i).is_none_or(|x| x.clip().is_none()));
        if gone {
            self.state.comparison = None;
        } else if c.mark != self.history_mark() && self.compare(a, b).is_err() {
            self.state.comparison = None;
        }
    }

    /// The compared take as a ghost in the reference's place: its bones as
    /// lines over everything, each coloured by its joint's mean error.
    pub(crate) fn comparison_overlay(&mut self) {
        let Some(c) = &self.state.comparison else { return };
        let (Some(a), Some(b)) = (self.state.stage.actors.get(c.a), self.state.stage.actors.get(c.b)) else { return };
        let Some(clip) = b.clip() else { return };
        let shift: Vec3 = a.placement() - b.placement();
        let scale = c.scale();
        let joints = clip.skeleton().joints();
        for (j, t) in b.extra.pose.iter().enumerate() {
            let Some(parent) = joints.get(j).and_then(|x| x.parent).and_then(|p| b.extra.pose.get(p)) else { continue };
            let name = joints.get(j).map_or("", |x| x.name.as_str());
            let error = c.error_of(name);
            self.scene.overlay_lines.push(mocap_render::Line {
                a: parent.translation + shift,
                b: t.translation + shift,
                color: color(error, scale),
                width_px: 3.0,
            });
        }
    }
}
