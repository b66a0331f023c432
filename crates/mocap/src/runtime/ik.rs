//! Inverse kinematics on a [`LocalPose`]: pull a chain's end effector toward a
//! target by changing the local rotations of the chain's joints (translations stay).
//!
//! Inputs of every solver: the skeleton, the local pose to correct (in place), a
//! [`Chain`] (root joint … end effector, each the parent of the next) and a target
//! in the skeleton's model space (file units). Output: a [`Solve`] saying how close
//! the effector got. Joints outside the chain keep their local rotations, so the
//! effector's children follow it.
//!
//! - [`two_bone`]: analytic, for a three-joint chain (shoulder–elbow–wrist,
//!   hip–knee–ankle); the middle joint bends toward a pole point.
//! - [`ccd`]: cyclic coordinate descent, any length.
//! - [`fabrik`]: forward and backward reaching, any length.
//!
//! Every solver stretches the chain straight toward a target it cannot reach,
//! honours the joint limits of the skeleton ([`crate::Limit`], Acclaim's `limits`)
//! when [`Options::limits`] is on, and never writes a non-finite rotation: a
//! non-finite target, zero-length bones or a NaN in the pose leave the pose as it
//! was or skip the degenerate step. None of them recurses or allocates per
//! iteration beyond the chain's own scratch.

use crate::model::channel::AngleUnit;
use crate::model::skeleton::{EulerConvention, Skeleton};
use crate::runtime::fk::Transform;
use crate::runtime::pose::LocalPose;
use glam::{EulerRot, Quat, Vec3};

/// Below this length (file units) a bone or distance counts as zero.
const EPSILON: f32 = 1e-6;

/// Why a chain cannot be built.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum ChainError {
    /// A joint index past the skeleton.
    #[error("joint {0} is not in the skeleton")]
    OutOfRange(usize),
    /// The root is not the effector or one of its ancestors.
    #[error("joint {root} is not an ancestor of joint {effector}")]
    NotAnAncestor {
        /// The chain's root.
        root: usize,
        /// The chain's end effector.
        effector: usize,
    },
}

/// Joints from a root down to an end effector, each the parent of the next.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Chain {
    joints: Vec<usize>,
}

impl Chain {
    /// The chain from `root` down to `effector` (walking parents up from the
    /// effector; a loop is impossible since parents come first).
    pub fn new(skeleton: &Skeleton, root: usize, effector: usize) -> Result<Chain, ChainError> {
        let joints = skeleton.joints();
        for j in [root, effector] {
            if j >= joints.len() {
                return Err(ChainError::OutOfRange(j));
            }
        }
        let mut path = vec![effector];
        let mut at = effector;
        while at != root {
            match joints.get(at).and_then(|j| j.parent).filter(|&p| p < at) {
                Some(p) => {
                    path.push(p);
                    at = p;
                }
                None => return Err(ChainError::NotAnAncestor { root, effector }),
            }
        }
        path.reverse();
        Ok(Chain { joints: path })
    }

    /// The chain of `bones` bones ending at `effector` (shorter when the root is
    /// reached first).
    pub fn up_from(skeleton: &Skeleton, effector: usize, bones: usize) -> Result<Chain, ChainError> {
        let mut root = effector;
        for _ in 0..bones {
            match skeleton.joints().get(root).and_then(|j| j.parent) {
                Some(p) => root = p,
                None => break,
            }
        }
        Chain::new(skeleton, root, effector)
    }

    /// The chain that moves `joint` when it is dragged: its limb when it ends one of
    /// the [`default_chains`] (a hand, a foot), else the two bones above it.
    pub fn for_joint(skeleton: &Skeleton, joint: usize) -> Result<Chain, ChainError> {
        match default_chains(skeleton).into_iter().map(|(_, c)| c).find(|c| c.effector() == joint) {
            Some(chain) => Ok(chain),
            None => Chain::up_from(skeleton, joint, 2),
        }
    }

    /// Total length of the chain's bones in the rest pose (file units): the scale
    /// for a solve's tolerance.
    pub fn rest_length(&self, skeleton: &Skeleton) -> f32 {
        let rest = crate::runtime::fk::rest_positions(skeleton);
        let at = |j: usize| rest.get(j).copied().unwrap_or(Vec3::ZERO);
        self.joints.windows(2).map(|w| at(w[0]).distance(at(w[1]))).sum()
    }

    /// The joints, root first.
    pub fn joints(&self) -> &[usize] {
        &self.joints
    }

    /// The first joint (the one that stays where it is).
    pub fn root(&self) -> usize {
        self.joints.first().copied().unwrap_or(0)
    }

    /// The last joint (the one pulled toward the target).
    pub fn effector(&self) -> usize {
        self.joints.last().copied().unwrap_or(0)
    }
}

/// Solver settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Options {
    /// Most passes over the chain (iterative solvers).
    pub iterations: usize,
    /// Stop when the effector is this close to the target (file units).
    pub tolerance: f32,
    /// Clamp rotations to the skeleton's joint limits (where it has any), and keep
    /// joints with limits to the axes they have channels for.
    pub limits: bool,
    /// The unit the limits are written in (the motion's angle unit).
    pub angle_unit: AngleUnit,
}

impl Default for Options {
    fn default() -> Options {
        Options { iterations: 32, tolerance: 1e-4, limits: true, angle_unit: AngleUnit::Degrees }
    }
}

/// How a solve ended.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Solve {
    /// Distance from the effector to the target afterwards (file units; infinite
    /// for a non-finite target).
    pub distance: f32,
    /// Whether that is within the tolerance.
    pub reached: bool,
    /// Passes made (1 for the analytic solver).
    pub iterations: usize,
}

/// Model transform of `joint` in `pose` (walking up its ancestors, no recursion).
pub fn model_transform(skeleton: &Skeleton, pose: &LocalPose, joint: usize) -> Transform {
    let mut path = Vec::new();
    let mut at = Some(joint);
    while let Some(j) = at {
        path.push(j);
        at = skeleton.joints().get(j).and_then(|x| x.parent).filter(|&p| p < j);
    }
    path.iter().rev().fold(None, |acc: Option<Transform>, &j| Some(compose(acc, local(pose, j)))).unwrap_or_default()
}

/// Joint `j`'s local transform in `pose` (identity past its end).
fn local(pose: &LocalPose, j: usize) -> Transform {
    Transform {
        rotation: pose.rotation.get(j).copied().unwrap_or(Quat::IDENTITY),
        translation: pose.translation.get(j).copied().unwrap_or(Vec3::ZERO),
        scale: pose.scale.get(j).copied().unwrap_or(Vec3::ONE),
    }
}

/// `parent ∘ child` (the rule of [`crate::runtime::fk`]); a root's model transform is its local one.
fn compose(parent: Option<Transform>, child: Transform) -> Transform {
    match parent {
        None => child,
        Some(p) => Transform {
            rotation: p.rotation * child.rotation,
            translation: p.translation + p.rotation * (p.scale * child.translation),
            scale: p.scale * child.scale,
        },
    }
}

/// Model transforms of the chain's joints (and of the root's parent first).
struct ChainPose {
    /// The root's parent's model transform (identity for a root joint).
    base: Transform,
    /// One per chain joint.
    model: Vec<Transform>,
}

impl ChainPose {
    fn new(skeleton: &Skeleton, pose: &LocalPose, chain: &Chain) -> ChainPose {
        let parent = skeleton.joints().get(chain.root()).and_then(|j| j.parent);
        let base = parent.map_or(Transform::IDENTITY, |p| model_transform(skeleton, pose, p));
        let mut cp = ChainPose { base, model: Vec::with_capacity(chain.joints.len()) };
        cp.update(pose, chain, 0);
        cp
    }

    /// Recomputes the model transforms from chain index `from` down.
    fn update(&mut self, pose: &LocalPose, chain: &Chain, from: usize) {
        self.model.truncate(from);
        for &j in chain.joints.iter().skip(from) {
            let parent = self.model.last().copied().unwrap_or(self.base);
            self.model.push(compose(Some(parent), local(pose, j)));
        }
    }

    fn position(&self, k: usize) -> Vec3 {
        self.model.get(k).map_or(Vec3::ZERO, |t| t.translation)
    }

    fn effector(&self) -> Vec3 {
        self.model.last().map_or(Vec3::ZERO, |t| t.translation)
    }

    /// World rotation of chain joint `k`'s parent.
    fn parent_rotation(&self, k: usize) -> Quat {
        if k == 0 { self.base.rotation } else { self.model.get(k - 1).map_or(Quat::IDENTITY, |t| t.rotation) }
    }
}

/// Turns chain joint `k` by the world-space rotation `delta` (about its own
/// position): `L' = P⁻¹ · delta · P · L`. Skipped when the result is not finite.
fn rotate_joint(pose: &mut LocalPose, chain: &Chain, cp: &ChainPose, k: usize, delta: Quat) {
    let Some(&j) = chain.joints.get(k) else { return };
    let Some(slot) = pose.rotation.get_mut(j) else { return };
    let parent = cp.parent_rotation(k);
    let turned = (parent.inverse() * delta * parent * *slot).normalize();
    if turned.is_finite() {
        *slot = turned;
    }
}

/// The shortest rotation taking direction `from` to direction `to`; identity when
/// either is (nearly) zero or not finite. Exact for tiny angles too (glam's
/// `from_rotation_arc` returns the identity below about 7e-4 rad, which stalls
/// iterative solvers short of the target): the half-way quaternion
/// `(a × b, 1 + a · b)`, normalised.
fn arc(from: Vec3, to: Vec3) -> Quat {
    let (a, b) = (from.normalize_or_zero(), to.normalize_or_zero());
    if a == Vec3::ZERO || b == Vec3::ZERO || !a.is_finite() || !b.is_finite() {
        return Quat::IDENTITY;
    }
    let w = 1.0 + a.dot(b);
    let q = if w < 1e-6 {
        // Opposite directions: half a turn about any axis across them.
        let axis = a.any_orthonormal_vector();
        Quat::from_xyzw(axis.x, axis.y, axis.z, 0.0)
    } else {
        let c = a.cross(b);
        Quat::from_xyzw(c.x, c.y, c.z, w).normalize()
    };
    if q.is_finite() { q } else { Quat::IDENTITY }
}

/// Clamps joint `j`'s local rotation to its limits (see [`Options::limits`]).
pub fn clamp_to_limits(skeleton: &Skeleton, pose: &mut LocalPose, j: usize, unit: AngleUnit) {
    let Some(joint) = skeleton.joints().get(j) else { return };
    if joint.limits.is_empty() {
        return;
    }
    let Some(slot) = pose.rotation.get_mut(j) else { return };
    // L = rest · M, M the channel rotations composed in the skeleton's convention:
    // as a product of axis rotations left to right, file order when intrinsic,
    // reversed when extrinsic.
    let mut axes: Vec<(usize, Option<usize>)> = Vec::new();
    for (k, c) in joint.channels.iter().enumerate() {
        if c.is_rotation() && !axes.iter().any(|(a, _)| *a == c.axis()) {
            axes.push((c.axis(), Some(k)));
        }
    }
    if skeleton.euler() == EulerConvention::Extrinsic {
        axes.reverse();
    }
    // Axes without a channel are locked at 0; they go last in the product.
    for a in 0..3 {
        if !axes.iter().any(|(x, _)| *x == a) {
            axes.push((a, None));
        }
    }
    let Some(order) = euler_order([axes[0].0, axes[1].0, axes[2].0]) else { return };
    let m = joint.rest_rotation.inverse() * *slot;
    let (a, b, c) = m.to_euler(order);
    let per_unit = unit.radians_per_unit();
    let clamped: Vec<f32> = [a, b, c]
        .iter()
        .zip(&axes)
        .map(|(&angle, (_, channel))| match channel.and_then(|k| joint.limits.get(k)) {
            Some(limit) => angle.clamp(limit.min.min(limit.max) * per_unit, limit.max.max(limit.min) * per_unit),
            None if channel.is_some() => angle,
            None => 0.0,
        })
        .collect();
    let rebuilt = joint.rest_rotation * Quat::from_euler(order, clamped[0], clamped[1], clamped[2]);
    if rebuilt.is_finite() {
        *slot = rebuilt.normalize();
    }
}

/// glam's intrinsic order for the product `R[a0] · R[a1] · R[a2]`.
fn euler_order(axes: [usize; 3]) -> Option<EulerRot> {
    Some(match axes {
        [0, 1, 2] => EulerRot::XYZ,
        [0, 2, 1] => EulerRot::XZY,
        [1, 0, 2] => EulerRot::YXZ,
        [1, 2, 0] => EulerRot::YZX,
        [2, 0, 1] => EulerRot::ZXY,
        [2, 1, 0] => EulerRot::ZYX,
        _ => return None,
    })
}

fn finish(cp: &ChainPose, target: Vec3, tolerance: f32, iterations: usize) -> Solve {
    let distance = cp.effector().distance(target);
    let distance = if distance.is_finite() { distance } else { f32::INFINITY };
    Solve { distance, reached: distance <= tolerance, iterations }
}

fn unreachable_target() -> Solve {
    Solve { distance: f32::INFINITY, reached: false, iterations: 0 }
}

/// Analytic two-bone IK on a three-joint chain `a → b → c` (c the effector): `a`
/// turns so that `b` lands where the two bones meet on the side of `pole` (a point
/// in model space, e.g. in front of the knee), then `b` turns so that `c` reaches
/// the target. A target out of reach (or too near) stretches the chain straight
/// toward it. Limits, when on, are applied after (the effector may then stop short).
pub fn two_bone(
    skeleton: &Skeleton,
    pose: &mut LocalPose,
    chain: &Chain,
    target: Vec3,
    pole: Vec3,
    options: &Options,
) -> Solve {
    if chain.joints.len() != 3 {
        return ccd(skeleton, pose, chain, target, options);
    }
    if !target.is_finite() {
        return unreachable_target();
    }
    let mut cp = ChainPose::new(skeleton, pose, chain);
    let (a, b, c) = (cp.position(0), cp.position(1), cp.position(2));
    let (lab, lbc) = (a.distance(b), b.distance(c));
    let to_target = target - a;
    let reach = to_target.length();
    if lab < EPSILON || lbc < EPSILON || reach < EPSILON || !(lab + lbc).is_finite() {
        // Degenerate: only aim the chain at the target.
        let delta = arc(c - a, to_target);
        rotate_joint(pose, chain, &cp, 0, delta);
        cp.update(pose, chain, 0);
        return finish(&cp, target, options.tolerance, 1);
    }
    let u = to_target / reach;
    let d = reach.clamp((lab - lbc).abs() + EPSILON, lab + lbc - EPSILON * (lab + lbc));
    // The bend plane holds the target and the pole; else the current bend; else any.
    let side = {
        let toward = |p: Vec3| p - u * (p.dot(u));
        let from_pole = toward(pole - a);
        let from_bend = toward(b - a);
        if from_pole.length() > EPSILON * lab && from_pole.is_finite() {
            from_pole.normalize()
        } else if from_bend.length() > EPSILON * lab {
            from_bend.normalize()
        } else {
            u.any_orthonormal_vector()
        }
    };
    let cos_a = ((lab * lab + d * d - lbc * lbc) / (2.0 * lab * d)).clamp(-1.0, 1.0);
    let sin_a = (1.0 - cos_a * cos_a).max(0.0).sqrt();
    let b_goal = a + (u * cos_a + side * sin_a) * lab;
    rotate_joint(pose, chain, &cp, 0, arc(b - a, b_goal - a));
    cp.update(pose, chain, 0);
    let (b_now, c_now) = (cp.position(1), cp.position(2));
    rotate_joint(pose, chain, &cp, 1, arc(c_now - b_now, a + u * d - b_now));
    if options.limits {
        for &j in &chain.joints {
            clamp_to_limits(skeleton, pose, j, options.angle_unit);
        }
    }
    cp.update(pose, chain, 0);
    finish(&cp, target, options.tolerance, 1)
}

/// Cyclic coordinate descent: from the joint above the effector up to the root,
/// each joint turns so that the effector points at the target; repeated until it
/// is within the tolerance or [`Options::iterations`] passes are made. Limits are
/// applied at each step.
pub fn ccd(skeleton: &Skeleton, pose: &mut LocalPose, chain: &Chain, target: Vec3, options: &Options) -> Solve {
    if !target.is_finite() {
        return unreachable_target();
    }
    let mut cp = ChainPose::new(skeleton, pose, chain);
    let n = chain.joints.len();
    let reach: f32 = (1..n).map(|k| cp.position(k - 1).distance(cp.position(k))).sum();
    if cp.position(0).distance(target) >= reach && reach.is_finite() {
        // Out of reach: every bone points at the target, root first.
        let toward = target - cp.position(0);
        for k in 0..n.saturating_sub(1) {
            rotate_joint(pose, chain, &cp, k, arc(cp.position(k + 1) - cp.position(k), toward));
            if options.limits {
                if let Some(&j) = chain.joints.get(k) {
                    clamp_to_limits(skeleton, pose, j, options.angle_unit);
                }
            }
            cp.update(pose, chain, k);
        }
        return finish(&cp, target, options.tolerance, 1);
    }
    let mut passes = 0;
    while passes < options.iterations.max(1) {
        if cp.effector().distance(target) <= options.tolerance {
            break;
        }
        passes += 1;
        for k in (0..n.saturating_sub(1)).rev() {
            let p = cp.position(k);
            let delta = arc(cp.effector() - p, target - p);
            rotate_joint(pose, chain, &cp, k, delta);
            if options.limits {
                if let Some(&j) = chain.joints.get(k) {
                    clamp_to_limits(skeleton, pose, j, options.angle_unit);
                }
            }
            cp.update(pose, chain, k);
        }
    }
    finish(&cp, target, options.tolerance, passes)
}

/// FABRIK: the chain's joint positions are pulled alternately from the effector to
/// the target and back from the root to where it stands, bone lengths kept, until
/// the effector is within the tolerance; then each joint turns, root first, to
/// point its bone at the new position of the next joint. A target out of reach
/// puts the chain straight toward it. Limits, when on, are applied as the joints
/// turn.
pub fn fabrik(skeleton: &Skeleton, pose: &mut LocalPose, chain: &Chain, target: Vec3, options: &Options) -> Solve {
    if !target.is_finite() {
        return unreachable_target();
    }
    let mut cp = ChainPose::new(skeleton, pose, chain);
    let n = chain.joints.len();
    if n < 2 {
        return finish(&cp, target, options.tolerance, 0);
    }
    let mut points: Vec<Vec3> = (0..n).map(|k| cp.position(k)).collect();
    let lengths: Vec<f32> = points.windows(2).map(|w| w[0].distance(w[1])).collect();
    let total: f32 = lengths.iter().sum();
    if !total.is_finite() || points.iter().any(|p| !p.is_finite()) {
        return finish(&cp, target, options.tolerance, 0);
    }
    let root = points[0];
    let mut passes = 0;
    if root.distance(target) >= total {
        // Out of reach: straight toward the target.
        let dir = (target - root).normalize_or_zero();
        for k in 1..n {
            points[k] = points[k - 1] + dir * lengths[k - 1];
        }
        passes = 1;
    } else {
        while passes < options.iterations.max(1) && points[n - 1].distance(target) > options.tolerance {
            passes += 1;
            points[n - 1] = target;
            for k in (0..n - 1).rev() {
                let dir = (points[k] - points[k + 1]).normalize_or_zero();
                points[k] = points[k + 1] + dir * lengths[k];
            }
            points[0] = root;
            for k in 1..n {
                let dir = (points[k] - points[k - 1]).normalize_or_zero();
                points[k] = points[k - 1] + dir * lengths[k - 1];
            }
        }
    }
    // Turn the joints to follow the positions, root first.
    for k in 0..n - 1 {
        let (p, next) = (cp.position(k), cp.position(k + 1));
        rotate_joint(pose, chain, &cp, k, arc(next - p, points[k + 1] - p));
        if options.limits {
            if let Some(&j) = chain.joints.get(k) {
                clamp_to_limits(skeleton, pose, j, options.angle_unit);
            }
        }
        cp.update(pose, chain, k);
    }
    finish(&cp, target, options.tolerance, passes)
}

/// A humanoid's default IK chains, found from the tree's shape in the rest pose
/// (no joint names): limbs are two long bones of similar length in a row ending
/// where only short bones follow (thigh and shin ending at the ankle, above the
/// foot; upper arm and forearm ending at the wrist, above the fingers). Every joint
/// with a parent and grandparent whose two bones differ by at most half and whose
/// descendants' bones are all under half the shorter one is scored by the two
/// lengths; the best scores win, a chain sharing a joint with a better one is
/// skipped, and at most four are kept (two legs and two arms on a humanoid),
/// returned as (effector name, chain), the lowest effector (a foot) first.
pub fn default_chains(skeleton: &Skeleton) -> Vec<(String, Chain)> {
    let joints = skeleton.joints();
    let rest = crate::runtime::fk::rest_positions(skeleton);
    let at = |j: usize| rest.get(j).copied().unwrap_or(Vec3::ZERO);
    // The longest bone below each joint (children come after parents: one pass back).
    let mut longest_below = vec![0.0f32; joints.len()];
    for (j, joint) in joints.iter().enumerate().rev() {
        if let Some(p) = joint.parent.filter(|&p| p < j) {
            let here = at(p).distance(at(j)).max(longest_below.get(j).copied().unwrap_or(0.0));
            if let Some(slot) = longest_below.get_mut(p) {
                *slot = slot.max(if here.is_finite() { here } else { 0.0 });
            }
        }
    }
    let mut scored: Vec<(f32, [usize; 3])> = Vec::new();
    for (j, joint) in joints.iter().enumerate() {
        let Some(p) = joint.parent else { continue };
        let Some(g) = joints.get(p).and_then(|x| x.parent) else { continue };
        let (upper, lower) = (at(g).distance(at(p)), at(p).distance(at(j)));
        let (short, long) = (upper.min(lower), upper.max(lower));
        let extremity = longest_below.get(j).is_some_and(|&below| below < 0.5 * short);
        if short.is_finite() && long > 0.0 && short >= 0.5 * long && extremity {
            scored.push((upper + lower, [g, p, j]));
        }
    }
    scored.sort_by(|a, b| b.0.total_cmp(&a.0));
    let mut kept: Vec<[usize; 3]> = Vec::new();
    for (_, chain) in scored {
        if kept.len() == 4 {
            break;
        }
        if !kept.iter().any(|k| k.iter().any(|j| chain.contains(j))) {
            kept.push(chain);
        }
    }
    kept.sort_by(|a, b| at(a[2]).y.total_cmp(&at(b[2]).y));
    kept.into_iter()
        .filter_map(|[g, _, e]| Some((joints.get(e)?.name.clone(), Chain::new(skeleton, g, e).ok()?)))
        .collect()
}
