//! Dragging joints in the 3D view (Edit mode): where joints are on screen, which
//! one the pointer grabs, and where on screen a point goes back into the world.
//!
//! A grabbed joint moves in the plane through where it was, facing the camera, so
//! it follows the pointer exactly whatever the view angle.

use mocap::glam::{Vec3, Vec4Swizzles};
use mocap_render::Camera;

/// The `character` of the handle of the tentacle demo's target sphere.
pub const TARGET: usize = usize::MAX;

/// Grab radius around a joint on screen, in points.
pub const GRAB_RADIUS: f32 = 14.0;

/// A joint that can be grabbed: its character, its index and where it is (world).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Handle {
    /// Character index.
    pub character: usize,
    /// Joint index in that character's skeleton.
    pub joint: usize,
    /// World position (metres).
    pub world: Vec3,
    /// For a point on a rotation ring of the selected joint: the ring's axis (world).
    pub ring: Option<Vec3>,
}

/// The 3D view's rectangle on screen and the camera it was drawn with.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ViewGeometry {
    /// Where the view is, in points.
    pub rect: egui::Rect,
    /// The camera of the last frame.
    pub camera: Camera,
}

impl ViewGeometry {
    /// Where a world point is on screen (points), if in front of the camera.
    pub fn project(&self, p: Vec3) -> Option<egui::Pos2> {
        let clip = self.camera.projection * self.camera.view * p.extend(1.0);
        if clip.w <= 1e-6 || !clip.is_finite() {
            return None;
        }
        let ndc = clip.xy() / clip.w;
        Some(egui::pos2(
            self.rect.left() + (ndc.x * 0.5 + 0.5) * self.rect.width(),
            self.rect.top() + (0.5 - ndc.y * 0.5) * self.rect.height(),
        ))
    }

    /// The world ray under a screen point: origin and unit direction.
    pub fn ray(&self, pos: egui::Pos2) -> Option<(Vec3, Vec3)> {
        let x = (pos.x - self.rect.left()) / self.rect.width().max(1.0) * 2.0 - 1.0;
        let y = 1.0 - (pos.y - self.rect.top()) / self.rect.height().max(1.0) * 2.0;
        let inverse = (self.camera.projection * self.camera.view).inverse();
        let near = inverse.project_point3(Vec3::new(x, y, 0.0));
        let far = inverse.project_point3(Vec3::new(x, y, 1.0));
        let dir = (far - near).normalize_or_zero();
        (near.is_finite() && dir != Vec3::ZERO).then_some((near, dir))
    }

    /// The point under `pos` on the plane through `through` that faces the camera.
    pub fn on_plane(&self, pos: egui::Pos2, through: Vec3) -> Option<Vec3> {
        let (origin, dir) = self.ray(pos)?;
        let eye = self.camera.eye();
        let normal = (eye - through).normalize_or_zero();
        let denom = dir.dot(normal);
        if denom.abs() < 1e-6 {
            return None;
        }
        let t = (through - origin).dot(normal) / denom;
        let p = origin + dir * t;
        (t > 0.0 && p.is_finite()).then_some(p)
    }
}

/// The handle nearest to `pos` on screen within [`GRAB_RADIUS`], if any.
pub fn pick(handles: &[Handle], view: &ViewGeometry, pos: egui::Pos2) -> Option<Handle> {
    handles
        .iter()
        .filter_map(|h| Some((view.project(h.world)?.distance(pos), *h)))
        .filter(|(d, _)| *d <= GRAB_RADIUS)
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .map(|(_, h)| h)
}

/// A joint being dragged this frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct JointDrag {
    /// The grabbed joint.
    pub handle: Handle,
    /// Where the pointer puts it (world).
    pub target: Vec3,
    /// The pointer (points).
    pub pointer: egui::Pos2,
    /// Where the press that grabbed it was (points).
    pub press: egui::Pos2,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn projecting_and_unprojecting_agree() {
        let camera = Camera::look_at(Vec3::new(0.0, 1.0, 5.0), Vec3::new(0.0, 1.0, 0.0), 0.8, 1.5);
        let view =
            ViewGeometry { rect: egui::Rect::from_min_size(egui::pos2(100.0, 50.0), egui::vec2(600.0, 400.0)), camera };
        let p = Vec3::new(0.4, 1.3, 0.2);
        let s = view.project(p).unwrap();
        let back = view.on_plane(s, p).unwrap();
        assert!(back.distance(p) < 1e-4, "{back} vs {p}");
        assert_eq!(
            view.project(Vec3::new(0.0, 1.0, 0.0)).map(|q| (q.x.round(), q.y.round())),
            Some((400.0, 250.0)),
            "the target is the centre"
        );
        let handles = [
            Handle { character: 0, joint: 3, world: p, ring: None },
            Handle { character: 1, joint: 0, world: Vec3::new(-1.0, 0.0, 0.0), ring: None },
        ];
        assert_eq!(pick(&handles, &view, s + egui::vec2(5.0, -5.0)).map(|h| h.joint), Some(3));
        assert_eq!(pick(&handles, &view, s + egui::vec2(40.0, 0.0)), None);
    }
}

/// Points of the three rotation rings around a joint at `center` with world
/// rotation `rotation` (its local X, Y and Z axes), `radius` across, as handles
/// (every 10°) and as line segments to draw (with the axis each belongs to).
pub fn rings(
    character: usize,
    joint: usize,
    center: Vec3,
    rotation: mocap::glam::Quat,
    radius: f32,
) -> (Vec<Handle>, Vec<(Vec3, Vec3, usize)>) {
    let mut handles = Vec::new();
    let mut segments = Vec::new();
    for k in 0..3 {
        let axis = rotation * [Vec3::X, Vec3::Y, Vec3::Z][k];
        let u = axis.any_orthonormal_vector();
        let v = axis.cross(u);
        let point = |i: usize| {
            let a = i as f32 * std::f32::consts::TAU / 36.0;
            center + (u * a.cos() + v * a.sin()) * radius
        };
        for i in 0..36 {
            handles.push(Handle { character, joint, world: point(i), ring: Some(axis) });
            segments.push((point(i), point(i + 1), k));
        }
    }
    (handles, segments)
}

/// The angle (radians) of the pointer around a ring: where the ray under `pos`
/// meets the ring's plane, measured about `axis` from `from` (a vector in the plane).
pub fn ring_angle(view: &ViewGeometry, pos: egui::Pos2, center: Vec3, axis: Vec3, from: Vec3) -> Option<f32> {
    let (origin, dir) = view.ray(pos)?;
    let denom = dir.dot(axis);
    if denom.abs() < 1e-4 {
        return None;
    }
    let t = (center - origin).dot(axis) / denom;
    let p = origin + dir * t - center;
    let v = p - axis * p.dot(axis);
    if v.length() < 1e-6 || !v.is_finite() {
        return None;
    }
    let from = (from - axis * from.dot(axis)).normalize_or_zero();
    let v = v.normalize();
    Some(from.cross(v).dot(axis).atan2(from.dot(v)))
}
