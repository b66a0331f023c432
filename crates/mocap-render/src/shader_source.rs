//! The renderer's WGSL modules as wgpu shader modules, the first frame's parsed
//! ahead of the graphics device.
//!
//! On WebGL2 (wgpu's GL back end) wgpu parses each WGSL module with naga when
//! the module is made, after the device exists. A web page's start waits for
//! the device, and in a browser's first, unoptimised tier of WebAssembly the
//! parse of the first frame's modules took about a fifth of that frame's 3D
//! work. [`parse_shaders_ahead`] parses them before the device exists (the web viewer
//! calls it while it waits for one), and [`module`] hands wgpu the parsed module
//! on the GL back end (`ShaderSource::Naga`, validated by wgpu as WGSL is).
//! Elsewhere (WebGPU, whose browser takes WGSL; Vulkan) wgpu gets the WGSL.

use std::borrow::Cow;
use std::cell::RefCell;
use std::collections::HashMap;

thread_local! {
    /// Modules parsed ahead, by their WGSL.
    static PARSED: RefCell<HashMap<String, wgpu::naga::Module>> = RefCell::new(HashMap::new());
}

/// The WGSL of the modules a first frame of capsules over the floor is drawn
/// with (a scene's pipelines are made on first use: see `pipeline_set.rs`).
fn first_frame_sources() -> [String; 2] {
    [crate::pipeline_set::lit_source(&crate::capsule::shader_source()), crate::pipeline_set::floor_source()]
}

/// Parses the first frame's modules for [`module`], if not yet parsed. A
/// module that does not parse is left to wgpu, which reports its error when it
/// is made.
pub fn parse_shaders_ahead() {
    for wgsl in first_frame_sources() {
        if PARSED.with(|p| p.borrow().contains_key(&wgsl)) {
            continue;
        }
        if let Ok(parsed) = wgpu::naga::front::wgsl::parse_str(&wgsl) {
            PARSED.with(|p| p.borrow_mut().insert(wgsl, parsed));
        }
    }
}

/// A shader module of `wgsl` named `label` on `device`: from its module
/// parsed by [`parse_shaders_ahead`] on the GL back end, else from the WGSL.
pub(crate) fn module(device: &wgpu::Device, label: &str, wgsl: String) -> wgpu::ShaderModule {
    let gl = device.adapter_info().backend == wgpu::Backend::Gl;
    let parsed = if gl { PARSED.with(|p| p.borrow().get(&wgsl).cloned()) } else { None };
    let source = match parsed {
        Some(parsed) => wgpu::ShaderSource::Naga(Cow::Owned(parsed)),
        None => wgpu::ShaderSource::Wgsl(wgsl.into()),
    };
    device.create_shader_module(wgpu::ShaderModuleDescriptor { label: Some(label), source })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_first_frames_modules_are_parsed_ahead() {
        parse_shaders_ahead();
        let parsed = PARSED.with(|p| p.borrow().len());
        assert_eq!(parsed, first_frame_sources().len());
        // Twice is once.
        parse_shaders_ahead();
        assert_eq!(PARSED.with(|p| p.borrow().len()), parsed);
    }
}
