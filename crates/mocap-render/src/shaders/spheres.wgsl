// Lit sphere impostors: camera-facing quads shaded as spheres.

// `Frame` and `frame` come from frame.wgsl.

struct Out {
    @builtin(position) position: vec4<f32>,
    @location(0) color: vec4<f32>,
    @location(1) uv: vec2<f32>,
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
    return out;
}

@fragment
fn fs_main(in: Out) -> @location(0) vec4<f32> {
    let r2 = dot(in.uv, in.uv);
    if (r2 > 1.0) {
        discard;
    }
    let normal = vec3<f32>(in.uv, sqrt(1.0 - r2));
    let light = normalize(vec3<f32>(-0.4, 0.6, 0.7));
    let diffuse = max(dot(normal, light), 0.0);
    let rim = smoothstep(0.85, 1.0, r2) * 0.25;
    let shade = 0.35 + 0.65 * diffuse;
    return vec4<f32>(in.color.rgb * shade * (1.0 - rim), in.color.a);
}
