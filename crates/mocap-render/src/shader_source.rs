//! The renderer's WGSL modules as wgpu shader modules, the first frame's made
//! into naga IR at build time and read back ahead of the graphics device.
//!
//! On WebGL2 (wgpu's GL back end) wgpu parses each WGSL module with naga when
//! the module is made, after the device exists. A web page's start waits for
//! the device, and in a browser's first, unoptimised tier of WebAssembly the
//! parse of the first frame's modules (capsules, floor) took 50–90 ms of the
//! page's start and made the browser recompile naga's parser with its
//! optimising tier on the same two cores. `build.rs` parses them at build time
//! into naga IR (postcard bytes, from the same text: `shader_text.rs`);
//! [`read_shaders_ahead`] reads that IR back before the device exists (the web
//! viewer calls it while it waits for one; a few milliseconds), and [`module`]
//! hands wgpu the module on the GL back end (`ShaderSource::Naga`, validated
//! by wgpu as WGSL is). Elsewhere (WebGPU, whose browser takes WGSL; Vulkan)
//! wgpu gets the WGSL.

use std::borrow::Cow;
use std::cell::RefCell;
use std::collections::HashMap;

use crate::shader_text::first_frame_sources;

thread_local! {
    /// Modules read ahead, by their WGSL.
    static READ_AHEAD: RefCell<HashMap<String, wgpu::naga::Module>> = RefCell::new(HashMap::new());
}

/// The first frame's modules as naga IR in postcard bytes, written by
/// `build.rs` from [`first_frame_sources`], in its order.
const FIRST_FRAME_IR: [&[u8]; 2] = [
    include_bytes!(concat!(env!("OUT_DIR"), "/first_frame_0.naga")),
    include_bytes!(concat!(env!("OUT_DIR"), "/first_frame_1.naga")),
];

/// Reads the first frame's modules for [`module`] from the IR made at build
/// time, if not yet read. IR that does not read (it cannot, being made from
/// the same text by the same naga) is left out: wgpu then parses the WGSL.
pub fn read_shaders_ahead() {
    for (wgsl, ir) in first_frame_sources().into_iter().zip(FIRST_FRAME_IR) {
        if READ_AHEAD.with(|p| p.borrow().contains_key(&wgsl)) {
            continue;
        }
        if let Ok(module) = postcard::from_bytes::<wgpu::naga::Module>(ir) {
            READ_AHEAD.with(|p| p.borrow_mut().insert(wgsl, module));
        }
    }
}

/// A shader module of `wgsl` named `label` on `device`: from its module
/// read by [`read_shaders_ahead`] on the GL back end, else from the WGSL.
pub(crate) fn module(device: &wgpu::Device, label: &str, wgsl: String) -> wgpu::ShaderModule {
    let gl = device.adapter_info().backend == wgpu::Backend::Gl;
    let read = if gl { READ_AHEAD.with(|p| p.borrow().get(&wgsl).cloned()) } else { None };
    let source = match read {
        Some(module) => wgpu::ShaderSource::Naga(Cow::Owned(module)),
        None => wgpu::ShaderSource::Wgsl(wgsl.into()),
    };
    device.create_shader_module(wgpu::ShaderModuleDescriptor { label: Some(label), source })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_first_frames_modules_are_read_ahead() {
        read_shaders_ahead();
        let read = READ_AHEAD.with(|p| p.borrow().len());
        assert_eq!(read, first_frame_sources().len());
        // Twice is once.
        read_shaders_ahead();
        assert_eq!(READ_AHEAD.with(|p| p.borrow().len()), read);
    }

    #[test]
    fn the_ir_made_at_build_time_is_the_wgsl_parsed_now() {
        for (wgsl, ir) in first_frame_sources().iter().zip(FIRST_FRAME_IR) {
            let parsed = naga::front::wgsl::parse_str(wgsl).expect("the first frame's WGSL parses");
            let now = postcard::to_allocvec(&parsed).expect("naga IR serialises");
            assert_eq!(now, ir, "build.rs's IR is stale or made from other text");
            // And it reads back into a module that validates as the parsed one does.
            let read: wgpu::naga::Module = postcard::from_bytes(ir).expect("the IR reads");
            let flags = naga::valid::ValidationFlags::all();
            let caps = naga::valid::Capabilities::empty();
            naga::valid::Validator::new(flags, caps).validate(&read).expect("the IR read back validates");
            assert_eq!(postcard::to_allocvec(&read).expect("serialises"), now);
        }
    }
}
