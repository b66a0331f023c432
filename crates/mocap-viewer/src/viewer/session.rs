//! The viewer's side of autosave ([`crate::session`]): what it stores, how it is
//! told that something changed, and opening a stored session again.

use super::Viewer;
use crate::session::{self, Restored, Shown, Stored};

impl Viewer {
    /// The work open now as a session to store (see [`crate::session::store`]).
    pub fn store_session(&self) -> Stored {
        let history = &self.state.history;
        let characters: Vec<(&str, &mocap::Asset, Shown)> = self
            .state
            .stage
            .actors
            .iter()
            .enumerate()
            .map(|(i, c)| {
                let shown = Shown {
                    up: c.up,
                    visible: c.visible,
                    offset: c.offset.to_array(),
                    color: c.extra.color,
                    saved: !history.unsaved(i),
                };
                (c.name.as_str(), &c.asset, shown)
            })
            .collect();
        session::store(&characters, history, self.state.view_fragment())
    }

    /// Changes whenever what [`Viewer::store_session`] stores does, except the view
    /// (the page stores the view, which changes every frame during playback, on its
    /// own and cheaply): the characters, how each is shown, and the history.
    pub fn session_stamp(&self) -> String {
        let mut stamp = self.state.history.stamp();
        for c in &self.state.stage.actors {
            let animation = c
                .model()
                .map(|m| m.animation_name().to_owned())
                .or_else(|| c.clip().and_then(|clip| clip.take_name().map(str::to_owned)));
            stamp.push_str(&format!(
                "|{}:{}:{:?}:{}:{:?}:{:?}:{animation:?}",
                c.name,
                c.asset.timeline().frames(),
                c.up,
                c.visible,
                c.offset.to_array(),
                c.extra.color,
            ));
        }
        stamp
    }

    /// Opens a stored session in place of what is open: its characters (each as it
    /// was shown), its edit history with what was saved, and its view.
    pub(super) fn restore(&mut self, restored: Restored) {
        let Restored { characters, history, view, .. } = restored;
        let (assets, shown): (Vec<_>, Vec<_>) = characters.into_iter().map(|(n, a, s)| ((n, a), s)).unzip();
        self.open_assets(assets);
        for (i, s) in shown.iter().enumerate() {
            if self.state.stage.actors.get(i).is_some_and(|c| c.up != s.up) {
                self.set_up_axis(i, s.up);
            }
            if let Some(c) = self.state.stage.actors.get_mut(i) {
                c.visible = s.visible;
                c.offset = mocap::glam::Vec3::from_array(s.offset);
                c.extra.color = s.color;
            }
        }
        self.state.history = history;
        for (i, s) in shown.iter().enumerate() {
            if s.saved {
                self.state.history.mark_saved(i);
            }
        }
        self.apply_view(&crate::view_state::ViewState::parse(&view));
    }
}
