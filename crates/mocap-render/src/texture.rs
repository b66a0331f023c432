//! Colour textures on the GPU (an MD2 model's skin, a glTF character's base
//! colour): [`SkinImage`], the RGBA8 picture handed over, and its upload into a
//! bind group of `pipeline::color_texture_layout` (texture at 0, sampler at 1),
//! halved until it fits the device (WebGL2 allows 2048 texels a side).

use std::borrow::Cow;
use wgpu::util::DeviceExt;

/// An RGBA8 skin, rows top to bottom, sRGB colours.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SkinImage {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// `width × height × 4` bytes.
    pub pixels: Vec<u8>,
}

impl SkinImage {
    /// The image halved (2×2 box filter) until both sides are at most `max_side`.
    pub fn fitted(&self, max_side: u32) -> Cow<'_, SkinImage> {
        let mut image = Cow::Borrowed(self);
        while (image.width > max_side || image.height > max_side) && image.width.max(image.height) > 1 {
            image = Cow::Owned(image.halved());
        }
        image
    }

    /// Half the size (an odd last row or column folded into its neighbour).
    fn halved(&self) -> SkinImage {
        let (w, h) = ((self.width / 2).max(1), (self.height / 2).max(1));
        let texel = |x: u32, y: u32| -> [u8; 4] {
            let (x, y) = (x.min(self.width.saturating_sub(1)), y.min(self.height.saturating_sub(1)));
            let i = (y as usize * self.width as usize + x as usize) * 4;
            self.pixels.get(i..i + 4).and_then(|p| p.try_into().ok()).unwrap_or([255; 4])
        };
        let mut pixels = Vec::with_capacity(w as usize * h as usize * 4);
        for y in 0..h {
            for x in 0..w {
                let four = [
                    texel(2 * x, 2 * y),
                    texel(2 * x + 1, 2 * y),
                    texel(2 * x, 2 * y + 1),
                    texel(2 * x + 1, 2 * y + 1),
                ];
                for c in 0..4 {
                    pixels.push(((four.iter().map(|p| u32::from(p[c])).sum::<u32>() + 2) / 4) as u8);
                }
            }
        }
        SkinImage { width: w, height: h, pixels }
    }
}

/// A bind group sampling `image` (uploaded as an sRGB texture, fitted to the
/// device) with `sampler`. An image whose bytes do not match its size is drawn
/// white.
pub(crate) fn skin_group(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    layout: &wgpu::BindGroupLayout,
    sampler: &wgpu::Sampler,
    image: &SkinImage,
) -> wgpu::BindGroup {
    let white = SkinImage { width: 1, height: 1, pixels: vec![255; 4] };
    let whole = u64::from(image.width) * u64::from(image.height) * 4 == image.pixels.len() as u64 && image.width > 0;
    let image = if whole { image.fitted(device.limits().max_texture_dimension_2d) } else { Cow::Borrowed(&white) };
    let texture = device.create_texture_with_data(
        queue,
        &wgpu::TextureDescriptor {
            label: Some("mocap skin"),
            size: wgpu::Extent3d { width: image.width, height: image.height, depth_or_array_layers: 1 },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: wgpu::TextureFormat::Rgba8UnormSrgb,
            usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
            view_formats: &[],
        },
        wgpu::util::TextureDataOrder::LayerMajor,
        &image.pixels,
    );
    let view = texture.create_view(&Default::default());
    device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("mocap skin"),
        layout,
        entries: &[
            wgpu::BindGroupEntry { binding: 0, resource: wgpu::BindingResource::TextureView(&view) },
            wgpu::BindGroupEntry { binding: 1, resource: wgpu::BindingResource::Sampler(sampler) },
        ],
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_image_is_halved_until_it_fits() {
        let image = SkinImage { width: 5, height: 2, pixels: (0..40).map(|i| (i * 6) as u8).collect() };
        let fitted = image.fitted(2);
        assert_eq!((fitted.width, fitted.height, fitted.pixels.len()), (2, 1, 8));
        let fitted = image.fitted(1);
        assert_eq!((fitted.width, fitted.height, fitted.pixels.len()), (1, 1, 4));
        assert!(matches!(image.fitted(8), Cow::Borrowed(_)), "an image that fits is not copied");
        let half = image.halved();
        assert_eq!((half.width, half.height, half.pixels.len()), (2, 1, 8));
        // The first texel is the mean of the top-left 2×2 block.
        let mean = (u32::from(image.pixels[0])
            + u32::from(image.pixels[4])
            + u32::from(image.pixels[20])
            + u32::from(image.pixels[24])
            + 2)
            / 4;
        assert_eq!(u32::from(half.pixels[0]), mean);
    }
}
