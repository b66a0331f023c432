//! The table of the first frame's stages' GLSL `build.rs` writes to
//! `$OUT_DIR/first_frame_glsl.rs` (compiled by `build.rs` and by the tests,
//! which check that what was written is what naga writes now).

use std::fmt::Write as _;

use crate::glsl_ahead::{stage_glsl, validate};
use crate::shader_text;

/// Rust source of two tables: `FIRST_FRAME_GLSL` (module index, vertex stage,
/// entry point, constants, index into the texts) and `FIRST_FRAME_GLSL_TEXTS`
/// (each distinct stage's GLSL with its bindings ahead, see [`stage_glsl`]).
pub(crate) fn first_frame_glsl(modules: &[naga::Module]) -> String {
    let infos: Vec<_> = modules
        .iter()
        .enumerate()
        .map(|(i, module)| validate(module).unwrap_or_else(|e| panic!("first-frame shader {i}: {e:?}")))
        .collect();
    let mut texts: Vec<String> = Vec::new();
    let mut table = String::new();
    for (m, vertex, entry, encode_srgb) in shader_text::FIRST_FRAME_STAGES {
        for constants in shader_text::first_frame_constants(encode_srgb) {
            let mut values = naga::back::PipelineConstants::default();
            for (name, on) in shader_text::OVERRIDES.iter().zip(constants) {
                values.insert((*name).to_owned(), if on { 1.0 } else { 0.0 });
            }
            let (module, info) = naga::back::pipeline_constants::process_overrides(&modules[m], &infos[m], None, &values)
                .unwrap_or_else(|e| panic!("first-frame shader {m} with {constants:?}: {e}"));
            let text = stage_glsl(&module, &info, vertex, entry);
            let index = texts.iter().position(|t| *t == text).unwrap_or_else(|| {
                texts.push(text);
                texts.len() - 1
            });
            writeln!(table, "    ({m}, {vertex}, {entry:?}, {constants:?}, {index}),").expect("writes to a string");
        }
    }
    let mut rs = String::from("/// The first frame's stages: (module, vertex stage, entry point, constants, text).\n");
    writeln!(rs, "pub(crate) const FIRST_FRAME_GLSL: &[(usize, bool, &str, [bool; 4], usize)] = &[\n{table}];").expect("writes");
    rs.push_str("/// Their GLSL, each with its bindings ahead.\npub(crate) const FIRST_FRAME_GLSL_TEXTS: &[&str] = &[\n");
    for text in &texts {
        writeln!(rs, "    {text:?},").expect("writes");
    }
    rs.push_str("];\n");
    rs
}

