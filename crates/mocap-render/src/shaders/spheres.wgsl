// Lit sphere impostors: camera-facing quads shaded as spheres.
// `Frame`, `frame`, `to_target` and `shade` come from frame.wgsl and lighting.wgsl.

struct Out {
    @builtin(position) position: vec4<f32>,
    @location(0) color: vec4<f32>,
    @location(1) uv: vec2<f32>,
    @location(2) center: vec3<f32>,
    @location(3) radius: f32,
    // Pixels per unit of `uv` (the disc's radius in pixels).
    @location(4) pixels: f32,
};

// The disc's radius on screen in pixels: the quad's centre and its right
// edge projected (perspective or orthographic alike).
fn radius_px(c: vec4<f32>, radius: f32) -> f32 {
    let m = frame.projection * c;
    let e = frame.projection * vec4<f32>(c.x + radius, c.yzw);
    return abs(e.x / e.w - m.x / m.w) * 0.5 * frame.viewport.x;
}

@vertex
fn vs_main(
    @builtin(vertex_index) vertex: u32,
    @location(0) center: vec3<f32>,
    @location(1) radius: f32,
    @location(2) color: vec4<f32>,
) -> Out {
    var xs = array<f32, 6>(-1.0, 1.0, -1.0, -1.0, 1.0, 1.0);
    var ys = array<f32, 6>(-1.0, -1.0, 1.0, 1.0, -1.0, 1.0);
    let i = vertex % 6u;
    let c = frame.view * vec4<f32>(center, 1.0);
    // Push the quad to the sphere's front so bones entering the joint stay hidden.
    let front = vec4<f32>(c.xy, c.z + radius, 1.0);
    let pixels = radius_px(front, radius);
    // With BLEND_OUTLINES the quad reaches a pixel past the disc for the
    // coverage filter.
    let reach = select(1.0, 1.0 + 1.0 / max(pixels, 1e-6), BLEND_OUTLINES);
    let uv = vec2<f32>(xs[i], ys[i]) * reach;
    let corner = front + vec4<f32>(uv * radius, 0.0, 0.0);
    var out: Out;
    out.position = frame.projection * corner;
    out.color = color;
    out.uv = uv;
    out.center = center;
    out.radius = radius;
    out.pixels = pixels;
    return out;
}

@fragment
fn fs_main(in: Out) -> @location(0) vec4<f32> {
    let r2 = dot(in.uv, in.uv);
    // How much of the pixel the disc covers: all or nothing at its centre,
    // or with BLEND_OUTLINES filtered across the outline (a pixel wide).
    var coverage = select(1.0, 0.0, r2 > 1.0);
    if (BLEND_OUTLINES) {
        coverage = outline_coverage((sqrt(r2) - 1.0) * in.pixels);
    }
    if (coverage <= 0.0) {
        discard;
    }
    // View-space normal back to world space (the view matrix is a rotation + shift);
    // on the fringe outside the disc, the outline's.
    let view_normal = vec3<f32>(in.uv, sqrt(max(1.0 - r2, 0.0))) / max(sqrt(r2), 1.0);
    let rot = mat3x3<f32>(frame.view[0].xyz, frame.view[1].xyz, frame.view[2].xyz);
    let n = normalize(transpose(rot) * view_normal);
    let p = in.center + n * in.radius;
    return to_target(vec4<f32>(shade(in.color.rgb, p, n), in.color.a * coverage));
}
