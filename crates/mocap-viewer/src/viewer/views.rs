//! The narrow views the panels get, built from the state each frame: a panel
//! sees only what it shows and returns commands.

use super::Viewer;
use crate::ui::capture::CaptureView;
use crate::ui::edit_menu::EditMenuView;
use crate::ui::hierarchy::TreeView;
use crate::ui::side::SideView;
use crate::ui::timeline::TimelineView;
use crate::ui::toolbar::ToolbarView;

impl Viewer {
    /// What the timeline shows.
    pub(super) fn timeline_view(&self) -> TimelineView<'_> {
        let s = &self.state;
        TimelineView {
            playback: &s.playback,
            timing: s.timing(),
            settings: &s.settings,
            character: s.current_character(),
            keys: s.history.keys(s.current()),
            corrections: s.has_corrections(),
            embed: s.panels.embed,
            comparison: s
                .comparison
                .as_ref()
                .and_then(|c| s.stage.actors.get(c.a).and_then(|x| x.clip()).map(|clip| (c, clip.frame_time()))),
        }
    }

    /// What the top bar (and its Edit menu) shows.
    pub(super) fn toolbar_view(&self) -> ToolbarView<'_> {
        let s = &self.state;
        ToolbarView {
            characters: &s.stage.actors,
            layout: s.stage.layout,
            settings: &s.settings,
            panels: &s.panels,
            current: s.current_character().map(|c| c.name.as_str()),
            edit: self.edit_menu_view(),
            previous_session: self.state.previous_session,
        }
    }

    /// What the Edit menu acts on.
    pub fn edit_menu_view(&self) -> EditMenuView<'_> {
        let s = &self.state;
        let index = s.current();
        EditMenuView {
            character: s.stage.actors.get(index).map(|c| (index, c)),
            joint: s.selected.filter(|sel| sel.character == index).map(|sel| sel.joint),
            range: s.playback.range,
            undo: s.history.next_undo(),
            redo: s.history.next_redo(),
            others: s.stage.actors.iter().enumerate().filter(|(i, c)| *i != index && c.clip().is_some()).count(),
            video_export: s.video_export,
            between: s.settings.between,
            compare_with: s
                .stage
                .actors
                .iter()
                .enumerate()
                .filter(|(i, c)| *i != index && c.clip().is_some())
                .map(|(i, c)| (i, c.name.as_str()))
                .collect(),
            comparing: s.comparison.is_some(),
        }
    }

    /// What the right-hand panel shows.
    pub(super) fn side_view(&self) -> SideView<'_> {
        let s = &self.state;
        SideView {
            characters: &s.stage.actors,
            current: s.current(),
            selected: s.selected,
            time: s.playback.time,
            pose_mode: s.settings.pose_mode,
            capture: CaptureView {
                characters: &s.stage.actors,
                progress: s.capture_progress(),
                rig_edit: s.rig_edit.as_ref(),
                capture_rig: s.capture_rig.as_ref(),
                result: s.capture_result.as_ref(),
            },
        }
    }

    /// What the hierarchy panel shows.
    pub(super) fn tree_view(&self) -> TreeView<'_> {
        let s = &self.state;
        TreeView { characters: &s.stage.actors, folds: &s.folds, selected: s.selected, current: s.current() }
    }
}
