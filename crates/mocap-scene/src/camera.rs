//! The orbit camera: plain state (target, angles, distance, the view's shape)
//! plus controls, and the one rule that frames a stage ([`OrbitCamera::frame`]),
//! used by the page and `mocap render` alike.

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
    /// Width over height of the view it frames for (the viewer sets it from the
    /// view each frame; [`OrbitCamera::frame`] fits the narrower field of view).
    pub aspect: f32,
}

impl Default for OrbitCamera {
    fn default() -> OrbitCamera {
        OrbitCamera { target: Vec3::ZERO, yaw: 0.6, pitch: 0.3, distance: 5.0, fov_y: 0.8, aspect: 1.0 }
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

    /// Looks at the centre of `bounds` from far enough to see all of it, keeping the
    /// angles: the one camera-fit rule ([`fit_distance`] for the box's enclosing
    /// sphere in a view of [`OrbitCamera::aspect`]). Empty or non-finite bounds
    /// change nothing.
    pub fn frame(&mut self, bounds: Aabb) {
        if bounds.is_empty() || !bounds.min.is_finite() || !bounds.max.is_finite() {
            return;
        }
        let radius = (bounds.size().length() * 0.5).max(1e-3);
        self.target = bounds.center();
        self.distance = fit_distance(radius, self.fov_y, self.aspect);
    }

    /// Sets the orbit angles (radians), the elevation clamped short of straight up or down.
    pub fn set_angles(&mut self, yaw: f32, pitch: f32) {
        self.yaw = yaw;
        self.pitch = pitch.clamp(-MAX_PITCH, MAX_PITCH);
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

/// How far from its centre a sphere of `radius` is seen whole, with 5% to spare,
/// through a view whose vertical field of view is `fov_y` (radians) and whose
/// width over height is `aspect`: the sphere's angular radius is the narrower
/// half field of view (vertical, or horizontal in a view taller than wide).
pub fn fit_distance(radius: f32, fov_y: f32, aspect: f32) -> f32 {
    let half_y = fov_y * 0.5;
    let aspect = if aspect.is_finite() && aspect > 0.0 { aspect } else { 1.0 };
    let half_x = (half_y.tan() * aspect).atan();
    radius / half_y.min(half_x).sin() * 1.05
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
    fn framing_fits_the_narrower_field_of_view() {
        let bounds = Aabb { min: Vec3::splat(-1.0), max: Vec3::splat(1.0) };
        let mut wide = OrbitCamera { aspect: 16.0 / 9.0, ..OrbitCamera::default() };
        wide.frame(bounds);
        let mut square = OrbitCamera::default();
        square.frame(bounds);
        assert_eq!(wide.distance, square.distance, "a wide view fits the height");
        let mut tall = OrbitCamera { aspect: 0.5, ..OrbitCamera::default() };
        tall.frame(bounds);
        assert!(tall.distance > square.distance * 1.5, "a tall view fits the width");
        // The sphere touches the narrower edge: its angular radius is the half field of view.
        let radius = 3.0_f32.sqrt();
        let seen = (radius / (tall.distance / 1.05)).asin();
        let half_x = ((0.4_f32).tan() * 0.5).atan();
        assert!((seen - half_x).abs() < 1e-4);
    }

    #[test]
    fn pitch_is_clamped() {
        let mut c = OrbitCamera::default();
        c.orbit(0.0, 1e6);
        assert!(c.pitch <= MAX_PITCH);
        assert!(c.to_camera(1.0).view.is_finite());
    }
}
