// Capsules as impostors (see capsule.rs): each capsule is one triangle (a
// small one) or two (a rectangle) covering its outline, and the fragment shader
// casts the pixel's ray at the capsule for the exact surface point, normal and
// depth. Spheres are capsules of zero length.
// `Frame`, `frame`, `to_target` and `shade` come from frame.wgsl and lighting.wgsl.
//
// "Ray coordinates" below: for a perspective view, the point (x / -z, y / -z)
// at which a ray from the eye crosses the plane one unit in front of it (view
// space); for an orthographic view, the ray's view-space (x, y). Both are
// linear in screen position.

// One corner of a capsule's quad (see `capsule_corner`).
struct CapsuleIn {
    @location(0) a: vec3<f32>,
    @location(1) radius: f32,
    @location(2) b: vec3<f32>,
    @location(3) corner: f32,
    @location(4) color: vec4<f32>,
};

struct Out {
    @builtin(position) position: vec4<f32>,
    // The shape's point in the world: in front of the capsule, on the pixel's ray.
    @location(0) world: vec3<f32>,
    // The capsule in the world.
    @location(1) @interpolate(flat) a: vec3<f32>,
    @location(2) @interpolate(flat) b: vec3<f32>,
    @location(3) @interpolate(flat) radius: f32,
    @location(4) @interpolate(flat) color: vec4<f32>,
};

fn is_perspective() -> bool {
    return frame.projection[3][3] < 0.5;
}

// Distance of the near plane (both the perspective and the orthographic
// projections map view depth `near` to 0).
fn near_distance() -> f32 {
    return frame.projection[3][2] / frame.projection[2][2];
}

// Ray coordinates of a point in normalised device coordinates.
fn ray_of_ndc(ndc: vec2<f32>) -> vec2<f32> {
    let p = frame.projection;
    let scale = vec2<f32>(p[0][0], p[1][1]);
    if (is_perspective()) {
        return (ndc + vec2<f32>(p[2][0], p[2][1])) / scale;
    }
    return (ndc - vec2<f32>(p[3][0], p[3][1])) / scale;
}

// A circle in ray coordinates (centre, radius) holding the outline of the
// sphere of radius `r` at view-space `p`; a negative radius when there is no
// such bound (the sphere reaches the eye's plane or about 85 degrees off the axis).
fn sphere_bound(p: vec3<f32>, r: f32) -> vec3<f32> {
    if (!is_perspective()) {
        return vec3<f32>(p.xy, r);
    }
    let z = -p.z;
    let l = length(p);
    if (z - r <= 0.0 || l <= r) {
        return vec3<f32>(0.0, 0.0, -1.0);
    }
    // The outline is the cone of half-angle `alpha` around the ray to `p`,
    // which leaves the axis at angle `phi`; along the ray plane it reaches
    // tan(phi + alpha) - tan(phi) from the centre's image, its farthest.
    let sin_a = r / l;
    let cos_a = sqrt(max(1.0 - sin_a * sin_a, 0.0));
    let cos_p = z / l;
    let sin_p = length(p.xy) / l;
    let den = cos_p * cos_a - sin_p * sin_a;
    if (den <= 0.08) {
        return vec3<f32>(0.0, 0.0, -1.0);
    }
    let reach = (sin_p * cos_a + cos_p * sin_a) / den - sin_p / cos_p;
    return vec3<f32>(p.xy / z, reach);
}

// Whether the sphere of view-space centre `c` and radius `r` lies wholly
// outside the view (beyond one of its planes).
fn outside_view(c: vec3<f32>, r: f32) -> bool {
    for (var i = 0; i < 6; i++) {
        let n = frame.view_planes[i];
        if (dot(n.xyz, c) + n.w < -r) {
            return true;
        }
    }
    return false;
}

// The image of a capsule's axis from `a` to `b`: its unit direction `w`
// (along x when it has no length), `u` square to it, and its length.
struct Axis {
    w: vec2<f32>,
    u: vec2<f32>,
    len: f32,
};

fn axis_of(a: vec2<f32>, b: vec2<f32>) -> Axis {
    let along = b - a;
    let len = length(along);
    let w = select(vec2<f32>(1.0, 0.0), along / len, len > 1e-12);
    return Axis(w, vec2<f32>(-w.y, w.x), len);
}

// Corner `k` (0: behind `a`, 1: beyond `b`, on one side; 2 and 3 on the
// other) of a rectangle along `axis` from `a` in a plane holding the circles
// of radius `ra` around `a` and `rb` around its other end (so their hull),
// grown by `margin`.
fn quad_corner(k: u32, axis: Axis, a: vec2<f32>, ra: f32, rb: f32, margin: f32) -> vec2<f32> {
    let side = select(-1.0, 1.0, k >= 2u);
    // Either circle may reach farther back or forward (an axis seen end-on).
    let back = min(-ra, axis.len - rb) - margin;
    let forward = max(axis.len + rb, ra) + margin;
    return a + axis.w * select(back, forward, (k & 1u) == 1u) + axis.u * (max(ra, rb) + margin) * side;
}

// `ONE_TRIANGLE_BELOW`: capsules narrower than this many pixels (texels in
// the shadow map) are drawn as one triangle, wider ones as a rectangle's two.
// Declared ahead of this file by capsule.rs (`shader_source`), whose rule for
// capsules small in every pass uses the same value.

// Whether the capsule of radii `ra`, `rb` grown by `margin` is drawn as one
// triangle where one pixel (texel) is `unit` long.
fn is_one_triangle(ra: f32, rb: f32, margin: f32, unit: f32) -> bool {
    return 2.0 * (max(ra, rb) + margin) < ONE_TRIANGLE_BELOW * unit;
}

// Whether `corner` is one of a forced triangle's (4-6: the CPU found the
// capsule small in every pass and gave its triangle alone, see capsule.rs's
// `is_one_triangle`).
fn is_forced_triangle(corner: f32) -> bool {
    return corner > 3.5;
}

// Corner `corner` (0-3) of the shape a capsule is drawn as: one triangle
// (`triangle_corner`, corner 3 on corner 2, so the quad's second triangle has
// no area and is dropped before shading) when it is small, else the rectangle
// (`quad_corner`); corners 4-6 are always the triangle's 0-2. A software
// rasteriser shades whole blocks of pixels per triangle: a small capsule's two
// triangles shared most of theirs, while a large one's triangle would cover
// far more pixels than its rectangle. (A software rasteriser also computes
// both shapes, whichever is drawn: they share `axis`, `axis_of(a, b)`.)
fn capsule_corner(corner: f32, axis: Axis, a: vec2<f32>, ra: f32, b: vec2<f32>, rb: f32, margin: f32, unit: f32) -> vec2<f32> {
    let forced = is_forced_triangle(corner);
    let k = u32(select(min(corner, 2.0), corner - 4.0, forced) + 0.5);
    let triangle = triangle_corner(k, axis, a, b, max(ra, rb) + margin);
    let quad = quad_corner(u32(corner + 0.5), axis, a, ra, rb, margin);
    return select(quad, triangle, forced || is_one_triangle(ra, rb, margin, unit));
}

// How far beyond `b` the apex of `triangle_corner`'s triangle lies, for an
// axis of length `len` and half width `h`: about the least area (2h for a
// ball, the equilateral triangle around it; farther for a longer capsule).
fn apex_distance(len: f32, h: f32) -> f32 {
    return 2.0 * h + 0.75 * len;
}

// Corner `k` (0: the apex beyond `b`; 1 and 2: behind `a`, one on each side)
// of a triangle along `axis` from `a` to `b` holding the circles of radius `h`
// around both ends (so the hull of any smaller circles there, a capsule's
// outline grown by a margin). Its sides are tangent to the circle around `b`
// and pass outside the one around `a`, and its base is tangent to that one.
fn triangle_corner(k: u32, axis: Axis, a: vec2<f32>, b: vec2<f32>, h: f32) -> vec2<f32> {
    let d = apex_distance(axis.len, h);
    // The sides leave the axis at the angle whose sine is h / d.
    let half_width = (axis.len + d + h) * h / sqrt(max(d * d - h * h, 1e-30));
    let base = a - axis.w * h + axis.u * half_width * select(-1.0, 1.0, k == 2u);
    return select(base, b + axis.w * d, k == 0u);
}

// How much wider than on the view's axis the edge filter's fringe is in ray
// coordinates around the capsule whose ends' outline bounds are `ea` and `eb`
// (`sphere_bound`'s). The filter measures how far a pixel's ray passes
// outside the capsule, across the ray; a ray at angle t off the axis turns
// that into t's secant times as much in ray coordinates (a secant squared for
// the angle, times the cosine by which the point is nearer than along the
// axis), which is at most the secant at the bounds' farthest point. 1 for an
// orthographic view.
fn fringe_stretch(ea: vec3<f32>, eb: vec3<f32>) -> f32 {
    if (!is_perspective()) {
        return 1.0;
    }
    let farthest = max(length(ea.xy) + ea.z, length(eb.xy) + eb.z);
    return sqrt(1.0 + farthest * farthest);
}

// Size of one pixel in ray coordinates.
fn pixel_in_ray_units() -> f32 {
    return 2.0 / max(frame.projection[1][1] * frame.viewport.y, 1e-20);
}

@vertex
fn vs_main(v: CapsuleIn) -> Out {
    let a = (frame.view * vec4<f32>(v.a, 1.0)).xyz;
    let b = (frame.view * vec4<f32>(v.b, 1.0)).xyz;
    let r = abs(v.radius);
    let ea = sphere_bound(a, r);
    let eb = sphere_bound(b, r);
    var ray: vec2<f32>;
    var depth: f32;
    let near = near_distance();
    var out: Out;
    if (ea.z < 0.0 || eb.z < 0.0) {
        // Too close to the eye for a bound: the whole view (rare), unless the
        // capsule is out of view (beside or behind the eye): then all four
        // corners at one point, nothing to draw.
        if (outside_view(0.5 * (a + b), 0.5 * length(b - a) + r)) {
            out.position = vec4<f32>(2.0, 2.0, 0.5, 1.0);
            return out;
        }
        let k = u32(v.corner + 0.5);
        var ndc = vec2<f32>(select(-1.0, 1.0, (k & 1u) == 1u), select(-1.0, 1.0, k >= 2u));
        if (is_forced_triangle(v.corner)) {
            // A forced triangle's three corners: one triangle over the view.
            ndc = vec2<f32>(select(-1.0, 3.0, k == 5u), select(-1.0, 3.0, k == 6u));
        }
        ray = ray_of_ndc(ndc);
        depth = near * 1.001;
    } else {
        // A triangle or rectangle (`capsule_corner`) around the axis's image
        // holding both end circles (so their hull, the capsule's outline),
        // with room for the edge filter: coverage falls to 0 half a pixel
        // out (none in the fast look), which `fringe_stretch` widens, and a
        // twentieth of a pixel against rounding.
        let fringe = (0.5 - frame.samples.x) * fringe_stretch(ea, eb) + 0.05;
        let margin = fringe * pixel_in_ray_units();
        ray = capsule_corner(v.corner, axis_of(ea.xy, eb.xy), ea.xy, ea.z, eb.xy, eb.z, margin, pixel_in_ray_units());
        // In front of the capsule, behind the near plane.
        depth = max(min(-a.z, -b.z) - r, near * 1.001);
    }
    var view_point = vec4<f32>(ray * depth, -depth, 1.0);
    if (!is_perspective()) {
        view_point = vec4<f32>(ray, -depth, 1.0);
    }
    out.position = frame.projection * view_point;
    // View space back to the world (the view matrix is a rotation + shift).
    let rot = transpose(mat3x3<f32>(frame.view[0].xyz, frame.view[1].xyz, frame.view[2].xyz));
    out.world = rot * (view_point.xyz - frame.view[3].xyz);
    out.a = v.a;
    out.b = v.b;
    out.radius = r;
    out.color = v.color;
    return out;
}

// Where a ray (origin `o`, unit direction `d`) enters the capsule `a` + `ab`
// of radius `r` (a distance along the ray), or 1e30 if it does not: the
// cylinder, or else the end sphere on the side the ray met the cylinder's line.
fn capsule_entry(o: vec3<f32>, d: vec3<f32>, a: vec3<f32>, ab: vec3<f32>, r: f32) -> f32 {
    let oa = o - a;
    let baba = dot(ab, ab);
    let bard = dot(ab, d);
    let baoa = dot(ab, oa);
    let qa = baba - bard * bard;
    let qb = baba * dot(d, oa) - baoa * bard;
    let qc = baba * dot(oa, oa) - baoa * baoa - r * r * baba;
    let h = qb * qb - qa * qc;
    // An axis along the ray (or no axis): the end nearer the eye.
    var y = select(0.0, baba, bard < 0.0);
    if (h >= 0.0 && qa > 1e-9 * baba) {
        let t = (-qb - sqrt(h)) / qa;
        y = baoa + t * bard;
        if (y > 0.0 && y < baba) {
            return t;
        }
    }
    let oc = select(oa, oa - ab, y > 0.0);
    let half_b = dot(oc, d);
    let k = half_b * half_b - (dot(oc, oc) - r * r);
    return select(1e30, -half_b - sqrt(max(k, 0.0)), k >= 0.0);
}

struct Shaded {
    @location(0) color: vec4<f32>,
    @builtin(frag_depth) depth: f32,
};

@fragment
fn fs_main(in: Out) -> Shaded {
    // The ray from the shape (in front of the capsule) on.
    let forward = -vec3<f32>(frame.view[0].z, frame.view[1].z, frame.view[2].z);
    let o = in.world;
    var d = forward;
    if (is_perspective()) {
        d = normalize(o - frame.eye.xyz);
    }
    let a = in.a;
    let ab = in.b - in.a;
    let r = in.radius;
    // Where the ray's line passes closest to the axis `a + s * ab`.
    let ao = a - o;
    let across = ao - d * dot(ao, d);
    let slope = ab - d * dot(ab, d);
    let ss = dot(slope, slope);
    // (An axis along the ray: its end nearer the eye.)
    var s = select(0.0, 1.0, dot(ab, d) < 0.0);
    if (ss > 1e-12 * dot(ab, ab)) {
        s = clamp(-dot(across, slope) / ss, 0.0, 1.0);
    }
    let miss = length(across + slope * s);
    let t_close = dot(ao + ab * s, d);
    // One pixel's size there, and how far outside the outline the pixel is.
    var pixel = pixel_in_ray_units();
    if (is_perspective()) {
        pixel *= max(dot(o + d * t_close - frame.eye.xyz, forward), 1e-20);
    }
    let coverage = outline_coverage((miss - r) / pixel);
    if (coverage <= 0.0 || coverage < frame.samples.x) {
        discard;
    }
    // The surface where the ray enters; on the anti-aliased fringe just
    // outside, the ray's closest point (lit as the surface below it).
    var t = t_close;
    if (miss < r) {
        t = min(capsule_entry(o, d, a, ab, r), t_close);
    }
    let p = o + d * t;
    let h = clamp(dot(p - a, ab) / max(dot(ab, ab), 1e-30), 0.0, 1.0);
    let out_of_axis = p - (a + ab * h);
    let n = select(-d, normalize(out_of_axis), dot(out_of_axis, out_of_axis) > 1e-20);
    let clip_z = dot(frame.clip_z, vec4<f32>(p, 1.0));
    let clip_w = dot(frame.clip_w, vec4<f32>(p, 1.0));
    // Cut by the near plane (or behind the eye): not drawn.
    if (clip_w <= 0.0 || clip_z < 0.0) {
        discard;
    }
    var out: Shaded;
    // Alpha is the coverage (turned into samples on a multisampled target,
    // blended over what is behind at full quality on one sample); the
    // pipeline keeps the target's alpha.
    // Towards the eye: the ray reversed (in an orthographic view, towards the
    // eye's point, as `shade` has it).
    var v = -d;
    if (!is_perspective()) {
        v = normalize(frame.eye.xyz - p);
    }
    out.color = to_target(vec4<f32>(shade_seen(in.color.rgb, p, n, v), coverage));
    out.depth = min(clip_z / clip_w, 1.0);
    return out;
}

// The shadow map: the same shapes seen from the key light (orthographic),
// in the plane through the capsule's axis, so each capsule stores the depth of
// its middle: its lit half stays in front of it, and everything behind is
// shadowed.

struct ShadowOut {
    @builtin(position) position: vec4<f32>,
    // Where in the light's view (x, y in world units: the map may be longer
    // one way than the other, its clip space is not).
    @location(0) xy: vec2<f32>,
    // The axis's ends (x, y) in the light's view, and the radius.
    @location(1) @interpolate(flat) ends: vec4<f32>,
    @location(2) @interpolate(flat) radius: f32,
};

// Depth at `xy` (the light's view) of the plane through the axis `a`-`b` of
// radius `r` (x, y in the light's view, z its depth), as the rasteriser
// interpolates it; an axis seen end-on takes its middle.
fn axis_plane_depth(xy: vec2<f32>, a: vec3<f32>, b: vec3<f32>, r: f32) -> f32 {
    let along = b.xy - a.xy;
    let len = length(along);
    if (len > r) {
        return mix(a.z, b.z, dot(xy - a.xy, along) / (len * len));
    }
    return 0.5 * (a.z + b.z);
}

fn in_depth_range(z: f32) -> bool {
    return z >= 0.0 && z <= 1.0;
}

@vertex
fn vs_shadow(v: CapsuleIn) -> ShadowOut {
    let m = frame.light_view_proj;
    // The light's clip space per world unit, across and down.
    let per_unit = vec2<f32>(length(vec3<f32>(m[0][0], m[1][0], m[2][0])), length(vec3<f32>(m[0][1], m[1][1], m[2][1])));
    let clip_a = (m * vec4<f32>(v.a, 1.0)).xyz;
    let clip_b = (m * vec4<f32>(v.b, 1.0)).xyz;
    let a = vec3<f32>(clip_a.xy / per_unit, clip_a.z);
    let b = vec3<f32>(clip_b.xy / per_unit, clip_b.z);
    let r = abs(v.radius);
    // One texel of room.
    let room = frame.light_dir.w;
    // The apex lies well past one end, where the plane's depth may leave the
    // map's range (a capsule pointing at the light): then it goes past the
    // other end if the depth stays in range there (the same for the three
    // corners: they compute it from the same capsule). Depths out of range
    // are clamped, which bends the plane.
    let axis = axis_of(a.xy, b.xy);
    let apex = apex_distance(axis.len, r + room);
    let past_b = axis_plane_depth(b.xy + axis.w * apex, a, b, r);
    let past_a = axis_plane_depth(a.xy - axis.w * apex, a, b, r);
    let one_triangle = is_forced_triangle(v.corner) || is_one_triangle(r, r, room, room);
    let flip = one_triangle && !in_depth_range(past_b) && in_depth_range(past_a);
    // Flipped, the shape runs from `b` to `a`: the same axis reversed.
    var along = axis;
    if (flip) {
        along = Axis(-axis.w, -axis.u, axis.len);
    }
    let xy = capsule_corner(v.corner, along, select(a.xy, b.xy, flip), r, select(b.xy, a.xy, flip), r, room, room);
    var out: ShadowOut;
    out.position = vec4<f32>(xy * per_unit, clamp(axis_plane_depth(xy, a, b, r), 0.0, 1.0), 1.0);
    out.xy = xy;
    out.ends = vec4<f32>(a.xy, b.xy);
    out.radius = r;
    return out;
}

@fragment
fn fs_shadow(in: ShadowOut) {
    let a = in.ends.xy;
    let ab = in.ends.zw - a;
    let s = clamp(dot(in.xy - a, ab) / max(dot(ab, ab), 1e-30), 0.0, 1.0);
    if (distance(in.xy, a + ab * s) > in.radius) {
        discard;
    }
}

// The fast look's floor shadows without a shadow map: each caster's footprint
// on the floor marks the depth there (the floor's, a little farther: MARK_DEPTH;
// no colour), then one quad over the shadow's rect darkens the marked pixels
// (floor.wgsl's `fs_marked`), each once however many footprints overlap. A floor point is in shadow where the key light's ray from it
// meets the capsule: where, in the plane across the light, it lies within the
// radius of the axis (the outline the shadow map's pass draws, without its
// texels).

struct FootprintOut {
    @builtin(position) position: vec4<f32>,
    // The floor point in the plane across the light (world units).
    @location(0) xy: vec2<f32>,
    // The axis's ends in that plane, and the radius.
    @location(1) @interpolate(flat) ends: vec4<f32>,
    @location(2) @interpolate(flat) radius: f32,
    @location(3) world: vec3<f32>,
};

// A unit vector across the key light (`l`); `cross(l, it)` is the other.
fn across_light(l: vec3<f32>) -> vec3<f32> {
    let other = select(vec3<f32>(0.0, 0.0, 1.0), vec3<f32>(1.0, 0.0, 0.0), abs(l.z) > 0.9);
    return normalize(cross(l, other));
}

@vertex
fn vs_footprint(v: CapsuleIn) -> FootprintOut {
    let l = frame.light_dir.xyz;
    let u = across_light(l);
    let w = cross(l, u);
    let a = vec2<f32>(dot(v.a, u), dot(v.a, w));
    let b = vec2<f32>(dot(v.b, u), dot(v.b, w));
    let r = abs(v.radius);
    // The outline's rectangle (or its triangle where the CPU forced one: it
    // holds the outline too), in the plane across the light.
    let q = capsule_corner(v.corner, axis_of(a, b), a, r, b, r, 0.0, 0.0);
    // The floor point seen there along the light: its coordinates across the
    // light are q's, and its height the floor's (the light comes from above).
    let floor_y = frame.floor_center.y;
    let t = (floor_y - q.x * u.y - q.y * w.y) / max(l.y, 1e-6);
    let p = q.x * u + q.y * w + t * l;
    var out: FootprintOut;
    out.position = frame.projection * frame.view * vec4<f32>(p, 1.0);
    out.position.z += MARK_DEPTH * out.position.w;
    out.xy = q;
    out.ends = vec4<f32>(a, b);
    out.radius = r;
    out.world = p;
    return out;
}

// Depth only (the pipeline writes no colour).
@fragment
fn fs_footprint(in: FootprintOut) -> @location(0) vec4<f32> {
    let a = in.ends.xy;
    let ab = in.ends.zw - a;
    let s = clamp(dot(in.xy - a, ab) / max(dot(ab, ab), 1e-30), 0.0, 1.0);
    if (distance(in.xy, a + ab * s) > in.radius) {
        discard;
    }
    return vec4<f32>(0.0);
}
