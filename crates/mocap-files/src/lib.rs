//! Motion files from disk, read as the page reads a dropped set (the core's
//! [`mocap::load`]): an Acclaim motion given alone finds its skeleton beside
//! it, a `.gltf` the `.bin` buffers and images it names. Used by the `mocap`
//! CLI and the Python package; the core itself never touches the file system.
//! Errors read `FILE: message` or `FILE:LINE:COL: message`.

pub mod batch;

use mocap::{Format, Input, Loaded};
use std::path::{Path, PathBuf};

fn read(path: &Path) -> Result<Vec<u8>, String> {
    std::fs::read(path).map_err(|e| format!("{}: cannot read: {e}", path.display()))
}

fn stem(path: &Path) -> String {
    path.file_stem().map(|s| s.to_string_lossy().to_ascii_lowercase()).unwrap_or_default()
}

/// The skeleton of an Acclaim motion given alone: in its folder, the `.asf` its
/// name starts with (`01_01.amc` → `01.asf`, the longest such), else the only
/// `.asf` there, else an error that says what is needed.
pub fn find_skeleton(amc: &Path) -> Result<PathBuf, String> {
    let dir = amc.parent().filter(|d| !d.as_os_str().is_empty()).unwrap_or(Path::new("."));
    let mut skeletons: Vec<PathBuf> = std::fs::read_dir(dir)
        .map_err(|e| format!("{}: cannot list {} to find its skeleton: {e}", amc.display(), dir.display()))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().and_then(|e| e.to_str()).is_some_and(|e| e.eq_ignore_ascii_case("asf")))
        .collect();
    skeletons.sort();
    let motion = stem(amc);
    let by_name = skeletons.iter().filter(|s| motion.starts_with(&stem(s))).max_by_key(|s| stem(s).len());
    match (by_name, skeletons.as_slice()) {
        (Some(s), _) => Ok(s.clone()),
        (None, [only]) => Ok(only.clone()),
        (None, []) => Err(format!(
            "{}: an Acclaim motion needs its skeleton, and {} has no .asf file; give it too: mocap … SKELETON.asf {}",
            amc.display(),
            dir.display(),
            amc.display()
        )),
        (None, _) => Err(format!(
            "{}: an Acclaim motion needs its skeleton: no .asf in {} starts its name, and there are {}; give the right one too: mocap … SKELETON.asf {}",
            amc.display(),
            dir.display(),
            skeletons.len(),
            amc.display()
        )),
    }
}

/// Reads a set of files as the viewer does (formats from content, Acclaim motions
/// paired with skeletons); an `.amc` with no `.asf` in the set finds its skeleton
/// with [`find_skeleton`]. Errors read `FILE:LINE:COL: message`.
pub fn read_set(paths: &[PathBuf]) -> Result<Vec<Loaded>, String> {
    let files = paths.iter().map(|p| read(p).map(|b| (p.clone(), b))).collect::<Result<Vec<_>, _>>()?;
    load_files(files)
}

/// [`read_set`] on files already read (`(path, bytes)`; the paths name them in
/// messages and locate an `.amc`'s skeleton and a `.gltf`'s buffers).
pub fn load_files(mut files: Vec<(PathBuf, Vec<u8>)>) -> Result<Vec<Loaded>, String> {
    let formats: Vec<Option<Format>> = files.iter().map(|(p, b)| Format::detect(&p.display().to_string(), b)).collect();
    if !formats.contains(&Some(Format::Asf)) {
        if let Some((amc, _)) = files.iter().zip(&formats).find(|(_, f)| **f == Some(Format::Amc)).map(|(f, _)| f) {
            let skeleton = find_skeleton(amc)?;
            let bytes = read(&skeleton)?;
            files.insert(0, (skeleton, bytes));
        }
    }
    add_gltf_companions(&mut files);
    let names: Vec<String> = files.iter().map(|(p, _)| p.display().to_string()).collect();
    let inputs: Vec<Input> = files.iter().zip(&names).map(|((_, bytes), name)| Input { name, bytes }).collect();
    mocap::load(&inputs).into_iter().map(|r| r.map_err(|e| e.to_string())).collect()
}

/// The `.bin` buffers and images a `.gltf` names, read from beside it when they
/// are there and not given already (as an AMC finds its ASF).
fn add_gltf_companions(files: &mut Vec<(PathBuf, Vec<u8>)>) {
    let mut extra: Vec<(PathBuf, Vec<u8>)> = Vec::new();
    for (path, bytes) in files.iter() {
        for name in mocap::formats::gltf::document::external_files(bytes) {
            let beside = path.parent().unwrap_or(Path::new("")).join(&name);
            let given = |p: &Path| p.file_name() == beside.file_name();
            if files.iter().chain(&extra).any(|(p, _)| given(p)) {
                continue;
            }
            if let Ok(data) = std::fs::read(&beside) {
                extra.push((beside, data));
            }
        }
    }
    files.extend(extra);
}
