//! The capture rig: a skeleton posed inside one frame of a vertex-animated mesh
//! (the set-up frame), each bone's spin (its "up" vector), and which bone each
//! vertex is bound to. Saved as a small JSON file:
//!
//! ```json
//! {
//!   "format": "mocap-capture-rig",
//!   "version": 1,
//!   "setup_frame": 0,
//!   "joints": [
//!     { "name": "Hips", "parent": null, "position": [0.0, 24.0, 0.0], "spin": null },
//!     { "name": "Spine", "parent": 0, "position": [0.0, 30.0, 0.0], "spin": [1.0, 0.0, 0.0] }
//!   ],
//!   "binding": [1, 1, null]
//! }
//! ```
//!
//! - `joints` are in parent-before-child order (`parent` is an earlier index, or
//!   `null` for a root); `position` is where the joint is in the set-up frame (the
//!   mesh's Y-up axes and units); `spin`, for a joint with exactly one child, is a
//!   direction across that bone (it is made perpendicular to the bone when used).
//! - A bone is a joint with a parent: the segment from its parent to it. It is
//!   named by the joint at its far end, so `binding[v]` is the index of the joint
//!   ending the bone vertex `v` is bound to, or `null` for an unbound vertex.
//!
//! [`Rig::fit`] places a humanoid skeleton (or any given one) inside a mesh,
//! scaled to it; [`Rig::bind`] binds every vertex to its nearest bone;
//! [`Rig::from_skeleton`] makes the rig of a skeleton in a known pose.

use crate::model::skeleton::Skeleton;
use crate::runtime::fk::Transform;
use glam::Vec3;
use serde::{Deserialize, Serialize};

/// The `format` string of a rig file.
pub const FORMAT: &str = "mocap-capture-rig";

/// A joint of the rig.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RigJoint {
    /// Its name (unique in the rig).
    pub name: String,
    /// Its parent (an earlier index), or `None` for a root.
    pub parent: Option<usize>,
    /// Where it is in the set-up frame (mesh axes and units).
    pub position: [f32; 3],
    /// For a joint with one child: a direction across that bone (its spin).
    #[serde(default)]
    pub spin: Option<[f32; 3]>,
}

/// A capture rig (see the module documentation).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Rig {
    /// Always [`FORMAT`].
    pub format: String,
    /// Always 1.
    pub version: u32,
    /// The mesh frame the joints are posed in.
    pub setup_frame: usize,
    /// The joints, parents first.
    pub joints: Vec<RigJoint>,
    /// Per vertex: the bone (its far joint's index) it is bound to.
    pub binding: Vec<Option<usize>>,
}

/// Why a rig is not usable.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("rig: {0}")]
pub struct RigError(pub String);

fn fail<T>(message: impl Into<String>) -> Result<T, RigError> {
    Err(RigError(message.into()))
}

/// Humanoid template: name, parent, and (forward, up, left) in heights, from the
/// feet's centre. MD2 characters face +X; left is −Z in Y-up axes.
const HUMANOID: [(&str, Option<usize>, [f32; 3]); 26] = [
    ("Hips", None, [0.0, 0.52, 0.0]),
    ("Spine", Some(0), [0.0, 0.62, 0.0]),
    ("Chest", Some(1), [0.0, 0.72, 0.0]),
    ("Neck", Some(2), [0.0, 0.84, 0.0]),
    ("Head", Some(3), [0.0, 0.89, 0.0]),
    ("Head_End", Some(4), [0.0, 0.99, 0.0]),
    ("LeftShoulder", Some(2), [0.0, 0.81, 0.05]),
    ("LeftArm", Some(6), [0.0, 0.80, 0.12]),
    ("LeftForeArm", Some(7), [0.0, 0.63, 0.15]),
    ("LeftHand", Some(8), [0.02, 0.49, 0.16]),
    ("LeftHand_End", Some(9), [0.03, 0.43, 0.16]),
    ("RightShoulder", Some(2), [0.0, 0.81, -0.05]),
    ("RightArm", Some(11), [0.0, 0.80, -0.12]),
    ("RightForeArm", Some(12), [0.0, 0.63, -0.15]),
    ("RightHand", Some(13), [0.02, 0.49, -0.16]),
    ("RightHand_End", Some(14), [0.03, 0.43, -0.16]),
    ("LeftUpLeg", Some(0), [0.0, 0.49, 0.06]),
    ("LeftLeg", Some(16), [0.01, 0.27, 0.065]),
    ("LeftFoot", Some(17), [0.0, 0.05, 0.07]),
    ("LeftToe", Some(18), [0.06, 0.02, 0.07]),
    ("LeftToe_End", Some(19), [0.10, 0.01, 0.07]),
    ("RightUpLeg", Some(0), [0.0, 0.49, -0.06]),
    ("RightLeg", Some(21), [0.01, 0.27, -0.065]),
    ("RightFoot", Some(22), [0.0, 0.05, -0.07]),
    ("RightToe", Some(23), [0.06, 0.02, -0.07]),
    ("RightToe_End", Some(24), [0.10, 0.01, -0.07]),
];

/// Bounds of a point set: (min, max).
fn bounds(points: &[Vec3]) -> (Vec3, Vec3) {
    points
        .iter()
        .fold((Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)), |(lo, hi), p| (lo.min(*p), hi.max(*p)))
}

/// The median of `values` (0 when empty).
fn median(mut values: Vec<f32>) -> f32 {
    values.sort_by(f32::total_cmp);
    values.get(values.len() / 2).copied().unwrap_or(0.0)
}

/// Moves bones onto the centre lines of the mesh parts nearest to them, `rounds`
/// times: the vertices are bound to their nearest bone; each bone with six or
/// more fits a line to them (their centroid and main direction); each joint moves
/// half-way to the mean of its places projected on the lines of its bones. So a
/// template's arm hanging down beside a raised arm of the mesh is drawn into it.
fn center_bones(joints: &mut [RigJoint], positions: &[Vec3], rounds: usize) {
    for _ in 0..rounds {
        let bones: Vec<(usize, usize)> =
            joints.iter().enumerate().filter_map(|(j, x)| x.parent.map(|p| (p, j))).collect();
        let at = |j: &RigJoint| Vec3::from_array(j.position);
        let mut members: Vec<Vec<Vec3>> = vec![Vec::new(); bones.len()];
        for v in positions {
            let nearest = bones.iter().enumerate().min_by(|(_, a), (_, b)| {
                segment_distance(*v, at(&joints[a.0]), at(&joints[a.1])).total_cmp(&segment_distance(
                    *v,
                    at(&joints[b.0]),
                    at(&joints[b.1]),
                ))
            });
            if let Some((k, _)) = nearest {
                members[k].push(*v);
            }
        }
        let mut sums = vec![(Vec3::ZERO, 0.0f32); joints.len()];
        for (k, &(p, j)) in bones.iter().enumerate() {
            let pts = &members[k];
            if pts.len() < 6 {
                continue;
            }
            let centre = pts.iter().copied().sum::<Vec3>() / pts.len() as f32;
            // Main direction by power iteration on the scatter, from the bone's own.
            let mut dir = (at(&joints[j]) - at(&joints[p])).normalize_or(Vec3::Y);
            for _ in 0..8 {
                let next: Vec3 = pts.iter().map(|x| (*x - centre) * (*x - centre).dot(dir)).sum();
                dir = next.normalize_or(dir);
            }
            for end in [p, j] {
                let x = at(&joints[end]);
                let on_line = centre + dir * (x - centre).dot(dir);
                sums[end].0 += on_line;
                sums[end].1 += 1.0;
            }
        }
        for (j, (sum, n)) in sums.iter().enumerate() {
            if *n > 0.0 {
                let x = at(&joints[j]);
                joints[j].position = (x + (*sum / *n - x) * 0.5).to_array();
            }
        }
    }
}

/// Distance from `p` to the segment `a`–`b`.
pub fn segment_distance(p: Vec3, a: Vec3, b: Vec3) -> f32 {
    let ab = b - a;
    let t = if ab.length_squared() > 0.0 { ((p - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0) } else { 0.0 };
    p.distance(a + ab * t)
}

impl Rig {
    /// A rig of these joints with no vertex bound yet.
    pub fn new(setup_frame: usize, joints: Vec<RigJoint>) -> Rig {
        Rig { format: FORMAT.to_owned(), version: 1, setup_frame, joints, binding: Vec::new() }
    }

    /// The rig of `skeleton` posed by its model transforms `model` (one per joint,
    /// the mesh's units) in frame `setup_frame`: joints where `model` puts them,
    /// each single-child joint's spin its own local axis most across the bone.
    pub fn from_skeleton(skeleton: &Skeleton, model: &[Transform], setup_frame: usize) -> Rig {
        let children = skeleton.children();
        let joints = skeleton
            .joints()
            .iter()
            .enumerate()
            .map(|(j, joint)| {
                let at = model.get(j).copied().unwrap_or(Transform::IDENTITY);
                let only = children
                    .get(j)
                    .filter(|c| c.len() == 1)
                    .and_then(|c| c.first())
                    .and_then(|&c| skeleton.joints().get(c));
                let spin = only.and_then(|child| {
                    let along = child.offset.normalize_or_zero();
                    let axis = [Vec3::X, Vec3::Y, Vec3::Z]
                        .into_iter()
                        .min_by(|a, b| a.dot(along).abs().total_cmp(&b.dot(along).abs()))?;
                    let across = (axis - along * axis.dot(along)).normalize_or_zero();
                    (along != Vec3::ZERO).then(|| (at.rotation * across).to_array())
                });
                RigJoint { name: joint.name.clone(), parent: joint.parent, position: at.translation.to_array(), spin }
            })
            .collect();
        Rig::new(setup_frame, joints)
    }

    /// Places a skeleton inside the mesh whose set-up frame has vertex positions
    /// `positions`: `template` (a skeleton and its model transforms) or, without
    /// one, a humanoid, scaled to the mesh's height, centred on it and facing +X;
    /// then each joint is drawn twice towards the centre of the mesh around it,
    /// and kept inside the mesh's bounds; leaves with (almost) no vertex near them
    /// are dropped ([`Rig::prune_empty_leaves`]).
    /// Spins default across each bone towards +X (the character's front), else +Y.
    pub fn fit(positions: &[Vec3], setup_frame: usize, template: Option<(&Skeleton, &[Transform])>) -> Rig {
        let (lo, hi) = bounds(positions);
        let height = (hi.y - lo.y).max(1e-6);
        let centre = Vec3::new(
            median(positions.iter().map(|p| p.x).collect()),
            lo.y,
            median(positions.iter().map(|p| p.z).collect()),
        );
        let mut joints: Vec<RigJoint> = match template {
            Some((skeleton, model)) => {
                let points: Vec<Vec3> = model.iter().map(|t| t.translation).collect();
                let (tlo, thi) = bounds(&points);
                let scale = height / (thi.y - tlo.y).max(1e-6);
                let tcentre = Vec3::new((tlo.x + thi.x) * 0.5, tlo.y, (tlo.z + thi.z) * 0.5);
                let rig = Rig::from_skeleton(skeleton, model, setup_frame);
                rig.joints
                    .into_iter()
                    .map(|j| RigJoint {
                        position: (centre + (Vec3::from_array(j.position) - tcentre) * scale).to_array(),
                        spin: None,
                        ..j
                    })
                    .collect()
            }
            None => HUMANOID
                .iter()
                .map(|(name, parent, [f, u, l])| RigJoint {
                    name: (*name).to_owned(),
                    parent: *parent,
                    position: (centre + Vec3::new(*f, *u, -*l) * height).to_array(),
                    spin: None,
                })
                .collect(),
        };
        if !positions.is_empty() {
            for _ in 0..2 {
                for j in &mut joints {
                    let at = Vec3::from_array(j.position);
                    let near: Vec<Vec3> =
                        positions.iter().copied().filter(|p| p.distance(at) < height * 0.07).collect();
                    if near.len() >= 6 {
                        let mean = near.iter().copied().sum::<Vec3>() / near.len() as f32;
                        j.position = (at + (mean - at) * 0.7).to_array();
                    }
                }
            }
            center_bones(&mut joints, positions, 6);
        }
        // Inside the mesh's bounds, whatever the template said.
        if lo.is_finite() && hi.is_finite() {
            for j in &mut joints {
                j.position = Vec3::from_array(j.position).clamp(lo, hi).to_array();
            }
        }
        let mut rig = Rig::new(setup_frame, joints);
        rig.bind(positions);
        rig.prune_empty_leaves(positions);
        rig.default_spins();
        rig
    }

    /// Drops, leaf by leaf, joints ending a bone that fewer than four vertices
    /// are bound to (a template's toes where the mesh has none), rebinding after
    /// each; the root stays.
    pub fn prune_empty_leaves(&mut self, positions: &[Vec3]) {
        loop {
            let children = self.children();
            let mut counts = vec![0usize; self.joints.len()];
            for b in self.binding.iter().flatten() {
                if let Some(c) = counts.get_mut(*b) {
                    *c += 1;
                }
            }
            let Some(drop) = (0..self.joints.len())
                .rev()
                .find(|&j| self.joints[j].parent.is_some() && children[j].is_empty() && counts[j] < 4)
            else {
                return;
            };
            self.joints.remove(drop);
            for j in &mut self.joints {
                j.parent = j.parent.map(|p| if p > drop { p - 1 } else { p });
            }
            self.bind(positions);
        }
    }

    /// Children of each joint.
    pub fn children(&self) -> Vec<Vec<usize>> {
        let mut out = vec![Vec::new(); self.joints.len()];
        for (j, joint) in self.joints.iter().enumerate() {
            if let Some(c) = joint.parent.and_then(|p| out.get_mut(p)) {
                c.push(j);
            }
        }
        out
    }

    /// Gives every single-child joint without a spin one across its bone,
    /// towards +X (the front of an MD2 character), else towards +Y.
    pub fn default_spins(&mut self) {
        let children = self.children();
        for (j, kids) in children.iter().enumerate() {
            let [c] = kids.as_slice() else { continue };
            let (Some(a), Some(b)) = (self.joints.get(j), self.joints.get(*c)) else { continue };
            if a.spin.is_some() {
                continue;
            }
            let along = (Vec3::from_array(b.position) - Vec3::from_array(a.position)).normalize_or_zero();
            let pick = if along.dot(Vec3::X).abs() < 0.9 { Vec3::X } else { Vec3::Y };
            let across = (pick - along * pick.dot(along)).normalize_or_zero();
            if let Some(j) = self.joints.get_mut(j) {
                j.spin = (across != Vec3::ZERO).then(|| across.to_array());
            }
        }
    }

    /// Binds every vertex (set-up frame positions) to its nearest bone.
    pub fn bind(&mut self, positions: &[Vec3]) {
        let bones: Vec<(usize, Vec3, Vec3)> = self
            .joints
            .iter()
            .enumerate()
            .filter_map(|(j, joint)| {
                let p = self.joints.get(joint.parent?)?;
                Some((j, Vec3::from_array(p.position), Vec3::from_array(joint.position)))
            })
            .collect();
        self.binding = positions
            .iter()
            .map(|v| {
                bones
                    .iter()
                    .min_by(|a, b| segment_distance(*v, a.1, a.2).total_cmp(&segment_distance(*v, b.1, b.2)))
                    .map(|b| b.0)
            })
            .collect();
    }

    /// The rig as pretty-printed JSON.
    pub fn to_json(&self) -> String {
        serde_json::to_string_pretty(self).unwrap_or_default()
    }

    /// Reads and checks a rig file (see [`Rig::check`]).
    pub fn from_json(text: &str) -> Result<Rig, RigError> {
        let rig: Rig = serde_json::from_str(text).map_err(|e| {
            // serde_json ends its message with the position; say it once, first.
            let message = e.to_string();
            let message = message.rfind(" at line ").map_or(message.as_str(), |i| &message[..i]);
            RigError(format!("line {}, column {}: {message}", e.line(), e.column()))
        })?;
        if rig.format != FORMAT {
            return fail(format!("format is {:?}, not {FORMAT:?}", rig.format));
        }
        if rig.version != 1 {
            return fail(format!("version {} (this reader knows version 1)", rig.version));
        }
        rig.check()?;
        Ok(rig)
    }

    /// Checks the rig on its own: joints parents first with unique non-empty
    /// names and finite positions and spins, at most one root, every bound bone a
    /// joint with a parent.
    pub fn check(&self) -> Result<(), RigError> {
        if self.joints.is_empty() {
            return fail("no joints");
        }
        let mut names = std::collections::HashSet::new();
        for (j, joint) in self.joints.iter().enumerate() {
            if joint.name.trim().is_empty() || !names.insert(joint.name.as_str()) {
                return fail(format!("joint {j}: the name {:?} is empty or used twice", joint.name));
            }
            if joint.parent.is_some_and(|p| p >= j) {
                return fail(format!("joint {j} ({}): its parent must come before it", joint.name));
            }
            if !joint.position.iter().chain(joint.spin.iter().flatten()).all(|x| x.is_finite()) {
                return fail(format!("joint {j} ({}): a position or spin is not finite", joint.name));
            }
        }
        if self.joints.iter().filter(|j| j.parent.is_none()).count() != 1 {
            return fail("a rig has exactly one root joint");
        }
        if let Some((v, b)) = self
            .binding
            .iter()
            .enumerate()
            .find_map(|(v, b)| b.filter(|&b| self.joints.get(b).is_none_or(|j| j.parent.is_none())).map(|b| (v, b)))
        {
            return fail(format!("vertex {v} is bound to {b}, which is not a bone (a joint with a parent)"));
        }
        Ok(())
    }

    /// Checks the rig against a mesh of `vertices` vertices and `frames` frames.
    pub fn check_for(&self, vertices: usize, frames: usize) -> Result<(), RigError> {
        self.check()?;
        if self.binding.len() != vertices {
            return fail(format!("{} vertices are bound but the model has {vertices}", self.binding.len()));
        }
        if self.setup_frame >= frames {
            return fail(format!(
                "set-up frame {} but the model has frames 0 to {}",
                self.setup_frame,
                frames.saturating_sub(1)
            ));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn json_round_trips_and_bad_rigs_are_refused() {
        let points: Vec<Vec3> = (0..200)
            .map(|i| Vec3::new((i as f32 * 0.7).sin() * 4.0, i as f32 * 0.3, (i as f32 * 0.3).cos() * 6.0))
            .collect();
        let rig = Rig::fit(&points, 0, None);
        assert!(rig.joints.len() <= HUMANOID.len() && rig.joints.len() > 10);
        assert_eq!(rig.binding.len(), points.len());
        assert!(rig.binding.iter().all(Option::is_some));
        let again = Rig::from_json(&rig.to_json()).unwrap();
        assert_eq!(again, rig);
        let mut bad = rig.clone();
        bad.joints[3].parent = Some(7);
        assert!(Rig::from_json(&bad.to_json()).unwrap_err().0.contains("parent must come before"));
        let mut bad = rig.clone();
        bad.binding[0] = Some(0);
        assert!(bad.check().unwrap_err().0.contains("not a bone"));
        assert!(Rig::from_json("{").unwrap_err().0.contains("line 1"));
        assert!(rig.check_for(3, 10).is_err() && rig.check_for(points.len(), 1).is_ok());
    }
}
