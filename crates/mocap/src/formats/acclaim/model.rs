//! Acclaim skeleton and motion → the animation model.
//!
//! The Acclaim definition: a bone's local rotation is `C · M · C⁻¹`, with `C` from
//! its `axis` (angles applied in the axis order, extrinsic) and `M` from its dof
//! rotations (in dof order, extrinsic); its world rotation is its parent's times
//! that; it starts at its parent's end and ends at its start plus its world
//! rotation applied to `direction × length`. The root takes its `order`, `axis`,
//! `position` and `orientation`.
//!
//! In the model each bone is a joint at the bone's start whose frame is the bone's
//! axis frame (world rotation × `C`). Then the joint's rest rotation is
//! `C_parent⁻¹ · C`, its channel rotations are `M` (the skeleton is
//! [`EulerConvention::Extrinsic`]), and its rest translation is the parent bone's
//! `C_parent⁻¹ · direction × length`: the model pose places every bone exactly as
//! the definition does. A bone without children gets an End Site at its end.

use super::{Amc, Asf, AxisOrder, Dof};
use crate::error::{ParseError, Warning};
use crate::model::channel::{AngleUnit, Channel};
use crate::model::clip::Clip;
use crate::model::motion::Motion;
use crate::model::skeleton::{EulerConvention, Joint, Limit, Skeleton};
use crate::runtime::pose::axis_rotation;
use glam::{Quat, Vec3};

/// Frame time used for AMC files, which carry none: 120 fps, the CMU database's rate.
pub const AMC_FRAME_TIME: f64 = 1.0 / 120.0;

/// The channel a degree of freedom animates.
fn channel(dof: Dof) -> Channel {
    match dof {
        Dof::Tx => Channel::Xposition,
        Dof::Ty => Channel::Yposition,
        Dof::Tz => Channel::Zposition,
        Dof::Rx => Channel::Xrotation,
        Dof::Ry => Channel::Yrotation,
        Dof::Rz => Channel::Zrotation,
        Dof::L => Channel::Length,
    }
}

/// `C` for an `axis` line: the three angles (x, y, z) applied in `order`, extrinsic.
pub fn axis_frame(angles: [f32; 3], order: AxisOrder, unit: AngleUnit) -> Quat {
    let mut c = Quat::IDENTITY;
    for axis in order.0 {
        let axis = usize::from(axis);
        let angle = angles.get(axis).copied().unwrap_or(0.0);
        c = axis_rotation(axis, angle, unit) * c;
    }
    c
}

/// An Acclaim skeleton in the model, with what is needed to read its motions.
#[derive(Clone, Debug)]
pub struct AcclaimSkeleton {
    /// The joints (root, bones, End Sites).
    pub skeleton: Skeleton,
    /// The motion row layout for the AMC reader: `("root", n)` then each bone.
    pub layout: Vec<(String, usize)>,
    /// Per motion column, what to add to the value read (the rest translation for
    /// translation dofs, which Acclaim adds to the rest position).
    pub column_bias: Vec<f32>,
    /// What the file says about itself, for the inspector.
    pub metadata: Vec<(String, String)>,
    /// Non-fatal problems.
    pub warnings: Vec<Warning>,
}

fn vec3(v: [f32; 3]) -> Vec3 {
    Vec3::from_array(v)
}

/// Builds the model skeleton of a parsed ASF.
pub fn skeleton(asf: &Asf) -> Result<AcclaimSkeleton, ParseError> {
    let unit = asf.units.angle;
    let root_frame = axis_frame(asf.root.orientation, asf.root.axis, unit);
    let frames: Vec<Quat> = asf.bones.iter().map(|b| axis_frame(b.axis, b.axis_order, unit)).collect();
    let mut has_children = vec![false; asf.bones.len()];
    for bone in &asf.bones {
        if let Some(flag) = bone.parent.and_then(|p| has_children.get_mut(p)) {
            *flag = true;
        }
    }
    let mut joints = Vec::with_capacity(asf.bones.len() * 2 + 1);
    let mut joint_of_bone = vec![0usize; asf.bones.len()];
    let mut layout = vec![("root".to_owned(), asf.root.order.len())];
    let root_offset = vec3(asf.root.position);
    joints.push(
        Joint::new("root", None, root_offset, asf.root.order.iter().map(|&d| channel(d)).collect())
            .with_rest_rotation(root_frame),
    );
    let mut column_bias: Vec<f32> = asf.root.order.iter().map(|&d| translation_bias(d, root_offset)).collect();
    for (b, bone) in asf.bones.iter().enumerate() {
        let (parent_joint, parent_frame, offset) = match bone.parent {
            None => (0, root_frame, Vec3::ZERO),
            Some(p) => {
                let parent = asf.bones.get(p).ok_or_else(|| {
                    ParseError::new(bone.line, 1, format!("bone `{}` has no parent bone {p}", bone.name))
                })?;
                let frame = frames.get(p).copied().unwrap_or(Quat::IDENTITY);
                let joint = joint_of_bone.get(p).copied().unwrap_or(0);
                (joint, frame, frame.inverse() * (vec3(parent.direction) * parent.length))
            }
        };
        let frame = frames.get(b).copied().unwrap_or(Quat::IDENTITY);
        let limits = bone.limits.iter().map(|&(min, max)| Limit { min, max }).collect();
        let joint =
            Joint::new(bone.name.clone(), Some(parent_joint), offset, bone.dofs.iter().map(|&d| channel(d)).collect())
                .with_rest_rotation(parent_frame.inverse() * frame)
                .with_limits(limits);
        if let Some(slot) = joint_of_bone.get_mut(b) {
            *slot = joints.len();
        }
        joints.push(joint);
        column_bias.extend(bone.dofs.iter().map(|&d| translation_bias(d, offset)));
        layout.push((bone.name.clone(), bone.dofs.len()));
        if !has_children.get(b).copied().unwrap_or(false) {
            let end = frame.inverse() * (vec3(bone.direction) * bone.length);
            joints.push(Joint::end_site(format!("{}_End", bone.name), Some(joints.len() - 1), end));
        }
    }
    let skeleton =
        Skeleton::new(joints, EulerConvention::Extrinsic).map_err(|e| ParseError::new(1, 1, e.to_string()))?;
    Ok(AcclaimSkeleton { skeleton, layout, column_bias, metadata: metadata(asf), warnings: asf.warnings.clone() })
}

/// What a translation dof adds to the value read (its rest component); 0 otherwise.
fn translation_bias(dof: Dof, rest: Vec3) -> f32 {
    match dof {
        Dof::Tx => rest.x,
        Dof::Ty => rest.y,
        Dof::Tz => rest.z,
        _ => 0.0,
    }
}

fn metadata(asf: &Asf) -> Vec<(String, String)> {
    let mut m = Vec::new();
    if let Some(name) = &asf.name {
        m.push(("name".to_owned(), name.clone()));
    }
    if let Some(version) = &asf.version {
        m.push(("version".to_owned(), version.clone()));
    }
    if let Some(mass) = asf.units.mass {
        m.push(("units mass".to_owned(), mass.to_string()));
    }
    if let Some(length) = asf.units.length {
        m.push(("units length".to_owned(), length.to_string()));
    }
    m.push(("units angle".to_owned(), asf.units.angle.name().to_owned()));
    m.extend(asf.units.other.iter().map(|(k, v)| (format!("units {k}"), v.clone())));
    if !asf.documentation.is_empty() {
        m.push(("documentation".to_owned(), asf.documentation.clone()));
    }
    m
}

impl AcclaimSkeleton {
    /// The skeleton alone, in its rest pose (no frames).
    pub fn rest_clip(&self) -> Clip {
        let motion = Motion::new(AMC_FRAME_TIME, self.skeleton.channel_count(), 0, Vec::new()).unwrap_or_default();
        let mut clip = Clip::new(self.skeleton.clone(), motion).unwrap_or_default();
        clip.metadata = self.metadata.clone();
        clip.warnings = self.warnings.clone();
        clip
    }

    /// Reads an AMC motion for this skeleton into a clip.
    pub fn motion_clip(&self, amc_bytes: &[u8]) -> Result<Clip, ParseError> {
        let layout: Vec<(&str, usize)> = self.layout.iter().map(|(n, c)| (n.as_str(), *c)).collect();
        let amc: Amc = super::parse_amc(amc_bytes, &layout)?;
        let width = self.skeleton.channel_count();
        let mut data = amc.data;
        if self.column_bias.iter().any(|&b| b != 0.0) && width > 0 {
            for row in data.chunks_mut(width) {
                for (v, b) in row.iter_mut().zip(&self.column_bias) {
                    *v += b;
                }
            }
        }
        let motion = Motion::new(AMC_FRAME_TIME, width, amc.frame_count, data)
            .ok_or_else(|| ParseError::new(1, 1, "the motion does not fit the skeleton's degrees of freedom"))?
            .with_angle_unit(amc.angle);
        let mut clip = Clip::new(self.skeleton.clone(), motion).map_err(|e| ParseError::new(1, 1, e.to_string()))?;
        clip.metadata = self.metadata.clone();
        clip.warnings = amc.warnings;
        clip.warnings.push(Warning {
            line: None,
            message: "AMC files carry no frame rate: playing at 120 fps (the CMU database's rate)".into(),
        });
        Ok(clip)
    }
}
