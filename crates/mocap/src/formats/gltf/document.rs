//! The first stage of reading glTF: bytes to a checked document and its buffers.
//!
//! Inputs: the file's bytes (`.glb` or `.gltf` JSON) and a way to find the other
//! files it names by URI (`.bin` buffers, images). Output: a [`Parsed`] document
//! whose index references are valid (the `gltf` crate's checks), whose required
//! extensions are all ones this reader handles, and whose buffers are all in
//! memory at least as long as the file says. Every failure is a [`ParseError`]
//! naming the byte offset or the JSON pointer.

use crate::error::ParseError;
use base64::Engine as _;
use gltf::json;

/// Extensions a file may require and still be read: the quantized attribute
/// types and texture transforms are read; the others only change the shading.
pub const SUPPORTED_EXTENSIONS: [&str; 9] = [
    "KHR_mesh_quantization",
    "KHR_texture_transform",
    "KHR_materials_unlit",
    "KHR_materials_emissive_strength",
    "KHR_materials_ior",
    "KHR_materials_specular",
    "KHR_materials_transmission",
    "KHR_materials_volume",
    "KHR_lights_punctual",
];

/// A buffer's bytes: borrowed from a `.glb`'s binary chunk, or owned (decoded
/// from a data URI, or another file).
pub type Buffer<'a> = std::borrow::Cow<'a, [u8]>;

/// A document with its buffers.
pub struct Parsed<'a> {
    /// The checked document.
    pub document: gltf::Document,
    /// Each buffer's bytes, by buffer index.
    pub buffers: Vec<Buffer<'a>>,
}

/// Looks up another file a `.gltf` names: given the URI's file name (decoded,
/// without folders), its bytes.
pub type Resources<'a> = &'a dyn Fn(&str) -> Option<Vec<u8>>;

/// True when `bytes` look like glTF: the GLB magic, or a JSON object that has an
/// `"asset"` member near its start.
pub fn sniff(bytes: &[u8]) -> bool {
    if bytes.starts_with(b"glTF") {
        return true;
    }
    let head = bytes.get(..bytes.len().min(4096)).unwrap_or(bytes);
    let text = String::from_utf8_lossy(head);
    let trimmed = text.trim_start_matches('\u{feff}').trim_start();
    trimmed.starts_with('{') && trimmed.contains("\"asset\"")
}

/// Reads the document and every buffer.
pub fn parse<'a>(bytes: &'a [u8], resources: Resources<'_>) -> Result<Parsed<'a>, ParseError> {
    let (json_bytes, blob) = if bytes.starts_with(b"glTF") { split_glb(bytes)? } else { (bytes, None) };
    let root: json::Root = json::deserialize::from_slice(json_bytes).map_err(|e| {
        let line = u32::try_from(e.line()).unwrap_or(u32::MAX);
        let column = u32::try_from(e.column()).unwrap_or(u32::MAX);
        ParseError::new(line, column, format!("not a glTF document: {e}"))
    })?;
    check_extensions(&root)?;
    check_animations(&root)?;
    check_valid(&root)?;
    let document = gltf::Document::from_json_without_validation(root);
    let buffers = read_buffers(&document, blob, resources)?;
    Ok(Parsed { document, buffers })
}

/// Splits a `.glb` into its JSON chunk and its binary chunk, checking every length
/// against the file.
fn split_glb(bytes: &[u8]) -> Result<(&[u8], Option<&[u8]>), ParseError> {
    let word = |at: usize| -> Result<u32, ParseError> {
        let b = bytes.get(at..at + 4).ok_or_else(|| ParseError::at_byte(at, "the file ends inside the GLB header"))?;
        Ok(u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
    };
    let version = word(4)?;
    if version != 2 {
        return Err(ParseError::at_byte(4, format!("GLB version {version}: only glTF 2.0 (version 2) is read")));
    }
    let total = word(8)? as usize;
    if total > bytes.len() || total < 12 {
        return Err(ParseError::at_byte(8, format!("the GLB header says {total} bytes, the file has {}", bytes.len())));
    }
    let (mut json, mut bin) = (None, None);
    let mut at = 12usize;
    while at + 8 <= total {
        let length = word(at)? as usize;
        let kind = word(at + 4)?;
        let start = at + 8;
        let end = start.checked_add(length).filter(|&e| e <= total).ok_or_else(|| {
            ParseError::at_byte(at, format!("chunk of {length} bytes runs past the end of the file ({total} bytes)"))
        })?;
        let data = bytes.get(start..end).unwrap_or(&[]);
        match kind {
            0x4E4F_534A if json.is_none() => json = Some(data),
            0x004E_4942 if bin.is_none() && json.is_some() => bin = Some(data),
            0x4E4F_534A | 0x004E_4942 => {
                return Err(ParseError::at_byte(at + 4, "a JSON or BIN chunk out of place (twice, or BIN first)"));
            }
            _ => {} // Unknown chunks are skipped, as the specification says.
        }
        at = end.saturating_add(3) & !3;
    }
    let json = json.ok_or_else(|| ParseError::at_byte(12, "the GLB has no JSON chunk"))?;
    Ok((json, bin))
}

/// Refuses a file that requires an extension this reader cannot honour.
fn check_extensions(root: &json::Root) -> Result<(), ParseError> {
    for (i, name) in root.extensions_required.iter().enumerate() {
        if !SUPPORTED_EXTENSIONS.contains(&name.as_str()) {
            let what = match name.as_str() {
                "KHR_draco_mesh_compression" => " (Draco-compressed meshes)",
                "EXT_meshopt_compression" | "KHR_meshopt_compression" => " (meshopt-compressed buffers)",
                "KHR_texture_basisu" => " (Basis Universal textures)",
                "EXT_texture_webp" => " (WebP textures)",
                _ => "",
            };
            return Err(ParseError::new(
                0,
                0,
                format!(
                    "extensionsRequired[{i}]: the file requires {name}{what}, which this reader does not support; \
                     re-export it without that extension"
                ),
            ));
        }
    }
    Ok(())
}

/// What the `gltf` crate does not check of animations before its accessors
/// unwrap them: each channel's target node and path, and each sampler's
/// accessors and interpolation.
fn check_animations(root: &json::Root) -> Result<(), ParseError> {
    use json::validation::Checked;
    let fail = |m: String| Err(ParseError::new(0, 0, m));
    for (a, animation) in root.animations.iter().enumerate() {
        for (c, channel) in animation.channels.iter().enumerate() {
            let at = format!("animations[{a}].channels[{c}]");
            if channel.sampler.value() >= animation.samplers.len() {
                return fail(format!("{at}.sampler: sampler {} does not exist", channel.sampler.value()));
            }
            if channel.target.node.value() >= root.nodes.len() {
                return fail(format!("{at}.target.node: node {} does not exist", channel.target.node.value()));
            }
            if matches!(channel.target.path, Checked::Invalid) {
                return fail(format!("{at}.target.path: not translation, rotation, scale or weights"));
            }
        }
        for (k, sampler) in animation.samplers.iter().enumerate() {
            let at = format!("animations[{a}].samplers[{k}]");
            for (what, index) in [("input", sampler.input.value()), ("output", sampler.output.value())] {
                if index >= root.accessors.len() {
                    return fail(format!("{at}.{what}: accessor {index} does not exist"));
                }
            }
            if matches!(sampler.interpolation, Checked::Invalid) {
                return fail(format!("{at}.interpolation: not LINEAR, STEP or CUBICSPLINE"));
            }
        }
    }
    Ok(())
}

/// The `gltf` crate's structural checks (every index in range, required members
/// present), skipping its own extension list (ours is [`check_extensions`]).
fn check_valid(root: &json::Root) -> Result<(), ParseError> {
    use json::validation::Validate as _;
    // The crate's own check of POSITION indexes before it checks the index.
    for (m, mesh) in root.meshes.iter().enumerate() {
        for (p, primitive) in mesh.primitives.iter().enumerate() {
            for (semantic, index) in &primitive.attributes {
                if index.value() >= root.accessors.len() {
                    let name = match semantic {
                        json::validation::Checked::Valid(s) => s.to_string(),
                        json::validation::Checked::Invalid => "?".into(),
                    };
                    return Err(ParseError::new(
                        0,
                        0,
                        format!(
                            "meshes[{m}].primitives[{p}].attributes.{name}: accessor {} does not exist ({} accessors)",
                            index.value(),
                            root.accessors.len()
                        ),
                    ));
                }
            }
        }
    }
    let mut first: Option<String> = None;
    root.validate(root, json::Path::new, &mut |path, error| {
        let path = path().to_string();
        if first.is_none() && !path.starts_with("extensionsRequired") {
            first = Some(format!("{path}: {error}"));
        }
    });
    match first {
        Some(message) => Err(ParseError::new(0, 0, message)),
        None => Ok(()),
    }
}

/// Each buffer's bytes: the GLB's binary chunk, a data URI, or another file.
fn read_buffers<'a>(
    document: &gltf::Document,
    blob: Option<&'a [u8]>,
    resources: Resources<'_>,
) -> Result<Vec<Buffer<'a>>, ParseError> {
    let mut out = Vec::new();
    for buffer in document.buffers() {
        let at = |m: String| ParseError::new(0, 0, format!("buffers[{}]: {m}", buffer.index()));
        let data = match buffer.source() {
            gltf::buffer::Source::Bin => {
                Buffer::Borrowed(blob.ok_or_else(|| at("it is the GLB's binary chunk, but the file has none".into()))?)
            }
            gltf::buffer::Source::Uri(uri) => Buffer::Owned(fetch(uri, resources).map_err(at)?),
        };
        if data.len() < buffer.length() {
            return Err(at(format!("the file says {} bytes, its data has {}", buffer.length(), data.len())));
        }
        out.push(data);
    }
    Ok(out)
}

/// The bytes a URI names: a base64 `data:` URI, or a file found by its name.
pub fn fetch(uri: &str, resources: Resources<'_>) -> Result<Vec<u8>, String> {
    if let Some(rest) = uri.strip_prefix("data:") {
        let (head, data) = rest.split_once(',').ok_or("a data URI without a comma")?;
        if !head.ends_with(";base64") {
            return Ok(percent_encoding::percent_decode_str(data).collect());
        }
        return base64::engine::general_purpose::STANDARD
            .decode(data.trim())
            .map_err(|e| format!("its data URI is not valid base64: {e}"));
    }
    let decoded = percent_encoding::percent_decode_str(uri).decode_utf8_lossy();
    let name = decoded.rsplit(['/', '\\']).next().unwrap_or(&decoded);
    resources(name).ok_or_else(|| format!("it names the file `{name}`: open that file together with this one"))
}

/// The other files a `.gltf` names (its `.bin` buffers and images), as relative
/// paths with their `%XX` escapes decoded; data URIs left out. Empty for a `.glb`
/// or for bytes that are not a glTF document (the reader reports those).
pub fn external_files(bytes: &[u8]) -> Vec<String> {
    if bytes.starts_with(b"glTF") {
        return Vec::new();
    }
    let Ok(root) = json::deserialize::from_slice::<json::Root>(bytes) else { return Vec::new() };
    let buffers = root.buffers.iter().filter_map(|b| b.uri.clone());
    let images = root.images.iter().filter_map(|i| i.uri.clone());
    let mut out: Vec<String> = Vec::new();
    for uri in buffers.chain(images).filter(|u| !u.starts_with("data:")) {
        let path = percent_encoding::percent_decode_str(&uri).decode_utf8_lossy().into_owned();
        if !out.contains(&path) {
            out.push(path);
        }
    }
    out
}
