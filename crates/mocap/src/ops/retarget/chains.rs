//! Joint mapping by the shape of the tree, for skeletons whose names say nothing
//! (`j12`, `Bone.004`) or say it in a convention [`canonical_name`] does not know.
//!
//! Input: a skeleton and its joints' positions in one pose (any orientation: the
//! rest pose, lying on its side or not). Output: its [`Body`]: the hips, the
//! spine to the head, two arms and two legs, each a chain of joints in
//! parent-before-child order, found from the tree and the bones' lengths alone:
//! - the hips are the first joint below the root with two or more children;
//! - two children of one joint are a pair when they mirror each other (as many
//!   joints, within a fifth, and as far a reach); the hips' farthest-reaching
//!   pair are the legs;
//! - the spine runs from the hips' largest other child along the largest
//!   subtrees; the chest is the joint on it whose pair reaches farthest (the
//!   arms: breasts, eyes and fingers are pairs too, shorter); the farthest-
//!   reaching other child of the chest is the neck, which runs on to the head;
//! - a star (arms, legs and neck all from one joint, as Kinect exports are):
//!   of the hips' two pairs, the legs point away from the neck;
//! - a limb runs from the joint below its branch while each joint has one child
//!   (stopping at the hand or foot, where fingers or toes branch);
//! - left and right: by name where the names say so (`l_`, `Left`, …), else by
//!   geometry: up is hips to head, forward the way the feet point (toes), and
//!   left is up × forward.
//!
//! [`match_bodies`] pairs two bodies joint for joint: hips to hips, chest to
//! chest, head to head; limbs joint for joint at the shift of one along the
//! other that best matches their bones' relative lengths (a clavicle or a hip
//! joint on one side only is left out); the joints between the hips and the
//! chest, and between the chest and the head, by their fraction of the way. Everything is iterative; no recursion on
//! the tree's depth.

use crate::model::skeleton::Skeleton;
use crate::ops::layer::canonical_name;
use glam::{Quat, Vec3};

/// Every joint's position built from the skeleton's offsets and rest rotations
/// alone: the shape of the skeleton even where position channels at zero would
/// put every joint on its parent (MakeHuman's exports).
pub fn rest_positions(skeleton: &Skeleton) -> Vec<Vec3> {
    let joints = skeleton.joints();
    let mut at: Vec<Vec3> = Vec::with_capacity(joints.len());
    let mut turn: Vec<Quat> = Vec::with_capacity(joints.len());
    for (i, j) in joints.iter().enumerate() {
        let (p, r) = j.parent.filter(|&p| p < i).map_or((Vec3::ZERO, Quat::IDENTITY), |p| (at[p], turn[p]));
        at.push(p + r * j.offset);
        turn.push(r * j.rest_rotation);
    }
    at
}

/// A limb: its joints from the branch outwards and their bones' lengths.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Limb {
    /// The joints, parent before child (End Sites left out).
    pub joints: Vec<usize>,
    /// Each joint's bone length: to the next joint, the last one's to its End
    /// Site (0 without one).
    pub lengths: Vec<f32>,
}

/// The chains a humanoid skeleton is made of.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Body {
    /// The hips (the first branching joint below the root).
    pub hips: usize,
    /// The joints between the hips and the chest.
    pub spine: Vec<usize>,
    /// Where the arms branch (the hips themselves in a star-shaped skeleton).
    pub chest: usize,
    /// From the chest's neck child up to the head.
    pub neck: Vec<usize>,
    /// Left and right arm.
    pub arms: [Limb; 2],
    /// Left and right leg.
    pub legs: [Limb; 2],
}

impl Body {
    /// Every joint of the body with the name of its chain (`hips`, `spine`,
    /// `neck`, `left arm`, `right arm`, `left leg`, `right leg`).
    pub fn labels(&self) -> Vec<(usize, &'static str)> {
        let mut out = vec![(self.hips, "hips")];
        out.extend(self.spine.iter().map(|&j| (j, "spine")));
        if self.chest != self.hips {
            out.push((self.chest, "spine"));
        }
        out.extend(self.neck.iter().map(|&j| (j, "neck")));
        for (limb, name) in [
            (&self.arms[0], "left arm"),
            (&self.arms[1], "right arm"),
            (&self.legs[0], "left leg"),
            (&self.legs[1], "right leg"),
        ] {
            out.extend(limb.joints.iter().map(|&j| (j, name)));
        }
        out
    }
}

/// The tree's children lists (End Sites left out) and subtree sizes.
struct Tree {
    children: Vec<Vec<usize>>,
    /// Joints in each subtree (itself included), End Sites left out.
    size: Vec<usize>,
    /// An End Site child's position, per joint, when it has one (a limb's tip).
    tip: Vec<Option<Vec3>>,
}

impl Tree {
    fn new(skeleton: &Skeleton, at: &[Vec3]) -> Tree {
        let n = skeleton.len();
        let mut children = vec![Vec::new(); n];
        let mut tip = vec![None; n];
        for (i, j) in skeleton.joints().iter().enumerate() {
            let Some(p) = j.parent.filter(|&p| p < i) else { continue };
            if skeleton.is_end_site(i) {
                tip[p] = at.get(i).copied();
            } else {
                children[p].push(i);
            }
        }
        let mut size = vec![1usize; n];
        // Parents come before children: one backward pass sums the subtrees.
        for i in (0..n).rev() {
            if let Some(p) = skeleton.joints()[i].parent.filter(|&p| p < i && !skeleton.is_end_site(i)) {
                size[p] += size[i];
            }
        }
        Tree { children, size, tip }
    }

    /// From `start`, down while a joint has one child that reaches more than
    /// twice as far as any other (helper bones hang off limbs; a hand's fingers
    /// reach alike, so the run stops there): the path, `start` included.
    fn run(&self, start: usize, at: &[Vec3]) -> Vec<usize> {
        let mut path = vec![start];
        let mut j = start;
        loop {
            let next = match self.children[j].as_slice() {
                [] => break,
                [only] => *only,
                kids => {
                    let mut reach: Vec<(f32, usize)> = kids.iter().map(|&c| (self.reach_len(c, j, at), c)).collect();
                    reach.sort_by(|x, y| y.0.total_cmp(&x.0));
                    match reach.as_slice() {
                        [(far, c), (second, _), ..] if *far > 2.0 * *second => *c,
                        _ => break,
                    }
                }
            };
            path.push(next);
            j = next;
        }
        path
    }

    /// How far the subtree of `c` reaches from joint `from`.
    fn reach_len(&self, c: usize, from: usize, at: &[Vec3]) -> f32 {
        self.reach(c, at[from], at).distance(at[from])
    }

    /// Pairs of `j`'s children that mirror each other (two arms, two legs): the
    /// same number of joints (within a fifth) and reaches within half of each
    /// other (captured rest poses are not symmetric), the most alike paired first,
    /// each child in one pair at most. Reaches are measured only for pairs of matching size, so the work
    /// stays linear in the tree.
    fn pairs(&self, j: usize, at: &[Vec3]) -> Vec<(usize, usize)> {
        let kids = &self.children[j];
        let mut out = Vec::new();
        for (x, &a) in kids.iter().enumerate() {
            for &b in &kids[x + 1..] {
                let (sa, sb) = (self.size[a], self.size[b]);
                if sa.abs_diff(sb) > sa.max(sb) / 5 {
                    continue;
                }
                let (ra, rb) = (self.reach_len(a, j, at), self.reach_len(b, j, at));
                if ra.min(rb) >= 0.5 * ra.max(rb) && ra.max(rb) > 0.0 {
                    out.push((a, b, ra.min(rb) / ra.max(rb)));
                }
            }
        }
        // The most alike first, each child in one pair.
        out.sort_by(|x, y| y.2.total_cmp(&x.2));
        let mut taken: Vec<usize> = Vec::new();
        let mut pairs = Vec::new();
        for (a, b, _) in out {
            if !taken.contains(&a) && !taken.contains(&b) {
                taken.extend([a, b]);
                pairs.push((a, b));
            }
        }
        // The farthest-reaching first.
        let reach = |p: &(usize, usize)| self.reach_len(p.0, j, at);
        pairs.sort_by(|x, y| reach(y).total_cmp(&reach(x)));
        pairs
    }

    /// The point farthest from `from` in the subtree of `start` (tips included).
    fn reach(&self, start: usize, from: Vec3, at: &[Vec3]) -> Vec3 {
        let mut best = at[start];
        let mut stack = vec![start];
        while let Some(j) = stack.pop() {
            for p in std::iter::once(at[j]).chain(self.tip[j]) {
                if p.distance_squared(from) > best.distance_squared(from) {
                    best = p;
                }
            }
            stack.extend(&self.children[j]);
        }
        best
    }
}

/// The body of `skeleton` with joint positions `at` (one per joint, one pose), or
/// `None` when the tree is not a humanoid's (no two legs, a spine with two arms).
pub fn find_body(skeleton: &Skeleton, at: &[Vec3]) -> Option<Body> {
    if at.len() != skeleton.len() || at.iter().any(|p| !p.is_finite()) {
        return None;
    }
    let tree = Tree::new(skeleton, at);
    // The root with the largest tree.
    let root = (0..skeleton.len())
        .filter(|&i| skeleton.joints()[i].parent.is_none() && !skeleton.is_end_site(i))
        .max_by_key(|&i| tree.size[i])?;
    let hips = *tree.run(root, at).last()?;
    let mut pairs = tree.pairs(hips, at);
    let ((l1, l2), (a, b), chest, spine) = if pairs.len() >= 2 {
        // A star (Kinect-style): arms and legs all branch from one joint; the legs
        // point away from the neck (the farthest-reaching unpaired child).
        let neck = tree.children[hips]
            .iter()
            .copied()
            .filter(|c| !pairs.iter().any(|p| p.0 == *c || p.1 == *c))
            .max_by(|&x, &y| tree.reach_len(x, hips, at).total_cmp(&tree.reach_len(y, hips, at)))?;
        let towards = |c: usize| (tree.reach(c, at[hips], at) - at[hips]).normalize_or_zero();
        let away = |p: &(usize, usize)| (towards(p.0) + towards(p.1)).dot(towards(neck));
        pairs.sort_by(|x, y| away(x).total_cmp(&away(y)));
        (pairs[0], pairs[1], hips, Vec::new())
    } else {
        let legs = *pairs.first()?;
        // The spine: along the largest subtrees, up to the joint where the
        // farthest-reaching pair branches (the chest; breasts and eyes are pairs
        // too, nearer).
        let up = tree.children[hips]
            .iter()
            .copied()
            .filter(|&c| c != legs.0 && c != legs.1)
            .max_by_key(|&c| tree.size[c])?;
        let mut path = vec![up];
        let mut best: Option<(f32, usize, (usize, usize))> = None;
        while let Some(&j) = path.last() {
            for p in tree.pairs(j, at) {
                let reach = tree.reach_len(p.0, j, at).min(tree.reach_len(p.1, j, at));
                if best.is_none_or(|b| reach > b.0) {
                    best = Some((reach, path.len() - 1, p));
                }
            }
            let Some(next) = tree.children[j].iter().copied().max_by_key(|&c| tree.size[c]) else { break };
            path.push(next);
        }
        let (_, at_chest, arms) = best?;
        path.truncate(at_chest + 1);
        let chest = path.pop()?;
        (legs, arms, chest, path)
    };
    let head_start = tree.children[chest]
        .iter()
        .copied()
        .filter(|&c| c != a && c != b && c != l1 && c != l2)
        .max_by(|&x, &y| tree.reach_len(x, chest, at).total_cmp(&tree.reach_len(y, chest, at)))?;
    let neck = tree.run(head_start, at);
    let limb = |start: usize| -> Limb {
        let joints = tree.run(start, at);
        let lengths = bone_lengths(&joints, &tree, at);
        Limb { joints, lengths }
    };
    let (arm_a, arm_b, leg_a, leg_b) = (limb(a), limb(b), limb(l1), limb(l2));
    let head = *neck.last()?;
    let up_dir = (at[head] - at[hips]).normalize_or_zero();
    let forward = forward(&[&leg_a, &leg_b], &tree, at, up_dir);
    let left_dir = up_dir.cross(forward);
    let arms = sided(skeleton, arm_a, arm_b, at, at[chest], left_dir);
    let legs = sided(skeleton, leg_a, leg_b, at, at[hips], left_dir);
    Some(Body { hips, spine, chest, neck, arms, legs })
}

/// Each joint's bone length along a chain (the last one's to its End Site).
fn bone_lengths(joints: &[usize], tree: &Tree, at: &[Vec3]) -> Vec<f32> {
    joints
        .iter()
        .enumerate()
        .map(|(k, &j)| match joints.get(k + 1) {
            Some(&next) => at[j].distance(at[next]),
            None => tree.tip[j].map_or(0.0, |t| at[j].distance(t)),
        })
        .collect()
}

/// The way the feet point (their last bone, across `up`), else the one of ±Z, ±X
/// most across `up`.
fn forward(legs: &[&Limb], tree: &Tree, at: &[Vec3], up: Vec3) -> Vec3 {
    let across = |v: Vec3| v - up * v.dot(up);
    let mut sum = Vec3::ZERO;
    for leg in legs {
        let Some(&last) = leg.joints.last() else { continue };
        // The foot's bone: to the tip, or from the joint before the last.
        let bone = match tree.tip[last] {
            Some(t) => t - at[last],
            None => leg.joints.iter().rev().nth(1).map_or(Vec3::ZERO, |&p| at[last] - at[p]),
        };
        let flat = across(bone);
        if flat.length() > 0.3 * bone.length() {
            sum += flat.normalize();
        }
    }
    if sum.length() > 1e-3 {
        return sum.normalize();
    }
    [Vec3::Z, Vec3::X].into_iter().map(across).find(|v| v.length() > 0.5).map_or(Vec3::Z, Vec3::normalize)
}

/// `[left, right]`: by the names' sides when they agree, else the one whose end
/// lies farther along `left` from `centre`.
fn sided(skeleton: &Skeleton, a: Limb, b: Limb, at: &[Vec3], centre: Vec3, left: Vec3) -> [Limb; 2] {
    let side = |limb: &Limb| -> Option<bool> {
        let names = limb.joints.iter().filter_map(|&j| skeleton.joints().get(j)).map(|j| canonical_name(&j.name));
        let (mut l, mut r) = (0, 0);
        for n in names {
            l += usize::from(n.starts_with("left"));
            r += usize::from(n.starts_with("right"));
        }
        (l != r).then_some(l > r)
    };
    match (side(&a), side(&b)) {
        (Some(true), Some(false)) => return [a, b],
        (Some(false), Some(true)) => return [b, a],
        _ => {}
    }
    let end = |limb: &Limb| limb.joints.last().map_or(0.0, |&j| (at[j] - centre).dot(left));
    if end(&a) >= end(&b) { [a, b] } else { [b, a] }
}

/// (target joint, source joint) pairs of two bodies (see the module documentation).
pub fn match_bodies(target: &Body, t_at: &[Vec3], source: &Body, s_at: &[Vec3]) -> Vec<(usize, usize)> {
    let mut pairs = vec![(target.hips, source.hips)];
    for (t, s) in target.arms.iter().zip(&source.arms).chain(target.legs.iter().zip(&source.legs)) {
        match_limbs(t, s, &mut pairs);
    }
    // Chest to chest and head to head; the joints between by fraction of the way.
    if let (Some(&th), Some(&sh)) = (target.neck.last(), source.neck.last()) {
        let (tc, sc) = (target.chest, source.chest);
        if (tc == target.hips) == (sc == source.hips) {
            pairs.push((tc, sc));
        }
        pairs.push((th, sh));
        let inner = |chain: &[usize]| chain.split_last().map_or(Vec::new(), |(_, rest)| rest.to_vec());
        let t_side = Segment { joints: &target.spine, at: t_at, from: target.hips, to: tc };
        let s_side = Segment { joints: &source.spine, at: s_at, from: source.hips, to: sc };
        by_fraction(&t_side, &s_side, &mut pairs);
        let t_side = Segment { joints: &inner(&target.neck), at: t_at, from: tc, to: th };
        let s_side = Segment { joints: &inner(&source.neck), at: s_at, from: sc, to: sh };
        by_fraction(&t_side, &s_side, &mut pairs);
    }
    pairs
}

/// Limbs paired joint for joint at the shift of one along the other whose bones'
/// lengths (each over its limb's longest; bones between the limb's joints, not
/// the last joint's, which a hand's fingers make unknown) differ least: a limb
/// with a clavicle or a hip joint pairs its upper arm or thigh with the other's.
fn match_limbs(t: &Limb, s: &Limb, pairs: &mut Vec<(usize, usize)>) {
    let bones = |l: &Limb| {
        let inner = l.lengths.get(..l.lengths.len().saturating_sub(1)).unwrap_or(&[]);
        let max = inner.iter().copied().fold(0.0f32, f32::max);
        inner.iter().map(|x| if max > 0.0 { x / max } else { 0.0 }).collect::<Vec<f32>>()
    };
    let (tb, sb) = (bones(t), bones(s));
    let (nt, ns) = (tb.len() as isize, sb.len() as isize);
    // Shift d pairs target joint k (and bone k) with source joint k - d.
    let cost = |d: isize| -> f32 {
        let (mut sum, mut n) = (0.0, 0isize);
        for k in d.max(0)..nt.min(ns + d) {
            let diff = tb[k as usize] - sb[(k - d) as usize];
            sum += diff * diff;
            n += 1;
        }
        if n == 0 { f32::INFINITY } else { sum / n as f32 + 0.02 * (nt + ns - 2 * n) as f32 }
    };
    let d = (-(ns - 1).max(0)..=(nt - 1).max(0))
        .min_by(|&a, &b| cost(a).total_cmp(&cost(b)).then(a.abs().cmp(&b.abs())))
        .unwrap_or(0);
    let (jt, js) = (t.joints.len() as isize, s.joints.len() as isize);
    for k in d.max(0)..jt.min(js + d) {
        pairs.push((t.joints[k as usize], s.joints[(k - d) as usize]));
    }
}

/// The joints strictly between two joints of a chain, with the pose's positions.
struct Segment<'a> {
    joints: &'a [usize],
    at: &'a [Vec3],
    from: usize,
    to: usize,
}

impl Segment<'_> {
    /// Each joint's fraction of the way from `from` to `to` along the chain.
    fn fractions(&self) -> Vec<f32> {
        let mut run = 0.0;
        let mut prev = self.at[self.from];
        let mut out = Vec::with_capacity(self.joints.len());
        for &j in self.joints {
            run += prev.distance(self.at[j]);
            prev = self.at[j];
            out.push(run);
        }
        let total = run + prev.distance(self.at[self.to]);
        out.into_iter().map(|x| if total > 0.0 { x / total } else { 0.0 }).collect()
    }
}

/// The joints of two segments paired by their fraction of the way, in order,
/// each source joint once: a target joint takes the nearest source joint not yet
/// taken, unless the next target joint is nearer to it.
fn by_fraction(t: &Segment, s: &Segment, pairs: &mut Vec<(usize, usize)>) {
    let (tf, sf) = (t.fractions(), s.fractions());
    let mut next = 0;
    for (k, &f) in tf.iter().enumerate() {
        let Some(best) = (next..sf.len()).min_by(|&x, &y| (sf[x] - f).abs().total_cmp(&(sf[y] - f).abs())) else {
            break;
        };
        let nearer_next = tf.get(k + 1).is_some_and(|&g| (sf[best] - g).abs() < (sf[best] - f).abs());
        if !nearer_next {
            pairs.push((t.joints[k], s.joints[best]));
            next = best + 1;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::skeleton::{EulerConvention, Joint};

    fn walk() -> crate::Clip {
        crate::formats::bvh::parse(include_bytes!("../../../../../data/walk.bvh")).unwrap()
    }

    fn names<'a>(s: &'a Skeleton, joints: &[usize]) -> Vec<&'a str> {
        joints.iter().map(|&j| s.joints()[j].name.as_str()).collect()
    }

    #[test]
    fn the_walks_chains_are_found_with_their_sides() {
        let clip = walk();
        let s = clip.skeleton();
        let body = find_body(s, &rest_positions(s)).unwrap();
        assert_eq!(s.joints()[body.hips].name, "Hips");
        assert_eq!(names(s, &body.spine), ["Spine"]);
        assert_eq!(s.joints()[body.chest].name, "Chest");
        assert_eq!(names(s, &body.neck), ["Neck", "Head"]);
        assert_eq!(names(s, &body.arms[0].joints), ["LeftShoulder", "LeftArm", "LeftForeArm", "LeftHand"]);
        assert_eq!(names(s, &body.arms[1].joints), ["RightShoulder", "RightArm", "RightForeArm", "RightHand"]);
        assert_eq!(names(s, &body.legs[0].joints), ["LeftUpLeg", "LeftLeg", "LeftFoot", "LeftToe"]);
        assert_eq!(names(s, &body.legs[1].joints), ["RightUpLeg", "RightLeg", "RightFoot", "RightToe"]);
        let labels = body.labels();
        assert_eq!(labels.len(), 1 + 2 + 2 + 4 * 4);
        assert!(labels.contains(&(s.find("RightForeArm").unwrap(), "right arm")));
    }

    #[test]
    fn a_limb_with_a_clavicle_pairs_its_upper_arm_with_one_without() {
        let with = Limb { joints: vec![10, 11, 12, 13], lengths: vec![0.4, 1.0, 0.9, 0.3] };
        let without = Limb { joints: vec![20, 21, 22], lengths: vec![1.0, 0.85, 0.35] };
        let mut pairs = Vec::new();
        match_limbs(&with, &without, &mut pairs);
        assert_eq!(pairs, [(11, 20), (12, 21), (13, 22)]);
        pairs.clear();
        match_limbs(&without, &with, &mut pairs);
        assert_eq!(pairs, [(20, 11), (21, 12), (22, 13)]);
    }

    #[test]
    fn segments_pair_by_fraction_each_source_joint_once() {
        // Three joints evenly up a segment against one halfway: the middle one takes it.
        let at: Vec<Vec3> = (0..6).map(|i| Vec3::new(0.0, i as f32, 0.0)).collect();
        let t = Segment { joints: &[1, 2, 3], at: &at, from: 0, to: 4 };
        let s_at = [Vec3::ZERO, Vec3::Y, Vec3::Y * 2.0];
        let s = Segment { joints: &[1], at: &s_at, from: 0, to: 2 };
        let mut pairs = Vec::new();
        by_fraction(&t, &s, &mut pairs);
        assert_eq!(pairs, [(2, 1)]);
    }

    #[test]
    fn a_tree_that_is_not_a_body_has_none_without_recursion() {
        let chain = |n: usize| {
            let joints =
                (0..n).map(|i| Joint::new(format!("j{i}"), i.checked_sub(1), Vec3::Y, vec![])).collect::<Vec<_>>();
            Skeleton::new(joints, EulerConvention::Intrinsic).unwrap()
        };
        for n in [1, 5, 200_000] {
            let s = chain(n);
            assert!(find_body(&s, &rest_positions(&s)).is_none());
        }
        let s = chain(3);
        assert!(find_body(&s, &[Vec3::NAN; 3]).is_none(), "non-finite positions");
        assert!(find_body(&s, &[]).is_none(), "positions missing");
    }
}
