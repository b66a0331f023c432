//! Skins: a triangle mesh bound to a skeleton, each vertex moved by up to
//! [`MAX_INFLUENCES`] joints with weights summing to 1 (linear-blend skinning).
//!
//! Inputs: the bind-pose mesh (model space), per-vertex joint indices and
//! weights, and the skeleton's model transforms in the bind pose (their inverses
//! are the inverse bind matrices). Per frame, [`skinning_matrices`] turns posed
//! model transforms into one matrix per joint (`model · bind⁻¹`), and
//! [`skin_vertices`] is the CPU reference of what the renderer's vertex shader
//! does: `v' = Σ wᵢ · Mᵢ · v`. Rigid skinning is the same with one influence.

use crate::runtime::fk::Transform;
use glam::{Mat4, Vec3};

/// Most joints that move one vertex.
pub const MAX_INFLUENCES: usize = 4;

/// Why a skin cannot be built.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum SkinError {
    /// The per-vertex arrays differ in length.
    #[error("{positions} positions, {normals} normals and {influences} influence sets: one of each per vertex")]
    Lengths {
        /// Positions given.
        positions: usize,
        /// Normals given.
        normals: usize,
        /// Influence sets given.
        influences: usize,
    },
    /// A triangle corner names no vertex.
    #[error("triangle corner {corner} uses vertex {vertex}, but there are {count} vertices")]
    Index {
        /// Position in the index list.
        corner: usize,
        /// The vertex it names.
        vertex: u32,
        /// Vertices in the mesh.
        count: usize,
    },
    /// The index list is not whole triangles.
    #[error("{0} indices are not whole triangles")]
    Triangles(usize),
    /// An influence names a joint past the skeleton.
    #[error("vertex {vertex} is weighted to joint {joint}, but the skeleton has {joints} joints")]
    Joint {
        /// The vertex.
        vertex: usize,
        /// The joint it names.
        joint: u32,
        /// Joints in the bind pose.
        joints: usize,
    },
    /// A weight is negative or not finite, or all of a vertex's weights are zero
    /// (or, in a stored skin, they do not sum to 1).
    #[error(
        "vertex {vertex} has weights {weights:?}: each must be finite and ≥ 0, and their sum > 0 (1 in a stored skin)"
    )]
    Weights {
        /// The vertex.
        vertex: usize,
        /// Its weights as given.
        weights: [f32; MAX_INFLUENCES],
    },
    /// A bind-pose transform cannot be inverted (a zero scale) or is not finite.
    #[error("joint {0}'s bind transform cannot be inverted")]
    Bind(usize),
}

/// A mesh bound to a skeleton.
#[derive(Clone, Debug, PartialEq)]
pub struct Skin {
    positions: Vec<Vec3>,
    normals: Vec<Vec3>,
    indices: Vec<u32>,
    joints: Vec<[u32; MAX_INFLUENCES]>,
    weights: Vec<[f32; MAX_INFLUENCES]>,
    inverse_bind: Vec<Mat4>,
}

/// A transform as a matrix (scale, then rotate, then translate).
pub fn matrix(t: &Transform) -> Mat4 {
    Mat4::from_scale_rotation_translation(t.scale, t.rotation, t.translation)
}

impl Skin {
    /// Binds a mesh: `positions` and `normals` in the bind pose (model space),
    /// `indices` three per triangle, and per vertex up to four (joint, weight)
    /// influences (unused slots weight 0). `bind` holds every joint's model
    /// transform in the bind pose. Weights are normalised to sum to 1.
    pub fn new(
        positions: Vec<Vec3>,
        normals: Vec<Vec3>,
        indices: Vec<u32>,
        joints: Vec<[u32; MAX_INFLUENCES]>,
        weights: Vec<[f32; MAX_INFLUENCES]>,
        bind: &[Transform],
    ) -> Result<Skin, SkinError> {
        let mut inverse_bind = Vec::with_capacity(bind.len());
        for (j, t) in bind.iter().enumerate() {
            let m = matrix(t);
            if m.determinant().abs() < 1e-12 || !m.is_finite() {
                return Err(SkinError::Bind(j));
            }
            inverse_bind.push(m.inverse());
        }
        Skin::with_inverse_bind(positions, normals, indices, joints, weights, inverse_bind)
    }

    /// [`Skin::new`] with the inverse bind matrices given (one per joint, as glTF
    /// stores them) rather than computed from a bind pose.
    pub fn with_inverse_bind(
        positions: Vec<Vec3>,
        normals: Vec<Vec3>,
        indices: Vec<u32>,
        joints: Vec<[u32; MAX_INFLUENCES]>,
        weights: Vec<[f32; MAX_INFLUENCES]>,
        inverse_bind: Vec<Mat4>,
    ) -> Result<Skin, SkinError> {
        Skin::build(positions, normals, indices, joints, weights, inverse_bind, true)
    }

    /// [`Skin::with_inverse_bind`] for weights already normalised (a stored skin,
    /// [`crate::formats::store`]): the same checks, and each vertex's weights
    /// must sum to 1 (within 1e-4); they are kept bit for bit.
    pub(crate) fn with_unit_weights(
        positions: Vec<Vec3>,
        normals: Vec<Vec3>,
        indices: Vec<u32>,
        joints: Vec<[u32; MAX_INFLUENCES]>,
        weights: Vec<[f32; MAX_INFLUENCES]>,
        inverse_bind: Vec<Mat4>,
    ) -> Result<Skin, SkinError> {
        Skin::build(positions, normals, indices, joints, weights, inverse_bind, false)
    }

    /// The checks of [`Skin::with_inverse_bind`]; `normalise` divides each
    /// vertex's weights by their sum, otherwise the sum must be 1 already.
    fn build(
        positions: Vec<Vec3>,
        normals: Vec<Vec3>,
        indices: Vec<u32>,
        joints: Vec<[u32; MAX_INFLUENCES]>,
        weights: Vec<[f32; MAX_INFLUENCES]>,
        inverse_bind: Vec<Mat4>,
        normalise: bool,
    ) -> Result<Skin, SkinError> {
        let n = positions.len();
        if normals.len() != n || joints.len() != n || weights.len() != n {
            return Err(SkinError::Lengths {
                positions: n,
                normals: normals.len(),
                influences: joints.len().min(weights.len()),
            });
        }
        if indices.len() % 3 != 0 {
            return Err(SkinError::Triangles(indices.len()));
        }
        if let Some((corner, &vertex)) = indices.iter().enumerate().find(|(_, v)| **v as usize >= n) {
            return Err(SkinError::Index { corner, vertex, count: n });
        }
        if let Some(j) = inverse_bind.iter().position(|m| !m.is_finite()) {
            return Err(SkinError::Bind(j));
        }
        let mut normalised = weights;
        for (vertex, (w, js)) in normalised.iter_mut().zip(&joints).enumerate() {
            let sum: f32 = w.iter().sum();
            let unit = normalise || (sum - 1.0).abs() <= 1e-4;
            if w.iter().any(|x| !x.is_finite() || *x < 0.0) || !(sum > 0.0) || !sum.is_finite() || !unit {
                return Err(SkinError::Weights { vertex, weights: *w });
            }
            for (k, weight) in w.iter_mut().enumerate() {
                if *weight > 0.0 && js[k] as usize >= inverse_bind.len() {
                    return Err(SkinError::Joint { vertex, joint: js[k], joints: inverse_bind.len() });
                }
                if normalise {
                    *weight /= sum;
                }
            }
        }
        Ok(Skin { positions, normals, indices, joints, weights: normalised, inverse_bind })
    }

    /// Bind-pose positions (model space).
    pub fn positions(&self) -> &[Vec3] {
        &self.positions
    }

    /// Bind-pose unit normals.
    pub fn normals(&self) -> &[Vec3] {
        &self.normals
    }

    /// Three vertex indices per triangle.
    pub fn indices(&self) -> &[u32] {
        &self.indices
    }

    /// Joint indices per vertex (slots with weight 0 are unused).
    pub fn joints(&self) -> &[[u32; MAX_INFLUENCES]] {
        &self.joints
    }

    /// Weights per vertex, summing to 1.
    pub fn weights(&self) -> &[[f32; MAX_INFLUENCES]] {
        &self.weights
    }

    /// One inverse bind matrix per joint.
    pub fn inverse_bind(&self) -> &[Mat4] {
        &self.inverse_bind
    }
}

/// Skinning matrices for a pose: `matrix(model[j]) · inverse_bind[j]` per joint
/// (identity past the end of either), into `out` (cleared first).
pub fn skinning_matrices(model: &[Transform], inverse_bind: &[Mat4], out: &mut Vec<Mat4>) {
    out.clear();
    out.extend(
        inverse_bind.iter().enumerate().map(|(j, inv)| model.get(j).map_or(Mat4::IDENTITY, |t| matrix(t) * *inv)),
    );
}

/// Linear-blend skinning on the CPU (the reference the GPU path is tested
/// against): every vertex moved by `Σ wᵢ · matrices[jᵢ]`, normals by the same
/// blend (renormalised). `out_positions` and `out_normals` are cleared first.
pub fn skin_vertices(skin: &Skin, matrices: &[Mat4], out_positions: &mut Vec<Vec3>, out_normals: &mut Vec<Vec3>) {
    out_positions.clear();
    out_normals.clear();
    for (((p, n), js), ws) in skin.positions.iter().zip(&skin.normals).zip(&skin.joints).zip(&skin.weights) {
        let mut m = Mat4::ZERO;
        for (j, w) in js.iter().zip(ws) {
            if *w > 0.0 {
                m += *matrices.get(*j as usize).unwrap_or(&Mat4::IDENTITY) * *w;
            }
        }
        out_positions.push(m.transform_point3(*p));
        out_normals.push(m.transform_vector3(*n).normalize_or_zero());
    }
}
