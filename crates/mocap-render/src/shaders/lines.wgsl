// Screen-space-wide line segments: one instance per segment, six vertices per quad.

// `Frame` and `frame` come from frame.wgsl.

struct Out {
    @builtin(position) position: vec4<f32>,
    @location(0) color: vec4<f32>,
};

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
    var dir = sb - sa;
    if (dot(dir, dir) < 1e-12) {
        dir = vec2<f32>(1.0, 0.0);
    }
    let normal = normalize(vec2<f32>(-dir.y, dir.x));
    // Quad corners: (end, side) for the two triangles.
    var ends = array<f32, 6>(0.0, 1.0, 0.0, 0.0, 1.0, 1.0);
    var sides = array<f32, 6>(-1.0, -1.0, 1.0, 1.0, -1.0, 1.0);
    let i = vertex % 6u;
    let p = select(ca, cb, ends[i] > 0.5);
    let offset = normal * sides[i] * width / size;
    out.position = vec4<f32>(p.xy + offset * p.w, p.z, p.w);
    return out;
}

@fragment
fn fs_main(in: Out) -> @location(0) vec4<f32> {
    return to_target(in.color);
}
