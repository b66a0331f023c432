//! Writes, from the WGSL text the renderer itself composes
//! (`src/shader_text.rs`, compiled here too):
//! - the first frame's shader modules (capsules, floor) as naga IR in postcard
//!   bytes, `$OUT_DIR/first_frame_<i>.naga`: on WebGL2 the renderer hands wgpu
//!   these modules instead of parsing their WGSL in the page's start;
//! - the GLSL of the first frame's pipeline stages for WebGL2, with each set
//!   of override constants a first frame uses, with what the GL back end
//!   needs to bind their resources, `$OUT_DIR/first_frame_glsl.rs`: the
//!   renderer hands wgpu these as pass-through shaders, so that a page's first
//!   frame runs none of naga's validation and GLSL writing (see
//!   `src/shader_source.rs`, and the reading of the bindings in
//!   `vendor/wgpu-hal`).
//!
//! A module that does not parse or validate fails the build with naga's message.

#[path = "src/shader_text.rs"]
mod shader_text;

#[path = "src/glsl_ahead.rs"]
mod glsl_ahead;

#[path = "src/first_frame_glsl.rs"]
mod first_frame_glsl;

fn main() {
    println!("cargo::rerun-if-changed=src/shader_text.rs");
    println!("cargo::rerun-if-changed=src/glsl_ahead.rs");
    println!("cargo::rerun-if-changed=src/first_frame_glsl.rs");
    println!("cargo::rerun-if-changed=src/shaders");
    let out = std::path::PathBuf::from(std::env::var("OUT_DIR").expect("cargo sets OUT_DIR"));
    let mut modules = Vec::new();
    for (i, wgsl) in shader_text::first_frame_sources().iter().enumerate() {
        let module = match naga::front::wgsl::parse_str(wgsl) {
            Ok(module) => module,
            Err(e) => panic!("first-frame shader {i}: {}", e.emit_to_string(wgsl)),
        };
        let bytes = postcard::to_allocvec(&module).expect("naga IR serialises");
        let path = out.join(format!("first_frame_{i}.naga"));
        std::fs::write(&path, bytes).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        modules.push(module);
    }
    let path = out.join("first_frame_glsl.rs");
    std::fs::write(&path, first_frame_glsl::first_frame_glsl(&modules)).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
}

