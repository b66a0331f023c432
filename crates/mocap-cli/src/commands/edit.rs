//! `mocap edit` and `mocap layer`: clip edits in command-line order, and layers.

use super::*;

/// The core's edit spec for the value flag `--NAME VALUE` of `mocap edit`: the
/// spec `NAME:VALUE` ([`mocap::ops::edit::EditSpec`]: `--knit 4` is `knit:4`,
/// `--up -z` is `up:-z`); an error names the flag.
pub fn flag_spec(name: &str, value: &str) -> Result<EditSpec, String> {
    format!("{name}:{value}").parse::<EditSpec>().map_err(|e| {
        // The spec's form as the flag takes it: `fps:N or fps:N:cubic` is `N or N:cubic`.
        let form = e.form.replace(&format!("{name}:"), "");
        if form.is_empty() {
            format!("--{name} {value}: expected {}", e.expected)
        } else {
            format!("--{name} {value}: expected {} ({form})", e.expected)
        }
    })
}

/// `mocap edit`: the edits in order, then BVH.
pub fn edit(inputs: &[PathBuf], specs: &[EditSpec], output: &Path) -> Result<ExitCode, String> {
    if output.extension().and_then(|e| e.to_str()).is_none_or(|e| !e.eq_ignore_ascii_case("bvh")) {
        return Err(format!("{}: edit writes .bvh files", output.display()));
    }
    let mut clip = read_clip(inputs)?;
    for spec in specs {
        // Units resolve against the clip as edited so far.
        let edit = spec.resolve(&clip);
        clip = mocap::ops::edit::apply(&clip, &edit).map_err(|e| format!("{}: {e}", shown(inputs)))?;
    }
    let (baked, warnings) = mocap::ops::bake::to_bvh(&clip);
    for w in warnings {
        eprintln!("{}: warning: {w}", output.display());
    }
    std::fs::write(output, mocap::formats::bvh::write(&baked))
        .map_err(|e| format!("{}: cannot write: {e}", output.display()))?;
    Ok(ExitCode::SUCCESS)
}

/// What `mocap layer` is asked.
pub struct LayerRequest<'a> {
    /// The base joint whose subtree the layer drives.
    pub subtree: &'a str,
    /// 0–1.
    pub weight: f32,
    /// Additive instead of override.
    pub additive: bool,
    /// Fade-in seconds.
    pub fade_in: f64,
    /// Fade-out seconds.
    pub fade_out: f64,
    /// `BASE=LAYER` pairs.
    pub map: &'a [String],
}

/// `mocap layer`: a layer on a subtree of the base, as BVH.
pub fn layer(base: &Path, layer: &Path, request: &LayerRequest, output: &Path) -> Result<ExitCode, String> {
    if output.extension().and_then(|e| e.to_str()).is_none_or(|e| !e.eq_ignore_ascii_case("bvh")) {
        return Err(format!("{}: layer writes .bvh files", output.display()));
    }
    let base_clip = read_clip(&[base.to_path_buf()])?;
    let layer_clip = read_clip(&[layer.to_path_buf()])?;
    let map = request
        .map
        .iter()
        .map(|m| {
            m.split_once('=')
                .map(|(b, l)| (b.to_owned(), l.to_owned()))
                .ok_or_else(|| format!("--map {m}: expected BASE=LAYER"))
        })
        .collect::<Result<Vec<_>, _>>()?;
    let settings = mocap::ops::layer::Layer {
        subtree: request.subtree.to_owned(),
        weight: request.weight,
        fade_in: request.fade_in,
        fade_out: request.fade_out,
        blend: if request.additive { mocap::ops::layer::Blend::Additive } else { mocap::ops::layer::Blend::Override },
        map,
    };
    let out = mocap::ops::layer::apply(&base_clip, &layer_clip, &settings)
        .map_err(|e| format!("{} + {}: {e}", base.display(), layer.display()))?;
    std::fs::write(output, mocap::formats::bvh::write(&out))
        .map_err(|e| format!("{}: cannot write: {e}", output.display()))?;
    Ok(ExitCode::SUCCESS)
}
