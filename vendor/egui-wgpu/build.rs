//! Vendored change: writes the GLSL wgpu's GL back end writes on WebGL2 for
//! egui's shader stages (`src/egui.wgsl`), with the bindings the vendored
//! wgpu-hal reads (`//!wgpu` lines), to `$OUT_DIR/egui_glsl.rs`:
//! `Renderer::new` hands wgpu these as pass-through modules on WebGL2 where
//! the device takes them, and a page's start runs none of naga for egui's
//! pipeline. The writing is the viewer's renderer's (`mocap-render`'s
//! `glsl_ahead.rs`, which writes its own first frame's stages the same way).

#[path = "../../crates/mocap-render/src/glsl_ahead.rs"]
mod glsl_ahead;

/// egui's pipeline stages: whether the vertex stage, the entry point.
const STAGES: [(bool, &str); 3] = [
    (true, "vs_main"),
    (false, "fs_main_gamma_framebuffer"),
    (false, "fs_main_linear_framebuffer"),
];

fn main() {
    println!("cargo::rerun-if-changed=src/egui.wgsl");
    println!("cargo::rerun-if-changed=../../crates/mocap-render/src/glsl_ahead.rs");
    let wgsl = include_str!("src/egui.wgsl");
    let module = naga::front::wgsl::parse_str(wgsl).unwrap_or_else(|e| panic!("egui.wgsl: {}", e.emit_to_string(wgsl)));
    let info = glsl_ahead::validate(&module).unwrap_or_else(|e| panic!("egui.wgsl: {e:?}"));
    let mut rs = String::from("/// egui's stages' GLSL for WebGL2: (entry point, GLSL with its bindings ahead).\n");
    rs.push_str("const EGUI_GLSL: [(&str, &str); 3] = [\n");
    for (vertex, entry) in STAGES {
        let glsl = glsl_ahead::stage_glsl(&module, &info, vertex, entry);
        rs.push_str(&format!("    ({entry:?}, {glsl:?}),\n"));
    }
    rs.push_str("];\n");
    let out = std::path::PathBuf::from(std::env::var("OUT_DIR").expect("cargo sets OUT_DIR")).join("egui_glsl.rs");
    std::fs::write(&out, rs).unwrap_or_else(|e| panic!("{}: {e}", out.display()));
}
