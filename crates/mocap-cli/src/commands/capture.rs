//! `mocap capture` and `mocap ik`: skeletal motion captured from a model, and IK on a clip.

use super::*;

/// What `mocap capture` is asked.
pub struct CaptureRequest<'a> {
    /// The MD2 model.
    pub model: &'a Path,
    /// A rig file, else the automatic fit.
    pub rig: Option<&'a Path>,
    /// A motion file whose skeleton is fitted (without a rig).
    pub skeleton: Option<&'a Path>,
    /// Only this animation.
    pub animation: Option<&'a str>,
    /// One BVH per animation too.
    pub split: bool,
    /// Vertices per joint.
    pub vertices: usize,
    /// Stored vertex places, not their rigid parts' best fit.
    pub raw_vertices: bool,
    /// Where to save the rig used.
    pub save_rig: Option<&'a Path>,
    /// Where to write the per-frame layout.
    pub frames_out: Option<&'a Path>,
    /// The BVH to write.
    pub output: &'a Path,
}

/// `mocap capture`: skeletal motion from an MD2 model's vertex animation.
pub fn capture(request: &CaptureRequest) -> Result<ExitCode, String> {
    let output = request.output;
    if output.extension().and_then(|e| e.to_str()).is_none_or(|e| !e.eq_ignore_ascii_case("bvh")) {
        return Err(format!("{}: capture writes .bvh files", output.display()));
    }
    let model_path = request.model;
    let bytes = std::fs::read(model_path).map_err(|e| format!("{}: cannot read: {e}", model_path.display()))?;
    let md2 = mocap::formats::md2::parse(&bytes)
        .map_err(|e| format!("{}:{}:{}: {}", model_path.display(), e.line, e.column, e.message))?;
    use mocap::capture::{Capturer, RigChoice};
    let given = match request.rig {
        Some(path) => {
            let text = std::fs::read_to_string(path).map_err(|e| format!("{}: cannot read: {e}", path.display()))?;
            Some(mocap::capture::Rig::from_json(&text).map_err(|e| format!("{}: {e}", path.display()))?)
        }
        None => None,
    };
    let template = match (&given, request.skeleton) {
        (None, Some(path)) => {
            let clip = read_clip(&[path.to_path_buf()])?;
            let mut model = Vec::new();
            mocap::local_to_model(clip.skeleton(), &mocap::LocalPose::rest(clip.skeleton()), &mut model);
            Some((clip, model))
        }
        _ => None,
    };
    let choice = match (&given, &template) {
        (Some(rig), _) => RigChoice::Given(rig),
        (None, t) => RigChoice::Fit(t.as_ref().map(|(clip, model)| (clip.skeleton(), model.as_slice()))),
    };
    let options = mocap::capture::Options {
        vertices_per_joint: request.vertices.max(4),
        average_shapes: !request.raw_vertices,
        ..mocap::capture::Options::default()
    };
    let started = std::time::Instant::now();
    let capturer = Capturer::new(&md2, choice, &options).map_err(|e| format!("{}: {e}", model_path.display()))?;
    if let Some(path) = request.save_rig {
        std::fs::write(path, capturer.rig().to_json()).map_err(|e| format!("{}: cannot write: {e}", path.display()))?;
    }
    let cap = capturer.finish().map_err(|e| format!("{}: {e}", model_path.display()))?;
    print!("{}", cap.report.text());
    println!(
        "{}: {} frames, {} joints ({} tracked) in {:.0} ms; animations: {}",
        model_path.display(),
        md2.frames.len(),
        cap.report.joints.len(),
        cap.report.joints.iter().filter(|j| j.tracked.is_ok()).count(),
        started.elapsed().as_secs_f64() * 1000.0,
        cap.animations.iter().map(|a| format!("{} {}–{}", a.name, a.first, a.last)).collect::<Vec<_>>().join(", ")
    );
    let clip = match request.animation {
        Some(name) => cap.animation_clip(name).ok_or_else(|| {
            format!(
                "--animation {name}: {} has {}",
                model_path.display(),
                cap.animations.iter().map(|a| a.name.as_str()).collect::<Vec<_>>().join(", ")
            )
        })?,
        None => cap.clip.clone(),
    };
    std::fs::write(output, mocap::formats::bvh::write(&clip))
        .map_err(|e| format!("{}: cannot write: {e}", output.display()))?;
    if request.split {
        let stem = output.file_stem().and_then(|s| s.to_str()).unwrap_or("capture");
        for a in &cap.animations {
            let Some(part) = cap.animation_clip(&a.name) else { continue };
            let path = output.with_file_name(format!("{stem}-{}.bvh", a.name));
            std::fs::write(&path, mocap::formats::bvh::write(&part))
                .map_err(|e| format!("{}: cannot write: {e}", path.display()))?;
        }
    }
    if let Some(path) = request.frames_out {
        std::fs::write(path, mocap::capture::frames::write(&cap.frames()))
            .map_err(|e| format!("{}: cannot write: {e}", path.display()))?;
    }
    Ok(ExitCode::SUCCESS)
}

/// What `mocap ik` is asked.
pub struct IkRequest<'a> {
    /// The effector's name.
    pub joint: &'a str,
    /// `x,y,z`.
    pub target: &'a str,
    /// Frame index.
    pub frame: usize,
    /// Bones above the effector.
    pub bones: Option<usize>,
    /// Solver name.
    pub solver: Option<&'a str>,
}

/// `mocap ik`: the pose at a frame, its chain solved toward a target.
pub fn ik(paths: &[PathBuf], request: &IkRequest) -> Result<ExitCode, String> {
    let clip = read_clip(paths)?;
    let skeleton = clip.skeleton();
    if request.frame >= clip.frame_count().max(1) {
        return Err(format!(
            "{}: frame {} is out of range (the clip has {} frames)",
            shown(paths),
            request.frame,
            clip.frame_count()
        ));
    }
    let effector =
        skeleton.find(request.joint).ok_or_else(|| format!("{}: no joint named `{}`", shown(paths), request.joint))?;
    let xyz: Vec<f32> = request
        .target
        .split(',')
        .map(|v| v.trim().parse::<f32>())
        .collect::<Result<_, _>>()
        .map_err(|_| format!("--target {}: expected x,y,z (numbers)", request.target))?;
    let target = match xyz.as_slice() {
        &[x, y, z] if xyz.iter().all(|v| v.is_finite()) => mocap::glam::Vec3::new(x, y, z),
        _ => return Err(format!("--target {}: expected x,y,z (three finite numbers)", request.target)),
    };
    let chain = match request.bones {
        Some(bones) => mocap::runtime::ik::Chain::up_from(skeleton, effector, bones.max(1)),
        None => mocap::runtime::ik::Chain::for_joint(skeleton, effector),
    }
    .map_err(|e| e.to_string())?;
    let solver = request.solver.unwrap_or(if chain.joints().len() == 3 { "two-bone" } else { "fabrik" });
    let mut pose = mocap::LocalPose::default();
    clip.local_pose_into(request.frame, &mut pose);
    // Within a ten-thousandth of the chain's length, with passes to spare (CCD
    // converges slowly on some chains; the others stop as soon as they are there).
    let length = chain.rest_length(skeleton);
    let options = mocap::runtime::ik::Options {
        angle_unit: clip.motion().angle_unit(),
        iterations: 2000,
        tolerance: 1e-4 * length.max(1e-6),
        ..Default::default()
    };
    let result = match solver {
        "two-bone" if chain.joints().len() == 3 => {
            // Bend toward where the middle joint points now (keeps the knee forward).
            let mid = mocap::runtime::ik::model_transform(skeleton, &pose, chain.joints()[1]).translation;
            let root = mocap::runtime::ik::model_transform(skeleton, &pose, chain.root()).translation;
            mocap::runtime::ik::two_bone(skeleton, &mut pose, &chain, target, mid + (mid - root), &options)
        }
        "two-bone" => {
            return Err(format!(
                "--solver two-bone needs a chain of two bones (this one has {})",
                chain.joints().len() - 1
            ));
        }
        "ccd" => mocap::runtime::ik::ccd(skeleton, &mut pose, &chain, target, &options),
        "fabrik" => mocap::runtime::ik::fabrik(skeleton, &mut pose, &chain, target, &options),
        other => return Err(format!("--solver {other}: expected two-bone, ccd or fabrik")),
    };
    let mut model = Vec::new();
    mocap::local_to_model(skeleton, &pose, &mut model);
    let name = |j: usize| skeleton.joints().get(j).map_or(String::new(), |x| x.name.clone());
    let joints: Vec<Value> = skeleton
        .joints()
        .iter()
        .zip(&model)
        .map(|(j, t)| json!({ "name": j.name, "parent": j.parent, "end_site": j.is_end_site(), "position": vec3(t.translation) }))
        .collect();
    print_json(&json!({
        "frame": request.frame,
        "time": clip.timeline().time_of(request.frame),
        "joint": request.joint,
        "target": vec3(target),
        "solver": solver,
        "chain": chain.joints().iter().map(|&j| name(j)).collect::<Vec<_>>(),
        "reached": result.reached,
        "distance": num(result.distance),
        "joints": joints,
    }))
}
