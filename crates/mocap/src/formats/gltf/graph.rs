//! The node graph of a glTF scene, flattened without recursion, and the joints
//! picked from it.
//!
//! Inputs: a checked document. Output: a [`Graph`]: the scene's nodes in
//! parent-before-child order (a node with two parents, or a cycle, is an error),
//! the skeleton's joints (every joint of the skins the scene uses, or every node
//! when there is no skin), each joint's parent joint and the static transform of
//! the non-joint nodes between them (for a root joint: everything above it), so
//! that a joint's local transform is `between · TRS(node)`.

use crate::error::ParseError;
use glam::{Mat4, Quat, Vec3};

/// A node's transform as translation, rotation and scale.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Trs {
    /// Translation.
    pub t: Vec3,
    /// Rotation (unit).
    pub r: Quat,
    /// Scale.
    pub s: Vec3,
}

impl Trs {
    /// The node's rest transform (a matrix is decomposed).
    pub fn of(node: &gltf::Node<'_>) -> Trs {
        let (t, r, s) = node.transform().decomposed();
        let r = Quat::from_array(r);
        let r = if r.is_finite() && r.length_squared() > 0.0 { r.normalize() } else { Quat::IDENTITY };
        Trs { t: Vec3::from_array(t), r, s: Vec3::from_array(s) }
    }

    /// As a matrix.
    pub fn matrix(&self) -> Mat4 {
        Mat4::from_scale_rotation_translation(self.s, self.r, self.t)
    }

    /// `between · self`, decomposed (exact when `between` has a uniform scale).
    pub fn after(&self, between: &Mat4) -> Trs {
        if *between == Mat4::IDENTITY {
            return *self;
        }
        let (s, r, t) = (*between * self.matrix()).to_scale_rotation_translation();
        Trs { t, r: r.normalize(), s }
    }
}

/// The scene's nodes and the skeleton's joints.
#[derive(Clone, Debug, Default)]
pub struct Graph {
    /// The scene's nodes, parents first.
    pub order: Vec<usize>,
    /// Parent node of each node of the file.
    pub parent: Vec<Option<usize>>,
    /// Node index of each skeleton joint, parents first.
    pub joints: Vec<usize>,
    /// Skeleton joint of each node, if it is one.
    pub joint_of: Vec<Option<usize>>,
    /// Parent joint of each joint.
    pub joint_parent: Vec<Option<usize>>,
    /// For each node: its nearest joint strictly above it.
    pub above: Vec<Option<usize>>,
    /// For each node: the transform of the non-joint nodes strictly between
    /// [`Graph::above`] (or the scene root) and the node.
    pub between: Vec<Mat4>,
    /// Every node's rest transform.
    pub rest: Vec<Trs>,
}

impl Graph {
    /// Flattens the default scene (or the first, or every parentless node when
    /// the file has no scene) and picks the joints.
    pub fn new(document: &gltf::Document) -> Result<Graph, ParseError> {
        let count = document.nodes().len();
        let mut parent: Vec<Option<usize>> = vec![None; count];
        for node in document.nodes() {
            for child in node.children() {
                let c = child.index();
                if let Some(p) = parent.get(c).copied().flatten() {
                    return Err(ParseError::new(
                        0,
                        0,
                        format!("nodes[{c}]: it is a child of both nodes[{p}] and nodes[{}]", node.index()),
                    ));
                }
                if let Some(slot) = parent.get_mut(c) {
                    *slot = Some(node.index());
                }
            }
        }
        let scene = document.default_scene().or_else(|| document.scenes().next());
        let roots: Vec<usize> = match &scene {
            Some(scene) => scene.nodes().map(|n| n.index()).collect(),
            None => (0..count).filter(|&n| parent[n].is_none()).collect(),
        };
        if let Some(&r) = roots.iter().find(|&&r| parent.get(r).copied().flatten().is_some()) {
            let p = parent[r].unwrap_or(0);
            return Err(ParseError::new(0, 0, format!("nodes[{r}]: a scene root, and a child of nodes[{p}]")));
        }
        let nodes: Vec<gltf::Node<'_>> = document.nodes().collect();
        let mut order = Vec::with_capacity(count);
        let mut seen = vec![false; count];
        let mut stack: Vec<usize> = roots.iter().rev().copied().collect();
        while let Some(n) = stack.pop() {
            match seen.get_mut(n) {
                Some(s) if !*s => *s = true,
                _ => {
                    return Err(ParseError::new(
                        0,
                        0,
                        format!("nodes[{n}]: reached twice (a cycle in the node graph)"),
                    ));
                }
            }
            order.push(n);
            let children: Vec<usize> =
                nodes.get(n).map_or(Vec::new(), |node| node.children().map(|c| c.index()).collect());
            stack.extend(children.into_iter().rev());
        }
        // A cycle not reachable from the roots leaves its nodes unvisited; those
        // nodes are not in the scene, so they are simply not read.
        let rest: Vec<Trs> = nodes.iter().map(Trs::of).collect();
        let is_joint = joint_set(document, &nodes, &order, count);
        let mut graph = Graph {
            order,
            parent,
            joints: Vec::new(),
            joint_of: vec![None; count],
            joint_parent: Vec::new(),
            above: vec![None; count],
            between: vec![Mat4::IDENTITY; count],
            rest,
        };
        for k in 0..graph.order.len() {
            let n = graph.order[k];
            if let Some(p) = graph.parent[n] {
                let p_joint = graph.joint_of[p];
                graph.above[n] = p_joint.or(graph.above[p]);
                graph.between[n] =
                    if p_joint.is_some() { Mat4::IDENTITY } else { graph.between[p] * graph.rest[p].matrix() };
            }
            if is_joint[n] {
                graph.joint_of[n] = Some(graph.joints.len());
                graph.joint_parent.push(graph.above[n]);
                graph.joints.push(n);
            }
        }
        Ok(graph)
    }

    /// A joint's rest transform relative to its parent joint.
    pub fn joint_rest(&self, joint: usize) -> Trs {
        let n = self.joints.get(joint).copied().unwrap_or(0);
        let rest = self.rest.get(n).copied().unwrap_or(Trs { t: Vec3::ZERO, r: Quat::IDENTITY, s: Vec3::ONE });
        rest.after(self.between.get(n).unwrap_or(&Mat4::IDENTITY))
    }

    /// Every joint's world transform at rest (parents first).
    pub fn joint_world_rest(&self) -> Vec<Mat4> {
        let mut world: Vec<Mat4> = Vec::with_capacity(self.joints.len());
        for j in 0..self.joints.len() {
            let local = self.joint_rest(j).matrix();
            let parent = self.joint_parent.get(j).copied().flatten().and_then(|p| world.get(p)).copied();
            world.push(parent.map_or(local, |p| p * local));
        }
        world
    }
}

/// Which nodes are joints: those of every skin used by a node of the scene (or
/// of every skin, when the scene uses none), else every node of the scene.
fn joint_set(document: &gltf::Document, nodes: &[gltf::Node<'_>], order: &[usize], count: usize) -> Vec<bool> {
    let mut is_joint = vec![false; count];
    let mut used: Vec<usize> = order.iter().filter_map(|&n| nodes.get(n)?.skin().map(|s| s.index())).collect();
    if used.is_empty() {
        used = document.skins().map(|s| s.index()).collect();
    }
    let mut in_scene = vec![false; count];
    order.iter().for_each(|&n| in_scene[n] = true);
    for skin in document.skins().filter(|s| used.contains(&s.index())) {
        for joint in skin.joints() {
            if in_scene.get(joint.index()).copied().unwrap_or(false) {
                is_joint[joint.index()] = true;
            }
        }
    }
    if !is_joint.contains(&true) {
        return in_scene;
    }
    is_joint
}
