//! The floor grid primitive and its expansion into lines.

use crate::Line;
use glam::Vec3;

/// A square grid on the horizontal (XZ) plane.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Grid {
    /// Centre of the grid; its `y` is the floor height.
    pub center: Vec3,
    /// Size of one cell in world units.
    pub cell: f32,
    /// Cells from the centre to each edge.
    pub half_cells: u32,
    /// Every `major_every`-th line is drawn with `major_color` (0 = never).
    pub major_every: u32,
    /// Colour of ordinary lines (sRGB, 0-255).
    pub color: [u8; 4],
    /// Colour of major lines and the axes through the centre.
    pub major_color: [u8; 4],
}

impl Grid {
    /// A floor under a motion: at the height of `min.y`, centred on the box (snapped
    /// to whole major cells so it does not swim), covering the box plus `margin`,
    /// with `cell`-sized cells and a major line every two. An empty or non-finite box
    /// (min > max) gives a 20-cell floor at the origin.
    pub fn floor(min: Vec3, max: Vec3, margin: f32, cell: f32) -> Grid {
        let cell = if cell.is_finite() && cell > 0.0 { cell } else { 1.0 };
        let size = max - min;
        let (center, half_cells) = if !(size.is_finite() && size.min_element() >= 0.0) {
            (Vec3::ZERO, 10)
        } else {
            let c = (min + max) * 0.5;
            let snap = |v: f32| (v / (2.0 * cell)).round() * 2.0 * cell;
            let half = size.x.max(size.z) * 0.5 + margin.max(0.0);
            (Vec3::new(snap(c.x), min.y, snap(c.z)), ((half / cell).ceil() as u32).clamp(4, 400))
        };
        Grid { center, cell, half_cells, major_every: 2, color: [75, 78, 88, 255], major_color: [110, 114, 126, 255] }
    }

    /// Appends the grid's lines to `out`.
    pub fn lines_into(&self, out: &mut Vec<Line>) {
        let n = self.half_cells.min(500) as i32;
        let extent = n as f32 * self.cell;
        for i in -n..=n {
            let major = i == 0 || (self.major_every > 0 && i.unsigned_abs() % self.major_every == 0);
            let (color, width_px) = if major { (self.major_color, 1.5) } else { (self.color, 1.0) };
            let d = i as f32 * self.cell;
            let c = self.center;
            out.push(Line { a: c + Vec3::new(d, 0.0, -extent), b: c + Vec3::new(d, 0.0, extent), color, width_px });
            out.push(Line { a: c + Vec3::new(-extent, 0.0, d), b: c + Vec3::new(extent, 0.0, d), color, width_px });
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn floor_sits_under_the_box_and_covers_it() {
        let g = Grid::floor(Vec3::new(-3.0, 1.5, -1.0), Vec3::new(5.0, 4.0, 1.0), 1.0, 0.5);
        assert_eq!(g.center, Vec3::new(1.0, 1.5, 0.0));
        assert_eq!(g.half_cells, 10);
        let empty = Grid::floor(Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY), 1.0, 0.5);
        assert_eq!((empty.center, empty.half_cells), (Vec3::ZERO, 10));
    }

    #[test]
    fn grid_has_two_lines_per_row() {
        let g = Grid { center: Vec3::ZERO, cell: 1.0, half_cells: 2, major_every: 2, color: [0; 4], major_color: [1; 4] };
        let mut out = Vec::new();
        g.lines_into(&mut out);
        assert_eq!(out.len(), 10);
        assert!(out.iter().all(|l| l.a.y == 0.0 && l.b.y == 0.0));
    }
}
