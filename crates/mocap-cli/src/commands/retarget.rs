//! `mocap retarget`: a motion on another skeleton ([`mocap::ops::retarget`]).

use super::*;

/// What `mocap retarget` is asked.
pub struct RetargetRequest<'a> {
    /// The motion (one file, or an Acclaim skeleton and motion).
    pub source: &'a [PathBuf],
    /// The skeleton that receives it (a motion file; its skeleton and reference pose).
    pub onto: &'a [PathBuf],
    /// A JSON object of explicit pairs, `{"TARGET": "SOURCE", …}` (`""`: leave out).
    pub map: Option<&'a Path>,
    /// Where to save the pairs used, in the same form.
    pub save_map: Option<&'a Path>,
    /// `first-frame` (default) or `rest`.
    pub reference: &'a str,
    /// The output (`.bvh`, `.glb` or `.gltf`).
    pub output: &'a Path,
    /// The source's glTF animation (default: its first).
    pub animation: Option<&'a str>,
}

/// Runs `mocap retarget`: writes the retargeted clip and says how many joints were mapped.
pub fn retarget(request: &RetargetRequest) -> Result<ExitCode, String> {
    let source = read_take(request.source, request.animation)?;
    let target = read_clip(request.onto)?;
    let map = match request.map {
        Some(path) => read_map(path)?,
        None => Vec::new(),
    };
    let reference = match request.reference {
        "first-frame" => mocap::ops::retarget::Reference::FirstFrame,
        "rest" => mocap::ops::retarget::Reference::Rest,
        other => return Err(format!("--reference {other}: expected first-frame or rest")),
    };
    let options = mocap::ops::retarget::Options { map, reference };
    let (clip, pairs) = mocap::ops::retarget::retarget(&source, &target, &options).map_err(|e| {
        let names = |p: &[PathBuf]| p.iter().map(|p| p.display().to_string()).collect::<Vec<_>>().join(" ");
        format!("{} onto {}: {e}", names(request.source), names(request.onto))
    })?;
    let (tj, sj) = (target.skeleton().joints(), source.skeleton().joints());
    let joints = tj.iter().filter(|j| !j.is_end_site()).count();
    eprintln!("mapped {} of {joints} target joints", pairs.len());
    if let Some(path) = request.save_map {
        let object: serde_json::Map<String, Value> = pairs
            .iter()
            .filter_map(|&(t, s)| Some((tj.get(t)?.name.clone(), Value::String(sj.get(s)?.name.clone()))))
            .collect();
        let text = serde_json::to_string_pretty(&Value::Object(object)).unwrap_or_default();
        std::fs::write(path, text + "\n").map_err(|e| format!("{}: cannot write: {e}", path.display()))?;
    }
    let ext = request.output.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    let name = request
        .source
        .last()
        .and_then(|p| p.file_stem())
        .map_or_else(|| "motion".to_owned(), |s| s.to_string_lossy().into_owned());
    let bytes = match ext.as_deref() {
        Some("bvh") => mocap::formats::bvh::write(&clip).into_bytes(),
        Some("glb") => mocap::formats::gltf::to_glb(&clip, &mocap::formats::gltf::Options { name, body: true })
            .map_err(|e| format!("{}: {e}", request.output.display()))?,
        Some("gltf") => mocap::formats::gltf::to_gltf(&clip, &mocap::formats::gltf::Options { name, body: true })
            .map_err(|e| format!("{}: {e}", request.output.display()))?
            .into_bytes(),
        _ => return Err(format!("{}: retarget writes .bvh, .glb or .gltf files", request.output.display())),
    };
    std::fs::write(request.output, bytes).map_err(|e| format!("{}: cannot write: {e}", request.output.display()))?;
    Ok(ExitCode::SUCCESS)
}

/// A map file: a JSON object of target joint names to source joint names.
pub(super) fn read_map(path: &Path) -> Result<Vec<(String, String)>, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("{}: cannot read: {e}", path.display()))?;
    let value: Value =
        serde_json::from_str(&text).map_err(|e| format!("{}:{}:{}: {e}", path.display(), e.line(), e.column()))?;
    let object =
        value.as_object().ok_or_else(|| format!("{}: expected an object of TARGET: SOURCE names", path.display()))?;
    object
        .iter()
        .map(|(t, s)| match s.as_str() {
            Some(s) => Ok((t.clone(), s.to_owned())),
            None => Err(format!(
                "{}: /{}: expected a joint name (a string)",
                path.display(),
                t.replace('~', "~0").replace('/', "~1")
            )),
        })
        .collect()
}
