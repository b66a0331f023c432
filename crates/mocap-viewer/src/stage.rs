//! The open characters, their layout and the facts derived from all of them
//! together: the world bounds and the shared timeline.

use crate::character::{self, Character};
use crate::document::Document;
use crate::layout::Layout;
use crate::playback::Timing;
use mocap::Aabb;
use mocap::glam::Vec3;

/// Gap between spread lanes, as a share of the largest character's size.
const GAP_PER_EXTENT: f32 = 0.5;

/// Every open character, in order, and how they are placed.
#[derive(Default)]
pub struct Stage {
    /// The characters (index 0 is "character 1" in the fragment).
    pub characters: Vec<Character>,
    /// Spread or overlay.
    pub layout: Layout,
}

impl Stage {
    /// Closes everything and opens `documents`, coloured from the start of the palette.
    pub fn replace(&mut self, documents: Vec<Document>) {
        self.characters.clear();
        documents.into_iter().for_each(|d| self.push(d));
        self.arrange();
    }

    /// Adds a character after the open ones, in the next free colour.
    pub fn add(&mut self, document: Document) {
        self.push(document);
        self.arrange();
    }

    /// Closes character `index`; returns whether it existed.
    pub fn remove(&mut self, index: usize) -> bool {
        if index >= self.characters.len() {
            return false;
        }
        self.characters.remove(index);
        self.arrange();
        true
    }

    /// Shows or hides character `index`; returns whether it exists.
    pub fn set_visible(&mut self, index: usize, visible: bool) -> bool {
        self.characters.get_mut(index).map(|c| c.visible = visible).is_some()
    }

    /// Switches the layout and places the characters again.
    pub fn set_layout(&mut self, layout: Layout) {
        self.layout = layout;
        self.arrange();
    }

    /// Recomputes every character's layout offset from the current layout. Spread
    /// lanes count hidden characters too, so hiding one moves no other.
    pub fn arrange(&mut self) {
        let offsets = match self.layout {
            Layout::Overlay => vec![Vec3::ZERO; self.characters.len()],
            Layout::Spread => {
                let bounds: Vec<Aabb> = self.characters.iter().map(Character::local_bounds).collect();
                let extent = self.characters.iter().map(Character::extent).fold(0.0f32, f32::max);
                let extent = if extent.is_finite() && extent > 0.0 { extent } else { 1.0 };
                mocap::arrange::spread(&bounds, extent * GAP_PER_EXTENT)
            }
        };
        for (c, o) in self.characters.iter_mut().zip(offsets) {
            c.layout_offset = o;
        }
    }

    /// The visible characters with their indices.
    pub fn visible(&self) -> impl Iterator<Item = (usize, &Character)> {
        self.characters.iter().enumerate().filter(|(_, c)| c.visible)
    }

    /// Union of the visible characters' motion bounds, in metres where they stand
    /// (empty when none is visible).
    pub fn bounds(&self) -> Aabb {
        self.visible().fold(Aabb::EMPTY, |union, (_, c)| union.union(&c.bounds()))
    }

    /// Largest first-pose size among the visible characters in metres (1 when none).
    pub fn extent(&self) -> f32 {
        let e = self.visible().map(|(_, c)| c.extent()).fold(0.0f32, f32::max);
        if e.is_finite() && e > 0.0 { e } else { 1.0 }
    }

    /// The longest clip's duration in seconds (all characters, hidden included).
    pub fn duration(&self) -> f64 {
        self.characters.iter().map(|c| c.document.clip.duration()).filter(|d| d.is_finite()).fold(0.0, f64::max)
    }

    /// The shared timeline: frames in the frame time of character `reference` (the
    /// first when out of range), as many as it takes to reach the end of the longest
    /// clip. With one character it is exactly that clip's timing.
    pub fn timing(&self, reference: usize) -> Option<Timing> {
        let r = self.characters.get(reference).or(self.characters.first())?.document.timing();
        let most = self.characters.iter().map(|c| c.document.clip.frame_count()).max().unwrap_or(0);
        let duration = self.duration();
        let frames = if duration > 0.0 && r.frame_time.is_finite() && r.frame_time > 0.0 {
            let spans = (duration / r.frame_time - 1e-6).ceil();
            if spans.is_finite() && spans < 1e9 { spans as usize + 1 } else { r.frames }
        } else {
            most.min(1)
        };
        Some(Timing { frames: frames.max(r.frames), frame_time: r.frame_time })
    }

    fn push(&mut self, document: Document) {
        let color = character::next_color(&self.characters);
        self.characters.push(Character::new(document, color));
    }
}
