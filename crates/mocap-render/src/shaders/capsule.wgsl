// Lit capsules: one instance per capsule over a shared unit-capsule mesh whose
// vertices carry a unit direction and which end (0 = a, 1 = b) they belong to.
// `Frame`, `frame`, `to_target` and `shade` come from frame.wgsl and lighting.wgsl.

struct Out {
    @builtin(position) position: vec4<f32>,
    @location(0) color: vec4<f32>,
    @location(1) world: vec3<f32>,
    @location(2) normal: vec3<f32>,
};

// World position and normal of a mesh vertex for the capsule `a`–`b`.
fn place(dir: vec3<f32>, end: f32, a: vec3<f32>, b: vec3<f32>, radius: f32) -> array<vec3<f32>, 2> {
    let axis = b - a;
    let len = length(axis);
    let z = select(vec3<f32>(0.0, 1.0, 0.0), axis / max(len, 1e-20), len > 1e-12);
    let helper = select(vec3<f32>(1.0, 0.0, 0.0), vec3<f32>(0.0, 0.0, 1.0), abs(z.x) > 0.8);
    let x = normalize(cross(helper, z));
    let y = cross(z, x);
    let n = x * dir.x + y * dir.y + z * dir.z;
    return array<vec3<f32>, 2>(mix(a, b, end) + n * radius, n);
}

// A mesh vertex (locations 0-1) of one capsule instance (locations 2-5).
struct CapsuleVertex {
    @location(0) dir: vec3<f32>,
    @location(1) end: f32,
    @location(2) a: vec3<f32>,
    @location(3) radius: f32,
    @location(4) b: vec3<f32>,
    @location(5) color: vec4<f32>,
};

@vertex
fn vs_main(v: CapsuleVertex) -> Out {
    let placed = place(v.dir, v.end, v.a, v.b, v.radius);
    var out: Out;
    out.position = frame.projection * frame.view * vec4<f32>(placed[0], 1.0);
    out.color = v.color;
    out.world = placed[0];
    out.normal = placed[1];
    return out;
}

// Depth-only pass into the shadow map.
@vertex
fn vs_shadow(v: CapsuleVertex) -> @builtin(position) vec4<f32> {
    let placed = place(v.dir, v.end, v.a, v.b, v.radius);
    return frame.light_view_proj * vec4<f32>(placed[0], 1.0);
}

// The same capsules placed on the CPU (see capsule::expand_lit): one plain
// draw instead of one instance each.
struct PlacedVertex {
    @location(0) position: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) color: vec4<f32>,
};

@vertex
fn vs_placed(v: PlacedVertex) -> Out {
    var out: Out;
    out.position = frame.projection * frame.view * vec4<f32>(v.position, 1.0);
    out.color = v.color;
    out.world = v.position;
    out.normal = v.normal;
    return out;
}

// Depth-only pass into the shadow map, capsules placed on the CPU
// (see capsule::expand): one plain draw instead of one instance each.
@vertex
fn vs_shadow_placed(@location(0) position: vec4<f32>) -> @builtin(position) vec4<f32> {
    return frame.light_view_proj * position;
}

@fragment
fn fs_main(in: Out) -> @location(0) vec4<f32> {
    let n = normalize(in.normal);
    return to_target(vec4<f32>(shade(in.color.rgb, in.world, n), in.color.a));
}
