//! The point at given distances from four (or more) known points: the
//! intersection of spheres, found two ways.
//!
//! - [`successive`]: the capture method of the source. Start from a point on
//!   sphere (i); move to the point of sphere (ii) on the line from its centre to
//!   the current point, then (iii), then (iv), then (i) again, until a whole round
//!   stops moving the point. Nothing proves it converges, so the rounds are capped
//!   and running out is an error ([`SolveError::NotConverged`]).
//! - [`least_squares`]: the closed form. Subtracting sphere (i)'s equation from
//!   the others leaves linear equations `2 (cₖ − c₀) · x = |cₖ|² − |c₀|² − rₖ² + r₀²`,
//!   solved in the least-squares sense (the normal equations, 3 × 3).
//!
//! Three spheres meet in two mirror points (either side of the centres' plane);
//! the fourth, off that plane, picks one. So both solvers refuse centres that are
//! (nearly) coplanar ([`SolveError::Coplanar`]), and both report how far the
//! answer is from each sphere ([`Solution::residual`]); spheres that do not meet
//! give [`SolveError::NoMeet`].

use glam::{DMat3, DVec3};

/// A sphere: the points at `radius` from `center`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sphere {
    /// Its centre.
    pub center: DVec3,
    /// Its radius (≥ 0).
    pub radius: f64,
}

/// A solved point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Solution {
    /// The point.
    pub point: DVec3,
    /// The largest distance from the point to one of the spheres, `| |p − c| − r |`.
    pub residual: f64,
    /// Rounds of successive approximation used (0 for the closed form).
    pub rounds: usize,
}

/// Why there is no solution.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum SolveError {
    /// Fewer than four spheres.
    #[error("{0} spheres: four are needed")]
    TooFew(usize),
    /// The centres are (nearly) on one plane: two mirror points fit equally.
    #[error("the centres are coplanar: two mirror points fit equally")]
    Coplanar,
    /// The point stops moving but stays `residual` away from a sphere.
    #[error("the spheres do not meet (the nearest point is {residual:.4} from one)")]
    NoMeet {
        /// Largest distance to a sphere at the end.
        residual: f64,
    },
    /// The rounds ran out before the point stopped moving.
    #[error("no convergence in {rounds} rounds (the point still moved {step:.3e})")]
    NotConverged {
        /// Rounds made.
        rounds: usize,
        /// How far the last round moved the point.
        step: f64,
    },
    /// A centre or radius is not finite.
    #[error("a centre or radius is not finite")]
    NotFinite,
}

/// Settings of [`successive`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settings {
    /// A round moving the point less than this (absolute) ends the iteration.
    pub tolerance: f64,
    /// Most rounds.
    pub max_rounds: usize,
    /// Largest accepted distance from the answer to a sphere (absolute).
    pub meet: f64,
}

impl Settings {
    /// Settings for points of size `scale` (a model's height): stop at 1e-6 of it (far below an 8-bit step),
    /// accept 2 % of it as "meeting" (vertex positions in MD2 are 8-bit).
    pub fn for_scale(scale: f64) -> Settings {
        let s = if scale.is_finite() && scale > 0.0 { scale } else { 1.0 };
        Settings { tolerance: s * 1e-6, max_rounds: 2000, meet: s * 0.02 }
    }
}

/// Largest `| |p − c| − r |` over the spheres.
pub fn residual(spheres: &[Sphere], p: DVec3) -> f64 {
    spheres.iter().map(|s| ((p - s.center).length() - s.radius).abs()).fold(0.0, f64::max)
}

/// Checks the count, finiteness and coplanarity of the centres: the largest
/// tetrahedron over the first centre and any three others must have a volume of at
/// least 1e-4 of (largest centre distance)³ / 6.
fn check(spheres: &[Sphere]) -> Result<(), SolveError> {
    if spheres.len() < 4 {
        return Err(SolveError::TooFew(spheres.len()));
    }
    if spheres.iter().any(|s| !s.center.is_finite() || !s.radius.is_finite() || s.radius < 0.0) {
        return Err(SolveError::NotFinite);
    }
    let c0 = spheres[0].center;
    let size = spheres.iter().map(|s| (s.center - c0).length()).fold(0.0, f64::max);
    if size <= 0.0 {
        return Err(SolveError::Coplanar);
    }
    let mut volume: f64 = 0.0;
    for i in 1..spheres.len() {
        for j in i + 1..spheres.len() {
            for k in j + 1..spheres.len() {
                let (a, b, c) = (spheres[i].center - c0, spheres[j].center - c0, spheres[k].center - c0);
                volume = volume.max(a.dot(b.cross(c)).abs());
            }
        }
    }
    if volume < 1e-4 * size * size * size {
        return Err(SolveError::Coplanar);
    }
    Ok(())
}

/// The point of `s` on the line from its centre through `p` (or, with `p` at the
/// centre, the one towards `fallback`).
fn project(s: &Sphere, p: DVec3, fallback: DVec3) -> DVec3 {
    let d = p - s.center;
    let len = d.length();
    let dir = if len > 1e-300 { d / len } else { fallback.normalize_or(DVec3::X) };
    s.center + dir * s.radius
}

/// Successive approximation from `start` (see the module documentation).
pub fn successive(spheres: &[Sphere], start: DVec3, settings: &Settings) -> Result<Solution, SolveError> {
    check(spheres)?;
    let first = &spheres[0];
    let mut p = project(first, start, DVec3::Y);
    let mut step = f64::INFINITY;
    for round in 1..=settings.max_rounds.max(1) {
        let before = p;
        for s in spheres[1..].iter().chain([first]) {
            p = project(s, p, p - first.center);
        }
        step = (p - before).length();
        if step <= settings.tolerance {
            let r = residual(spheres, p);
            if r > settings.meet {
                return Err(SolveError::NoMeet { residual: r });
            }
            return Ok(Solution { point: p, residual: r, rounds: round });
        }
    }
    Err(SolveError::NotConverged { rounds: settings.max_rounds.max(1), step })
}

/// The closed-form least-squares point (see the module documentation); `meet` is
/// the largest accepted residual.
pub fn least_squares(spheres: &[Sphere], meet: f64) -> Result<Solution, SolveError> {
    check(spheres)?;
    let c0 = spheres[0].center;
    let r0 = spheres[0].radius;
    // Relative to c0 for precision: 2 (cₖ − c₀) · y = |cₖ − c₀|² − rₖ² + r₀², x = c₀ + y.
    let mut ata = DMat3::ZERO;
    let mut atb = DVec3::ZERO;
    for s in &spheres[1..] {
        let a = 2.0 * (s.center - c0);
        let b = (s.center - c0).length_squared() - s.radius * s.radius + r0 * r0;
        ata += DMat3::from_cols(a * a.x, a * a.y, a * a.z);
        atb += a * b;
    }
    let det = ata.determinant();
    if !det.is_finite() || det.abs() < 1e-300 {
        return Err(SolveError::Coplanar);
    }
    let point = c0 + ata.inverse() * atb;
    let r = residual(spheres, point);
    if r > meet {
        return Err(SolveError::NoMeet { residual: r });
    }
    Ok(Solution { point, residual: r, rounds: 0 })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spheres_around(p: DVec3, centers: &[DVec3]) -> Vec<Sphere> {
        centers.iter().map(|&c| Sphere { center: c, radius: (p - c).length() }).collect()
    }

    const CENTERS: [DVec3; 4] =
        [DVec3::new(0.0, 0.0, 0.0), DVec3::new(1.0, 0.1, 0.0), DVec3::new(0.2, 1.0, 0.1), DVec3::new(0.1, 0.3, 0.9)];

    #[test]
    fn exact_on_noise_free_spheres() {
        let settings = Settings::for_scale(1.0);
        for p in [DVec3::new(0.4, 0.5, 0.3), DVec3::new(1.5, -0.7, 0.8), DVec3::new(-0.3, 2.0, -1.0)] {
            let s = spheres_around(p, &CENTERS);
            let a = successive(&s, p + DVec3::new(0.05, -0.05, 0.02), &settings).unwrap();
            assert!((a.point - p).length() < 1e-5, "{p} → {}", a.point);
            let b = least_squares(&s, 1e-6).unwrap();
            assert!((b.point - p).length() < 1e-9, "{p} → {}", b.point);
        }
    }

    #[test]
    fn the_fourth_sphere_picks_the_right_mirror_point() {
        // The mirror of p through the plane of the first three centres fits those
        // three exactly; starting right at it, the fourth sphere still leads to p.
        let p = DVec3::new(0.3, 0.4, 0.6);
        let s = spheres_around(p, &CENTERS);
        let n = (CENTERS[1] - CENTERS[0]).cross(CENTERS[2] - CENTERS[0]).normalize();
        let mirror = p - 2.0 * n * (p - CENTERS[0]).dot(n);
        assert!(residual(&s[..3], mirror) < 1e-9 && residual(&s, mirror) > 0.1);
        let a = successive(&s, mirror, &Settings::for_scale(1.0)).unwrap();
        assert!((a.point - p).length() < 1e-5, "{} not {p}", a.point);
    }

    #[test]
    fn coplanar_centres_and_spheres_that_do_not_meet_fail_cleanly() {
        let flat = [DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::new(1.0, 1.0, 0.0)];
        let s = spheres_around(DVec3::new(0.3, 0.3, 0.5), &flat);
        assert_eq!(successive(&s, DVec3::ZERO, &Settings::for_scale(1.0)), Err(SolveError::Coplanar));
        assert_eq!(least_squares(&s, 1.0), Err(SolveError::Coplanar));
        let apart: Vec<Sphere> = CENTERS.iter().map(|&c| Sphere { center: c * 10.0, radius: 0.5 }).collect();
        assert!(matches!(successive(&apart, DVec3::ZERO, &Settings::for_scale(1.0)), Err(SolveError::NoMeet { .. })));
        assert!(matches!(least_squares(&apart, 0.02), Err(SolveError::NoMeet { .. })));
        assert_eq!(successive(&apart[..3], DVec3::ZERO, &Settings::for_scale(1.0)), Err(SolveError::TooFew(3)));
        let nan = [Sphere { center: DVec3::NAN, radius: 1.0 }; 4];
        assert_eq!(least_squares(&nan, 1.0), Err(SolveError::NotFinite));
    }

    #[test]
    fn rounds_are_capped() {
        let p = DVec3::new(0.4, 0.5, 0.3);
        let s = spheres_around(p, &CENTERS);
        let tight = Settings { tolerance: 0.0, max_rounds: 3, meet: 1.0 };
        assert!(matches!(
            successive(&s, DVec3::new(5.0, 5.0, 5.0), &tight),
            Err(SolveError::NotConverged { rounds: 3, .. })
        ));
    }

    #[test]
    fn noisy_spheres_still_converge_near_the_point() {
        let p = DVec3::new(0.4, 0.5, 0.3);
        let mut s = spheres_around(p, &CENTERS);
        for (k, x) in s.iter_mut().enumerate() {
            x.radius += [0.004, -0.003, 0.002, -0.004][k];
        }
        let a = successive(&s, p, &Settings::for_scale(1.0)).unwrap();
        let b = least_squares(&s, 0.02).unwrap();
        assert!((a.point - p).length() < 0.02 && (b.point - p).length() < 0.02, "{} {}", a.point, b.point);
    }
}
