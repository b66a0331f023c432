//! RGBA to 8-bit I420 (4:2:0), BT.601 limited range.

/// One picture as three planes: Y (`w*h`), U and V (`w/2 * h/2`); `w` and `h` even.
pub struct I420 {
    /// Luma, row by row.
    pub y: Vec<u8>,
    /// Blue difference, one per 2x2 block.
    pub u: Vec<u8>,
    /// Red difference, one per 2x2 block.
    pub v: Vec<u8>,
}

impl I420 {
    /// Empty planes for a `w`x`h` picture.
    pub fn new(w: usize, h: usize) -> I420 {
        I420 { y: vec![0; w * h], u: vec![0; (w / 2) * (h / 2)], v: vec![0; (w / 2) * (h / 2)] }
    }

    /// Fills the planes from `rgba` (`w*h*4` bytes; the caller checked the length).
    pub fn fill(&mut self, rgba: &[u8], w: usize, h: usize) {
        for (row, y_row) in self.y.chunks_exact_mut(w).enumerate().take(h) {
            let src = &rgba[row * w * 4..(row + 1) * w * 4];
            for (y, px) in y_row.iter_mut().zip(src.chunks_exact(4)) {
                *y = luma(px[0], px[1], px[2]);
            }
        }
        let cw = w / 2;
        for cy in 0..h / 2 {
            for cx in 0..cw {
                let (mut r, mut g, mut b) = (0u32, 0u32, 0u32);
                for (dx, dy) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
                    let i = ((cy * 2 + dy) * w + cx * 2 + dx) * 4;
                    r += rgba[i] as u32;
                    g += rgba[i + 1] as u32;
                    b += rgba[i + 2] as u32;
                }
                let (u, v) = chroma((r + 2) / 4, (g + 2) / 4, (b + 2) / 4);
                self.u[cy * cw + cx] = u;
                self.v[cy * cw + cx] = v;
            }
        }
    }
}

/// BT.601 limited-range luma, in 16.16 fixed point.
fn luma(r: u8, g: u8, b: u8) -> u8 {
    let y = (16_829 * r as i32 + 33_039 * g as i32 + 6_416 * b as i32 + (16 << 16) + 32_768) >> 16;
    y.clamp(16, 235) as u8
}

/// BT.601 limited-range chroma of an averaged 2x2 block.
fn chroma(r: u32, g: u32, b: u32) -> (u8, u8) {
    let (r, g, b) = (r as i32, g as i32, b as i32);
    let u = (-9_714 * r - 19_070 * g + 28_784 * b + (128 << 16) + 32_768) >> 16;
    let v = (28_784 * r - 24_103 * g - 4_681 * b + (128 << 16) + 32_768) >> 16;
    (u.clamp(16, 240) as u8, v.clamp(16, 240) as u8)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn greys_and_primaries() {
        assert_eq!(luma(0, 0, 0), 16);
        assert_eq!(luma(255, 255, 255), 235);
        assert_eq!(chroma(128, 128, 128), (128, 128));
        let (u, v) = chroma(255, 0, 0);
        assert!(u < 128 && v == 240, "{u} {v}");
    }

    #[test]
    fn planes_from_a_picture() {
        let rgba: Vec<u8> = (0..4 * 2).flat_map(|i| [i as u8 * 30, 0, 0, 255]).collect();
        let mut p = I420::new(4, 2);
        p.fill(&rgba, 4, 2);
        assert_eq!(p.y.len(), 8);
        assert_eq!(p.u.len(), 2);
        assert!(p.y[7] > p.y[0]);
    }
}
