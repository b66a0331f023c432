//! Vendored change: which parts of the window a frame has to redraw, for a
//! painter whose window keeps its pixels between frames (WebGL2, see
//! `web_painter_wgpu.rs`).
//!
//! Each frame's paint jobs are compared with the last frame's, job by job in
//! paint order: a job that differs (another mesh, clip rect or texture, or
//! another place in the order) damages where it is drawn now and where the
//! job at its place was drawn before; within a mesh of the same clip rect and
//! texture, only where its triangles differ (found chunk by chunk). A paint callback with a copy source
//! damages what its texture says changed ([`egui_wgpu::CopyChange`]). The
//! damaged rects are merged into a few regions; redrawing every job inside
//! each region (over the clear colour) gives the pixels of a full redraw.

use egui::epaint::Primitive;

/// A rect in pixels: `[x0, y0, x1, y1]`, `x0 <= x1`, `y0 <= y1`.
pub(crate) type PxRect = [u32; 4];

/// The most regions damaged rects are merged into (each region is its own
/// scissored draws, and apart from the others: see [`disjoint`]).
const MAX_REGIONS: usize = 4;

/// Triangles per chunk of a mesh compared on its own (see [`Drawn::chunks`]).
const CHUNK_TRIANGLES: usize = 32;

/// One paint job as drawn last frame.
#[derive(Clone, Default, PartialEq, Eq)]
struct Drawn {
    /// A hash of the job's bytes as egui gave them (clip rect, texture,
    /// vertices and indices, or the callback's rect) with the window's size
    /// and scale: where it is the same the frame after, the job is the same
    /// and nothing below is computed again (see [`quick_hash`]).
    quick: u64,
    /// Its clip rect, mesh (vertices, indices, texture) or callback rect.
    hash: u64,
    /// Where it drew, in pixels.
    rect: PxRect,
    /// A mesh's clip rect and texture.
    frame: u64,
    /// A mesh's triangles in chunks of [`CHUNK_TRIANGLES`] in draw order:
    /// a hash of each chunk's vertices and where it drew.
    chunks: Vec<(u64, PxRect)>,
    /// The same for each triangle. Where a mesh changed (the timeline's
    /// playhead, a number), only the triangles that differ at their place
    /// are redrawn, looked for in the chunks that differ; a pixel that no
    /// differing triangle reaches is drawn by the same triangles in the same
    /// order. (A chunk's rect would do, but a moving handle's chunk often
    /// holds the end of the rail it moves along, as wide as the window.)
    triangles: Vec<(u64, PxRect)>,
}

/// What the last frame drew; see the module docs.
#[derive(Default)]
pub(crate) struct Damage {
    drawn: Vec<Drawn>,
    /// Window size in pixels and pixels per point of the last frame; `None`
    /// before the first one and after [`Damage::forget`].
    screen: Option<([u32; 2], u32)>,
}

impl Damage {
    /// Makes the next frame a full redraw (the window's pixels are lost or
    /// were drawn by someone else).
    pub fn forget(&mut self) {
        self.screen = None;
        self.drawn.clear();
    }

    /// The regions of the window (`[x, y, width, height]` in pixels, apart
    /// from each other) that `jobs` must be redrawn in; `None` when
    /// everything must be.
    /// `callback_change(index)` tells what changed in the copy source of the
    /// paint callback at `index` (relative to its rect, in pixels).
    pub fn regions(
        &mut self,
        jobs: &[egui::ClippedPrimitive],
        size: [u32; 2],
        pixels_per_point: f32,
        mut callback_change: impl FnMut(usize) -> egui_wgpu::CopyChange,
    ) -> Option<Vec<[u32; 4]>> {
        let screen = (size, pixels_per_point.to_bits());
        let full = self.screen != Some(screen);
        let mut rects = Vec::new();
        let mut drawn = Vec::with_capacity(jobs.len());
        let mut last = std::mem::take(&mut self.drawn);
        for (index, job) in jobs.iter().enumerate() {
            let quick = quick_hash(job, pixels_per_point, size);
            let now = match last.get_mut(index) {
                // The same job as last frame: it damages nothing, and its
                // triangles were found and hashed then.
                Some(before) if before.quick == quick => std::mem::take(before),
                before => {
                    let now = drawn_job(job, quick, pixels_per_point, size);
                    damaged(before.as_deref(), &now, &mut rects);
                    now
                }
            };
            if let Primitive::Callback(callback) = &job.primitive {
                // Always asked, so that the change is taken.
                let change = callback_change(index);
                rects.extend(changed_rects(change, callback.rect, job.clip_rect, pixels_per_point, size));
            }
            drawn.push(now);
        }
        rects.extend(last.iter().skip(jobs.len()).map(|d| d.rect));
        self.drawn = drawn;
        self.screen = Some(screen);
        if full {
            return None;
        }
        rects.retain(|r| r[2] > r[0] && r[3] > r[1]);
        Some(disjoint(merge(rects)).into_iter().map(|[x0, y0, x1, y1]| [x0, y0, x1 - x0, y1 - y0]).collect())
    }

    /// Sets `runs` to the ranges of the indices of this frame's mesh job
    /// `job` (as given to the last [`Damage::regions`]) whose triangles may
    /// draw inside `region` (`[x, y, width, height]` in pixels), in draw
    /// order: the chunks of [`CHUNK_TRIANGLES`] triangles whose rect meets
    /// it, adjacent ones joined; `false` (`runs` left empty): all of them
    /// (the job is not known here). `runs` is the caller's, kept between
    /// calls: this runs for every mesh in every region, every frame.
    ///
    /// A triangle draws only inside its rect, so a redraw of `region` that
    /// draws only these ranges (in order, with the region as the scissor)
    /// gives its pixels as a draw of the whole mesh does; a software
    /// rasteriser no longer shades and sets up every vertex and triangle of
    /// a window-wide mesh (a panel's text, the timeline) for a few pixels.
    pub fn index_runs(&self, job: usize, region: [u32; 4], runs: &mut Vec<std::ops::Range<u32>>) -> bool {
        runs.clear();
        let Some(drawn) = self.drawn.get(job).filter(|d| !d.chunks.is_empty()) else {
            return false;
        };
        let [x, y, w, h] = region;
        let region: PxRect = [x, y, x.saturating_add(w), y.saturating_add(h)];
        let meets = |r: &PxRect| r[0] < region[2] && region[0] < r[2] && r[1] < region[3] && region[1] < r[3];
        let triangles = drawn.triangles.len();
        for (i, (_, rect)) in drawn.chunks.iter().enumerate() {
            if !meets(rect) {
                continue;
            }
            let first = i * CHUNK_TRIANGLES;
            let end = (first + CHUNK_TRIANGLES).min(triangles);
            let (start, end) = ((first * 3) as u32, (end * 3) as u32);
            match runs.last_mut() {
                Some(last) if last.end == start => last.end = end,
                _ => runs.push(start..end),
            }
        }
        true
    }
}

/// More damaged rects than this are joined into one at once (the pairwise
/// merge below takes the cube of their count).
const MAX_MERGED: usize = 48;

/// Pixels a join of two touching rects may add (over their two areas) and
/// still be made: beyond it, and beyond [`JOIN_ADDS_PART`] of their areas,
/// they are redrawn apart (the pixels they share twice, to the same values):
/// a tall figure and its long shadow share a corner, and the rect around
/// both is mostly floor that did not change, while each region costs its
/// passes.
const JOIN_ADDS_PX: u64 = 16_384;

/// See [`JOIN_ADDS_PX`]: the part of two touching rects' areas their join may add.
const JOIN_ADDS_PART: f64 = 0.25;

/// `rects` merged into at most [`MAX_REGIONS`] rects covering them: rects
/// that overlap or touch are joined (unless their join adds much more than
/// it saves, see [`JOIN_ADDS_PX`]), then the pair whose join adds the least
/// area, until few enough are left.
fn merge(mut rects: Vec<PxRect>) -> Vec<PxRect> {
    if rects.len() > MAX_MERGED {
        return rects.into_iter().reduce(join).into_iter().collect();
    }
    loop {
        let mut best: Option<(u64, usize, usize)> = None;
        for i in 0..rects.len() {
            for j in i + 1..rects.len() {
                let joined = join(rects[i], rects[j]);
                let apart = area(rects[i]) + area(rects[j]);
                let added = area(joined).saturating_sub(apart);
                let touching = touches(rects[i], rects[j])
                    && (added <= JOIN_ADDS_PX || (added as f64) <= JOIN_ADDS_PART * apart as f64);
                if touching || rects.len() > MAX_REGIONS {
                    let cost = if touching { 0 } else { added };
                    if best.is_none_or(|(c, _, _)| cost < c) {
                        best = Some((cost, i, j));
                    }
                }
            }
        }
        let Some((_, i, j)) = best else { return rects };
        let joined = join(rects[i], rects[j]);
        rects.swap_remove(j);
        rects[i] = joined;
    }
}

/// `rects` as rects apart from each other covering the same pixels: each
/// less the ones before it, in bands. Regions apart can be redrawn in any
/// order, all in one pass (the web painter's `redraw_regions`); overlapping
/// ones would draw translucent jobs twice where they overlap.
fn disjoint(rects: Vec<PxRect>) -> Vec<PxRect> {
    let mut apart: Vec<PxRect> = Vec::with_capacity(rects.len());
    for rect in rects {
        let mut left = vec![rect];
        for &hole in &apart {
            left = left.into_iter().flat_map(|r| subtract(r, hole)).collect();
        }
        apart.extend(left);
    }
    apart
}

/// `region` less `holes` (both `[x, y, width, height]`), as a few rects in
/// that form: what of a redrawn region no copy or covering callback writes
/// (the web painter draws the background there).
pub(crate) fn uncovered(region: [u32; 4], holes: &[[u32; 4]]) -> Vec<[u32; 4]> {
    let corners = |[x, y, w, h]: [u32; 4]| [x, y, x + w, y + h];
    let mut left = vec![corners(region)];
    for &hole in holes {
        left = left.into_iter().flat_map(|r| subtract(r, corners(hole))).collect();
    }
    left.into_iter().map(|[x0, y0, x1, y1]| [x0, y0, x1 - x0, y1 - y0]).collect()
}

/// `a` less `b`: up to four bands (above, below, left, right of `b`).
fn subtract(a: PxRect, b: PxRect) -> Vec<PxRect> {
    let [x0, y0, x1, y1] = a;
    if b[2] <= x0 || x1 <= b[0] || b[3] <= y0 || y1 <= b[1] {
        return vec![a];
    }
    let (top, bottom) = (b[1].max(y0), b[3].min(y1));
    let bands = [
        [x0, y0, x1, top],
        [x0, bottom, x1, y1],
        [x0, top, b[0].max(x0), bottom],
        [b[2].min(x1), top, x1, bottom],
    ];
    bands.into_iter().filter(|r| r[2] > r[0] && r[3] > r[1]).collect()
}

fn join(a: PxRect, b: PxRect) -> PxRect {
    [a[0].min(b[0]), a[1].min(b[1]), a[2].max(b[2]), a[3].max(b[3])]
}

fn area(r: PxRect) -> u64 {
    u64::from(r[2] - r[0]) * u64::from(r[3] - r[1])
}

fn touches(a: PxRect, b: PxRect) -> bool {
    a[0] <= b[2] && b[0] <= a[2] && a[1] <= b[3] && b[1] <= a[3]
}

/// `rect` (points) in pixels, rounded as egui-wgpu rounds clip rects, and
/// grown by `grow` pixels, within the window.
fn to_pixels(rect: egui::Rect, pixels_per_point: f32, size: [u32; 2], grow: f32) -> PxRect {
    let px = |v: f32, max: u32, d: f32| ((v * pixels_per_point).round() + d).clamp(0.0, max as f32) as u32;
    [
        px(rect.min.x, size[0], -grow),
        px(rect.min.y, size[1], -grow),
        px(rect.max.x, size[0], grow),
        px(rect.max.y, size[1], grow),
    ]
}

/// Where `job` draws: its mesh's bounds (a pixel more each way for edges'
/// rounding) or its callback's rect, within its clip rect.
fn job_rect(job: &egui::ClippedPrimitive, pixels_per_point: f32, size: [u32; 2]) -> PxRect {
    let clip = to_pixels(job.clip_rect, pixels_per_point, size, 0.0);
    let drawn = match &job.primitive {
        Primitive::Mesh(mesh) => {
            let bounds = mesh.calc_bounds();
            if !bounds.is_positive() {
                return [0; 4];
            }
            to_pixels(bounds, pixels_per_point, size, 1.0)
        }
        Primitive::Callback(callback) => to_pixels(callback.rect, pixels_per_point, size, 0.0),
    };
    intersect(clip, drawn)
}

fn intersect(a: PxRect, b: PxRect) -> PxRect {
    let x0 = a[0].max(b[0]);
    let y0 = a[1].max(b[1]);
    [x0, y0, a[2].min(b[2]).max(x0), a[3].min(b[3]).max(y0)]
}

/// The pixels of a paint callback whose copy source changed by `change`
/// (one rect, or two for a change in two rects).
fn changed_rects(
    change: egui_wgpu::CopyChange,
    rect: egui::Rect,
    clip: egui::Rect,
    pixels_per_point: f32,
    size: [u32; 2],
) -> Vec<PxRect> {
    let whole = to_pixels(rect, pixels_per_point, size, 0.0);
    let clip = to_pixels(clip, pixels_per_point, size, 0.0);
    let within = |[x, y, w, h]: [u32; 4]| {
        let at = |o: u32, d: u32, max: u32| o.saturating_add(d).min(max);
        let r = [
            at(whole[0], x, whole[2]),
            at(whole[1], y, whole[3]),
            at(whole[0], x.saturating_add(w), whole[2]),
            at(whole[1], y.saturating_add(h), whole[3]),
        ];
        intersect(clip, r)
    };
    match change {
        egui_wgpu::CopyChange::Nothing => Vec::new(),
        egui_wgpu::CopyChange::All => vec![intersect(clip, whole)],
        rects => rects.rects().into_iter().map(within).collect(),
    }
}

/// Pushes onto `rects` where the job drawn as `now` damages the window, given
/// the job drawn at its place last frame (`before`, none for a new place).
fn damaged(before: Option<&Drawn>, now: &Drawn, rects: &mut Vec<PxRect>) {
    match before {
        Some(before) if before.hash == now.hash && before.rect == now.rect => {}
        Some(before) if before.frame == now.frame && !now.chunks.is_empty() && !before.chunks.is_empty() => {
            let count = before.chunks.len().max(now.chunks.len());
            for i in 0..count {
                if before.chunks.get(i) != now.chunks.get(i) {
                    let at = i * CHUNK_TRIANGLES..(i + 1) * CHUNK_TRIANGLES;
                    rects.push(differing(&before.triangles, &now.triangles, at));
                }
            }
        }
        Some(before) => {
            rects.push(before.rect);
            rects.push(now.rect);
        }
        None => rects.push(now.rect),
    }
}

/// A hash of `job` as egui gave it, with the window's `size` and
/// `pixels_per_point` (what [`drawn_job`] reads): the clip rect, the texture,
/// the vertices' and indices' bytes, or the callback's rect. Several times
/// quicker than [`drawn_job`]'s hash of every triangle, which is needed only
/// where this one changed.
fn quick_hash(job: &egui::ClippedPrimitive, pixels_per_point: f32, size: [u32; 2]) -> u64 {
    let mut h = Hasher::default();
    let r = job.clip_rect;
    h.floats(&[r.min.x, r.min.y, r.max.x, r.max.y, pixels_per_point]);
    h.word(u64::from(size[0]) << 32 | u64::from(size[1]));
    match &job.primitive {
        Primitive::Mesh(mesh) => {
            h.word(texture_word(mesh.texture_id));
            h.bytes(bytemuck::cast_slice(&mesh.vertices));
            h.word(mesh.vertices.len() as u64);
            h.bytes(bytemuck::cast_slice(&mesh.indices));
            h.word(mesh.indices.len() as u64);
        }
        Primitive::Callback(callback) => {
            let r = callback.rect;
            h.word(2);
            h.floats(&[r.min.x, r.min.y, r.max.x, r.max.y]);
        }
    }
    h.0
}

/// `id` as one word, managed and user textures apart.
fn texture_word(id: egui::TextureId) -> u64 {
    match id {
        egui::TextureId::Managed(id) => id,
        egui::TextureId::User(id) => id ^ (1 << 63),
    }
}

/// What `job` (whose [`quick_hash`] is `quick`) draws and where: hashes (FxHash-style over its words) of the
/// whole and, for a mesh, of each chunk of its triangles, with their rects.
fn drawn_job(job: &egui::ClippedPrimitive, quick: u64, pixels_per_point: f32, size: [u32; 2]) -> Drawn {
    let rect = job_rect(job, pixels_per_point, size);
    let mut h = Hasher::default();
    let r = job.clip_rect;
    h.floats(&[r.min.x, r.min.y, r.max.x, r.max.y]);
    match &job.primitive {
        Primitive::Mesh(mesh) => {
            h.word(texture_word(mesh.texture_id));
            let frame = h.0;
            let clip = to_pixels(job.clip_rect, pixels_per_point, size, 0.0);
            let triangles = mesh
                .indices
                .chunks(3)
                .map(|indices| triangle(&mesh.vertices, indices, clip, pixels_per_point, size))
                .collect::<Vec<_>>();
            let chunks = triangles.chunks(CHUNK_TRIANGLES).map(chunk).collect::<Vec<_>>();
            for (hash, _) in &chunks {
                h.word(*hash);
            }
            h.word(chunks.len() as u64);
            Drawn { quick, hash: h.0, rect, frame, chunks, triangles }
        }
        Primitive::Callback(callback) => {
            h.word(2);
            let r = callback.rect;
            h.floats(&[r.min.x, r.min.y, r.max.x, r.max.y]);
            Drawn { quick, hash: h.0, rect, frame: 0, chunks: Vec::new(), triangles: Vec::new() }
        }
    }
}

/// The rect holding the triangles at `at` that differ between `before` and
/// `now` (one of them missing counts as differing), where they drew then and
/// now; an empty rect where none differ.
fn differing(before: &[(u64, PxRect)], now: &[(u64, PxRect)], at: std::ops::Range<usize>) -> PxRect {
    let empty = |r: &PxRect| r[2] <= r[0] || r[3] <= r[1];
    let mut rect: Option<PxRect> = None;
    for i in at {
        let (old, new) = (before.get(i), now.get(i));
        if old.is_none() && new.is_none() {
            break;
        }
        if old != new {
            for r in old.into_iter().chain(new).map(|t| t.1).filter(|r| !empty(r)) {
                rect = Some(rect.map_or(r, |a| join(a, r)));
            }
        }
    }
    rect.unwrap_or([0; 4])
}

/// A hash of a chunk of triangles (each hashed by [`triangle`]) and the
/// rect holding them.
fn chunk(triangles: &[(u64, PxRect)]) -> (u64, PxRect) {
    let mut h = Hasher::default();
    let mut rect: Option<PxRect> = None;
    for &(hash, r) in triangles {
        h.word(hash);
        if r[2] > r[0] && r[3] > r[1] {
            rect = Some(rect.map_or(r, |a| join(a, r)));
        }
    }
    (h.0, rect.unwrap_or([0; 4]))
}

/// A hash of the vertices `indices` draw (in order) and their rect within
/// `clip`, grown by a pixel; an index past the vertices (egui never makes
/// one) hashes as itself.
fn triangle(
    vertices: &[egui::epaint::Vertex],
    indices: &[u32],
    clip: PxRect,
    pixels_per_point: f32,
    size: [u32; 2],
) -> (u64, PxRect) {
    let mut h = Hasher::default();
    let mut bounds = egui::Rect::NOTHING;
    for &i in indices {
        match vertices.get(i as usize) {
            Some(v) => {
                h.floats(&[v.pos.x, v.pos.y, v.uv.x, v.uv.y]);
                h.word(u64::from(u32::from_le_bytes(v.color.to_array())));
                bounds.extend_with(v.pos);
            }
            None => h.word(u64::from(i) | (1 << 40)),
        }
    }
    let rect = if bounds.min.x <= bounds.max.x && bounds.min.y <= bounds.max.y {
        intersect(clip, to_pixels(bounds, pixels_per_point, size, 1.0))
    } else {
        [0; 4]
    };
    (h.0, rect)
}

#[derive(Default)]
struct Hasher(u64);

impl Hasher {
    fn word(&mut self, w: u64) {
        self.0 = (self.0.rotate_left(5) ^ w).wrapping_mul(0x51_7c_c1_b7_27_22_0a_95);
    }

    /// `bytes` eight at a time (the last word padded with zeros).
    fn bytes(&mut self, bytes: &[u8]) {
        let mut words = bytes.chunks_exact(8);
        for w in &mut words {
            let mut word = [0u8; 8];
            word.copy_from_slice(w);
            self.word(u64::from_le_bytes(word));
        }
        let rest = words.remainder();
        if !rest.is_empty() {
            let mut word = [0u8; 8];
            word[..rest.len()].copy_from_slice(rest);
            self.word(u64::from_le_bytes(word));
        }
    }

    fn floats(&mut self, values: &[f32]) {
        for v in values {
            self.word(u64::from(v.to_bits()));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn merge_joins_overlapping_and_caps_the_count() {
        let rects = vec![[0, 0, 10, 10], [5, 5, 20, 20], [100, 100, 110, 110]];
        let merged = merge(rects);
        assert_eq!(merged.len(), 2);
        assert!(merged.contains(&[0, 0, 20, 20]));
        let many: Vec<PxRect> = (0..10).map(|i| [i * 100, 0, i * 100 + 10, 10]).collect();
        assert_eq!(merge(many).len(), MAX_REGIONS);
    }

    #[test]
    fn touching_rects_whose_join_is_mostly_new_stay_apart() {
        // A tall figure (130 x 400) and its long shadow (350 x 90) sharing a corner.
        let figure = [540, 90, 670, 490];
        let shadow = [540, 450, 890, 540];
        let merged = merge(vec![figure, shadow]);
        assert_eq!(merged.len(), 2, "{merged:?}");
        // As the 3.6 MB take's: their join adds 30 % to their areas.
        let merged = merge(vec![[490, 81, 700, 500], [540, 380, 1000, 580]]);
        assert_eq!(merged.len(), 2, "{merged:?}");
        // Two that mostly overlap are joined.
        let merged = merge(vec![[0, 0, 200, 200], [10, 10, 210, 210]]);
        assert_eq!(merged, vec![[0, 0, 210, 210]]);
        // Small neighbours (text) are joined whatever their shape.
        let merged = merge(vec![[0, 0, 100, 10], [100, 0, 110, 60]]);
        assert_eq!(merged, vec![[0, 0, 110, 60]]);
    }

    #[test]
    fn a_change_in_two_rects_damages_both_apart() {
        let rect = egui::Rect::from_min_max(egui::pos2(100.0, 100.0), egui::pos2(900.0, 700.0));
        let change = egui_wgpu::CopyChange::Rects([[400, 0, 130, 400], [400, 360, 350, 90]]);
        let rects = changed_rects(change, rect, rect, 1.0, [1000, 800]);
        assert_eq!(rects, vec![[500, 100, 630, 500], [500, 460, 850, 550]]);
        assert_eq!(merge(rects).len(), 2);
        // Cut to the callback's rect.
        let change = egui_wgpu::CopyChange::Rects([[700, 500, 500, 500], [0; 4]]);
        assert_eq!(
            changed_rects(change, rect, rect, 1.0, [1000, 800]),
            vec![[800, 600, 900, 700], [100, 100, 100, 100]]
        );
    }

    #[test]
    fn a_changed_chunk_damages_only_its_differing_triangles() {
        use egui::epaint::{Mesh, Vertex};
        // A rail as wide as the window and a small handle in the same mesh
        // (and chunk); the handle moves a little.
        let mesh = |handle_x: f32| {
            let mut m = Mesh::default();
            let quad = |m: &mut Mesh, x0: f32, y0: f32, x1: f32, y1: f32| {
                let base = m.vertices.len() as u32;
                for (x, y) in [(x0, y0), (x1, y0), (x1, y1), (x0, y1)] {
                    m.vertices.push(Vertex {
                        pos: egui::pos2(x, y),
                        uv: egui::Pos2::ZERO,
                        color: egui::Color32::WHITE,
                    });
                }
                m.indices.extend([base, base + 1, base + 2, base, base + 2, base + 3]);
            };
            quad(&mut m, 0.0, 100.0, 1000.0, 104.0);
            quad(&mut m, handle_x, 96.0, handle_x + 10.0, 108.0);
            m
        };
        let job = |x: f32| egui::ClippedPrimitive {
            clip_rect: egui::Rect::from_min_max(egui::pos2(0.0, 0.0), egui::pos2(1000.0, 200.0)),
            primitive: Primitive::Mesh(mesh(x)),
        };
        let mut damage = Damage::default();
        let size = [1000, 200];
        assert!(damage.regions(&[job(500.0)], size, 1.0, |_| egui_wgpu::CopyChange::All).is_none(), "first frame: all");
        let regions = damage.regions(&[job(503.0)], size, 1.0, |_| egui_wgpu::CopyChange::All).unwrap();
        assert_eq!(regions.len(), 1, "{regions:?}");
        let [x, y, w, h] = regions[0];
        assert!(
            x >= 495 && x + w <= 520 && y >= 90 && y + h <= 112,
            "the handle's old and new place only: {regions:?}"
        );
        // Nothing changed: nothing to redraw.
        let regions = damage.regions(&[job(503.0)], size, 1.0, |_| egui_wgpu::CopyChange::All).unwrap();
        assert!(regions.is_empty(), "{regions:?}");
        // After a frame the same as the one before (its triangles kept, not
        // found again), a move is still found, and only there.
        let regions = damage.regions(&[job(503.0)], size, 1.0, |_| egui_wgpu::CopyChange::All).unwrap();
        assert!(regions.is_empty(), "{regions:?}");
        let regions = damage.regions(&[job(520.0)], size, 1.0, |_| egui_wgpu::CopyChange::All).unwrap();
        let [x, y, w, h] = regions.first().copied().unwrap_or_default();
        assert!(regions.len() == 1 && x >= 495 && x + w <= 540 && y >= 90 && y + h <= 112, "{regions:?}");
        // A new window size redraws everything.
        assert!(damage.regions(&[job(520.0)], [900, 200], 1.0, |_| egui_wgpu::CopyChange::All).is_none());
    }

    #[test]
    fn the_quick_hash_sees_every_part_of_a_job() {
        use egui::epaint::{Mesh, Vertex};
        let vertex = |x: f32, c: u8| Vertex {
            pos: egui::pos2(x, 1.0),
            uv: egui::Pos2::ZERO,
            color: egui::Color32::from_gray(c),
        };
        let mesh = |x: f32, c: u8, i: u32| {
            let mut m = Mesh::default();
            m.vertices.extend([vertex(0.0, c), vertex(x, c), vertex(x, 255)]);
            m.indices.extend([0, 1, i]);
            m
        };
        let clip = egui::Rect::from_min_max(egui::pos2(0.0, 0.0), egui::pos2(100.0, 100.0));
        let job = |m: Mesh, clip: egui::Rect| egui::ClippedPrimitive { clip_rect: clip, primitive: Primitive::Mesh(m) };
        let base = quick_hash(&job(mesh(10.0, 9, 2), clip), 1.0, [100, 100]);
        assert_eq!(base, quick_hash(&job(mesh(10.0, 9, 2), clip), 1.0, [100, 100]));
        let others = [
            quick_hash(&job(mesh(11.0, 9, 2), clip), 1.0, [100, 100]),
            quick_hash(&job(mesh(10.0, 8, 2), clip), 1.0, [100, 100]),
            quick_hash(&job(mesh(10.0, 9, 1), clip), 1.0, [100, 100]),
            quick_hash(&job(mesh(10.0, 9, 2), clip.translate(egui::vec2(1.0, 0.0))), 1.0, [100, 100]),
            quick_hash(&job(mesh(10.0, 9, 2), clip), 2.0, [100, 100]),
            quick_hash(&job(mesh(10.0, 9, 2), clip), 1.0, [100, 101]),
        ];
        for (i, other) in others.iter().enumerate() {
            assert_ne!(base, *other, "change {i}");
        }
        let mut textured = mesh(10.0, 9, 2);
        textured.texture_id = egui::TextureId::User(1);
        assert_ne!(base, quick_hash(&job(textured, clip), 1.0, [100, 100]));
    }

    #[test]
    fn a_region_draws_only_the_chunks_of_triangles_that_reach_it() {
        use egui::epaint::{Mesh, Vertex};
        // A row of 100 small quads (200 triangles: chunks of 32) across the
        // window, as a panel's text; the quad at `moved` moves down a pixel.
        let mesh = |moved: usize| {
            let mut m = Mesh::default();
            for i in 0..100 {
                let (x, y) = (i as f32 * 10.0, if i == moved { 11.0 } else { 10.0 });
                let base = m.vertices.len() as u32;
                for (dx, dy) in [(0.0, 0.0), (8.0, 0.0), (8.0, 8.0), (0.0, 8.0)] {
                    m.vertices.push(Vertex {
                        pos: egui::pos2(x + dx, y + dy),
                        uv: egui::Pos2::ZERO,
                        color: egui::Color32::WHITE,
                    });
                }
                m.indices.extend([base, base + 1, base + 2, base, base + 2, base + 3]);
            }
            m
        };
        let clip = egui::Rect::from_min_max(egui::pos2(0.0, 0.0), egui::pos2(1000.0, 100.0));
        let job = |moved| egui::ClippedPrimitive { clip_rect: clip, primitive: Primitive::Mesh(mesh(moved)) };
        let mut damage = Damage::default();
        let size = [1000, 100];
        assert!(damage.regions(&[job(40)], size, 1.0, |_| egui_wgpu::CopyChange::All).is_none());
        let regions = damage.regions(&[job(41)], size, 1.0, |_| egui_wgpu::CopyChange::All).unwrap();
        assert_eq!(regions.len(), 1, "{regions:?}");
        // The runs, or `None` for all of them (a buffer with runs of an
        // earlier call is cleared).
        let runs = |job, region| {
            let mut buffer = vec![0..1];
            damage.index_runs(job, region, &mut buffer).then_some(buffer)
        };
        // Quads 40 and 41 are triangles 80..84: the chunk of triangles 64..96.
        assert_eq!(runs(0, regions[0]), Some(vec![64 * 3..96 * 3]));
        // A region across two chunks gets one run; one reaching none, none.
        assert_eq!(runs(0, [300, 0, 40, 30]), Some(vec![32 * 3..96 * 3]));
        assert_eq!(runs(0, [0, 50, 1000, 30]), Some(Vec::new()));
        // The first chunk alone; all of them as one run.
        assert_eq!(runs(0, [0, 0, 5, 30]), Some(vec![0..32 * 3]));
        assert_eq!(runs(0, [0, 0, 1000, 30]), Some(vec![0..200 * 3]));
        // The last chunk ends at the last triangle.
        assert_eq!(runs(0, [990, 0, 10, 30]), Some(vec![192 * 3..200 * 3]));
        // A job this frame does not have: all of it.
        assert_eq!(runs(1, regions[0]), None);
    }

    #[test]
    fn regions_are_apart_and_cover_what_was_damaged() {
        // A tall figure and its long shadow sharing a corner stay two rects
        // (see above); what they share belongs to one of them only.
        let figure = [540, 90, 670, 490];
        let shadow = [540, 450, 890, 540];
        let apart = disjoint(merge(vec![figure, shadow]));
        let covered = |x: u32, y: u32| apart.iter().filter(|r| r[0] <= x && x < r[2] && r[1] <= y && y < r[3]).count();
        for y in (80..560).step_by(5) {
            for x in (530..900).step_by(5) {
                let inside = [figure, shadow].iter().any(|r| r[0] <= x && x < r[2] && r[1] <= y && y < r[3]);
                assert_eq!(covered(x, y), usize::from(inside), "({x}, {y}) in {apart:?}");
            }
        }
        // A rect inside another is gone; ones apart are kept as they are.
        assert_eq!(disjoint(vec![[0, 0, 100, 100], [10, 10, 20, 20]]), vec![[0, 0, 100, 100]]);
        assert_eq!(disjoint(vec![[0, 0, 10, 10], [20, 0, 30, 10]]), vec![[0, 0, 10, 10], [20, 0, 30, 10]]);
        // A rect across the middle of another: its two ends.
        assert_eq!(disjoint(vec![[10, 0, 20, 100], [0, 40, 30, 50]]), vec![[10, 0, 20, 100], [0, 40, 10, 50], [20, 40, 30, 50]]);
    }

    #[test]
    fn the_background_goes_where_nothing_covers_a_region() {
        // A region with a copy across its middle and one beside it.
        let bands = uncovered([0, 0, 100, 50], &[[20, 10, 30, 20], [200, 0, 10, 10]]);
        let area: u32 = bands.iter().map(|b| b[2] * b[3]).sum();
        assert_eq!(area, 100 * 50 - 30 * 20, "{bands:?}");
        let inside = |x: u32, y: u32, [bx, by, bw, bh]: [u32; 4]| bx <= x && x < bx + bw && by <= y && y < by + bh;
        for (x, y) in [(0, 0), (19, 15), (50, 15), (25, 30), (99, 49)] {
            assert_eq!(bands.iter().filter(|&&b| inside(x, y, b)).count(), 1, "({x}, {y}) in {bands:?}");
        }
        assert!(!bands.iter().any(|&b| inside(25, 15, b)), "{bands:?}");
        // Nothing covered: the region itself.
        assert_eq!(uncovered([5, 5, 10, 10], &[]), vec![[5, 5, 10, 10]]);
    }
}
