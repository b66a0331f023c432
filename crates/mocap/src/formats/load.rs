//! Loading a set of files: each file's format is detected from its content (the
//! extension is only a hint), Acclaim skeletons are paired with their motions,
//! models with their skins, and every motion (or lone skeleton) becomes one clip,
//! every model one [`Model`].

use crate::error::LoadError;
use crate::formats::acclaim::{self, AcclaimSkeleton};
use crate::formats::image::{self, ImageFormat, Rgba};
use crate::model::asset::Asset;
use crate::model::mesh::{self, Model, MorphMesh, Skin};
use std::sync::Arc;

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
    /// Quake 2 model (`.md2`): mesh and vertex frames; its skin comes as an image.
    Md2,
    /// glTF 2.0 (`.glb`, or `.gltf` with its `.bin` and images): a character.
    Gltf,
}

impl Format {
    /// Every format, in the order content sniffing tries them.
    pub const ALL: [Format; 6] = [Format::Md2, Format::Gltf, Format::Bvh, Format::Bva, Format::Asf, Format::Amc];

    /// File extensions of the formats (for file pickers), without the dot; skins
    /// add [`ImageFormat::EXTENSIONS`].
    pub const EXTENSIONS: [&'static str; 7] = ["bvh", "bva", "asf", "amc", "md2", "glb", "gltf"];

    /// The usual extension.
    pub fn extension(self) -> &'static str {
        match self {
            Format::Bvh => "bvh",
            Format::Bva => "bva",
            Format::Asf => "asf",
            Format::Amc => "amc",
            Format::Md2 => "md2",
            Format::Gltf => "glb",
        }
    }

    /// True when `bytes` look like this format.
    fn sniff(self, bytes: &[u8]) -> bool {
        match self {
            Format::Bvh => crate::formats::bvh::sniff(bytes),
            Format::Bva => crate::formats::bva::sniff(bytes),
            Format::Asf => acclaim::sniff_asf(bytes),
            Format::Amc => acclaim::sniff_amc(bytes),
            Format::Md2 => crate::formats::md2::sniff(bytes),
            Format::Gltf => crate::formats::gltf::sniff(bytes),
        }
    }

    /// The format of a file: from its content first; when the content matches no
    /// format, from the extension (so a damaged file still gets its reader's error).
    pub fn detect(file_name: &str, bytes: &[u8]) -> Option<Format> {
        if let Some(format) = Format::ALL.into_iter().find(|f| f.sniff(bytes)) {
            return Some(format);
        }
        let ext = file_name.rsplit_once('.').map(|(_, e)| e.to_ascii_lowercase());
        if ext.as_deref() == Some("gltf") {
            return Some(Format::Gltf);
        }
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

/// An asset read from a set of files.
#[derive(Clone, Debug)]
pub struct Loaded {
    /// The name to show: the motion or model file's name (an AMC's, not its skeleton's).
    pub name: String,
    /// The clip or model.
    pub asset: Asset,
}

impl Loaded {
    /// The clip, when the asset is one.
    pub fn clip(&self) -> Option<&crate::Clip> {
        self.asset.clip()
    }

    /// The clip by value, when the asset is one.
    pub fn into_clip(self) -> Option<crate::Clip> {
        match self.asset {
            Asset::Clip(c) => Some(c),
            Asset::Model(_) => None,
        }
    }
}

/// What a file in a set is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Kind {
    Asset(Format),
    Image(ImageFormat),
    Unknown,
}

impl Kind {
    /// From the content first (any asset format, then any image), then the extension.
    fn detect(file: &Input<'_>) -> Kind {
        if let Some(format) = Format::ALL.into_iter().find(|f| f.sniff(file.bytes)) {
            return Kind::Asset(format);
        }
        if let Some(format) = ImageFormat::detect(file.bytes) {
            return Kind::Image(format);
        }
        match (Format::detect(file.name, file.bytes), ImageFormat::from_extension(file.name)) {
            (Some(format), _) => Kind::Asset(format),
            (None, Some(format)) => Kind::Image(format),
            (None, None) => Kind::Unknown,
        }
    }
}

/// Reads sets of files, remembering the last Acclaim skeleton so that a motion
/// dropped later without its skeleton still opens.
#[derive(Clone, Debug, Default)]
pub struct Loader {
    skeleton: Option<(String, AcclaimSkeleton)>,
}

/// The part of a file name after its last folder.
fn base_name(name: &str) -> &str {
    name.rsplit(['/', '\\']).next().unwrap_or(name)
}

/// True for a glTF buffer file (`.bin`).
fn is_buffer(name: &str) -> bool {
    name.rsplit_once('.').is_some_and(|(_, e)| e.eq_ignore_ascii_case("bin"))
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

    /// Reads `files`: one result per BVH, BVA, AMC and MD2 file, and per ASF file no
    /// motion in the set uses (its rest pose), in file order. An AMC takes the ASF
    /// of the set whose name its own name starts with (`01_01.amc` → `01.asf`),
    /// else the set's last ASF, else the last one this loader read. An MD2 takes
    /// its skin from the images of the set ([`mesh::choose_skin`]); images in a set
    /// with no model are an error each ([`LoadError::LoneImage`]).
    pub fn load(&mut self, files: &[Input<'_>]) -> Vec<Result<Loaded, LoadError>> {
        let kinds: Vec<Kind> = files.iter().map(Kind::detect).collect();
        let formats: Vec<Option<Format>> =
            kinds.iter().map(|k| if let Kind::Asset(f) = k { Some(*f) } else { None }).collect();
        let mut skins = Skins::new(files, &kinds);
        skins.decode_all(files);
        // Models are read first so that images a model names are not handed to another.
        let mut models: Vec<Option<Result<MorphMesh, LoadError>>> = files
            .iter()
            .zip(&formats)
            .map(|(file, format)| {
                (*format == Some(Format::Md2)).then(|| {
                    crate::formats::md2::parse(file.bytes)
                        .map(|m| MorphMesh::from_md2(&m))
                        .map_err(|e| parse_error(file, e))
                })
            })
            .collect();
        for (file, model) in files.iter().zip(&models) {
            if let Some(Ok(mesh)) = model {
                skins.claim(file.name, mesh);
            }
        }
        let mut skeletons: Vec<(usize, Result<AcclaimSkeleton, LoadError>)> = Vec::new();
        for (i, (file, format)) in files.iter().zip(&formats).enumerate() {
            if *format == Some(Format::Asf) {
                skeletons.push((i, read_asf(file)));
            }
        }
        let mut used = vec![false; files.len()];
        let has_gltf = formats.contains(&Some(Format::Gltf));
        let mut results: Vec<(usize, Result<Loaded, LoadError>)> = Vec::new();
        for (i, (file, format)) in files.iter().zip(&formats).enumerate() {
            let result: Result<Asset, LoadError> = match format {
                // A glTF's buffers and images come in the same set.
                None if has_gltf && (is_buffer(file.name) || matches!(kinds.get(i), Some(Kind::Image(_)))) => continue,
                None => match kinds.get(i) {
                    Some(Kind::Image(_)) => match skins.lone_image_error(i) {
                        Some(e) => Err(e),
                        None => continue,
                    },
                    _ => Err(LoadError::UnknownFormat { file: file.name.to_owned() }),
                },
                Some(Format::Bvh) => {
                    crate::formats::bvh::parse(file.bytes).map(Asset::from).map_err(|e| parse_error(file, e))
                }
                Some(Format::Bva) => crate::formats::bva::parse(file.bytes)
                    .and_then(|b| crate::formats::bva::to_clip(&b))
                    .map(Asset::from)
                    .map_err(|e| parse_error(file, e)),
                Some(Format::Md2) => match models.get_mut(i).and_then(Option::take) {
                    Some(mesh) => mesh.map(|mesh| skins.model(file.name, mesh)),
                    None => continue,
                },
                Some(Format::Asf) => continue,
                Some(Format::Gltf) => {
                    let resources =
                        |name: &str| files.iter().find(|f| base_name(f.name) == name).map(|f| f.bytes.to_vec());
                    crate::formats::gltf::parse_asset(file.bytes, &resources).map_err(|e| parse_error(file, e))
                }
                Some(Format::Amc) => {
                    let chosen = self.skeleton_for(file.name, files, &skeletons);
                    if let Some(index) = chosen.index {
                        if let Some(flag) = used.get_mut(index) {
                            *flag = true;
                        }
                    }
                    match chosen.skeleton {
                        Some(Ok(skeleton)) => {
                            skeleton.motion_clip(file.bytes).map(Asset::from).map_err(|e| parse_error(file, e))
                        }
                        Some(Err(e)) => {
                            Err(LoadError::SkeletonFailed { file: file.name.to_owned(), skeleton: Box::new(e) })
                        }
                        None => Err(LoadError::MissingSkeleton {
                            file: file.name.to_owned(),
                            named: named_skeleton(file.bytes),
                        }),
                    }
                }
            };
            results.push((i, result.map(|asset| Loaded { name: file.name.to_owned(), asset })));
        }
        for (i, skeleton) in &skeletons {
            if used.get(*i).copied().unwrap_or(false) {
                continue;
            }
            let name = files.get(*i).map_or(String::new(), |f| f.name.to_owned());
            results.push((*i, skeleton.clone().map(|s| Loaded { name, asset: Asset::Clip(s.rest_clip()) })));
        }
        if let Some((i, Ok(skeleton))) = skeletons.iter().rev().find(|(_, s)| s.is_ok()) {
            let name = files.get(*i).map_or(String::new(), |f| f.name.to_owned());
            self.skeleton = Some((name, skeleton.clone()));
        }
        results.sort_by_key(|(i, _)| *i);
        results.into_iter().map(|(_, r)| r).collect()
    }

    /// The skeleton an AMC named `name` uses (see [`Loader::load`]).
    fn skeleton_for<'s>(
        &'s self,
        name: &str,
        files: &[Input<'_>],
        skeletons: &'s [(usize, Result<AcclaimSkeleton, LoadError>)],
    ) -> Chosen<'s> {
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

/// The images of a set, decoded on first use, and which models took them.
struct Skins<'f> {
    /// (index in the set, file name, decoded image or why not).
    images: Vec<(usize, &'f str, Option<Result<Arc<Rgba>, LoadError>>)>,
    /// Whether the set holds a model at all.
    has_model: bool,
    /// Taken by a model already.
    used: Vec<bool>,
    /// Named by some model of the set (by its skin names or its file name).
    claimed: Vec<bool>,
}

impl<'f> Skins<'f> {
    fn new(files: &[Input<'f>], kinds: &[Kind]) -> Skins<'f> {
        let images: Vec<_> = files
            .iter()
            .zip(kinds)
            .enumerate()
            .filter(|(_, (_, k))| matches!(k, Kind::Image(_)))
            .map(|(i, (f, _))| (i, f.name, None))
            .collect();
        let has_model = kinds.contains(&Kind::Asset(Format::Md2));
        let used = vec![false; images.len()];
        let claimed = used.clone();
        Skins { images, has_model, used, claimed }
    }

    /// Marks the image the model `name` names, if any, as claimed.
    fn claim(&mut self, name: &str, mesh: &MorphMesh) {
        let names: Vec<&str> = self.images.iter().map(|(_, n, _)| *n).collect();
        if let Some(flag) = mesh::match_skin(name, &mesh.skins, &names).and_then(|k| self.claimed.get_mut(k)) {
            *flag = true;
        }
    }

    /// A model with the skin it takes from the set (none when the set has no image
    /// or its image cannot be decoded; that image reports its own error).
    fn model(&mut self, name: &str, mesh: MorphMesh) -> Asset {
        let names: Vec<&str> = self.images.iter().map(|(_, n, _)| *n).collect();
        // An image the model names, or named like it; else the first image no model
        // names or took; else the first one no model took; else the first image.
        let free = |k: &usize| !self.used.get(*k).copied().unwrap_or(true);
        let unclaimed = |k: &usize| free(k) && !self.claimed.get(*k).copied().unwrap_or(true);
        let chosen = mesh::match_skin(name, &mesh.skins, &names)
            .or_else(|| (0..names.len()).find(unclaimed))
            .or_else(|| (0..names.len()).find(free))
            .or((!names.is_empty()).then_some(0));
        let skin = chosen.and_then(|k| {
            if let Some(flag) = self.used.get_mut(k) {
                *flag = true;
            }
            let (_, file, image) = self.images.get_mut(k)?;
            match image {
                Some(Ok(image)) => Some(Skin { name: (*file).to_owned(), image: image.clone() }),
                _ => None,
            }
        });
        Asset::Model(Model::new(mesh, skin))
    }

    /// Decodes every image (once), keeping the results.
    fn decode_all(&mut self, files: &[Input<'_>]) {
        for (i, name, image) in &mut self.images {
            if image.is_none() {
                let bytes = files.get(*i).map_or(&[][..], |f| f.bytes);
                *image = Some(
                    image::decode_any(name, bytes)
                        .map(Arc::new)
                        .map_err(|error| LoadError::Parse { file: (*name).to_owned(), error }),
                );
            }
        }
    }

    /// The error to report for image `index` of the set: it cannot be decoded, or
    /// there is no model in the set to put it on; `None` when it is fine.
    fn lone_image_error(&self, index: usize) -> Option<LoadError> {
        let (_, name, image) = self.images.iter().find(|(i, _, _)| *i == index)?;
        if !self.has_model {
            return Some(LoadError::LoneImage { file: (*name).to_owned() });
        }
        match image {
            Some(Err(e)) => Some(e.clone()),
            _ => None,
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

/// Reads one file that holds a whole asset (BVH, BVA, MD2, or an ASF alone).
pub fn load_one(file_name: &str, bytes: &[u8]) -> Result<Asset, LoadError> {
    let mut results = load(&[Input { name: file_name, bytes }]);
    match results.pop() {
        Some(result) => result.map(|l| l.asset),
        None => Err(LoadError::UnknownFormat { file: file_name.to_owned() }),
    }
}
