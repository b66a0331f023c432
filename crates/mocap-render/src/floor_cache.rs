//! The floor drawn once and copied into each frame while nothing it depends on
//! changes.
//!
//! On a software rasteriser the floor's shader (grid lines, their fade, the
//! fade to the background) is one of a frame's largest costs: it covers much
//! of the view, and at 4× MSAA every pixel's samples are blended and stored.
//! A clip playing under a still camera redraws the same floor pixels every
//! frame. So once a frame's floor inputs equal the previous frame's, the floor
//! is drawn into a colour and a depth texture of the target's format, size and
//! sample count, and each frame after that starts from copies of them (plain
//! memory copies) instead of clears and the floor's shader. OpenGL (WebGL2)
//! copies only single-sampled colour textures: there a single-sampled frame
//! copies the floor's colour and draws its depth (a depth-only quad), and a
//! multisampled one draws its floor. The pixels are those of drawing the floor
//! (tested in `tests/headless.rs`, both ways). A moving camera never fills the
//! textures: a frame whose floor differs from the last one's draws the floor
//! directly.

use crate::target::RenderTarget;
use crate::uniforms::FrameUniforms;

/// The largest colour texture cached (bytes; the depth is as large): a
/// 2560×1440 target at 4× MSAA.
const MAX_BYTES: u64 = 64 << 20;

/// What a device can copy of the floor.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Copies {
    /// Colour and depth, of any sample count.
    All,
    /// Single-sampled colour textures of a non-sRGB format only (OpenGL: no
    /// multisampled textures, and depth cannot be copied).
    SingleSampledColor,
}

impl Copies {
    /// What `device` can copy.
    pub fn of(device: &wgpu::Device) -> Copies {
        if device.adapter_info().backend == wgpu::Backend::Gl { Copies::SingleSampledColor } else { Copies::All }
    }

    /// Whether multisampled colour and depth targets can be copy destinations.
    pub fn all(self) -> bool {
        self == Copies::All
    }
}

/// Everything the floor's pixels depend on.
#[derive(Clone, Copy, PartialEq)]
pub(crate) struct FloorKey {
    /// The floor's uniforms (view, projection, viewport, floor placement and colours).
    uniforms: [[f32; 4]; 14],
    /// The clear colour under the floor, as the target stores it.
    background: [f32; 4],
    size: [u32; 2],
    samples: u32,
    format: wgpu::TextureFormat,
}

impl FloorKey {
    /// The key of a frame drawn with `uniforms` over `background` into a
    /// target of `size`, `samples` and `format`.
    pub fn new(
        uniforms: &FrameUniforms,
        background: [f32; 4],
        size: [u32; 2],
        samples: u32,
        format: wgpu::TextureFormat,
    ) -> FloorKey {
        let u = uniforms;
        let [v0, v1, v2, v3] = u.view;
        let [p0, p1, p2, p3] = u.projection;
        let mut viewport = u.viewport;
        // The shadow strength (w) does not change the floor's own pixels.
        viewport[3] = 0.0;
        let uniforms = [
            v0,
            v1,
            v2,
            v3,
            p0,
            p1,
            p2,
            p3,
            viewport,
            u.floor_center,
            u.floor_grid,
            u.floor_minor,
            u.floor_major,
            u.floor_color,
        ];
        FloorKey { uniforms, background, size, samples, format }
    }

    fn bytes(&self) -> u64 {
        let texel = u64::from(self.format.block_copy_size(None).unwrap_or(16));
        u64::from(self.size[0]) * u64::from(self.size[1]) * u64::from(self.samples) * texel
    }
}

/// A frame's floor copied from `color`, and from `depth` when set (else its
/// depth is drawn), drawn into them first when `fill` is set (without a
/// `FloorCopy`, the frame draws its floor).
pub(crate) struct FloorCopy {
    pub color: wgpu::Texture,
    /// The floor's depth (the fill pass's depth buffer either way).
    pub depth: wgpu::Texture,
    pub copy_depth: bool,
    pub fill: bool,
}

impl FloorCopy {
    /// Records the copy of the floor into `target`: all of it, or the rect
    /// `redraw` (min x, min y, max x, max y) of a frame redrawn there alone
    /// (see damage.rs). A multisampled texture and depth are copied whole
    /// (WebGPU copies no part of them); the frame's draws still stay inside
    /// the rect. `false` (and nothing recorded) for an empty rect.
    pub fn copy_into(&self, encoder: &mut wgpu::CommandEncoder, target: &RenderTarget, redraw: Option<[u32; 4]>) -> bool {
        let [width, height] = target.size();
        let [x0, y0, x1, y1] = redraw.unwrap_or([0, 0, width, height]);
        if x1 <= x0 || y1 <= y0 {
            return false;
        }
        let [x0, y0, x1, y1] = if target.sample_count() == 1 { [x0, y0, x1, y1] } else { [0, 0, width, height] };
        let extent = wgpu::Extent3d { width: x1 - x0, height: y1 - y0, depth_or_array_layers: 1 };
        let origin = wgpu::Origin3d { x: x0, y: y0, z: 0 };
        let at = |texture| wgpu::TexelCopyTextureInfo { origin, ..wgpu::Texture::as_image_copy(texture) };
        encoder.copy_texture_to_texture(at(&self.color), at(target.attachment_texture()), extent);
        if self.copy_depth {
            let whole = wgpu::Extent3d { width, height, depth_or_array_layers: 1 };
            encoder.copy_texture_to_texture(self.depth.as_image_copy(), target.depth_texture().as_image_copy(), whole);
        }
        true
    }
}

/// The texture holding the floor and what it holds.
pub(crate) struct FloorCache {
    /// What the device copies.
    copies: Copies,
    /// The colour and depth textures and the floor they were made for (its
    /// size, samples and format are what matter).
    textures: Option<(wgpu::Texture, wgpu::Texture, FloorKey)>,
    /// What the texture holds, once filled.
    holds: Option<FloorKey>,
    /// The floor of the previous frame (none: it had no floor).
    previous: Option<FloorKey>,
}

impl FloorCache {
    /// An empty cache for a device that copies `copies`.
    pub fn new(copies: Copies) -> FloorCache {
        FloorCache { copies, textures: None, holds: None, previous: None }
    }

    /// Plans a frame whose floor is `key` (none: no floor). A floor equal to
    /// the previous frame's is copied from the cache, filled first when it
    /// holds another floor; any other frame draws its floor (`None`).
    pub fn plan(&mut self, device: &wgpu::Device, key: Option<FloorKey>) -> Option<FloorCopy> {
        let previous = std::mem::replace(&mut self.previous, key);
        let copyable = |k: &FloorKey| self.copies.all() || (k.samples == 1 && !k.format.is_srgb());
        let Some(key) = key.filter(|k| copyable(k) && previous == Some(*k) && k.bytes() <= MAX_BYTES) else {
            return None;
        };
        let same_texture = |t: &FloorKey| t.size == key.size && t.samples == key.samples && t.format == key.format;
        if !self.textures.as_ref().is_some_and(|(_, _, made_for)| same_texture(made_for)) {
            let texture = |label, format| {
                device.create_texture(&wgpu::TextureDescriptor {
                    label: Some(label),
                    size: wgpu::Extent3d { width: key.size[0], height: key.size[1], depth_or_array_layers: 1 },
                    mip_level_count: 1,
                    sample_count: key.samples,
                    dimension: wgpu::TextureDimension::D2,
                    format,
                    usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
                    view_formats: &[],
                })
            };
            let color = texture("mocap floor cache", key.format);
            let depth = texture("mocap floor cache depth", crate::DEPTH_FORMAT);
            self.textures = Some((color, depth, key));
            self.holds = None;
        }
        let fill = self.holds != Some(key);
        self.holds = Some(key);
        let copy_depth = self.copies.all();
        self.textures.as_ref().map(|(color, depth, _)| FloorCopy {
            color: color.clone(),
            depth: depth.clone(),
            copy_depth,
            fill,
        })
    }
}
