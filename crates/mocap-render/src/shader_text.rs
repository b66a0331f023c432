//! The WGSL text of the renderer's lit modules: the shared prelude, the
//! capsules' and the floor's modules, and which of their stages and override
//! constants a first frame uses. Plain `std` code with no other crate paths,
//! so that `build.rs` compiles this same file (`#[path]`) to make the first
//! frame's modules into naga IR, and their stages into WebGL2's GLSL, at build
//! time from exactly the text the renderer uses (see `shader_source.rs`).

/// The shared uniform and lighting code prepended to each lit shader.
pub(crate) const LIT_PRELUDE: &str = concat!(include_str!("shaders/frame.wgsl"), include_str!("shaders/lighting.wgsl"));

/// Capsules narrower than this many pixels (texels in the shadow map) are
/// drawn as one triangle (by capsule.wgsl, which gets it from
/// [`capsule_body`]).
pub(crate) const ONE_TRIANGLE_BELOW: f32 = 16.0;

/// A lit module's source: [`LIT_PRELUDE`], then `body`.
pub(crate) fn lit_source(body: &str) -> String {
    format!("{LIT_PRELUDE}{body}")
}

/// capsule.wgsl (without the lit prelude) with [`ONE_TRIANGLE_BELOW`]
/// declared ahead of it: one value for the shader's shapes and the CPU's
/// `capsule::is_one_triangle`.
pub(crate) fn capsule_body() -> String {
    format!("const ONE_TRIANGLE_BELOW: f32 = {ONE_TRIANGLE_BELOW:?};\n{}", include_str!("shaders/capsule.wgsl"))
}

/// The capsules' module source.
pub(crate) fn capsule_source() -> String {
    lit_source(&capsule_body())
}

/// The floor's module source.
pub(crate) fn floor_source() -> String {
    lit_source(include_str!("shaders/floor.wgsl"))
}

/// The index of the capsules' module in [`first_frame_sources`].
pub(crate) const CAPSULES: usize = 0;
/// The index of the floor's module in [`first_frame_sources`].
pub(crate) const FLOOR: usize = 1;

/// The sources of the modules a first frame of capsules over the floor is
/// drawn with ([`CAPSULES`], [`FLOOR`]), in the order `build.rs` writes their
/// IR.
pub(crate) fn first_frame_sources() -> [String; 2] {
    [capsule_source(), floor_source()]
}

/// The lit shaders' override constants, in the order of [`FIRST_FRAME_CONSTANTS`]
/// and of `pipeline::build`'s constants.
pub(crate) const OVERRIDES: [&str; 4] = ["FAST_LOOK", "SHADOWS", "ENCODE_SRGB", "BLEND_OUTLINES"];

/// The stages of a first frame's pipelines on WebGL2 (the shadow casters, the
/// floor, its shadow, the capsules): the module's index in
/// [`first_frame_sources`], whether it is the vertex stage, the entry point,
/// and its `ENCODE_SRGB` (the shadow map has no colour; WebGL2's canvas is not
/// sRGB).
#[cfg_attr(not(test), allow(dead_code, reason = "read by build.rs and the tests only"))]
pub(crate) const FIRST_FRAME_STAGES: [(usize, bool, &str, bool); 8] = [
    (CAPSULES, true, "vs_shadow", false),
    (CAPSULES, false, "fs_shadow", false),
    (CAPSULES, true, "vs_main", true),
    (CAPSULES, false, "fs_main", true),
    (FLOOR, true, "vs_main", true),
    (FLOOR, false, "fs_main", true),
    (FLOOR, true, "vs_shadow", true),
    (FLOOR, false, "fs_shadow", true),
];

/// The values of [`OVERRIDES`] a first frame's stage in [`FIRST_FRAME_STAGES`]
/// is made with, by its `ENCODE_SRGB`: the full look with shadows, on one
/// sample (outlines blended) or several.
#[cfg_attr(not(test), allow(dead_code, reason = "read by build.rs and the tests only"))]
pub(crate) fn first_frame_constants(encode_srgb: bool) -> [[bool; 4]; 2] {
    [[false, true, encode_srgb, true], [false, true, encode_srgb, false]]
}
