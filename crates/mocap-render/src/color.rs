//! Colour conversion.

/// Converts an sRGB colour (0-255, straight alpha) to linear RGBA floats.
pub fn srgb_to_linear(c: [u8; 4]) -> [f32; 4] {
    let f = |v: u8| {
        let s = v as f32 / 255.0;
        if s <= 0.04045 { s / 12.92 } else { ((s + 0.055) / 1.055).powf(2.4) }
    };
    [f(c[0]), f(c[1]), f(c[2]), c[3] as f32 / 255.0]
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
}
