//! Skeletal motion from a vertex-animated model (a Quake 2 MD2): the capture.
//!
//! Inputs: the model's vertex frames and a [`Rig`] (a skeleton posed inside its
//! set-up frame, bone spins, vertex binding; [`Rig::fit`] makes one for any
//! humanoid). Output: a [`Capture`]: a skeletal [`Clip`] (joint rotations
//! relative to the parent, the root's translation; one frame per model frame at
//! 10 fps) with the model's animations as frame ranges, every joint's position
//! and every bone's rotation per frame, and a [`Report`].
//!
//! Per joint, four tracked vertices ([`track::joint_sets`]) keep their set-up
//! distances to it. Their places in each frame are, by default, the best fit of
//! the rigid part they belong to, its shape averaged over all frames
//! ([`shape::RigidShape`]; MD2's 8-bit noise is divided among the part's
//! vertices), or their stored places ([`Options::average_shapes`] off). In each
//! frame the joint is where the four spheres meet, found
//! by successive approximation ([`spheres::successive`], started from the joint's
//! place in the previous frame) and checked by the closed form
//! ([`spheres::least_squares`]): the report gives where they disagree, and each
//! joint's residual (how far the solved joint is from its four spheres). A joint
//! with no valid vertex set, or a frame that does not converge, takes the
//! closed-form answer if it has one, else follows its parent rigidly; the report
//! says which. A bone's rotation comes from its direction and its spin (tracked
//! by a triangle, [`track::spin_triangle`]); a joint with two or more children
//! takes its rotation from two of its bones' directions.
//!
//! Work is split by frame ([`Capturer::step`]) so a caller can show progress.
//! Nothing recurses: joints are visited in parent-before-child order.

pub mod frames;
pub mod rig;
pub mod shape;
pub mod spheres;
pub mod track;

pub use rig::{Rig, RigError, RigJoint};

use crate::formats::md2::{Animation, Md2};
use crate::model::channel::Channel;
use crate::model::clip::Clip;
use crate::model::skeleton::{EulerConvention, Joint, Skeleton};
use crate::runtime::pose::LocalPose;
use glam::{Mat3, Quat, Vec3};
use spheres::{Settings, Sphere};

/// The rig a capture uses: a given one, or one fitted into the model's first
/// frame ([`Rig::fit`]: a humanoid, or the given skeleton in the given pose), so
/// the frames are decoded once whichever it is.
#[derive(Clone, Copy, Debug)]
pub enum RigChoice<'a> {
    /// This rig.
    Given(&'a Rig),
    /// Fit one: `None` for the humanoid, else a skeleton and its model transforms.
    Fit(Option<(&'a crate::Skeleton, &'a [crate::Transform])>),
}

impl<'a> From<&'a Rig> for RigChoice<'a> {
    fn from(rig: &'a Rig) -> RigChoice<'a> {
        RigChoice::Given(rig)
    }
}

/// Settings of a capture.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Options {
    /// Largest accepted change of a distance between two tracked vertices over
    /// the frames, as a share of the model's height (MD2 positions are 8-bit:
    /// one step is about 0.4 % of a frame's size).
    pub rigid_tolerance: f32,
    /// Most rounds of successive approximation per joint and frame.
    pub max_rounds: usize,
    /// Vertices tracked per joint: four (the source's method), or more to average
    /// out noise (every one is another sphere in the same iteration).
    pub vertices_per_joint: usize,
    /// Whether the tracked vertices are placed, in each frame, by the best fit of
    /// their rigid part's shape averaged over all frames ([`shape::RigidShape`]),
    /// which divides MD2's 8-bit noise among the part's vertices; false uses each
    /// vertex's stored place as it is (the source's method, noisier).
    pub average_shapes: bool,
}

impl Default for Options {
    fn default() -> Options {
        Options { rigid_tolerance: 0.015, max_rounds: 2000, vertices_per_joint: 4, average_shapes: true }
    }
}

/// Why there is no capture.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("capture: {0}")]
pub struct CaptureError(pub String);

/// What happened to one joint.
#[derive(Clone, Debug, PartialEq)]
pub struct JointReport {
    /// The joint's name.
    pub name: String,
    /// The four tracked vertices and the bone they are bound to, or why the joint has none.
    pub tracked: Result<track::JointSet, String>,
    /// Largest distance from the solved joint to one of its spheres (mesh units).
    pub max_residual: f64,
    /// Mean over frames of that distance.
    pub mean_residual: f64,
    /// Frames where successive approximation did not converge, with why.
    pub failures: Vec<(usize, String)>,
    /// Largest distance between the successive and the closed-form answers.
    pub max_disagreement: f64,
    /// Frame of that largest disagreement.
    pub disagreement_frame: usize,
    /// Whether the bone leaving this joint has a tracked spin.
    pub spin: bool,
}

/// The capture's report.
#[derive(Clone, Debug, PartialEq)]
pub struct Report {
    /// Per joint, in rig order.
    pub joints: Vec<JointReport>,
    /// The model's height (mesh units), the scale of the tolerances.
    pub height: f32,
}

impl Report {
    /// A plain-text table: per joint its vertices, residuals, convergence and
    /// agreement with the closed form.
    pub fn text(&self) -> String {
        let mut out = format!(
            "{:<16} {:<24} {:>10} {:>10} {:>8} {:>12}  spin\n",
            "joint", "vertices (bone)", "max resid", "mean", "failed", "vs closed"
        );
        for j in &self.joints {
            let tracked = match &j.tracked {
                Ok(s) => format!("{:?} ({})", s.vertices, s.bone),
                Err(_) => "none".to_owned(),
            };
            out.push_str(&format!(
                "{:<16} {:<24} {:>10.4} {:>10.4} {:>8} {:>12.4}  {}\n",
                j.name,
                tracked,
                j.max_residual,
                j.mean_residual,
                j.failures.len(),
                j.max_disagreement,
                if j.spin { "yes" } else { "no" }
            ));
        }
        for j in &self.joints {
            if let Err(why) = &j.tracked {
                out.push_str(&format!("no vertex set: {why}\n"));
            }
            if let Some((f, why)) = j.failures.first() {
                out.push_str(&format!(
                    "{}: frame {f} did not converge ({why}){}\n",
                    j.name,
                    if j.failures.len() > 1 {
                        format!(" and {} more frames", j.failures.len() - 1)
                    } else {
                        String::new()
                    }
                ));
            }
        }
        out
    }
}

/// A finished capture.
#[derive(Clone, Debug)]
pub struct Capture {
    /// The skeletal clip (rig joints; rotations relative to the parent, root
    /// translation), one frame per model frame, in metres (an MD2's Quake units
    /// read as inches, as the viewer reads the model, so the two stand together).
    pub clip: Clip,
    /// The model's animations, as frame ranges of the clip.
    pub animations: Vec<Animation>,
    /// The model's frame names.
    pub frame_names: Vec<String>,
    /// Per frame, every joint's position (mesh units, Y-up).
    pub positions: Vec<Vec<Vec3>>,
    /// Per frame, every joint's rotation from the set-up pose (world).
    pub rotations: Vec<Vec<Quat>>,
    /// The report.
    pub report: Report,
    /// Metres per mesh unit (the clip is in metres, positions in mesh units).
    pub meters_per_unit: f32,
    /// The rig used (given or fitted).
    pub rig: Rig,
}

impl Capture {
    /// The clip of one animation (its frame range), or `None` without one of that name.
    pub fn animation_clip(&self, name: &str) -> Option<Clip> {
        let a = self.animations.iter().find(|a| a.name == name)?;
        crate::ops::edit::apply(&self.clip, &crate::ops::edit::Edit::Trim { first: a.first, last: a.last }).ok()
    }

    /// The capture in the source's per-frame layout ([`frames`]).
    pub fn frames(&self) -> frames::CaptureFrames {
        let bones = self.report.joints.iter().map(|j| j.name.clone()).collect();
        let records = self
            .positions
            .iter()
            .zip(&self.rotations)
            .enumerate()
            .map(|(f, (p, r))| {
                frames::FrameRecord::from_y_up(self.frame_names.get(f).cloned().unwrap_or_default(), p, r)
            })
            .collect();
        frames::CaptureFrames { bones, frames: records }
    }
}

/// Every frame's vertex positions (Y-up, mesh units).
pub fn model_frames(md2: &Md2) -> Vec<Vec<Vec3>> {
    let mut scratch = Vec::new();
    (0..md2.frames.len())
        .map(|f| {
            md2.frame_positions(f, &mut scratch);
            scratch.iter().map(|p| Vec3::from_array(*p)).collect()
        })
        .collect()
}

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

/// The rotation taking the frame of (`a0`, across `b0`) to that of (`a1`, `b1`).
fn from_frames(a0: Vec3, b0: Vec3, a1: Vec3, b1: Vec3) -> Option<Quat> {
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

fn centroid(points: &[Vec3]) -> Vec3 {
    if points.is_empty() {
        return Vec3::ZERO;
    }
    points.iter().copied().sum::<Vec3>() / points.len() as f32
}

/// Captures every frame of `md2` with `rig` (see the module documentation).
pub fn capture(md2: &Md2, rig: &Rig, options: &Options) -> Result<Capture, CaptureError> {
    Capturer::new(md2, rig, options)?.finish()
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
