//! The floor primitive: a plane with grid lines (drawn by floor.wgsl).

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
    /// Colour of major lines.
    pub major_color: [u8; 4],
    /// Colour of the floor between the lines (it fades to the background at the edge).
    pub floor_color: [u8; 4],
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
            // Wide enough that the fade towards the edge starts beyond the motion.
            let half = (size.x.max(size.z) * 0.5 + margin.max(0.0)) * 1.8;
            (Vec3::new(snap(c.x), min.y, snap(c.z)), ((half / cell).ceil() as u32).clamp(4, 400))
        };
        Grid {
            center,
            cell,
            half_cells,
            major_every: 2,
            color: [72, 76, 86, 255],
            major_color: [100, 105, 118, 255],
            floor_color: [50, 53, 60, 255],
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
        assert_eq!(g.half_cells, 18);
        let empty = Grid::floor(Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY), 1.0, 0.5);
        assert_eq!((empty.center, empty.half_cells), (Vec3::ZERO, 10));
    }
}
