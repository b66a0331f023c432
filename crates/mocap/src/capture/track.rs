//! Choosing what to track: four vertices per joint, and a triangle per bone for
//! its spin.
//!
//! **Joints.** A joint is fixed relative to each bone that meets at it (the bone
//! ending at it and the bones leaving it). So four vertices bound to one of those
//! bones, whose distances to each other stay constant over all frames (they move
//! rigidly with the bone), keep constant distances to the joint too: the joint is
//! where four spheres around them meet. [`joint_sets`] picks, per joint, among
//! the bones meeting there, the four vertices that are rigid (every pairwise
//! distance varies by at most the tolerance over all frames) and spread out (the
//! largest tetrahedron a greedy search finds), and says why a joint has none.
//!
//! **Spins.** [`spin_triangle`] shoots the bone's spin vector from mid-bone out
//! through the mesh, to a triangle bound to the bone (all three vertices), and
//! keeps the angle `R` about the bone between the spin and the perpendicular from
//! the bone to the triangle's centroid; [`SpinTrack::spin`] turns that back into
//! the spin in any frame.

use super::rig::Rig;
use glam::Vec3;

/// Most vertices of a bone considered for a joint (those nearest to it).
pub const CANDIDATES: usize = 96;

/// The four vertices tracking a joint.
#[derive(Clone, Debug, PartialEq)]
pub struct JointSet {
    /// The bone (its far joint) they are bound to.
    pub bone: usize,
    /// The vertices (four, or more when asked for: the best four first).
    pub vertices: Vec<usize>,
    /// Their distances to the joint in the set-up frame.
    pub radii: Vec<f64>,
    /// The largest change of a distance between two of them over all frames.
    pub drift: f32,
    /// The rigid part they belong to: the bone's vertices (near the joint) rigid
    /// with every tracked one, the tracked ones included.
    pub part: Vec<usize>,
}

/// Bones meeting at each joint: the one ending there and those leaving it.
fn bones_at(rig: &Rig) -> Vec<Vec<usize>> {
    let mut out: Vec<Vec<usize>> = vec![Vec::new(); rig.joints.len()];
    for (j, joint) in rig.joints.iter().enumerate() {
        if let Some(p) = joint.parent {
            out[j].push(j);
            if let Some(o) = out.get_mut(p) {
                o.push(j);
            }
        }
    }
    out
}

/// How much the distance between vertices `a` and `b` changes over the frames.
fn drift(frames: &[Vec<Vec3>], a: usize, b: usize) -> f32 {
    let mut lo = f32::INFINITY;
    let mut hi = f32::NEG_INFINITY;
    for f in frames {
        if let (Some(p), Some(q)) = (f.get(a), f.get(b)) {
            let d = p.distance(*q);
            lo = lo.min(d);
            hi = hi.max(d);
        }
    }
    if hi >= lo { hi - lo } else { f32::INFINITY }
}

/// What choosing a joint's vertices needs besides the frames and the rig: the
/// bones meeting at each joint and the vertices bound to each bone.
#[derive(Clone, Debug)]
pub struct Chooser {
    bones: Vec<Vec<usize>>,
    bound: Vec<Vec<usize>>,
    tolerance: f32,
    count: usize,
}

impl Chooser {
    /// A chooser for `rig`: `tolerance` is the largest accepted drift of a
    /// distance (mesh units), `count` the vertices wanted per joint (at least 4).
    pub fn new(rig: &Rig, tolerance: f32, count: usize) -> Chooser {
        let mut bound: Vec<Vec<usize>> = vec![Vec::new(); rig.joints.len()];
        for (v, b) in rig.binding.iter().enumerate() {
            if let Some(list) = b.and_then(|b| bound.get_mut(b)) {
                list.push(v);
            }
        }
        Chooser { bones: bones_at(rig), bound, tolerance, count: count.max(4) }
    }

    /// Joint `j`'s set (see the module documentation), or why it has none.
    pub fn joint(&self, frames: &[Vec<Vec3>], rig: &Rig, j: usize) -> Result<JointSet, String> {
        let setup = frames.get(rig.setup_frame).map(Vec::as_slice).unwrap_or(&[]);
        let joint = rig.joints.get(j).ok_or_else(|| format!("no joint {j}"))?;
        let at = Vec3::from_array(joint.position);
        let mut best: Option<JointSet> = None;
        let mut why = format!("{}: no bone meets here", joint.name);
        for &bone in self.bones.get(j).into_iter().flatten() {
            let mut candidates: Vec<usize> = self.bound.get(bone).cloned().unwrap_or_default();
            candidates.retain(|&v| setup.get(v).is_some());
            candidates.sort_by(|&a, &b| setup[a].distance(at).total_cmp(&setup[b].distance(at)));
            candidates.truncate(CANDIDATES);
            match pick_four(frames, setup, at, &candidates, self.tolerance, self.count) {
                Ok((vertices, d, part)) => {
                    let radii = vertices.iter().map(|&v| f64::from(setup[v].distance(at))).collect();
                    let set = JointSet { bone, vertices, radii, drift: d, part };
                    if best.as_ref().is_none_or(|b| set.drift < b.drift) {
                        best = Some(set);
                    }
                }
                Err(reason) => {
                    why = format!(
                        "{}: bone {}: {reason}",
                        joint.name,
                        rig.joints.get(bone).map_or("?", |b| b.name.as_str())
                    )
                }
            }
        }
        best.ok_or(why)
    }
}

/// Picks the vertices of every joint (see the module documentation and
/// [`Chooser`]): `frames` holds every frame's vertex positions.
pub fn joint_sets(frames: &[Vec<Vec3>], rig: &Rig, tolerance: f32, count: usize) -> Vec<Result<JointSet, String>> {
    let chooser = Chooser::new(rig, tolerance, count);
    (0..rig.joints.len()).map(|j| chooser.joint(frames, rig, j)).collect()
}

/// Most candidates searched exhaustively for the best four.
const SEARCH: usize = 24;

/// Four rigid vertices among `candidates` that fix the joint at `at` best: of
/// the vertices rigid with the one with the most rigid partners, up to
/// [`SEARCH`] spread by direction seen from the joint, every four that are
/// pairwise rigid and not coplanar are scored by `√λ / (drift + tolerance / 4)`:
/// `λ` the smallest eigenvalue of `Σ uᵢ uᵢᵀ` (`uᵢ` the unit direction from vertex
/// `i` to the joint; the larger, the less noise in the distances moves the solved
/// joint), `drift` the largest change of a distance between two of them. Returns
/// the four, their drift and the rigid part (see [`JointSet::part`]).
fn pick_four(
    frames: &[Vec<Vec3>],
    setup: &[Vec3],
    at: Vec3,
    candidates: &[usize],
    tolerance: f32,
    count: usize,
) -> Result<(Vec<usize>, f32, Vec<usize>), String> {
    let n = candidates.len();
    if n < 4 {
        return Err(format!("{n} vertices bound, four are needed"));
    }
    let mut drifts = vec![0.0f32; n * n];
    for a in 0..n {
        for b in a + 1..n {
            let d = drift(frames, candidates[a], candidates[b]);
            drifts[a * n + b] = d;
            drifts[b * n + a] = d;
        }
    }
    let rigid = |a: usize, b: usize| drifts[a * n + b] <= tolerance;
    let first = (0..n).max_by_key(|&a| (0..n).filter(|&b| b != a && rigid(a, b)).count()).unwrap_or(0);
    let cluster: Vec<usize> = std::iter::once(first).chain((0..n).filter(|&b| b != first && rigid(first, b))).collect();
    if cluster.len() < 4 {
        return Err(format!(
            "no four of its vertices keep their distances over all frames (at most {} do)",
            cluster.len()
        ));
    }
    let p = |a: usize| setup[candidates[a]];
    let dir = |a: usize| (at - p(a)).normalize_or_zero();
    // Farthest-point sampling by direction.
    let mut pool = vec![cluster[0]];
    while pool.len() < SEARCH.min(cluster.len()) {
        let next = cluster.iter().copied().filter(|c| !pool.contains(c)).max_by(|&x, &y| {
            let near = |c: usize| pool.iter().map(|&q| dir(q).dot(dir(c))).fold(f32::NEG_INFINITY, f32::max);
            near(y).total_cmp(&near(x))
        });
        match next {
            Some(c) => pool.push(c),
            None => break,
        }
    }
    let size = pool.iter().flat_map(|&a| pool.iter().map(move |&b| p(a).distance(p(b)))).fold(0.0, f32::max).max(1e-9);
    let mut scored: Vec<([usize; 4], f32)> = Vec::new();
    let m = pool.len();
    for i in 0..m {
        for j in i + 1..m {
            if !rigid(pool[i], pool[j]) {
                continue;
            }
            for k in j + 1..m {
                if !rigid(pool[i], pool[k]) || !rigid(pool[j], pool[k]) {
                    continue;
                }
                for l in k + 1..m {
                    let four = [pool[i], pool[j], pool[k], pool[l]];
                    if !rigid(four[0], four[3]) || !rigid(four[1], four[3]) || !rigid(four[2], four[3]) {
                        continue;
                    }
                    if volume(p(four[0]), p(four[1]), p(four[2]), p(four[3])) < 0.01 * size * size * size {
                        continue;
                    }
                    // Expected error ∝ (drift + noise) / √λ: prefer rigid and well spread.
                    let d = [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)]
                        .iter()
                        .map(|&(x, y)| drifts[four[x] * n + four[y]])
                        .fold(0.0, f32::max);
                    let score = smallest_eigenvalue(four.map(dir)).max(0.0).sqrt() / (d + tolerance * 0.25);
                    scored.push((four, score));
                }
            }
        }
    }
    // The best-scoring four that stays off one plane in every frame (a solver
    // needs that), looking at the 64 best at most.
    scored.sort_by(|a, b| b.1.total_cmp(&a.1));
    let flat_somewhere = |four: &[usize; 4]| {
        frames.iter().any(|f| {
            let q = four.map(|k| f.get(candidates[k]).copied().unwrap_or(Vec3::ZERO));
            volume(q[0], q[1], q[2], q[3]) < 0.002 * size * size * size
        })
    };
    let best = scored.iter().take(64).find(|(four, _)| !flat_somewhere(four));
    let Some(&(four, _)) = best else {
        return Err("its rigid vertices are (nearly) on one plane in some frame".into());
    };
    // More than four when asked for: add, one at a time, the vertex rigid with
    // all chosen that keeps the best score.
    let mut chosen = four.to_vec();
    while chosen.len() < count {
        let next = pool
            .iter()
            .copied()
            .filter(|c| !chosen.contains(c) && chosen.iter().all(|&x| rigid(x, *c)))
            .map(|c| {
                let d = chosen.iter().map(|&x| drifts[x * n + c]).fold(0.0, f32::max);
                (c, d)
            })
            .min_by(|a, b| a.1.total_cmp(&b.1));
        match next {
            Some((c, _)) => chosen.push(c),
            None => break,
        }
    }
    let d = chosen
        .iter()
        .flat_map(|&a| chosen.iter().map(move |&b| (a, b)))
        .filter(|(a, b)| a != b)
        .map(|(a, b)| drifts[a * n + b])
        .fold(0.0, f32::max);
    let part = cluster
        .iter()
        .copied()
        .filter(|&c| chosen.iter().all(|&x| x == c || rigid(x, c)))
        .map(|k| candidates[k])
        .collect();
    Ok((chosen.iter().map(|&k| candidates[k]).collect(), d, part))
}

/// Smallest eigenvalue of `Σ uᵢ uᵢᵀ` (symmetric 3 × 3), by the trigonometric
/// solution of its characteristic polynomial.
fn smallest_eigenvalue(us: [Vec3; 4]) -> f32 {
    let mut m = [[0.0f64; 3]; 3];
    for u in us {
        let u = [f64::from(u.x), f64::from(u.y), f64::from(u.z)];
        for (r, row) in m.iter_mut().enumerate() {
            for (c, x) in row.iter_mut().enumerate() {
                *x += u[r] * u[c];
            }
        }
    }
    let p1 = m[0][1] * m[0][1] + m[0][2] * m[0][2] + m[1][2] * m[1][2];
    let q = (m[0][0] + m[1][1] + m[2][2]) / 3.0;
    let p2 = (m[0][0] - q).powi(2) + (m[1][1] - q).powi(2) + (m[2][2] - q).powi(2) + 2.0 * p1;
    let p = (p2 / 6.0).sqrt();
    if p < 1e-12 {
        return q as f32;
    }
    let b = |r: usize, c: usize| (m[r][c] - if r == c { q } else { 0.0 }) / p;
    let det = b(0, 0) * (b(1, 1) * b(2, 2) - b(1, 2) * b(2, 1)) - b(0, 1) * (b(1, 0) * b(2, 2) - b(1, 2) * b(2, 0))
        + b(0, 2) * (b(1, 0) * b(2, 1) - b(1, 1) * b(2, 0));
    let phi = (det / 2.0).clamp(-1.0, 1.0).acos() / 3.0;
    (q + 2.0 * p * (phi + 2.0 * std::f64::consts::PI / 3.0).cos()) as f32
}

fn volume(a: Vec3, b: Vec3, c: Vec3, d: Vec3) -> f32 {
    (b - a).dot((c - a).cross(d - a)).abs()
}

/// A bone's spin, tracked by a triangle.
#[derive(Clone, Debug, PartialEq)]
pub struct SpinTrack {
    /// The triangle's vertices.
    pub triangle: [usize; 3],
    /// Angle (radians) about the bone from the spin to the triangle's direction
    /// in the set-up frame.
    pub angle: f32,
}

/// Foot of the perpendicular from `p` to the line through `a` and `b`.
fn foot(p: Vec3, a: Vec3, b: Vec3) -> Vec3 {
    let ab = b - a;
    let t = if ab.length_squared() > 0.0 { (p - a).dot(ab) / ab.length_squared() } else { 0.0 };
    a + ab * t
}

/// Signed angle from `u` to `v` about `axis` (all perpendicular to it).
fn angle_about(u: Vec3, v: Vec3, axis: Vec3) -> f32 {
    u.cross(v).dot(axis).atan2(u.dot(v))
}

/// Where the ray from `origin` along `dir` meets triangle `a b c` (distance), if it does.
fn hit(origin: Vec3, dir: Vec3, a: Vec3, b: Vec3, c: Vec3) -> Option<f32> {
    let (e1, e2) = (b - a, c - a);
    let p = dir.cross(e2);
    let det = e1.dot(p);
    if det.abs() < 1e-12 {
        return None;
    }
    let s = origin - a;
    let u = s.dot(p) / det;
    let q = s.cross(e1);
    let v = dir.dot(q) / det;
    let t = e2.dot(q) / det;
    (u >= 0.0 && v >= 0.0 && u + v <= 1.0 && t > 0.0).then_some(t)
}

/// The spin triangle of the bone from joint `from` to joint `to` (bound to bone
/// `to`): the one the spin ray from mid-bone hits first, else the one whose
/// centroid lies most in the spin's direction. `None` without a spin or a
/// triangle bound to the bone.
pub fn spin_triangle(setup: &[Vec3], triangles: &[[usize; 3]], rig: &Rig, from: usize, to: usize) -> Option<SpinTrack> {
    let (a, b) = (Vec3::from_array(rig.joints.get(from)?.position), Vec3::from_array(rig.joints.get(to)?.position));
    let axis = (b - a).normalize_or_zero();
    let spin = Vec3::from_array(rig.joints.get(from)?.spin?);
    let spin = (spin - axis * spin.dot(axis)).normalize_or_zero();
    if axis == Vec3::ZERO || spin == Vec3::ZERO {
        return None;
    }
    let mid = (a + b) * 0.5;
    let bound =
        |t: &[usize; 3]| t.iter().all(|&v| rig.binding.get(v).copied().flatten() == Some(to) && v < setup.len());
    let mine: Vec<&[usize; 3]> = triangles.iter().filter(|t| bound(t)).collect();
    let centroid = |t: &[usize; 3]| (setup[t[0]] + setup[t[1]] + setup[t[2]]) / 3.0;
    let by_ray = mine
        .iter()
        .filter_map(|t| hit(mid, spin, setup[t[0]], setup[t[1]], setup[t[2]]).map(|d| (d, **t)))
        .min_by(|x, y| x.0.total_cmp(&y.0))
        .map(|x| x.1);
    let across = |t: &[usize; 3]| {
        let c = centroid(t);
        (c - foot(c, a, b)).normalize_or_zero().dot(spin)
    };
    let triangle = by_ray.or_else(|| mine.iter().max_by(|x, y| across(x).total_cmp(&across(y))).map(|t| **t))?;
    let c = centroid(&triangle);
    let out = (c - foot(c, a, b)).normalize_or_zero();
    if out == Vec3::ZERO {
        return None;
    }
    Some(SpinTrack { triangle, angle: angle_about(spin, out, axis) })
}

impl SpinTrack {
    /// The spin (unit, across the bone `a`→`b`) in a frame with vertex positions
    /// `positions`: the perpendicular from the bone to the triangle's centroid,
    /// turned back by the set-up angle about the bone.
    pub fn spin(&self, positions: &[Vec3], a: Vec3, b: Vec3) -> Option<Vec3> {
        let [p, q, r] = self.triangle.map(|v| positions.get(v).copied());
        let c = (p? + q? + r?) / 3.0;
        let axis = (b - a).normalize_or_zero();
        let out = (c - foot(c, a, b)).normalize_or_zero();
        if axis == Vec3::ZERO || out == Vec3::ZERO {
            return None;
        }
        Some(glam::Quat::from_axis_angle(axis, -self.angle) * out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn eigenvalue_of_spread_and_clustered_directions() {
        let spread = [
            Vec3::new(1.0, 1.0, 1.0),
            Vec3::new(1.0, -1.0, -1.0),
            Vec3::new(-1.0, 1.0, -1.0),
            Vec3::new(-1.0, -1.0, 1.0),
        ]
        .map(Vec3::normalize);
        assert!((smallest_eigenvalue(spread) - 4.0 / 3.0).abs() < 1e-5);
        let flat = [Vec3::X, Vec3::Y, -Vec3::X, -Vec3::Y];
        assert!(smallest_eigenvalue(flat).abs() < 1e-6);
    }
}
