//! `mocap` for Python: the core's readers, FK, edits, retargeting and writers,
//! with NumPy arrays out. Parsing and computing run with the GIL released.
//! The Python-side package (`python/mocap/__init__.py`) re-exports this module
//! and adds `batch`.

use mocap::glam::Vec3;
use mocap::model::skeleton::{EulerConvention, Joint, Skeleton};
use mocap::runtime::pose::LocalPose;
use mocap::{Asset, Channel, Clip as CoreClip, Motion};
use numpy::ndarray::{Array2, Array3};
use numpy::{IntoPyArray, PyArray1, PyArray2, PyArray3, PyReadonlyArray2, PyReadonlyArray1};
use pyo3::exceptions::{PyIndexError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict, PyList};
use std::path::PathBuf;

pyo3::create_exception!(
    _mocap,
    ParseError,
    PyValueError,
    "A file that cannot be read: the message is `FILE:LINE:COL: message`, as the CLI prints it."
);

fn parse_error(message: String) -> PyErr {
    ParseError::new_err(message)
}

/// A motion: a skeleton (joints in parent-before-child order, End Sites
/// included) and its channel values per frame.
#[pyclass(module = "mocap", frozen)]
pub struct Clip {
    clip: CoreClip,
    name: String,
}

/// Reads one clip from a path (an `.amc` finds its `.asf` as the CLI does) or
/// from bytes (`format` names it when the content does not).
fn read_clip(
    source: Source,
    format: Option<&str>,
    skeleton: Option<PathBuf>,
    animation: Option<&str>,
) -> Result<(CoreClip, String), String> {
    let (loaded, name) = match source {
        Source::Path(path) => {
            let mut paths = Vec::new();
            paths.extend(skeleton);
            paths.push(path.clone());
            let name = path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
            (mocap_files::read_set(&paths)?, name)
        }
        Source::Bytes(bytes) => {
            let name = match format {
                Some(f) => format!("clip.{}", f.trim_start_matches('.')),
                None => "clip".to_string(),
            };
            let mut files = Vec::new();
            if let Some(s) = skeleton {
                let data = std::fs::read(&s).map_err(|e| format!("{}: cannot read: {e}", s.display()))?;
                files.push((s, data));
            }
            files.push((PathBuf::from(&name), bytes));
            (mocap_files::load_files(files)?, name)
        }
    };
    let mut clips = loaded.into_iter().filter_map(|l| match l.asset {
        Asset::Clip(c) => Some(c),
        Asset::Model(_) => None,
    });
    let mut clip = clips.next().ok_or_else(|| format!("{name}: a model has no skeleton or motion to read as a Clip"))?;
    if let Some(take) = animation {
        if !clip.set_take(take) {
            let names: Vec<&str> = clip.takes().iter().map(|t| t.name.as_str()).collect();
            return Err(format!("{name}: no animation named `{take}`; the file has: {}", names.join(", ")));
        }
    }
    Ok((clip, name))
}

enum Source {
    Path(PathBuf),
    Bytes(Vec<u8>),
}

fn source(obj: &Bound<'_, PyAny>) -> PyResult<Source> {
    if let Ok(b) = obj.cast::<PyBytes>() {
        return Ok(Source::Bytes(b.as_bytes().to_vec()));
    }
    let path: PathBuf = obj.extract().map_err(|_| PyValueError::new_err("expected a path (str or os.PathLike) or bytes"))?;
    Ok(Source::Path(path))
}

/// Reads a motion file: BVH, BVA, Acclaim ASF/AMC, glTF/GLB (an `.amc`
/// finds its `.asf` beside it, or give `skeleton=`); `animation` picks a
/// glTF animation. Raises `ParseError` with `FILE:LINE:COL: message`.
#[pyfunction]
#[pyo3(signature = (path_or_bytes, *, format=None, skeleton=None, animation=None))]
fn read(
    py: Python<'_>,
    path_or_bytes: &Bound<'_, PyAny>,
    format: Option<String>,
    skeleton: Option<PathBuf>,
    animation: Option<String>,
) -> PyResult<Clip> {
    let src = source(path_or_bytes)?;
    let (clip, name) =
        py.detach(|| read_clip(src, format.as_deref(), skeleton, animation.as_deref())).map_err(parse_error)?;
    Ok(Clip { clip, name })
}

/// Reads many files in parallel (every core), in order; the first failure
/// raises `ParseError` naming its file.
#[pyfunction]
#[pyo3(signature = (paths, *, jobs=None))]
fn read_many(py: Python<'_>, paths: Vec<PathBuf>, jobs: Option<usize>) -> PyResult<Vec<Clip>> {
    let jobs = jobs.unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get())).max(1);
    let results: Vec<Result<(CoreClip, String), String>> = py.detach(|| {
        let next = std::sync::atomic::AtomicUsize::new(0);
        let slots: Vec<std::sync::Mutex<Option<Result<(CoreClip, String), String>>>> =
            paths.iter().map(|_| std::sync::Mutex::new(None)).collect();
        std::thread::scope(|s| {
            for _ in 0..jobs.min(paths.len().max(1)) {
                s.spawn(|| {
                    loop {
                        let i = next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                        let Some(path) = paths.get(i) else { break };
                        let r = read_clip(Source::Path(path.clone()), None, None, None);
                        if let Some(Ok(mut slot)) = slots.get(i).map(|m| m.lock()) {
                            *slot = Some(r);
                        }
                    }
                });
            }
        });
        slots.into_iter().map(|m| m.into_inner().ok().flatten().unwrap_or_else(|| Err("not read".into()))).collect()
    });
    results.into_iter().map(|r| r.map(|(clip, name)| Clip { clip, name }).map_err(parse_error)).collect()
}

/// Builds a clip from arrays (a network's output back to a file): joint names,
/// parent indices (-1 for a root; parents before children), rest offsets
/// (J×3), each joint's channel names (`Xposition`, `Zrotation`, …; none for an
/// End Site), the values (F×C in that order, degrees) and the frame time.
#[pyfunction]
#[pyo3(signature = (joint_names, parents, offsets, channels, values, frame_time))]
fn from_arrays(
    joint_names: Vec<String>,
    parents: PyReadonlyArray1<'_, i32>,
    offsets: PyReadonlyArray2<'_, f32>,
    channels: Vec<Vec<String>>,
    values: PyReadonlyArray2<'_, f32>,
    frame_time: f64,
) -> PyResult<Clip> {
    let n = joint_names.len();
    let parents = parents.as_array();
    let offsets = offsets.as_array();
    if parents.len() != n || offsets.shape() != [n, 3] || channels.len() != n {
        return Err(PyValueError::new_err(format!(
            "{n} joint names need {n} parents, {n}x3 offsets and {n} channel lists (got {}, {:?}, {})",
            parents.len(),
            offsets.shape(),
            channels.len()
        )));
    }
    let mut joints = Vec::with_capacity(n);
    for (j, name) in joint_names.iter().enumerate() {
        let parent = match parents[j] {
            p if p < 0 => None,
            p => Some(p as usize),
        };
        let offset = Vec3::new(offsets[[j, 0]], offsets[[j, 1]], offsets[[j, 2]]);
        let list = channels[j]
            .iter()
            .map(|c| Channel::from_name(c.as_bytes()).ok_or_else(|| PyValueError::new_err(format!("joint {name}: unknown channel `{c}`"))))
            .collect::<PyResult<Vec<Channel>>>()?;
        joints.push(if list.is_empty() && j > 0 && !joint_names.iter().skip(j + 1).zip(parents.iter().skip(j + 1)).any(|(_, p)| *p == j as i32) {
            Joint::end_site(name.clone(), parent, offset)
        } else {
            Joint::new(name.clone(), parent, offset, list)
        });
    }
    let skeleton = Skeleton::new(joints, EulerConvention::Intrinsic).map_err(|e| PyValueError::new_err(e.to_string()))?;
    let values = values.as_array();
    let c = skeleton.channel_count();
    if values.shape()[1] != c {
        return Err(PyValueError::new_err(format!("values: {c} columns expected (the channels), got {}", values.shape()[1])));
    }
    let frames = values.shape()[0];
    let data: Vec<f32> = values.iter().copied().collect();
    let motion = Motion::new(frame_time, c, frames, data).ok_or_else(|| PyValueError::new_err("values do not fit the frame count"))?;
    let clip = CoreClip::new(skeleton, motion).map_err(|e| PyValueError::new_err(e.to_string()))?;
    Ok(Clip { clip, name: "arrays".into() })
}

/// A clip stored by `Clip.__reduce__` (the core's lossless store format).
#[pyfunction]
fn _from_store(bytes: &[u8], name: String) -> PyResult<Clip> {
    match mocap::formats::store::parse(bytes).map_err(|e| parse_error(format!("{name}: {e}")))? {
        Asset::Clip(clip) => Ok(Clip { clip, name }),
        Asset::Model(_) => Err(PyValueError::new_err("the stored asset is a model, not a clip")),
    }
}

impl Clip {
    fn frames(&self, frames: Option<Vec<i64>>) -> PyResult<Vec<usize>> {
        let count = self.clip.frame_count();
        match frames {
            None => Ok((0..count).collect()),
            Some(list) => list
                .into_iter()
                .map(|f| {
                    let i = if f < 0 { f + count as i64 } else { f };
                    usize::try_from(i).ok().filter(|&i| i < count).ok_or_else(|| {
                        PyIndexError::new_err(format!("frame {f} is out of range (the clip has {count} frames)"))
                    })
                })
                .collect(),
        }
    }

    fn joints(&self) -> &[Joint] {
        self.clip.skeleton().joints()
    }
}

#[pymethods]
impl Clip {
    /// The file name it was read from.
    #[getter]
    fn name(&self) -> &str {
        &self.name
    }

    /// Joint names, End Sites included (parents before children).
    #[getter]
    fn joint_names(&self) -> Vec<String> {
        self.joints().iter().map(|j| j.name.clone()).collect()
    }

    /// Each joint's parent index (`-1` for a root), int32.
    #[getter]
    fn parents<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<i32>> {
        self.joints().iter().map(|j| j.parent.map_or(-1, |p| p as i32)).collect::<Vec<_>>().into_pyarray(py)
    }

    /// Whether each joint is an End Site.
    #[getter]
    fn end_sites(&self) -> Vec<bool> {
        self.joints().iter().map(Joint::is_end_site).collect()
    }

    /// Rest offsets from the parent (J×3, file units).
    #[getter]
    fn offsets<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f32>> {
        let data: Vec<f32> = self.joints().iter().flat_map(|j| j.offset.to_array()).collect();
        Array2::from_shape_vec((self.joints().len(), 3), data).unwrap_or_default().into_pyarray(py)
    }

    /// Each joint's channel names in file order (`Xposition`, `Zrotation`, …).
    #[getter]
    fn channels(&self) -> Vec<Vec<String>> {
        self.joints().iter().map(|j| j.channels.iter().map(|c| c.to_string()).collect()).collect()
    }

    /// Seconds between frames.
    #[getter]
    fn frame_time(&self) -> f64 {
        self.clip.frame_time()
    }

    /// Number of frames.
    #[getter]
    fn frame_count(&self) -> usize {
        self.clip.frame_count()
    }

    /// Seconds from the first frame to the last.
    #[getter]
    fn duration(&self) -> f64 {
        self.clip.duration()
    }

    /// The guessed length unit (`cm`, `m`, `inch`, …) of the file's numbers.
    #[getter]
    fn units(&self) -> &'static str {
        self.clip.units().name()
    }

    /// Metres per file unit (by the guessed unit).
    #[getter]
    fn meters_per_unit(&self) -> f32 {
        self.clip.units().meters_per_unit()
    }

    /// The guessed up axis, `y` or `z`.
    #[getter]
    fn up_axis(&self) -> &'static str {
        self.clip.up_axis().name()
    }

    /// The file's channel values (F×C float32, one row per frame, degrees for rotations).
    #[getter]
    fn values<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f32>> {
        let (f, c) = (self.clip.frame_count(), self.clip.skeleton().channel_count());
        Array2::from_shape_vec((f, c), self.clip.motion().data().to_vec()).unwrap_or_default().into_pyarray(py)
    }

    /// Local rotations (F×J×4 quaternions, x y z w) per frame.
    fn local_rotations<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray3<f32>> {
        let clip = &self.clip;
        let j = clip.skeleton().len();
        let data = py.detach(|| {
            let mut pose = LocalPose::rest(clip.skeleton());
            let mut out = Vec::with_capacity(clip.frame_count() * j * 4);
            for f in 0..clip.frame_count() {
                clip.local_pose_into(f, &mut pose);
                out.extend(pose.rotation.iter().flat_map(|q| q.to_array()));
            }
            out
        });
        Array3::from_shape_vec((self.clip.frame_count(), j, 4), data).unwrap_or_default().into_pyarray(py)
    }

    /// Local translations (F×J×3, file units) per frame.
    fn local_translations<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray3<f32>> {
        let clip = &self.clip;
        let j = clip.skeleton().len();
        let data = py.detach(|| {
            let mut pose = LocalPose::rest(clip.skeleton());
            let mut out = Vec::with_capacity(clip.frame_count() * j * 3);
            for f in 0..clip.frame_count() {
                clip.local_pose_into(f, &mut pose);
                out.extend(pose.translation.iter().flat_map(|v| v.to_array()));
            }
            out
        });
        Array3::from_shape_vec((self.clip.frame_count(), j, 3), data).unwrap_or_default().into_pyarray(py)
    }

    /// World positions of every joint, End Sites included (F×J×3 float32) at
    /// `frames` (all by default; negative counts from the end), in the file's
    /// units or `units="m"` for metres.
    #[pyo3(signature = (frames=None, *, units=None))]
    fn world_positions<'py>(
        &self,
        py: Python<'py>,
        frames: Option<Vec<i64>>,
        units: Option<&str>,
    ) -> PyResult<Bound<'py, PyArray3<f32>>> {
        let scale = match units {
            None | Some("file") => 1.0,
            Some("m") => self.clip.units().meters_per_unit(),
            Some(other) => return Err(PyValueError::new_err(format!("units={other}: expected None, 'file' or 'm'"))),
        };
        let frames = self.frames(frames)?;
        let clip = &self.clip;
        let j = clip.skeleton().len();
        let data = py.detach(|| {
            let mut out = Vec::with_capacity(frames.len() * j * 3);
            let mut scratch = Vec::new();
            for &f in &frames {
                clip.world_positions_into(f, &mut scratch);
                out.extend(scratch.iter().flat_map(|p| (*p * scale).to_array()));
            }
            out
        });
        Ok(Array3::from_shape_vec((frames.len(), j, 3), data).unwrap_or_default().into_pyarray(py))
    }

    /// World positions at `times` in seconds (T×J×3 float32), sampled between
    /// frames by `interpolation`: `"nearest"`, `"linear"` (default) or
    /// `"cubic"` (Catmull-Rom positions, squad rotations: through every frame,
    /// smooth across them); file units or `units="m"`.
    #[pyo3(signature = (times, *, interpolation="linear", units=None))]
    fn positions_at<'py>(
        &self,
        py: Python<'py>,
        times: Vec<f64>,
        interpolation: &str,
        units: Option<&str>,
    ) -> PyResult<Bound<'py, PyArray3<f32>>> {
        let between = mocap::Interpolation::from_name(interpolation)
            .filter(|i| *i != mocap::Interpolation::Step)
            .ok_or_else(|| PyValueError::new_err(format!("interpolation={interpolation}: expected 'nearest', 'linear' or 'cubic'")))?;
        let scale = match units {
            None | Some("file") => 1.0,
            Some("m") => self.clip.units().meters_per_unit(),
            Some(other) => return Err(PyValueError::new_err(format!("units={other}: expected None, 'file' or 'm'"))),
        };
        let clip = &self.clip;
        let j = clip.skeleton().len();
        let data = py.detach(|| {
            let mut out = Vec::with_capacity(times.len() * j * 3);
            let mut scratch = Vec::new();
            for &t in &times {
                clip.sample_world_positions_into(t, between, &mut scratch);
                out.extend(scratch.iter().flat_map(|p| (*p * scale).to_array()));
            }
            out
        });
        Ok(Array3::from_shape_vec((times.len(), j, 3), data).unwrap_or_default().into_pyarray(py))
    }

    /// World rotations of every joint (F×J×4 quaternions, x y z w) at `frames`.
    #[pyo3(signature = (frames=None))]
    fn world_rotations<'py>(&self, py: Python<'py>, frames: Option<Vec<i64>>) -> PyResult<Bound<'py, PyArray3<f32>>> {
        let frames = self.frames(frames)?;
        let clip = &self.clip;
        let j = clip.skeleton().len();
        let data = py.detach(|| {
            let mut out = Vec::with_capacity(frames.len() * j * 4);
            let mut scratch = Vec::new();
            for &f in &frames {
                clip.world_transforms_into(f, &mut scratch);
                out.extend(scratch.iter().flat_map(|t| t.rotation.to_array()));
            }
            out
        });
        Ok(Array3::from_shape_vec((frames.len(), j, 4), data).unwrap_or_default().into_pyarray(py))
    }

    /// The clip edited as the CLI's and the page's edit strings say
    /// (`"trim:10:50"`, `"fps:30"`, `"reverse"`, …), several separated by `,`
    /// or given as a list; a new Clip.
    fn edit(&self, py: Python<'_>, specs: &Bound<'_, PyAny>) -> PyResult<Clip> {
        let list: Vec<String> = match specs.extract::<String>() {
            Ok(one) => one.split(',').map(|s| s.trim().to_string()).filter(|s| !s.is_empty()).collect(),
            Err(_) => specs.extract()?,
        };
        let parsed = list
            .iter()
            .map(|s| s.parse::<mocap::ops::edit::EditSpec>().map_err(|e| PyValueError::new_err(format!("{s}: {e}"))))
            .collect::<PyResult<Vec<_>>>()?;
        let clip = py.detach(|| {
            let mut clip = self.clip.clone();
            for spec in &parsed {
                let edit = spec.resolve(&clip);
                clip = mocap::ops::edit::apply(&clip, &edit).map_err(|e| e.to_string())?;
            }
            Ok::<_, String>(clip)
        });
        Ok(Clip { clip: clip.map_err(PyValueError::new_err)?, name: self.name.clone() })
    }

    /// This motion on another skeleton (a Clip, or a path read as one):
    /// joints matched by name, then by the shape of the tree; `map` gives
    /// `{target_joint: source_joint}` pairs first.
    #[pyo3(signature = (target, *, map=None))]
    fn retarget(&self, py: Python<'_>, target: &Bound<'_, PyAny>, map: Option<Vec<(String, String)>>) -> PyResult<Clip> {
        let target_clip = match target.cast::<Clip>() {
            Ok(c) => c.get().clip.clone(),
            Err(_) => read(py, target, None, None, None)?.clip,
        };
        let options = mocap::ops::retarget::Options { map: map.unwrap_or_default(), ..Default::default() };
        let out = py.detach(|| mocap::ops::retarget::retarget(&self.clip, &target_clip, &options));
        let (clip, _) = out.map_err(|e| PyValueError::new_err(e.to_string()))?;
        Ok(Clip { clip, name: self.name.clone() })
    }

    /// This take against `other` (a Clip or a path), sampled at this one's
    /// frame times, both in metres with Y up: `{mpjpe, mpjpe_m, worst_frame,
    /// joints: [{name, mean, max, angle}], frames}` (`mpjpe`, joint errors and
    /// `frames` (a float32 array) in this clip's file units; `angle` in degrees
    /// where the skeletons are the same, else None). `align`: `"none"`,
    /// `"root"` or `"procrustes"`; `map` gives `(this_joint, other_joint)` pairs.
    #[pyo3(signature = (other, *, align="none", map=None))]
    fn compare<'py>(
        &self,
        py: Python<'py>,
        other: &Bound<'py, PyAny>,
        align: &str,
        map: Option<Vec<(String, String)>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        use mocap::ops::compare::Align;
        let align = Align::from_name(align).ok_or_else(|| PyValueError::new_err(format!("align={align}: expected 'none', 'root', 'procrustes', 'root-once' or 'procrustes-once'")))?;
        let other_clip = match other.cast::<Clip>() {
            Ok(c) => c.get().clip.clone(),
            Err(_) => read(py, other, None, None, None)?.clip,
        };
        let map = map.unwrap_or_default();
        let report = py
            .detach(|| mocap::ops::compare::compare(&self.clip, &other_clip, align, &map))
            .map_err(|e| PyValueError::new_err(e.to_string()))?;
        let d = PyDict::new(py);
        d.set_item("mpjpe", report.mpjpe)?;
        d.set_item("mpjpe_m", report.mpjpe_m)?;
        d.set_item("worst_frame", report.worst_frame)?;
        let joints = PyList::empty(py);
        for j in &report.joints {
            let item = PyDict::new(py);
            item.set_item("name", &j.name)?;
            item.set_item("mean", j.mean)?;
            item.set_item("max", j.max)?;
            item.set_item("angle", j.angle)?;
            joints.append(item)?;
        }
        d.set_item("joints", joints)?;
        d.set_item("frames", report.frames.into_pyarray(py))?;
        Ok(d)
    }

    /// Writes the clip as BVH (every edit baked in).
    fn write_bvh(&self, py: Python<'_>, path: PathBuf) -> PyResult<()> {
        let text = py.detach(|| mocap::formats::bvh::write(&self.clip));
        std::fs::write(&path, text).map_err(|e| PyValueError::new_err(format!("{}: {e}", path.display())))
    }

    /// The clip as BVH text.
    fn to_bvh(&self, py: Python<'_>) -> String {
        py.detach(|| mocap::formats::bvh::write(&self.clip))
    }

    /// Writes the clip as binary glTF: joints, a skinned body, the animation, metres, Y up.
    fn write_glb(&self, py: Python<'_>, path: PathBuf) -> PyResult<()> {
        let bytes = py
            .detach(|| mocap::formats::gltf::write::to_glb(&self.clip, &Default::default()))
            .map_err(|e| PyValueError::new_err(e.to_string()))?;
        std::fs::write(&path, bytes).map_err(|e| PyValueError::new_err(format!("{}: {e}", path.display())))
    }

    /// `{joint_names, parents, offsets, channels, values, frame_time}`: what
    /// `mocap.from_arrays(**d)` takes back.
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        d.set_item("joint_names", self.joint_names())?;
        d.set_item("parents", self.parents(py))?;
        d.set_item("offsets", self.offsets(py))?;
        d.set_item("channels", PyList::new(py, self.channels())?)?;
        d.set_item("values", self.values(py))?;
        d.set_item("frame_time", self.frame_time())?;
        Ok(d)
    }

    fn __reduce__<'py>(&self, py: Python<'py>) -> PyResult<(Bound<'py, PyAny>, (Bound<'py, PyBytes>, String))> {
        let bytes = py.detach(|| mocap::formats::store::write(&Asset::Clip(self.clip.clone())));
        let f = py.import("mocap._mocap")?.getattr("_from_store")?;
        Ok((f, (PyBytes::new(py, &bytes), self.name.clone())))
    }

    fn __len__(&self) -> usize {
        self.clip.frame_count()
    }

    fn __repr__(&self) -> String {
        format!(
            "<mocap.Clip {:?}: {} joints, {} frames at {:.2} fps, {}, {}-up>",
            self.name,
            self.clip.skeleton().len(),
            self.clip.frame_count(),
            self.clip.fps(),
            self.clip.units().name(),
            self.clip.up_axis().name()
        )
    }
}

fn batch_task(to: Option<&str>, out: Option<PathBuf>) -> PyResult<mocap_files::batch::Task> {
    use mocap_files::batch::Task;
    let need = |out: Option<PathBuf>| out.ok_or_else(|| PyValueError::new_err("to='bvh' or 'glb' needs out="));
    match to {
        None | Some("validate") => Ok(Task::Validate),
        Some("json") => Ok(Task::Summary),
        Some("bvh") => Ok(Task::Bvh(need(out)?)),
        Some("glb") => Ok(Task::Glb(need(out)?)),
        Some(other) => Err(PyValueError::new_err(format!("to={other}: expected None, 'json', 'bvh' or 'glb'"))),
    }
}

/// The manifest line of one file (`to` as in `batch`), as JSON text: what
/// `mocap batch` writes for it; never raises for a bad file.
#[pyfunction]
#[pyo3(signature = (path, *, to=Some("json".to_string()), out=None, root=None))]
fn _run_one(py: Python<'_>, path: PathBuf, to: Option<String>, out: Option<PathBuf>, root: Option<PathBuf>) -> PyResult<String> {
    let task = batch_task(to.as_deref(), out)?;
    let root = root.unwrap_or_else(|| path.parent().map(PathBuf::from).unwrap_or_default());
    Ok(py.detach(|| mocap_files::batch::run_one(&path, &root, &task).to_string()))
}

/// `mocap batch` over `files` (outputs relative to `root`), as JSON lines.
#[pyfunction]
#[pyo3(signature = (files, root, *, to=None, out=None, manifest=None, jobs=None))]
fn _batch(
    py: Python<'_>,
    files: Vec<PathBuf>,
    root: PathBuf,
    to: Option<String>,
    out: Option<PathBuf>,
    manifest: Option<PathBuf>,
    jobs: Option<usize>,
) -> PyResult<Vec<String>> {
    let task = batch_task(to.as_deref(), out)?;
    let jobs = jobs.unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()));
    let lines = py
        .detach(|| mocap_files::batch::run(&files, &root, &task, manifest.as_deref(), jobs.max(1), &|_, _| {}))
        .map_err(PyValueError::new_err)?;
    Ok(lines.iter().map(|l| l.to_string()).collect())
}

/// Every motion file under a folder (recursively, sorted), as `mocap batch` walks it.
#[pyfunction]
fn motion_files(root: PathBuf) -> Vec<PathBuf> {
    mocap_files::batch::motion_files(&root)
}

/// The compiled half of the `mocap` package.
#[pymodule]
fn _mocap(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("ParseError", m.py().get_type::<ParseError>())?;
    m.add_class::<Clip>()?;
    m.add_function(wrap_pyfunction!(read, m)?)?;
    m.add_function(wrap_pyfunction!(read_many, m)?)?;
    m.add_function(wrap_pyfunction!(from_arrays, m)?)?;
    m.add_function(wrap_pyfunction!(_from_store, m)?)?;
    m.add_function(wrap_pyfunction!(_run_one, m)?)?;
    m.add_function(wrap_pyfunction!(_batch, m)?)?;
    m.add_function(wrap_pyfunction!(motion_files, m)?)?;
    Ok(())
}
