//! Rotations from tracked directions: from two frames of two directions, and the
//! best fit to any number of direction pairs.

use glam::{Mat3, Quat, Vec3};

/// The rotation taking the frame of (`a0`, across `b0`) to that of (`a1`, `b1`).
pub(super) fn from_frames(a0: Vec3, b0: Vec3, a1: Vec3, b1: Vec3) -> Option<Quat> {
    let basis = |a: Vec3, b: Vec3| {
        let x = a.normalize_or_zero();
        let y = (b - x * b.dot(x)).normalize_or_zero();
        (x != Vec3::ZERO && y != Vec3::ZERO).then(|| Mat3::from_cols(x, y, x.cross(y)))
    };
    let (m0, m1) = (basis(a0, b0)?, basis(a1, b1)?);
    let q = Quat::from_mat3(&(m1 * m0.transpose())).normalize();
    q.is_finite().then_some(q)
}

/// The rotation `q` minimising `Σ |q · aᵢ − bᵢ|²` over the pairs (`aᵢ`, `bᵢ`)
/// (Horn's quaternion method: the eigenvector of the largest eigenvalue of a
/// 4 × 4 symmetric matrix, found by power iteration on it shifted to be positive,
/// by repeated squaring).
pub fn fit_rotation(pairs: &[(Vec3, Vec3)]) -> Option<Quat> {
    let mut s = [[0.0f64; 3]; 3];
    for (a, b) in pairs {
        let (a, b) = (a.as_dvec3(), b.as_dvec3());
        for (r, ar) in [a.x, a.y, a.z].into_iter().enumerate() {
            for (c, bc) in [b.x, b.y, b.z].into_iter().enumerate() {
                s[r][c] += ar * bc;
            }
        }
    }
    let [[xx, xy, xz], [yx, yy, yz], [zx, zy, zz]] = s;
    let n = [
        [xx + yy + zz, yz - zy, zx - xz, xy - yx],
        [yz - zy, xx - yy - zz, xy + yx, zx + xz],
        [zx - xz, xy + yx, -xx + yy - zz, yz + zy],
        [xy - yx, zx + xz, yz + zy, -xx - yy + zz],
    ];
    let shift: f64 = n.iter().map(|row| row.iter().map(|x| x.abs()).sum::<f64>()).fold(0.0, f64::max);
    if !(shift > 0.0) || !shift.is_finite() {
        return None;
    }
    // (N + shift·I)^1024 by ten squarings (each scaled to stay finite), applied
    // to a start vector: 1024 steps of power iteration for 640 multiply-adds.
    let mut m = n;
    for (r, row) in m.iter_mut().enumerate() {
        row[r] += shift;
    }
    for _ in 0..10 {
        let mut sq = [[0.0f64; 4]; 4];
        for r in 0..4 {
            for c in 0..4 {
                sq[r][c] = (0..4).map(|k| m[r][k] * m[k][c]).sum();
            }
        }
        let scale = sq.iter().flatten().fold(0.0f64, |a, x| a.max(x.abs()));
        if !(scale > 0.0) || !scale.is_finite() {
            return None;
        }
        m = sq.map(|row| row.map(|x| x / scale));
    }
    let start = [1.0f64, 0.1, 0.1, 0.1];
    let w: [f64; 4] = std::array::from_fn(|r| (0..4).map(|c| m[r][c] * start[c]).sum());
    let len = w.iter().map(|x| x * x).sum::<f64>().sqrt();
    if !(len > 0.0) {
        return None;
    }
    let v = w.map(|x| x / len);
    let q = Quat::from_xyzw(v[1] as f32, v[2] as f32, v[3] as f32, v[0] as f32).normalize();
    q.is_finite().then_some(q)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fit_rotation_recovers_a_turn() {
        let q = Quat::from_euler(glam::EulerRot::ZXY, 0.7, -0.3, 1.9);
        let points = [Vec3::X, Vec3::new(0.0, 2.0, 0.5), Vec3::new(-1.0, 0.3, 1.0), Vec3::new(0.2, -0.4, -2.0)];
        let pairs: Vec<(Vec3, Vec3)> = points.iter().map(|p| (*p, q * *p)).collect();
        let got = fit_rotation(&pairs).unwrap();
        assert!(got.dot(q).abs() > 0.99999, "{got} vs {q}");
    }
}
