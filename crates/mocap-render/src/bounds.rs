//! Axis-aligned boxes carried through transforms (for fitting the shadow map and
//! sizing draws on screen).

use glam::{Mat4, Vec3};

/// The axis-aligned box around the box `min`–`max` after `m` (an affine
/// transform); `None` for an empty box (`min` past `max`) or a result that is not
/// finite.
pub(crate) fn transform_box(m: &Mat4, min: Vec3, max: Vec3) -> Option<(Vec3, Vec3)> {
    if !(min.cmple(max).all()) {
        return None;
    }
    let center = m.transform_point3((min + max) * 0.5);
    let half = (max - min) * 0.5;
    // Each world axis reaches as far as the box's half-extents along the
    // transformed axes, taken in absolute value.
    let reach =
        m.x_axis.truncate().abs() * half.x + m.y_axis.truncate().abs() * half.y + m.z_axis.truncate().abs() * half.z;
    let (lo, hi) = (center - reach, center + reach);
    (lo.is_finite() && hi.is_finite()).then_some((lo, hi))
}

/// The box around two boxes.
pub(crate) fn union(a: Option<(Vec3, Vec3)>, b: Option<(Vec3, Vec3)>) -> Option<(Vec3, Vec3)> {
    match (a, b) {
        (Some((a0, a1)), Some((b0, b1))) => Some((a0.min(b0), a1.max(b1))),
        (a, None) => a,
        (None, b) => b,
    }
}

/// The box around every finite caster (ends `a`, `b` grown by the radius), if any.
pub(crate) fn caster_bounds(casters: impl Iterator<Item = (Vec3, Vec3, f32)>) -> Option<(Vec3, Vec3)> {
    let (mut min, mut max) = (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY));
    for (a, b, radius) in casters {
        let r = Vec3::splat(radius.abs());
        if a.is_finite() && b.is_finite() && r.is_finite() {
            min = min.min(a.min(b) - r);
            max = max.max(a.max(b) + r);
        }
    }
    (min.x <= max.x).then_some((min, max))
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Quat;

    #[test]
    fn a_box_through_a_transform_holds_every_corner() {
        let m = Mat4::from_scale_rotation_translation(
            Vec3::splat(2.0),
            Quat::from_rotation_y(0.7) * Quat::from_rotation_x(-0.3),
            Vec3::new(1.0, -2.0, 3.0),
        );
        let (min, max) = (Vec3::new(-1.0, 0.0, -0.5), Vec3::new(0.5, 2.0, 0.25));
        let (lo, hi) = transform_box(&m, min, max).unwrap();
        let mut tight = (Vec3::INFINITY, Vec3::NEG_INFINITY);
        for i in 0..8 {
            let pick = |bit: usize, a: f32, b: f32| if i & bit == 0 { a } else { b };
            let p = m.transform_point3(Vec3::new(pick(1, min.x, max.x), pick(2, min.y, max.y), pick(4, min.z, max.z)));
            tight = (tight.0.min(p), tight.1.max(p));
        }
        assert!(
            (lo - tight.0).abs().max_element() < 1e-5 && (hi - tight.1).abs().max_element() < 1e-5,
            "{lo} {hi} vs {tight:?}"
        );
        assert_eq!(transform_box(&m, max, min), None, "an empty box");
        assert_eq!(transform_box(&Mat4::from_translation(Vec3::NAN), min, max), None);
        assert_eq!(union(None, Some((min, max))), Some((min, max)));
        assert_eq!(union(Some((min, min)), Some((max, max))), Some((min, max)));
    }
}
