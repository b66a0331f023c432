// Screen-space-wide line segments: one instance per segment, six vertices per quad.
// With BLEND_OUTLINES the quad reaches a pixel past the line's edges and ends,
// and the fragment's alpha is its pixel's coverage (a one-pixel box filter).

// `Frame` and `frame` come from frame.wgsl.

struct Out {
    @builtin(position) position: vec4<f32>,
    @location(0) color: vec4<f32>,
    // With BLEND_OUTLINES: pixels from the line's middle across it (x) and
    // from its first end along it (y), the line's half width (z) and length
    // in pixels (w), each times the vertex's clip w; and that w. Their
    // perspective-correct ratio is the screen-space (linear) interpolation,
    // which OpenGL ES (WebGL2) has no qualifier for.
    @location(1) reach_w: vec4<f32>,
    @location(2) w: f32,
};

// Pixels the quads reach past a line's edges and ends for the coverage filter.
fn fringe_px() -> f32 {
    return select(0.0, 1.0, BLEND_OUTLINES);
}

// How much of the span from `lo` to `hi` a pixel centred at `d` covers, along
// one axis (a one-pixel box filter).
fn box_coverage(d: f32, lo: f32, hi: f32) -> f32 {
    return clamp(min(d + 0.5, hi) - max(d - 0.5, lo), 0.0, 1.0);
}

// Moves a clip-space point that lies behind the near region towards the other end.
fn clip_to_front(p: vec4<f32>, q: vec4<f32>) -> vec4<f32> {
    let eps = 1e-4;
    if (p.w >= eps) {
        return p;
    }
    let t = (eps - p.w) / (q.w - p.w);
    return mix(p, q, t);
}

@vertex
fn vs_main(
    @builtin(vertex_index) vertex: u32,
    @location(0) a: vec3<f32>,
    @location(1) b: vec3<f32>,
    @location(2) color: vec4<f32>,
    @location(3) width: f32,
) -> Out {
    var out: Out;
    out.color = color;
    let view_proj = frame.projection * frame.view;
    let ca0 = view_proj * vec4<f32>(a, 1.0);
    let cb0 = view_proj * vec4<f32>(b, 1.0);
    if (ca0.w < 1e-4 && cb0.w < 1e-4) {
        out.position = vec4<f32>(2.0, 2.0, 2.0, 1.0);
        return out;
    }
    let ca = clip_to_front(ca0, cb0);
    let cb = clip_to_front(cb0, ca0);
    let size = frame.viewport.xy;
    let sa = ca.xy / ca.w * size;
    let sb = cb.xy / cb.w * size;
    // (sa and sb are in half pixels: clip space spans 2 across the view.)
    var dir = sb - sa;
    let length_px = length(dir) * 0.5;
    if (dot(dir, dir) < 1e-12) {
        dir = vec2<f32>(1.0, 0.0);
    }
    let along = normalize(dir);
    let normal = vec2<f32>(-along.y, along.x);
    // Quad corners: (end, side) for the two triangles.
    var ends = array<f32, 6>(0.0, 1.0, 0.0, 0.0, 1.0, 1.0);
    var sides = array<f32, 6>(-1.0, -1.0, 1.0, 1.0, -1.0, 1.0);
    let i = vertex % 6u;
    let end = ends[i] > 0.5;
    let p = select(ca, cb, end);
    let fringe = fringe_px();
    let half_width = width * 0.5;
    let across_px = sides[i] * (half_width + fringe);
    let along_px = select(-fringe, fringe, end);
    let offset = (normal * across_px + along * along_px) * 2.0 / size;
    out.position = vec4<f32>(p.xy + offset * p.w, p.z, p.w);
    out.reach_w = vec4<f32>(across_px, select(0.0, length_px, end) + along_px, half_width, length_px) * p.w;
    out.w = p.w;
    return out;
}

@fragment
fn fs_main(in: Out) -> @location(0) vec4<f32> {
    if (!BLEND_OUTLINES) {
        return to_target(in.color);
    }
    let reach = in.reach_w / in.w;
    let coverage = box_coverage(reach.x, -reach.z, reach.z) * box_coverage(reach.y, 0.0, reach.w);
    if (coverage <= 0.0) {
        discard;
    }
    return to_target(vec4<f32>(in.color.rgb, in.color.a * coverage));
}
