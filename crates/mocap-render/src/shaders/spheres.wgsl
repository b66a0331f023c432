// Lit sphere impostors: camera-facing quads shaded as spheres.
// `Frame`, `frame`, `to_target` and `shade` come from frame.wgsl and lighting.wgsl.

struct Out {
    @builtin(position) position: vec4<f32>,
    @location(0) color: vec4<f32>,
    @location(1) uv: vec2<f32>,
    @location(2) center: vec3<f32>,
    @location(3) radius: f32,
};

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
    let uv = vec2<f32>(xs[i], ys[i]);
    let c = frame.view * vec4<f32>(center, 1.0);
    // Push the quad to the sphere's front so bones entering the joint stay hidden.
    let corner = vec4<f32>(c.xy + uv * radius, c.z + radius, 1.0);
    var out: Out;
    out.position = frame.projection * corner;
    out.color = color;
    out.uv = uv;
    out.center = center;
    out.radius = radius;
    return out;
}

@fragment
fn fs_main(in: Out) -> @location(0) vec4<f32> {
    let r2 = dot(in.uv, in.uv);
    if (r2 > 1.0) {
        discard;
    }
    // View-space normal back to world space (the view matrix is a rotation + shift).
    let view_normal = vec3<f32>(in.uv, sqrt(1.0 - r2));
    let rot = mat3x3<f32>(frame.view[0].xyz, frame.view[1].xyz, frame.view[2].xyz);
    let n = normalize(transpose(rot) * view_normal);
    let p = in.center + n * in.radius;
    return to_target(vec4<f32>(shade(in.color.rgb, p, n), in.color.a));
}
