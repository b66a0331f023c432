// The floor: one quad on the plane y = floor height, with anti-aliased grid lines
// and a fade to the background with distance; then the key light's soft shadow as
// a second quad covering only the floor where a lookup can find a caster
// (`frame.shadow_rect`), multiplied over it (so the shadow lookups, costly on
// software rasterisers, run only where needed).
// `Frame`, `frame` and `key_visibility` come from frame.wgsl and lighting.wgsl.

struct Out {
    @builtin(position) position: vec4<f32>,
    @location(0) world: vec3<f32>,
};

@vertex
fn vs_main(@builtin(vertex_index) vertex: u32) -> Out {
    var xs = array<f32, 6>(-1.0, 1.0, -1.0, -1.0, 1.0, 1.0);
    var zs = array<f32, 6>(-1.0, -1.0, 1.0, 1.0, -1.0, 1.0);
    let i = vertex % 6u;
    let half = frame.floor_grid.z;
    let p = frame.floor_center.xyz + vec3<f32>(xs[i] * half, 0.0, zs[i] * half);
    var out: Out;
    out.position = frame.projection * frame.view * vec4<f32>(p, 1.0);
    out.world = p;
    return out;
}

// Coverage (0..1) of lines one unit apart, `width` pixels wide, at `coord`,
// where `w` is `fwidth(coord)`.
fn grid_lines(coord: vec2<f32>, w: vec2<f32>, width: f32) -> f32 {
    let d = abs(fract(coord - 0.5) - 0.5) / w;
    let line = 1.0 - min(min(d.x, d.y) / width, 1.0);
    // Lines closer together than about two pixels fade out instead of shimmering.
    let dense = smoothstep(0.3, 0.6, max(w.x, w.y));
    return line * (1.0 - dense);
}

// The floor's colours arrive as the target stores them (sRGB-encoded for a
// plain unorm target, see `FrameUniforms`), so the lines are mixed there and
// nothing is encoded per pixel: on a software rasteriser the encoding's powers
// were most of this shader's cost, and it covers much of the screen.
@fragment
fn fs_main(in: Out) -> @location(0) vec4<f32> {
    let rel = in.world.xz - frame.floor_center.xz;
    let coord = rel / max(frame.floor_grid.x, 1e-6);
    // The major lines' coordinates are the minor ones scaled, and so are their
    // derivatives: one `fwidth` serves both.
    let w = max(fwidth(coord), vec2<f32>(1e-6));
    let major_every = max(frame.floor_grid.y, 1.0);
    let minor = grid_lines(coord, w, 1.0);
    let major = grid_lines(coord / major_every, w / major_every, 1.5);
    var color = frame.floor_color.rgb;
    color = mix(color, frame.floor_minor.rgb, minor * frame.floor_minor.a);
    color = mix(color, frame.floor_major.rgb, major * frame.floor_major.a);
    return vec4<f32>(color, floor_alpha(in.world) * frame.floor_color.a);
}

// The floor's depth only, under a floor whose colour was copied from the cache
// (floor_cache.rs): the pipeline writes no colour.
@fragment
fn fs_depth() -> @location(0) vec4<f32> {
    return vec4<f32>(0.0);
}

@vertex
fn vs_shadow(@builtin(vertex_index) vertex: u32) -> Out {
    var xs = array<f32, 6>(0.0, 1.0, 0.0, 0.0, 1.0, 1.0);
    var zs = array<f32, 6>(0.0, 0.0, 1.0, 1.0, 0.0, 1.0);
    let i = vertex % 6u;
    let r = frame.shadow_rect;
    let p = vec3<f32>(mix(r.x, r.z, xs[i]), frame.floor_center.y, mix(r.y, r.w, zs[i]));
    var out: Out;
    out.position = frame.projection * frame.view * vec4<f32>(p, 1.0);
    // Between the floor and the marks of `fs_marked` (the map's shadow quad
    // draws whatever the depth).
    out.position.z += 0.5 * MARK_DEPTH * out.position.w;
    out.world = p;
    return out;
}

// The fast look's shadow where the casters' footprints marked the floor's
// depth (capsule.wgsl's `vs_footprint`; the pipeline's depth test passes there
// only): the factor of the floor in full shadow.
@fragment
fn fs_marked(in: Out) -> @location(0) vec4<f32> {
    let k = floor_shadow_factor(in.world, 1.0 - frame.viewport.w);
    return vec4<f32>(k, k, k, 1.0);
}

// A factor the colour below is multiplied by: 1 in light, darker in shadow.
@fragment
fn fs_shadow(in: Out) -> @location(0) vec4<f32> {
    let k = floor_shadow_factor(in.world, key_visibility(in.world, vec3<f32>(0.0, 1.0, 0.0)));
    return vec4<f32>(k, k, k, 1.0);
}
