//! A rigid part of the mesh: its shape averaged over every frame, and its place
//! in each frame by a best fit.
//!
//! MD2 stores each frame's vertices in 8 bits per axis, so every vertex is off by
//! up to half a step (about 0.2 % of the model's size) and the error changes from
//! frame to frame (each frame has its own scale). A part that moves as one body
//! (vertices whose distances stay constant) carries the same shape in every
//! frame: [`RigidShape::average`] aligns the part of every frame onto the set-up
//! frame (Horn's best-fit rotation) and averages, so the shape's error shrinks
//! with the number of frames; [`RigidShape::fit`] places that shape in a frame by
//! the best-fit rigid motion over all its vertices, so a point fixed to the part
//! (a tracked vertex, or the joint itself) is placed with the noise of one vertex
//! divided among all of them.
//!
//! Inputs: every frame's vertex positions and the part's vertex indices. Output:
//! the shape in the set-up frame's coordinates. Nothing allocates per vertex per
//! frame beyond one list of pairs.

use super::fit_rotation;
use glam::{Quat, Vec3};

/// A rigid part's vertices and their averaged places (set-up frame coordinates).
#[derive(Clone, Debug, PartialEq)]
pub struct RigidShape {
    /// The part's vertices (indices into a frame).
    pub vertices: Vec<usize>,
    /// Each vertex's place, averaged over the frames, in the set-up frame.
    pub reference: Vec<Vec3>,
}

/// A rigid motion: `p ↦ rotation · (p − from) + to`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Motion {
    /// The rotation.
    pub rotation: Quat,
    /// The point it turns about (the shape's centroid).
    pub from: Vec3,
    /// Where that point goes (the frame's centroid of the part).
    pub to: Vec3,
}

impl Motion {
    /// Where the motion takes `p`.
    pub fn apply(&self, p: Vec3) -> Vec3 {
        self.to + self.rotation * (p - self.from)
    }
}

/// The best-fit rigid motion taking `from[i]` onto `to[i]` (three points at least).
fn best_fit(from: &[Vec3], to: &[Vec3]) -> Option<Motion> {
    if from.len() < 3 || from.len() != to.len() {
        return None;
    }
    let (c0, c1) = (super::centroid(from), super::centroid(to));
    let pairs: Vec<(Vec3, Vec3)> = from.iter().zip(to).map(|(a, b)| (*a - c0, *b - c1)).collect();
    Some(Motion { rotation: fit_rotation(&pairs)?, from: c0, to: c1 })
}

impl RigidShape {
    /// The part `vertices` as it is in frame `setup` (no averaging); `None` with
    /// fewer than three vertices or one missing from that frame.
    pub fn in_frame(frames: &[Vec<Vec3>], setup: usize, vertices: Vec<usize>) -> Option<RigidShape> {
        let frame = frames.get(setup)?;
        let reference = vertices.iter().map(|&v| frame.get(v).copied()).collect::<Option<Vec<_>>>()?;
        (vertices.len() >= 3).then_some(RigidShape { vertices, reference })
    }

    /// The part `vertices` averaged over every frame (see the module
    /// documentation), in frame `setup`'s coordinates: `rounds` rounds of aligning
    /// every frame onto the current average and averaging again.
    pub fn average(frames: &[Vec<Vec3>], setup: usize, vertices: Vec<usize>, rounds: usize) -> Option<RigidShape> {
        let mut shape = RigidShape::in_frame(frames, setup, vertices)?;
        let n = shape.vertices.len();
        for _ in 0..rounds {
            let mut sum = vec![Vec3::ZERO; n];
            let mut count = 0usize;
            for frame in frames {
                let Some(now) = shape.points(frame) else {
                    continue;
                };
                // The motion taking this frame's part onto the current shape.
                let Some(back) = best_fit(&now, &shape.reference) else {
                    continue;
                };
                for (s, p) in sum.iter_mut().zip(&now) {
                    *s += back.apply(*p);
                }
                count += 1;
            }
            if count == 0 {
                return Some(shape);
            }
            let mean: Vec<Vec3> = sum.iter().map(|s| *s / count as f32).collect();
            // Keep it where the set-up frame has it.
            let setup_points = shape.points(frames.get(setup)?)?;
            let onto = best_fit(&mean, &setup_points)?;
            shape.reference = mean.iter().map(|p| onto.apply(*p)).collect();
        }
        Some(shape)
    }

    /// The part's vertices in `frame`, or `None` if one is missing.
    fn points(&self, frame: &[Vec3]) -> Option<Vec<Vec3>> {
        self.vertices.iter().map(|&v| frame.get(v).copied()).collect()
    }

    /// The rigid motion that best takes the shape onto its vertices in `frame`.
    pub fn fit(&self, frame: &[Vec3]) -> Option<Motion> {
        best_fit(&self.reference, &self.points(frame)?)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn frames_of(shape: &[Vec3], motions: &[Motion], noise: f32) -> Vec<Vec<Vec3>> {
        motions
            .iter()
            .enumerate()
            .map(|(f, m)| {
                shape
                    .iter()
                    .enumerate()
                    .map(|(i, p)| {
                        // Deterministic noise, different per vertex and frame.
                        let h = ((i * 7919 + f * 104_729) % 1000) as f32 / 1000.0 - 0.5;
                        let g = ((i * 3571 + f * 65_537) % 997) as f32 / 997.0 - 0.5;
                        let k = ((i * 1237 + f * 48_611) % 991) as f32 / 991.0 - 0.5;
                        m.apply(*p) + Vec3::new(h, g, k) * noise
                    })
                    .collect()
            })
            .collect()
    }

    #[test]
    fn averaging_shrinks_the_noise_and_a_fit_places_a_fixed_point() {
        let shape: Vec<Vec3> =
            (0..40).map(|i| Vec3::new((i as f32 * 0.7).sin(), (i as f32 * 1.3).cos(), (i % 5) as f32 * 0.3)).collect();
        let motions: Vec<Motion> = (0..120)
            .map(|f| {
                let t = f as f32 * 0.05;
                Motion {
                    rotation: Quat::from_euler(glam::EulerRot::ZXY, t, 0.5 * t, -0.3 * t),
                    from: Vec3::ZERO,
                    to: Vec3::new(t, 0.2 * t, -t),
                }
            })
            .collect();
        let frames = frames_of(&shape, &motions, 0.02);
        let vertices: Vec<usize> = (0..shape.len()).collect();
        let raw = RigidShape::in_frame(&frames, 0, vertices.clone()).unwrap();
        let avg = RigidShape::average(&frames, 0, vertices, 2).unwrap();
        let error = |s: &RigidShape| s.reference.iter().zip(&shape).map(|(a, b)| a.distance(*b)).fold(0.0f32, f32::max);
        assert!(error(&avg) < error(&raw) * 0.5, "averaged {} vs raw {}", error(&avg), error(&raw));
        // A point fixed to the part (off it) is placed within the noise in every frame.
        let joint = Vec3::new(0.3, -1.5, 0.4);
        for (frame, m) in frames.iter().zip(&motions) {
            let placed = avg.fit(frame).unwrap().apply(joint);
            assert!(placed.distance(m.apply(joint)) < 0.01, "{placed} vs {}", m.apply(joint));
        }
    }

    #[test]
    fn too_few_or_missing_vertices_give_none() {
        let frames = vec![vec![Vec3::ZERO, Vec3::X]];
        assert!(RigidShape::in_frame(&frames, 0, vec![0, 1]).is_none());
        assert!(RigidShape::in_frame(&frames, 0, vec![0, 1, 5]).is_none());
        assert!(RigidShape::average(&frames, 3, vec![0, 1, 1], 2).is_none());
    }
}
