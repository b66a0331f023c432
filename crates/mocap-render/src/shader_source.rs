//! The renderer's WGSL modules as wgpu shader modules; on WebGL2 the first
//! frame's made ahead, at build time.
//!
//! On WebGL2 (wgpu's GL back end) wgpu parses each WGSL module with naga when
//! the module is made, validates it, and for each pipeline replaces its
//! override constants and writes GLSL: in a browser's first, unoptimised tier
//! of WebAssembly, a large part of a page's first frame, and work that made
//! the browser recompile naga's parser, validator and GLSL writer with its
//! optimising tier on the same cores. So `build.rs` does it ahead, from the
//! same text (`shader_text.rs`):
//! - it writes the GLSL wgpu's GL back end would write for each stage of a
//!   first frame's pipelines, with its bindings ([`written_modules`]), which
//!   `pipeline::build` hands wgpu as pass-through modules where the device
//!   takes them: a page's first frame runs none of naga;
//! - it makes the first frame's modules (capsules, floor) into naga IR
//!   (postcard bytes), which [`Shader::module`] reads back for their other
//!   pipelines on the GL back end (`ShaderSource::Naga`, validated by wgpu as
//!   WGSL is) instead of parsing their WGSL.
//!
//! Elsewhere (WebGPU, whose browser takes WGSL; Vulkan) wgpu gets the WGSL.

use std::borrow::Cow;

use crate::shader_text::first_frame_sources;

// `FIRST_FRAME_GLSL`, `FIRST_FRAME_GLSL_TEXTS`: see `build.rs`.
include!(concat!(env!("OUT_DIR"), "/first_frame_glsl.rs"));

/// A shader of the renderer, its wgpu module made when a pipeline first needs
/// it ([`Shader::module`]): on WebGL2 a first frame's pipelines are made from
/// GLSL written ahead instead ([`written_modules`]), and the module (naga's
/// validation of it) waits for a pipeline that was not written.
pub(crate) struct Shader {
    device: wgpu::Device,
    label: String,
    wgsl: String,
    /// The first-frame module it is, if one (its index in
    /// [`first_frame_sources`]): the one whose stages' GLSL `build.rs` wrote.
    pub(crate) first_frame: Option<usize>,
    module: std::cell::OnceCell<wgpu::ShaderModule>,
}

impl Shader {
    /// The wgpu module: on the GL back end from the IR made at build time
    /// where it is a first-frame module, else from the WGSL; made at the
    /// first call.
    pub(crate) fn module(&self) -> &wgpu::ShaderModule {
        self.module.get_or_init(|| {
            let gl = self.device.adapter_info().backend == wgpu::Backend::Gl;
            let read = self.first_frame.filter(|_| gl).and_then(read_ir);
            let source = match read {
                Some(module) => wgpu::ShaderSource::Naga(Cow::Owned(module)),
                None => wgpu::ShaderSource::Wgsl(Cow::Borrowed(&self.wgsl)),
            };
            self.device.create_shader_module(wgpu::ShaderModuleDescriptor { label: Some(&self.label), source })
        })
    }
}

/// The first frame's modules as naga IR in postcard bytes, written by
/// `build.rs` from [`first_frame_sources`], in its order.
const FIRST_FRAME_IR: [&[u8]; 2] = [
    include_bytes!(concat!(env!("OUT_DIR"), "/first_frame_0.naga")),
    include_bytes!(concat!(env!("OUT_DIR"), "/first_frame_1.naga")),
];

/// The first-frame module `index` read from its IR. IR that does not read
/// (it cannot, being made from the same text by the same naga) gives `None`:
/// wgpu then parses the WGSL.
fn read_ir(index: usize) -> Option<wgpu::naga::Module> {
    postcard::from_bytes(FIRST_FRAME_IR.get(index)?).ok()
}

/// The shader of `wgsl` named `label` on `device` (its module made when
/// first needed: [`Shader::module`]).
pub(crate) fn module(device: &wgpu::Device, label: &str, wgsl: String) -> Shader {
    Shader { device: device.clone(), label: label.to_owned(), wgsl, first_frame: None, module: std::cell::OnceCell::new() }
}

/// The shader of the first-frame module `index` (in [`first_frame_sources`]:
/// `shader_text::CAPSULES` or `FLOOR`) named `label` on `device`: its stages'
/// GLSL written ahead, its IR made at build time.
pub(crate) fn first_frame_module(device: &wgpu::Device, label: &str, index: usize) -> Shader {
    let wgsl = first_frame_sources().into_iter().nth(index).unwrap_or_default();
    Shader { first_frame: Some(index), ..module(device, label, wgsl) }
}

/// The GLSL `build.rs` wrote for stage `entry` (the vertex stage or not) of
/// the first-frame module `first_frame` with override constants `constants`
/// (the values of `shader_text::OVERRIDES`), if it wrote it.
pub(crate) fn written_glsl(first_frame: usize, vertex: bool, entry: &str, constants: [bool; 4]) -> Option<&'static str> {
    FIRST_FRAME_GLSL
        .iter()
        .find(|&&(m, v, e, c, _)| m == first_frame && v == vertex && e == entry && c == constants)
        .and_then(|&(.., text)| FIRST_FRAME_GLSL_TEXTS.get(text).copied())
}

/// Pass-through modules of the GLSL written ahead for a pipeline of `shader`
/// with vertex stage `vertex_entry`, fragment stage `fragment_entry` (if it
/// has one) and override constants `constants`: on WebGL2 (wgpu's GL back end
/// in a browser, GLSL ES 3.00, whose device was asked for pass-through
/// shaders), where the GLSL of each of its stages was written. Otherwise
/// `None`, and the pipeline is made from `shader`'s module.
///
/// wgpu's GL back end then compiles the GLSL as it is and binds what its
/// `//!wgpu` lines name (`vendor/wgpu-hal`), with none of naga's validation,
/// override processing and GLSL writing in the page's first frame.
pub(crate) fn written_modules(
    device: &wgpu::Device,
    shader: &Shader,
    vertex_entry: &str,
    fragment_entry: Option<&str>,
    constants: [bool; 4],
) -> Option<(wgpu::ShaderModule, Option<wgpu::ShaderModule>)> {
    let webgl = cfg!(target_arch = "wasm32") && device.adapter_info().backend == wgpu::Backend::Gl;
    if !webgl || !device.features().contains(wgpu::Features::PASSTHROUGH_SHADERS) {
        return None;
    }
    let first_frame = shader.first_frame?;
    let vertex = written_glsl(first_frame, true, vertex_entry, constants)?;
    let fragment = match fragment_entry {
        Some(entry) => Some((entry, written_glsl(first_frame, false, entry, constants)?)),
        None => None,
    };
    let make = |entry: &str, glsl: &'static str| {
        let desc = wgpu::ShaderModuleDescriptorPassthrough {
            label: Some(entry),
            entry_points: Cow::Owned(vec![wgpu::PassthroughShaderEntryPoint {
                name: Cow::Owned(entry.to_owned()),
                workgroup_size: (0, 0, 0),
            }]),
            glsl: Some(Cow::Borrowed(glsl)),
            ..Default::default()
        };
        // SAFETY: the GLSL is what naga writes for this stage of the module
        // (validated at build time) with the GL back end's WebGL2 options, as
        // the back end itself would write it; the tests check it against
        // naga's output now.
        unsafe { device.create_shader_module_passthrough(desc) }
    };
    Some((make(vertex_entry, vertex), fragment.map(|(entry, glsl)| make(entry, glsl))))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_first_frames_modules_read_from_their_ir() {
        for index in 0..first_frame_sources().len() {
            assert!(read_ir(index).is_some(), "module {index}");
        }
        assert!(read_ir(first_frame_sources().len()).is_none());
    }

    #[test]
    fn the_glsl_written_at_build_time_is_what_naga_writes_now() {
        let modules: Vec<_> = first_frame_sources()
            .iter()
            .map(|wgsl| naga::front::wgsl::parse_str(wgsl).expect("the first frame's WGSL parses"))
            .collect();
        let now = crate::first_frame_glsl::first_frame_glsl(&modules);
        let written = include_str!(concat!(env!("OUT_DIR"), "/first_frame_glsl.rs"));
        assert!(now == written, "build.rs's GLSL is stale or made from other text");
    }

    #[test]
    fn every_stage_of_a_first_frame_has_its_glsl_and_bindings() {
        use crate::shader_text::{FIRST_FRAME_STAGES, first_frame_constants};
        for (module, vertex, entry, encode_srgb) in FIRST_FRAME_STAGES {
            for constants in first_frame_constants(encode_srgb) {
                let glsl = written_glsl(module, vertex, entry, constants).expect("written ahead");
                let mut lines = glsl.lines().skip_while(|l| l.starts_with("//!wgpu "));
                assert_eq!(lines.next(), Some("#version 300 es"), "{entry}");
                // Every stage reads the frame's uniforms but the casters' fragments.
                let frame = if vertex { "Frame_block_0Vertex 0 0" } else { "Frame_block_0Fragment 0 0" };
                assert_eq!(glsl.contains(&format!("//!wgpu uniform {frame}\n")), (module, entry) != (0, "fs_shadow"), "{entry}");
            }
        }
        // The lit fragments sample the shadow map (group 1, binding 0) with its sampler (binding 1).
        for (module, entry) in [(0, "fs_main"), (1, "fs_shadow")] {
            let glsl = written_glsl(module, false, entry, [false, true, true, false]).expect("written ahead");
            assert!(glsl.contains("//!wgpu texture _group_1_binding_0_fs 1 0 1 1\n"), "{entry}");
        }
        // Other constants, stages or modules were not written.
        assert_eq!(written_glsl(0, true, "vs_main", [true, true, true, false]), None);
        assert_eq!(written_glsl(0, true, "vs_footprint", [false, true, true, false]), None);
        assert_eq!(written_glsl(2, true, "vs_main", [false, true, true, false]), None);
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
