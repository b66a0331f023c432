//! Loading a set of files: each file's format is detected from its content (the
//! extension is only a hint), Acclaim skeletons are paired with their motions, and
//! every motion (or lone skeleton) becomes one clip.

use crate::acclaim::{self, AcclaimSkeleton};
use crate::clip::Clip;
use crate::error::LoadError;

/// The formats [`Loader`] reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Format {
    /// Biovision hierarchy (`.bvh`): skeleton and motion.
    Bvh,
    /// Biovision BVA (`.bva`): segments in world space, no hierarchy.
    Bva,
    /// Acclaim skeleton (`.asf`).
    Asf,
    /// Acclaim motion (`.amc`): needs its skeleton.
    Amc,
}

impl Format {
    /// Every format, in the order content sniffing tries them.
    pub const ALL: [Format; 4] = [Format::Bvh, Format::Bva, Format::Asf, Format::Amc];

    /// File extensions readers accept (for file pickers), without the dot.
    pub const EXTENSIONS: [&'static str; 4] = ["bvh", "bva", "asf", "amc"];

    /// The usual extension.
    pub fn extension(self) -> &'static str {
        match self {
            Format::Bvh => "bvh",
            Format::Bva => "bva",
            Format::Asf => "asf",
            Format::Amc => "amc",
        }
    }

    /// True when `bytes` look like this format.
    fn sniff(self, bytes: &[u8]) -> bool {
        match self {
            Format::Bvh => crate::bvh::sniff(bytes),
            Format::Bva => crate::bva::sniff(bytes),
            Format::Asf => acclaim::sniff_asf(bytes),
            Format::Amc => acclaim::sniff_amc(bytes),
        }
    }

    /// The format of a file: from its content first; when the content matches no
    /// format, from the extension (so a damaged file still gets its reader's error).
    pub fn detect(file_name: &str, bytes: &[u8]) -> Option<Format> {
        if let Some(format) = Format::ALL.into_iter().find(|f| f.sniff(bytes)) {
            return Some(format);
        }
        let ext = file_name.rsplit_once('.').map(|(_, e)| e.to_ascii_lowercase());
        Format::ALL.into_iter().find(|f| ext.as_deref() == Some(f.extension()))
    }
}

/// One file handed to the loader.
#[derive(Clone, Copy, Debug)]
pub struct Input<'a> {
    /// Its name (a hint for the format, and the name in messages).
    pub name: &'a str,
    /// Its bytes.
    pub bytes: &'a [u8],
}

/// A clip read from a set of files.
#[derive(Clone, Debug)]
pub struct Loaded {
    /// The name to show: the motion file's name (an AMC's, not its skeleton's).
    pub name: String,
    /// The clip.
    pub clip: Clip,
}

/// Reads sets of files, remembering the last Acclaim skeleton so that a motion
/// dropped later without its skeleton still opens.
#[derive(Clone, Debug, Default)]
pub struct Loader {
    skeleton: Option<(String, AcclaimSkeleton)>,
}

/// The part of a file name before its last dot and after its last folder.
fn stem(name: &str) -> &str {
    let base = name.rsplit(['/', '\\']).next().unwrap_or(name);
    base.rsplit_once('.').map_or(base, |(s, _)| s)
}

impl Loader {
    /// The file name of the remembered Acclaim skeleton.
    pub fn skeleton_name(&self) -> Option<&str> {
        self.skeleton.as_ref().map(|(n, _)| n.as_str())
    }

    /// Reads `files`: one result per BVH, BVA and AMC file, and per ASF file no
    /// motion in the set uses (its rest pose), in file order. An AMC takes the ASF
    /// of the set whose name its own name starts with (`01_01.amc` → `01.asf`),
    /// else the set's last ASF, else the last one this loader read.
    pub fn load(&mut self, files: &[Input<'_>]) -> Vec<Result<Loaded, LoadError>> {
        let formats: Vec<Option<Format>> = files.iter().map(|f| Format::detect(f.name, f.bytes)).collect();
        let mut skeletons: Vec<(usize, Result<AcclaimSkeleton, LoadError>)> = Vec::new();
        for (i, (file, format)) in files.iter().zip(&formats).enumerate() {
            if *format == Some(Format::Asf) {
                skeletons.push((i, read_asf(file)));
            }
        }
        let mut used = vec![false; files.len()];
        let mut results: Vec<(usize, Result<Loaded, LoadError>)> = Vec::new();
        for (i, (file, format)) in files.iter().zip(&formats).enumerate() {
            let result = match format {
                None => Err(LoadError::UnknownFormat { file: file.name.to_owned() }),
                Some(Format::Bvh) => crate::bvh::parse(file.bytes).map_err(|e| parse_error(file, e)),
                Some(Format::Bva) => crate::bva::parse(file.bytes).and_then(|b| crate::bva::to_clip(&b)).map_err(|e| parse_error(file, e)),
                Some(Format::Asf) => continue,
                Some(Format::Amc) => {
                    let chosen = self.skeleton_for(file.name, files, &skeletons);
                    if let Some(index) = chosen.index {
                        if let Some(flag) = used.get_mut(index) {
                            *flag = true;
                        }
                    }
                    match chosen.skeleton {
                        Some(Ok(skeleton)) => skeleton.motion_clip(file.bytes).map_err(|e| parse_error(file, e)),
                        Some(Err(e)) => Err(LoadError::SkeletonFailed { file: file.name.to_owned(), skeleton: Box::new(e) }),
                        None => Err(LoadError::MissingSkeleton { file: file.name.to_owned(), named: named_skeleton(file.bytes) }),
                    }
                }
            };
            results.push((i, result.map(|clip| Loaded { name: file.name.to_owned(), clip })));
        }
        for (i, skeleton) in &skeletons {
            if used.get(*i).copied().unwrap_or(false) {
                continue;
            }
            let name = files.get(*i).map_or(String::new(), |f| f.name.to_owned());
            results.push((*i, skeleton.clone().map(|s| Loaded { name, clip: s.rest_clip() })));
        }
        if let Some((i, Ok(skeleton))) = skeletons.iter().rev().find(|(_, s)| s.is_ok()) {
            let name = files.get(*i).map_or(String::new(), |f| f.name.to_owned());
            self.skeleton = Some((name, skeleton.clone()));
        }
        results.sort_by_key(|(i, _)| *i);
        results.into_iter().map(|(_, r)| r).collect()
    }

    /// The skeleton an AMC named `name` uses (see [`Loader::load`]).
    fn skeleton_for<'s>(&'s self, name: &str, files: &[Input<'_>], skeletons: &'s [(usize, Result<AcclaimSkeleton, LoadError>)]) -> Chosen<'s> {
        let motion = stem(name).to_ascii_lowercase();
        let by_name = skeletons
            .iter()
            .filter(|(i, _)| files.get(*i).is_some_and(|f| motion.starts_with(&stem(f.name).to_ascii_lowercase())))
            .max_by_key(|(i, _)| files.get(*i).map_or(0, |f| stem(f.name).len()));
        match by_name.or(skeletons.last()) {
            Some((i, s)) => Chosen { index: Some(*i), skeleton: Some(s.as_ref().map_err(Clone::clone)) },
            None => Chosen { index: None, skeleton: self.skeleton.as_ref().map(|(_, s)| Ok(s)) },
        }
    }
}

/// The skeleton picked for a motion, and which file it came from.
struct Chosen<'s> {
    index: Option<usize>,
    skeleton: Option<Result<&'s AcclaimSkeleton, LoadError>>,
}

/// The skeleton file an AMC names in its `#!OML:ASF <path>` header line (its base
/// name), if it has one.
fn named_skeleton(amc: &[u8]) -> Option<String> {
    let head = amc.get(..amc.len().min(1024)).unwrap_or(amc);
    let line = head.split(|&b| b == b'\n' || b == b'\r').find(|l| l.starts_with(b"#!OML:ASF"))?;
    let path = String::from_utf8_lossy(line.get(9..)?).trim().to_owned();
    let base = path.rsplit(['/', '\\']).next().unwrap_or(&path).trim().to_owned();
    (!base.is_empty()).then_some(base)
}

fn parse_error(file: &Input<'_>, error: crate::error::ParseError) -> LoadError {
    LoadError::Parse { file: file.name.to_owned(), error }
}

fn read_asf(file: &Input<'_>) -> Result<AcclaimSkeleton, LoadError> {
    acclaim::parse_asf(file.bytes).and_then(|asf| acclaim::skeleton(&asf)).map_err(|e| parse_error(file, e))
}

/// Reads a set of files with a fresh [`Loader`].
pub fn load(files: &[Input<'_>]) -> Vec<Result<Loaded, LoadError>> {
    Loader::default().load(files)
}

/// Reads one file that holds a whole clip (BVH, BVA, or an ASF alone).
pub fn load_one(file_name: &str, bytes: &[u8]) -> Result<Clip, LoadError> {
    let mut results = load(&[Input { name: file_name, bytes }]);
    match results.pop() {
        Some(result) => result.map(|l| l.clip),
        None => Err(LoadError::UnknownFormat { file: file_name.to_owned() }),
    }
}
