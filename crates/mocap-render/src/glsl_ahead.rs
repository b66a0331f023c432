//! The GLSL wgpu's GL back end writes on WebGL2 for a shader's stage, written
//! ahead with the bindings the back end reads (`//!wgpu` lines; see
//! `vendor/wgpu-hal`'s `consume_written_ahead`). Plain `std` and naga code
//! with no other crate paths: build scripts compile this file (`#[path]`):
//! this crate's (`build.rs`, for the first frame's stages) and the vendored
//! egui-wgpu's (egui's shader).

use naga::back::glsl;

/// `module` validated as wgpu validates a module on WebGL2.
pub(crate) fn validate(module: &naga::Module) -> Result<naga::valid::ModuleInfo, Box<naga::WithSpan<naga::valid::ValidationError>>> {
    let mut validator = naga::valid::Validator::new(naga::valid::ValidationFlags::all(), naga::valid::Capabilities::empty());
    validator.validate(module).map_err(Box::new)
}

/// The GLSL ES 3.00 wgpu's GL back end writes on WebGL2 for the stage `entry`
/// of `module` (its override constants already replaced), with lines ahead
/// naming what the back end binds where (`//!wgpu` lines: each uniform
/// block's, texture's and sampler's group and binding, each varying's
/// location), as it learns them from naga's reflection when it writes the
/// GLSL itself. The writer's flags are the back end's on WebGL2 where the
/// context has neither shadow-sampler LOD nor full instancing; a stage whose
/// GLSL those flags would change fails the build.
pub(crate) fn stage_glsl(module: &naga::Module, info: &naga::valid::ModuleInfo, vertex: bool, entry: &str) -> String {
    let stage = if vertex { naga::ShaderStage::Vertex } else { naga::ShaderStage::Fragment };
    let base = glsl::WriterFlags::ADJUST_COORDINATE_SPACE | glsl::WriterFlags::FORCE_POINT_SIZE;
    let write = |flags: glsl::WriterFlags| {
        let options = glsl::Options {
            version: glsl::Version::Embedded { version: 300, is_webgl: true },
            writer_flags: flags,
            binding_map: Default::default(),
            zero_initialize_workgroup_memory: true,
        };
        let pipeline = glsl::PipelineOptions { shader_stage: stage, entry_point: entry.to_owned(), multiview: None };
        let policies = naga::proc::BoundsCheckPolicies::default();
        let mut text = String::new();
        let reflection = glsl::Writer::new(&mut text, module, info, &options, &pipeline, policies)
            .and_then(|mut w| w.write())
            .unwrap_or_else(|e| panic!("{entry}: {e}"));
        (text, reflection)
    };
    let (text, reflection) = write(base);
    for other in [glsl::WriterFlags::TEXTURE_SHADOW_LOD, glsl::WriterFlags::DRAW_PARAMETERS] {
        assert_eq!(write(base | other).0, text, "{entry}'s GLSL depends on the context's {other:?}");
    }
    assert!(reflection.immediates_items.is_empty() && reflection.clip_distance_count == 0, "{entry}: immediates or clip distances");
    let index = module
        .entry_points
        .iter()
        .position(|ep| ep.stage == stage && ep.name == entry)
        .unwrap_or_else(|| panic!("no entry point {entry}"));
    let used = info.get_entry_point(index);
    let binding = |h: naga::Handle<naga::GlobalVariable>| {
        let b = module.global_variables[h].binding.as_ref().unwrap_or_else(|| panic!("{entry}: a resource without a binding"));
        format!("{} {}", b.group, b.binding)
    };
    let mut lines = Vec::new();
    for (handle, var) in module.global_variables.iter() {
        if used[handle].is_empty() {
            continue;
        }
        assert!(!matches!(var.space, naga::AddressSpace::Storage { .. }), "{entry}: storage buffers");
        if var.space != naga::AddressSpace::Uniform {
            continue;
        }
        if let Some(name) = reflection.uniforms.get(&handle) {
            lines.push(format!("//!wgpu uniform {name} {}", binding(handle)));
        }
    }
    for (name, mapping) in &reflection.texture_mapping {
        let texture = &module.global_variables[mapping.texture];
        let storage = matches!(module.types[texture.ty].inner, naga::TypeInner::Image { class: naga::ImageClass::Storage { .. }, .. });
        assert!(!storage, "{entry}: storage images");
        let sampler = mapping.sampler.map(|s| format!(" {}", binding(s))).unwrap_or_default();
        lines.push(format!("//!wgpu texture {name} {}{sampler}", binding(mapping.texture)));
    }
    for (name, location) in &reflection.varying {
        assert_eq!(location.index, 0, "{entry}: dual-source blending");
        lines.push(format!("//!wgpu varying {name} {}", location.location));
    }
    lines.sort();
    let mut out: String = lines.iter().map(|line| format!("{line}\n")).collect();
    out.push_str(&text);
    out
}
