//! The renderer's lines, overlay lines and spheres: uploaded each frame, in
//! the order their outlines need.

use super::SceneRenderer;
use crate::lines::LineInstance;
use crate::pipeline_set::PipelineKey;
use crate::spheres::SphereInstance;
use crate::{Camera, Scene};
use glam::Vec3;

impl SceneRenderer {
    /// Uploads the scene's lines, overlay lines and spheres, the lines and
    /// spheres farthest first where `look` blends their outlines.
    pub(super) fn upload_lines_and_spheres(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        scene: &Scene,
        camera: &Camera,
        look: PipelineKey,
    ) {
        let ppp = self.pixels_per_point;
        let z_row = camera.view.row(2);
        let view_z = |p: Vec3| z_row.dot(p.extend(1.0));
        self.line_scratch.clear();
        self.line_scratch.extend(scene.overlay_lines.iter().map(|l| LineInstance::new(l, ppp)));
        self.overlay_lines.upload_quads(device, queue, &self.line_scratch);
        self.line_scratch.clear();
        self.line_scratch.extend(scene.lines.iter().map(|l| LineInstance::new(l, ppp)));
        self.sphere_scratch.clear();
        self.sphere_scratch.extend(scene.spheres.iter().map(SphereInstance::new));
        if look.blends_outlines() {
            sort_farthest_first(&mut self.line_scratch, |l| view_z((Vec3::from(l.a) + Vec3::from(l.b)) * 0.5));
            sort_farthest_first(&mut self.sphere_scratch, |s| view_z(Vec3::from(s.center)));
        }
        self.lines.upload_quads(device, queue, &self.line_scratch);
        self.spheres.upload_quads(device, queue, &self.sphere_scratch);
    }
}


/// Orders `items` farthest first by their view-space depth `z` (more negative
/// is farther): blended outlines need what lies behind them drawn first.
pub(super) fn sort_farthest_first<T>(items: &mut [T], z: impl Fn(&T) -> f32) {
    items.sort_unstable_by(|p, q| z(p).total_cmp(&z(q)));
}
