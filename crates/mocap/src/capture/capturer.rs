//! The capture, step by step ([`Capturer`]): each joint's tracked vertices
//! chosen, then each frame solved (joints where their spheres meet, bones turned
//! by their directions and spins), then the skeletal clip written.

use super::rotation::{fit_rotation, from_frames};
use super::spheres::{self, Settings, Sphere};
use super::{
    Capture, CaptureError, JointReport, Options, Report, Rig, RigChoice, centroid, model_frames, shape, track,
};
use crate::formats::md2::{Animation, Md2};
use crate::model::channel::Channel;
use crate::model::clip::Clip;
use crate::model::skeleton::{EulerConvention, Joint, Skeleton};
use crate::runtime::pose::LocalPose;
use glam::{Quat, Vec3};

/// A capture in progress, one [`Capturer::step`] at a time: first each joint's
/// tracked vertices are chosen, then each frame is solved.
pub struct Capturer {
    frames: Vec<Vec<Vec3>>,
    names: Vec<String>,
    animations: Vec<Animation>,
    rig: Rig,
    chooser: track::Chooser,
    /// Vertex sets chosen so far (one [`Capturer::step`] per joint first).
    sets: Vec<Result<track::JointSet, String>>,
    /// Per joint with a set, its rigid part (with [`Options::average_shapes`]).
    parts: Vec<Option<TrackedPart>>,
    average_shapes: bool,
    spins: Vec<Option<track::SpinTrack>>,
    /// Each joint's children, longest bone first.
    children: Vec<Vec<usize>>,
    /// Per joint without a vertex set: the vertices of the bones meeting there
    /// (the 64 nearest), which it follows as a best-fit rigid body.
    followed: Vec<Option<shape::RigidShape>>,
    settings: Settings,
    height: f32,
    /// Metres per mesh unit: the clip is written in metres.
    meters_per_unit: f32,
    done: usize,
    positions: Vec<Vec<Vec3>>,
    rotations: Vec<Vec<Quat>>,
    reports: Vec<JointReport>,
    residual_sums: Vec<f64>,
}

impl Capturer {
    /// Starts a capture of `md2` with `rig` (see the module documentation).
    pub fn new<'a>(md2: &Md2, rig: impl Into<RigChoice<'a>>, options: &Options) -> Result<Capturer, CaptureError> {
        let frames = model_frames(md2);
        let triangles: Vec<[usize; 3]> = md2.triangles.iter().map(|t| t.vertices.map(usize::from)).collect();
        let names = md2.frames.iter().map(|f| f.name.clone()).collect();
        let mut capturer = Capturer::from_frames(frames, names, md2.animations.clone(), &triangles, rig, options)?;
        // Quake units, read as inches by the rule every MD2 follows (see `MorphMesh::units`).
        capturer.meters_per_unit = crate::Units::guess(crate::model::mesh::QUAKE_PLAYER_HEIGHT).meters_per_unit();
        Ok(capturer)
    }

    /// Starts a capture of a model's mesh (file vertices, its unit: the clip is in
    /// metres like the model on the stage).
    pub fn from_mesh<'a>(
        mesh: &crate::MorphMesh,
        rig: impl Into<RigChoice<'a>>,
        options: &Options,
    ) -> Result<Capturer, CaptureError> {
        let mut capturer = Capturer::from_frames(
            mesh.source_frames(),
            mesh.frame_names().to_vec(),
            mesh.animations().to_vec(),
            &mesh.source_triangles(),
            rig,
            options,
        )?;
        capturer.meters_per_unit = mesh.units().meters_per_unit();
        Ok(capturer)
    }

    /// The vertex frames being captured.
    pub fn frames(&self) -> &[Vec<Vec3>] {
        &self.frames
    }

    /// The rig used (given or fitted).
    pub fn rig(&self) -> &Rig {
        &self.rig
    }

    /// Starts a capture of vertex frames (Y-up) with their names, animations and
    /// triangles; the clip keeps the frames' unit.
    pub fn from_frames<'a>(
        frames: Vec<Vec<Vec3>>,
        names: Vec<String>,
        animations: Vec<Animation>,
        triangles: &[[usize; 3]],
        rig: impl Into<RigChoice<'a>>,
        options: &Options,
    ) -> Result<Capturer, CaptureError> {
        let fitted;
        let rig = match rig.into() {
            RigChoice::Given(rig) => rig,
            RigChoice::Fit(template) => {
                fitted = Rig::fit(frames.first().map_or(&[][..], Vec::as_slice), 0, template);
                &fitted
            }
        };
        let vertices = frames.first().map_or(0, Vec::len);
        rig.check_for(vertices, frames.len()).map_err(|e| CaptureError(e.to_string()))?;
        let setup = &frames[rig.setup_frame];
        let (lo, hi) = setup
            .iter()
            .fold((Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)), |(lo, hi), p| (lo.min(*p), hi.max(*p)));
        let height = (hi - lo).max_element().max(1e-6);
        // Each joint's children, longest bone first (the primary one of a rotation).
        let mut children = rig.children();
        let length = |j: usize, c: usize| {
            Vec3::from_array(rig.joints[c].position).distance(Vec3::from_array(rig.joints[j].position))
        };
        for (j, kids) in children.iter_mut().enumerate() {
            kids.sort_by(|&a, &b| length(j, b).total_cmp(&length(j, a)));
        }
        let spins = (0..rig.joints.len())
            .map(|j| match children.get(j).map(Vec::as_slice) {
                Some([c]) => track::spin_triangle(setup, triangles, rig, j, *c),
                _ => None,
            })
            .collect::<Vec<_>>();
        let settings = Settings { max_rounds: options.max_rounds, ..Settings::for_scale(f64::from(height)) };
        let n = rig.joints.len();
        Ok(Capturer {
            names,
            animations,
            rig: rig.clone(),
            chooser: track::Chooser::new(rig, options.rigid_tolerance * height, options.vertices_per_joint),
            sets: Vec::with_capacity(n),
            parts: Vec::with_capacity(n),
            average_shapes: options.average_shapes,
            spins,
            children,
            followed: Vec::new(),
            settings,
            height,
            meters_per_unit: 1.0,
            done: 0,
            positions: Vec::with_capacity(frames.len()),
            rotations: Vec::with_capacity(frames.len()),
            frames,
            reports: Vec::new(),
            residual_sums: vec![0.0; n],
        })
    }

    /// After the last joint's vertex set: the report rows and, for joints without
    /// a set, the vertices they follow.
    fn sets_done(&mut self) {
        let rig = &self.rig;
        let setup = &self.frames[rig.setup_frame];
        self.reports = rig
            .joints
            .iter()
            .zip(&self.sets)
            .zip(&self.spins)
            .map(|((j, s), spin)| JointReport {
                name: j.name.clone(),
                tracked: s.clone(),
                max_residual: 0.0,
                mean_residual: 0.0,
                failures: Vec::new(),
                max_disagreement: 0.0,
                disagreement_frame: 0,
                spin: spin.is_some(),
            })
            .collect();
        let frames = &self.frames;
        let average = self.average_shapes;
        self.followed = (0..rig.joints.len())
            .map(|j| {
                if self.sets.get(j).is_some_and(Result::is_ok) {
                    return None;
                }
                let at = Vec3::from_array(rig.joints[j].position);
                let mine = |b: Option<usize>| {
                    b.is_some_and(|b| b == j || rig.joints.get(b).is_some_and(|x| x.parent == Some(j)))
                };
                let mut near: Vec<usize> = (0..setup.len()).filter(|&v| mine(rig.binding[v])).collect();
                near.sort_by(|&a, &b| setup[a].distance(at).total_cmp(&setup[b].distance(at)));
                near.truncate(64);
                part_shape(frames, rig.setup_frame, near, average)
            })
            .collect();
    }

    /// (steps done, steps in all): one step per joint (choosing its vertices),
    /// then one per frame.
    pub fn progress(&self) -> (usize, usize) {
        (self.sets.len() + self.done, self.rig.joints.len() + self.frames.len())
    }

    /// Chooses the next joint's vertices, or solves the next frame; false when
    /// everything is done.
    pub fn step(&mut self) -> bool {
        if self.sets.len() < self.rig.joints.len() {
            let j = self.sets.len();
            let mut set = self.chooser.joint(&self.frames, &self.rig, j);
            let at = self.rig.joints.get(j).map_or(Vec3::ZERO, |x| Vec3::from_array(x.position));
            let part = match &mut set {
                Ok(set) if self.average_shapes => TrackedPart::new(&self.frames, self.rig.setup_frame, set, at),
                _ => None,
            };
            self.sets.push(set);
            self.parts.push(part);
            if self.sets.len() == self.rig.joints.len() {
                self.sets_done();
            }
            return true;
        }
        let Some(vertices) = self.frames.get(self.done) else { return false };
        let f = self.done;
        let n = self.rig.joints.len();
        let setup_at = |j: usize| self.rig.joints.get(j).map_or(Vec3::ZERO, |x| Vec3::from_array(x.position));
        // 1. Tracked joints: where their spheres meet.
        let mut solved: Vec<Option<Vec3>> = vec![None; n];
        for j in 0..n {
            let Some(Ok(set)) = self.sets.get(j) else { continue };
            // The tracked vertices' places: by their part's best fit, or as stored.
            let fitted = self.parts.get(j).and_then(Option::as_ref).and_then(|p| Some((p, p.shape.fit(vertices)?)));
            let centers: Vec<Vec3> = match fitted {
                Some((part, motion)) => part.points.iter().map(|&p| motion.apply(p)).collect(),
                None => set.vertices.iter().map(|&v| vertices[v]).collect(),
            };
            let spheres: Vec<Sphere> =
                centers.iter().zip(&set.radii).map(|(c, &r)| Sphere { center: c.as_dvec3(), radius: r }).collect();
            // Start from the closed-form point (a frame can move far from the last
            // one: a jump), else from where the joint was in the last frame.
            let closed = spheres::least_squares(&spheres, f64::INFINITY).ok();
            let previous =
                self.positions.last().and_then(|p| p.get(j)).copied().unwrap_or_else(|| setup_at(j)).as_dvec3();
            let start = closed.map_or(previous, |c| c.point);
            let report = &mut self.reports[j];
            let point = match spheres::successive(&spheres, start, &self.settings) {
                Ok(s) => {
                    if let Some(c) = closed {
                        let d = (c.point - s.point).length();
                        if d > report.max_disagreement {
                            report.max_disagreement = d;
                            report.disagreement_frame = f;
                        }
                    }
                    Some(s.point)
                }
                Err(e) => {
                    report.failures.push((f, e.to_string()));
                    closed.map(|c| c.point).filter(|p| p.is_finite())
                }
            };
            if let Some(p) = point {
                let r = spheres::residual(&spheres, p);
                report.max_residual = report.max_residual.max(r);
                self.residual_sums[j] += r;
                solved[j] = Some(p.as_vec3());
            }
        }
        // 2. In parent-before-child order: untracked joints follow their parent;
        //    every joint's rotation from its children (and spin).
        let mut pos = vec![Vec3::ZERO; n];
        let mut rot = vec![Quat::IDENTITY; n];
        for j in 0..n {
            let parent = self.rig.joints[j].parent;
            let follow = self.follow(j, vertices);
            pos[j] = match (solved[j].or(follow), parent) {
                (Some(p), _) => p,
                (None, Some(p)) => pos[p] + rot[p] * (setup_at(j) - setup_at(p)),
                (None, None) => setup_at(j) + centroid(vertices) - centroid(&self.frames[self.rig.setup_frame]),
            };
            for &c in self.children.get(j).into_iter().flatten() {
                if let Some(p) = solved[c] {
                    // Provisional: a child's solved place is needed for this joint's rotation.
                    pos[c] = p;
                }
            }
            let inherited = parent.map_or(Quat::IDENTITY, |p| rot[p]);
            rot[j] = self.rotation(j, &pos, &solved, vertices, inherited);
        }
        self.positions.push(pos);
        self.rotations.push(rot);
        self.done += 1;
        true
    }

    /// An untracked joint's place: where the best-fit rigid motion of the vertices
    /// of its bones (from the set-up frame to this one) takes it; `None` with
    /// fewer than three of them.
    fn follow(&self, j: usize, vertices: &[Vec3]) -> Option<Vec3> {
        let shape = self.followed.get(j)?.as_ref()?;
        Some(shape.fit(vertices)?.apply(Vec3::from_array(self.rig.joints.get(j)?.position)))
    }

    /// Joint `j`'s rotation from the set-up pose: from two bone directions when
    /// two or more children are solved, from one direction and its spin, or the
    /// shortest turn of the bone from `inherited` (the parent's rotation).
    fn rotation(&self, j: usize, pos: &[Vec3], solved: &[Option<Vec3>], vertices: &[Vec3], inherited: Quat) -> Quat {
        let setup_at = |k: usize| self.rig.joints.get(k).map_or(Vec3::ZERO, |x| Vec3::from_array(x.position));
        // Children are kept longest first (see `from_frames`).
        let kids: Vec<usize> = self
            .children
            .get(j)
            .into_iter()
            .flatten()
            .copied()
            .filter(|&c| solved[c].is_some() && setup_at(c) != setup_at(j))
            .collect();
        let Some(&first) = kids.first() else { return inherited };
        let (a0, a1) = (setup_at(first) - setup_at(j), pos[first] - pos[j]);
        // Two or more bones not all in one line: the rotation that best turns their
        // set-up directions into today's.
        let spread = kids[1..]
            .iter()
            .any(|&k| (setup_at(k) - setup_at(j)).normalize_or_zero().cross(a0.normalize_or_zero()).length() > 0.2);
        if spread {
            let pairs: Vec<(Vec3, Vec3)> = kids.iter().map(|&k| (setup_at(k) - setup_at(j), pos[k] - pos[j])).collect();
            return fit_rotation(&pairs).unwrap_or(inherited);
        }
        if let (Some(track), Some(spin)) = (&self.spins[j], self.rig.joints[j].spin) {
            if let Some(now) = track.spin(vertices, pos[j], pos[first]) {
                return from_frames(a0, Vec3::from_array(spin), a1, now).unwrap_or(inherited);
            }
        }
        Quat::from_rotation_arc((inherited * a0).normalize_or_zero(), a1.normalize_or_zero()) * inherited
    }

    /// Ends the capture: the clip, the animations and the report.
    pub fn finish(mut self) -> Result<Capture, CaptureError> {
        while self.step() {}
        let frames = self.positions.len().max(1) as f64;
        for (r, sum) in self.reports.iter_mut().zip(&self.residual_sums) {
            r.mean_residual = sum / frames;
        }
        let clip = self.clip()?;
        Ok(Capture {
            clip,
            animations: self.animations,
            frame_names: self.names,
            positions: self.positions,
            rotations: self.rotations,
            report: Report { joints: self.reports, height: self.height },
            meters_per_unit: self.meters_per_unit,
            rig: self.rig,
        })
    }

    /// The skeletal clip: offsets from the set-up pose, the root with position
    /// channels, leaves as End Sites.
    fn clip(&self) -> Result<Clip, CaptureError> {
        let rot_channels = vec![Channel::Zrotation, Channel::Xrotation, Channel::Yrotation];
        let joints: Vec<Joint> = self
            .rig
            .joints
            .iter()
            .enumerate()
            .map(|(j, joint)| {
                let at = Vec3::from_array(joint.position);
                let offset =
                    joint.parent.and_then(|p| self.rig.joints.get(p)).map_or(at, |p| at - Vec3::from_array(p.position))
                        * self.meters_per_unit;
                if joint.parent.is_none() {
                    let mut channels = vec![Channel::Xposition, Channel::Yposition, Channel::Zposition];
                    channels.extend(rot_channels.iter().copied());
                    Joint::new(joint.name.clone(), None, offset, channels)
                } else if self.children.get(j).is_none_or(Vec::is_empty) {
                    Joint::end_site(joint.name.clone(), joint.parent, offset)
                } else {
                    Joint::new(joint.name.clone(), joint.parent, offset, rot_channels.clone())
                }
            })
            .collect();
        let skeleton = Skeleton::new(joints, EulerConvention::Intrinsic).map_err(|e| CaptureError(e.to_string()))?;
        let poses: Vec<LocalPose> = self
            .positions
            .iter()
            .zip(&self.rotations)
            .map(|(pos, rot)| {
                let mut local = LocalPose::default();
                for (j, joint) in skeleton.joints().iter().enumerate() {
                    let parent = joint.parent.map_or(Quat::IDENTITY, |p| rot[p]);
                    local.rotation.push((parent.inverse() * rot[j]).normalize());
                    local.translation.push(if joint.parent.is_none() {
                        pos[j] * self.meters_per_unit
                    } else {
                        joint.offset
                    });
                    local.scale.push(Vec3::ONE);
                }
                local
            })
            .collect();
        crate::ops::edit::clip_from_poses(skeleton, crate::model::mesh::FRAME_TIME, &poses)
            .map_err(|e| CaptureError(e.to_string()))
    }
}

/// A joint's tracked vertices placed by their rigid part: the part's shape
/// averaged over the frames, and the tracked vertices' places in it (in the
/// set's order), found once so a frame only fits the shape.
struct TrackedPart {
    shape: shape::RigidShape,
    points: Vec<Vec3>,
}

impl TrackedPart {
    /// The part of `set` averaged over `frames`; sets the set's radii to the
    /// averaged places' distances to the joint at `at`. `None` when the part has
    /// too few vertices or lacks a tracked one.
    fn new(frames: &[Vec<Vec3>], setup: usize, set: &mut track::JointSet, at: Vec3) -> Option<TrackedPart> {
        let shape = part_shape(frames, setup, set.part.clone(), true)?;
        let place =
            |v: usize| shape.vertices.iter().position(|&x| x == v).and_then(|i| shape.reference.get(i)).copied();
        let points = set.vertices.iter().map(|&v| place(v)).collect::<Option<Vec<Vec3>>>()?;
        set.radii = points.iter().map(|p| f64::from(p.distance(at))).collect();
        Some(TrackedPart { shape, points })
    }
}

/// The shape of the part `vertices`: averaged over the frames (two rounds), or
/// as frame `setup` has it.
fn part_shape(frames: &[Vec<Vec3>], setup: usize, vertices: Vec<usize>, average: bool) -> Option<shape::RigidShape> {
    if average {
        shape::RigidShape::average(frames, setup, vertices, 2)
    } else {
        shape::RigidShape::in_frame(frames, setup, vertices)
    }
}
