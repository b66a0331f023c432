//! Placing several clips side by side: pure arithmetic on bounding boxes, shared by
//! the viewer and the command line.

use crate::Aabb;
use glam::Vec3;

/// Up to this many clips stand in one row; more wrap into rows.
pub const MAX_SINGLE_ROW: usize = 8;

/// Offsets that stand boxes side by side on the floor, one lane each along X.
///
/// Each box (e.g. a clip's motion bounds, already in metres) gets a lane as wide as
/// the box, with `gap` between lanes; the box is centred in its lane and the whole row
/// is centred on `x = 0`. Up to [`MAX_SINGLE_ROW`] boxes make one row and keep their
/// own Z (offset `z = 0`). With more, they wrap into rows of `ceil(sqrt(n))` along Z:
/// the first row farthest back (−Z), each box centred on its row's middle line, rows
/// `gap` apart and the block centred on `z = 0`. Offsets never move boxes vertically
/// (`y = 0`), so each clip keeps its own floor height.
///
/// An empty or non-finite box counts as a point at the origin (it still gets a lane);
/// a negative or non-finite `gap` counts as 0. The result has one finite offset per box.
///
/// ```
/// use mocap::{Aabb, glam::Vec3, stage::arrange::spread};
/// let a = Aabb { min: Vec3::new(-1.0, 0.0, 0.0), max: Vec3::new(1.0, 2.0, 0.0) };
/// let offsets = spread(&[a, a], 1.0);
/// assert_eq!(offsets, vec![Vec3::new(-1.5, 0.0, 0.0), Vec3::new(1.5, 0.0, 0.0)]);
/// ```
pub fn spread(bounds: &[Aabb], gap: f32) -> Vec<Vec3> {
    let gap = if gap.is_finite() && gap > 0.0 { gap } else { 0.0 };
    let boxes: Vec<Aabb> = bounds.iter().map(|b| sanitize(*b)).collect();
    let per_row = per_row(boxes.len());
    let rows = boxes.len().div_ceil(per_row);
    let mut offsets = Vec::with_capacity(boxes.len());
    let mut row_z = 0.0f32;
    let mut block_depth = 0.0f32;
    for row in boxes.chunks(per_row) {
        let depth = row.iter().map(|b| b.size().z).fold(0.0, f32::max);
        let middle_z = row_z + depth * 0.5;
        let row_start = offsets.len();
        let mut cursor = 0.0f32;
        for b in row {
            let width = b.size().x;
            let z = if rows > 1 { middle_z - b.center().z } else { 0.0 };
            offsets.push(Vec3::new(cursor + width * 0.5 - b.center().x, 0.0, z));
            cursor += width + gap;
        }
        let row_width = (cursor - gap).max(0.0);
        offsets.iter_mut().skip(row_start).for_each(|o| o.x -= row_width * 0.5);
        block_depth = row_z + depth;
        row_z += depth + gap;
    }
    if rows > 1 {
        offsets.iter_mut().for_each(|o| o.z -= block_depth * 0.5);
    }
    offsets
}

/// Boxes per row for `n` boxes: all of them up to [`MAX_SINGLE_ROW`], else `ceil(sqrt(n))`.
pub fn per_row(n: usize) -> usize {
    if n <= MAX_SINGLE_ROW {
        return n.max(1);
    }
    let mut k = n.isqrt();
    if k * k < n {
        k += 1;
    }
    k
}

/// The box itself when it is non-empty and finite, else a point at the origin.
fn sanitize(b: Aabb) -> Aabb {
    if b.is_empty() || !b.min.is_finite() || !b.max.is_finite() || !b.size().is_finite() {
        Aabb { min: Vec3::ZERO, max: Vec3::ZERO }
    } else {
        b
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn boxed(min: [f32; 3], max: [f32; 3]) -> Aabb {
        Aabb { min: Vec3::from_array(min), max: Vec3::from_array(max) }
    }

    #[test]
    fn nothing_to_arrange() {
        assert!(spread(&[], 1.0).is_empty());
    }

    #[test]
    fn one_box_is_centred_on_x_and_keeps_its_z() {
        let o = spread(&[boxed([2.0, 0.0, 5.0], [4.0, 1.0, 7.0])], 0.5);
        assert_eq!(o, vec![Vec3::new(-3.0, 0.0, 0.0)]);
    }

    #[test]
    fn lanes_are_as_wide_as_the_boxes_with_gaps_between() {
        // Widths 1 and 2, gap 0.5: the row is 3.5 wide, from -1.75 to 1.75.
        let a = boxed([10.0, 0.0, 0.0], [11.0, 1.0, 1.0]);
        let b = boxed([-1.0, 0.0, 0.0], [1.0, 1.0, 3.0]);
        let o = spread(&[a, b], 0.5);
        let placed: Vec<(f32, f32)> = [a, b].iter().zip(&o).map(|(b, o)| (b.min.x + o.x, b.max.x + o.x)).collect();
        assert_eq!(placed, vec![(-1.75, -0.75), (-0.25, 1.75)]);
        assert!(o.iter().all(|o| o.y == 0.0 && o.z == 0.0));
    }

    #[test]
    fn empty_and_non_finite_boxes_get_finite_offsets() {
        let nan = boxed([f32::NAN; 3], [f32::NAN; 3]);
        let inf = boxed([f32::NEG_INFINITY; 3], [f32::INFINITY; 3]);
        for gap in [1.0, f32::NAN, f32::INFINITY, -3.0] {
            let o = spread(&[Aabb::EMPTY, nan, inf, boxed([0.0; 3], [1.0; 3])], gap);
            assert_eq!(o.len(), 4);
            assert!(o.iter().all(|v| v.is_finite()), "{o:?}");
        }
    }

    #[test]
    fn more_than_eight_wrap_into_square_rows() {
        assert_eq!(per_row(8), 8);
        assert_eq!(per_row(9), 3);
        assert_eq!(per_row(10), 4);
        assert_eq!(per_row(0), 1);
        let unit = boxed([0.0; 3], [1.0, 2.0, 1.0]);
        let o = spread(&[unit; 9], 1.0);
        // Three rows of three: x in {-2, 0, 2} (minus the box centre 0.5), z likewise.
        let xs: Vec<f32> = o.iter().map(|v| v.x + 0.5).collect();
        let zs: Vec<f32> = o.iter().map(|v| v.z + 0.5).collect();
        assert_eq!(&xs[..3], &[-2.0, 0.0, 2.0]);
        assert_eq!(&xs[6..], &[-2.0, 0.0, 2.0]);
        assert_eq!((zs[0], zs[3], zs[8]), (-2.0, 0.0, 2.0));
        assert!(o.iter().all(|v| v.y == 0.0));
    }
}
