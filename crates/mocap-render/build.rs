//! Writes the first frame's shader modules (capsules, floor) as naga IR in
//! postcard bytes, `$OUT_DIR/first_frame_<i>.naga`, from the WGSL text the
//! renderer itself composes (`src/shader_text.rs`, compiled here too): on
//! WebGL2 the renderer hands wgpu these modules instead of parsing their WGSL
//! in the page's start (see `src/shader_source.rs`). A module that does not
//! parse fails the build with naga's message.

#[path = "src/shader_text.rs"]
mod shader_text;

fn main() {
    println!("cargo::rerun-if-changed=src/shader_text.rs");
    println!("cargo::rerun-if-changed=src/shaders");
    let out = std::path::PathBuf::from(std::env::var("OUT_DIR").expect("cargo sets OUT_DIR"));
    for (i, wgsl) in shader_text::first_frame_sources().iter().enumerate() {
        let module = match naga::front::wgsl::parse_str(wgsl) {
            Ok(module) => module,
            Err(e) => panic!("first-frame shader {i}: {}", e.emit_to_string(wgsl)),
        };
        let bytes = postcard::to_allocvec(&module).expect("naga IR serialises");
        let path = out.join(format!("first_frame_{i}.naga"));
        std::fs::write(&path, bytes).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    }
}
