//! Colour conversion.

/// Converts an sRGB colour (0-255, straight alpha) to linear RGBA floats.
/// From a table of the 256 levels, made once: the renderer converts every
/// capsule's colour every frame (thousands in a crowd).
pub fn srgb_to_linear(c: [u8; 4]) -> [f32; 4] {
    static LEVELS: std::sync::OnceLock<[f32; 256]> = std::sync::OnceLock::new();
    let levels = LEVELS.get_or_init(|| std::array::from_fn(|v| decode(v as f32 / 255.0)));
    [levels[c[0] as usize], levels[c[1] as usize], levels[c[2] as usize], c[3] as f32 / 255.0]
}

/// The sRGB transfer function undone: an encoded level (0-1) to linear light.
fn decode(s: f32) -> f32 {
    if s <= 0.04045 { s / 12.92 } else { ((s + 0.055) / 1.055).powf(2.4) }
}

/// The colour as the shader must output it for `format`: linear for sRGB targets
/// (the hardware encodes), unchanged for plain unorm targets.
pub(crate) fn for_target(c: [u8; 4], format: wgpu::TextureFormat) -> [f32; 4] {
    if format.is_srgb() { srgb_to_linear(c) } else { c.map(|v| v as f32 / 255.0) }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn endpoints_are_exact() {
        assert_eq!(srgb_to_linear([0, 255, 0, 255]), [0.0, 1.0, 0.0, 1.0]);
    }

    #[test]
    fn every_level_is_the_transfer_function_undone() {
        for v in 0..=255u8 {
            let s = v as f32 / 255.0;
            let expected = if s <= 0.04045 { s / 12.92 } else { ((s + 0.055) / 1.055).powf(2.4) };
            assert_eq!(srgb_to_linear([v, 0, 255, v]), [expected, 0.0, 1.0, s], "level {v}");
        }
        // Mid grey is about a fifth of the light.
        assert!((srgb_to_linear([128; 4])[0] - 0.2158).abs() < 1e-3);
    }
}
