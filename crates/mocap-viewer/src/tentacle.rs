//! The bendy-tentacle demo: a chain of bones ([`mocap::build::demo::tentacle`]) with one
//! soft or rigid skin, bent by sliders (forward kinematics) and, when following,
//! pulled toward a target sphere the user drags in the view (IK, solver chosen).
//!
//! The demo's pose is built each frame as a correction of the tentacle's single
//! frame: slider rotations first, then the solver from there toward the target.

use crate::character::{Character, Correction};
use mocap::glam::{Quat, Vec3};
use mocap::runtime::ik::{self, Chain, Options};
use mocap_scene::Body;

/// The IK solvers the demo offers.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Solver {
    /// Analytic, two bones (with more bones, FABRIK is used).
    TwoBone,
    /// Cyclic coordinate descent.
    Ccd,
    /// Forward and backward reaching.
    #[default]
    Fabrik,
}

impl Solver {
    /// Every solver, in menu order.
    pub const ALL: [Solver; 3] = [Solver::TwoBone, Solver::Ccd, Solver::Fabrik];

    /// Name in menus, the JS API and tests.
    pub fn name(self) -> &'static str {
        match self {
            Solver::TwoBone => "two-bone",
            Solver::Ccd => "ccd",
            Solver::Fabrik => "fabrik",
        }
    }

    /// The solver called `name`.
    pub fn from_name(name: &str) -> Option<Solver> {
        Solver::ALL.into_iter().find(|s| s.name() == name)
    }
}

/// The demo's settings.
#[derive(Clone, Debug, PartialEq)]
pub struct Tentacle {
    /// Bones in the chain.
    pub bones: usize,
    /// Per bone: bend about Z and swing about X, degrees.
    pub angles: Vec<[f32; 2]>,
    /// Pull the tip toward the target by IK.
    pub follow: bool,
    /// The target (world, metres).
    pub target: Vec3,
    /// Which solver pulls it.
    pub solver: Solver,
    /// Soft skin (blended across joints) or rigid (each vertex on one bone).
    pub soft: bool,
    /// Where the tip was drawn last (world).
    pub tip: Vec3,
}

impl Tentacle {
    /// A tentacle of `bones` bones, slightly bent, following a target to its side.
    pub fn new(bones: usize) -> Tentacle {
        let bones = bones.clamp(*mocap::build::demo::BONES.start(), *mocap::build::demo::BONES.end());
        let length = bones as f32 * mocap::build::demo::BONE_LENGTH;
        Tentacle {
            bones,
            angles: (0..bones).map(|b| [if b == 0 { -10.0 } else { 20.0 }, 0.0]).collect(),
            follow: true,
            target: Vec3::new(length * 0.45, length * 0.7, 0.15 * length),
            solver: Solver::default(),
            soft: true,
            tip: Vec3::ZERO,
        }
    }

    /// The skin for the current softness, as the renderer draws it.
    pub fn body(&self, clip: &mocap::Clip) -> Option<Body> {
        let skin = mocap::build::demo::tentacle_skin(clip, self.soft).ok()?;
        Body::from_skin(&skin, None, clip.skeleton().len())
    }

    /// Sets the character's pose for this frame: slider rotations, then (when
    /// following) the solver toward the target.
    pub fn pose(&self, c: &mut Character) {
        let Some(clip) = c.clip() else { return };
        let skeleton = clip.skeleton();
        let mut local = mocap::LocalPose::rest(skeleton);
        for (b, [bend, swing]) in self.angles.iter().enumerate() {
            if let Some(slot) = local.rotation.get_mut(b) {
                *slot = Quat::from_rotation_z(bend.to_radians()) * Quat::from_rotation_x(swing.to_radians());
            }
        }
        let target = c.to_file(self.target);
        if self.follow && target.is_finite() {
            if let Ok(chain) = Chain::new(skeleton, 0, skeleton.len().saturating_sub(1)) {
                let options = Options { iterations: 64, tolerance: 1e-4, ..Options::default() };
                match self.solver {
                    Solver::TwoBone if chain.joints().len() == 3 => {
                        let mid = ik::model_transform(skeleton, &local, 1).translation;
                        ik::two_bone(skeleton, &mut local, &chain, target, mid * 2.0, &options);
                    }
                    Solver::Ccd => {
                        ik::ccd(skeleton, &mut local, &chain, target, &options);
                    }
                    _ => {
                        ik::fabrik(skeleton, &mut local, &chain, target, &options);
                    }
                }
            }
        }
        let rotations = (0..self.bones).filter_map(|b| Some((b, *local.rotation.get(b)?))).collect();
        c.extra.correction = Some(Correction { frame: 0, rotations, translations: Vec::new(), ghost: false });
    }
}
