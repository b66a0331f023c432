//! The orbit camera: plain state (target, angles, distance) plus controls.

use mocap::Aabb;
use mocap::glam::Vec3;
use mocap_render::Camera;

/// Named viewpoints for the 1/2/3 keys.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Waypoint {
    /// Looking at the front (+Z side) of the clip.
    Front,
    /// Looking from the side (+X).
    Side,
    /// Looking down from above.
    Top,
}

/// An orbit camera around a target point; Y is up.
#[derive(Clone, Debug, PartialEq)]
pub struct OrbitCamera {
    /// Point looked at.
    pub target: Vec3,
    /// Rotation about Y in radians (0 = looking along -Z from +Z).
    pub yaw: f32,
    /// Elevation in radians.
    pub pitch: f32,
    /// Distance from the target.
    pub distance: f32,
    /// Vertical field of view in radians.
    pub fov_y: f32,
}

impl Default for OrbitCamera {
    fn default() -> OrbitCamera {
        OrbitCamera { target: Vec3::ZERO, yaw: 0.6, pitch: 0.3, distance: 5.0, fov_y: 0.8 }
    }
}

const MAX_PITCH: f32 = 1.55;

impl OrbitCamera {
    /// Eye position.
    pub fn eye(&self) -> Vec3 {
        let (sy, cy) = self.yaw.sin_cos();
        let (sp, cp) = self.pitch.sin_cos();
        self.target + Vec3::new(cp * sy, sp, cp * cy) * self.distance
    }

    /// Matrices for the renderer at the given aspect ratio.
    pub fn to_camera(&self, aspect: f32) -> Camera {
        Camera::look_at(self.eye(), self.target, self.fov_y, aspect)
    }

    /// Looks at the centre of `bounds` from far enough to see all of it, keeping the angles.
    pub fn frame(&mut self, bounds: Aabb) {
        if bounds.is_empty() || !bounds.min.is_finite() || !bounds.max.is_finite() {
            return;
        }
        let radius = (bounds.size().length() * 0.5).max(1e-3);
        self.target = bounds.center();
        self.distance = radius / (self.fov_y * 0.5).sin() * 1.05;
    }

    /// Rotates around the target by pixel deltas.
    pub fn orbit(&mut self, dx: f32, dy: f32) {
        self.yaw -= dx * 0.008;
        self.pitch = (self.pitch + dy * 0.008).clamp(-MAX_PITCH, MAX_PITCH);
    }

    /// Moves the target in the view plane by pixel deltas for a view `height_px` tall.
    pub fn pan(&mut self, dx: f32, dy: f32, height_px: f32) {
        let forward = (self.target - self.eye()).normalize_or_zero();
        let right = forward.cross(Vec3::Y).normalize_or(Vec3::X);
        let up = right.cross(forward);
        let per_px = 2.0 * self.distance * (self.fov_y * 0.5).tan() / height_px.max(1.0);
        self.target += (-right * dx + up * dy) * per_px;
    }

    /// Multiplies the distance (< 1 zooms in).
    pub fn zoom(&mut self, factor: f32) {
        if factor.is_finite() && factor > 0.0 {
            self.distance = (self.distance * factor).clamp(1e-3, 1e7);
        }
    }

    /// Jumps to a named view, keeping target and distance.
    pub fn waypoint(&mut self, waypoint: Waypoint) {
        (self.yaw, self.pitch) = match waypoint {
            Waypoint::Front => (0.0, 0.1),
            Waypoint::Side => (std::f32::consts::FRAC_PI_2, 0.1),
            Waypoint::Top => (0.0, MAX_PITCH),
        };
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn framing_sees_the_box() {
        let mut c = OrbitCamera::default();
        c.frame(Aabb { min: Vec3::new(-1.0, 0.0, -1.0), max: Vec3::new(1.0, 2.0, 1.0) });
        assert_eq!(c.target, Vec3::new(0.0, 1.0, 0.0));
        assert!(c.distance > 3.0_f32.sqrt());
        assert!((c.eye() - c.target).length() - c.distance < 1e-4);
    }

    #[test]
    fn pitch_is_clamped() {
        let mut c = OrbitCamera::default();
        c.orbit(0.0, 1e6);
        assert!(c.pitch <= MAX_PITCH);
        assert!(c.to_camera(1.0).view.is_finite());
    }
}
