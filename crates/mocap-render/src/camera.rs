//! The camera handed to the renderer: plain view and projection matrices.

use glam::{Mat4, Vec3};

/// View and projection matrices (right-handed, Y up, depth 0..1).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// World to view space.
    pub view: Mat4,
    /// View to clip space.
    pub projection: Mat4,
}

impl Camera {
    /// A perspective camera at `eye` looking at `target` with Y up; near and far
    /// planes are derived from the distance so any scene scale works.
    pub fn look_at(eye: Vec3, target: Vec3, fov_y: f32, aspect: f32) -> Camera {
        let distance = eye.distance(target).max(1e-4);
        let up = if (eye - target).normalize_or_zero().abs().y > 0.999 { Vec3::Z } else { Vec3::Y };
        Camera {
            view: glam::camera::rh::view::look_at_mat4(eye, target, up),
            projection: glam::camera::rh::proj::directx::perspective(
                fov_y,
                aspect.max(1e-4),
                distance * 0.01,
                distance * 100.0,
            ),
        }
    }

    /// The eye's position in the world (the view's inverse's translation).
    pub fn eye(&self) -> Vec3 {
        self.view.inverse().w_axis.truncate()
    }

    /// Whether the projection is a perspective one (else orthographic).
    pub fn is_perspective(&self) -> bool {
        self.projection.w_axis.w < 0.5
    }

    /// Pixels per world unit on a target `height_px` pixels tall: at one unit
    /// in front of the eye in a perspective view, everywhere in an
    /// orthographic one.
    pub fn pixels_per_unit(&self, height_px: f32) -> f32 {
        self.projection.y_axis.y.abs() * 0.5 * height_px
    }
}
