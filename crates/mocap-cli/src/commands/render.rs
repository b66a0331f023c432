//! `mocap render`: stills, frame sequences and contact sheets as PNG.

use super::*;

/// What `mocap render` produces.
pub enum Shot {
    /// One frame (in the first clip's frame time).
    Frame(usize),
    /// One time in seconds.
    Time(f64),
    /// `a:b:step` frames into a directory.
    Sequence(String),
    /// A contact sheet with this many columns.
    Sheet(u32),
    /// A video (`out` is an .mp4, .webm or .gif file).
    Video(super::video::VideoRequest),
}

/// Parses `a:b[:step]` (end inclusive).
fn parse_range(text: &str) -> Result<(usize, usize, usize), String> {
    let parts: Vec<Option<usize>> = text.split(':').map(|p| p.trim().parse().ok()).collect();
    let (a, b, step) = match parts.as_slice() {
        [Some(a), Some(b)] => (*a, *b, 1),
        [Some(a), Some(b), Some(s)] => (*a, *b, *s),
        _ => return Err(format!("--frames: expected a:b or a:b:step, found `{text}`")),
    };
    if step == 0 || b < a {
        return Err(format!("--frames {text}: need a <= b and step >= 1"));
    }
    Ok((a, b, step))
}

/// What `mocap render` draws besides the files: how, from where, and which
/// model animation.
pub struct RenderOptions<'a> {
    /// Draw mode name (`capsules`, `sticks`).
    pub mode: &'a str,
    /// Camera `yaw,pitch[,distance]`.
    pub camera: Option<&'a str>,
    /// Animation the models play (`all` for every frame).
    pub animation: Option<&'a str>,
    /// The up axis of every clip (`y` or `z`; guessed per clip when absent).
    pub up: Option<&'a str>,
    /// Sampling between frames: `nearest`, `linear` (default) or `cubic`.
    pub interpolation: Option<&'a str>,
    /// The joint whose path is drawn (`--trail`).
    pub trail: Option<&'a str>,
}

/// `--interpolation NAME`.
pub(super) fn interpolation(name: &str) -> Result<mocap::Interpolation, String> {
    mocap::Interpolation::from_name(name)
        .filter(|i| *i != mocap::Interpolation::Step)
        .ok_or_else(|| format!("--interpolation {name}: expected nearest, linear or cubic"))
}

/// The stage `files` make, drawn and played as `options` say, and the orbit
/// the camera takes (shared by stills, sequences, sheets and videos).
pub(super) fn prepare(
    files: &[PathBuf],
    options: &RenderOptions,
) -> Result<(crate::render::StageView, crate::render::Orbit), String> {
    let mode = options.mode;
    let mode = mocap_render::DrawMode::from_name(mode)
        .ok_or_else(|| format!("--mode {mode}: expected `capsules`, `sticks` or `body`"))?;
    let orbit = options.camera.map(crate::render::parse_orbit).transpose()?.unwrap_or_default();
    let assets = read_set(files)?.into_iter().map(|l| (l.name, l.asset)).collect();
    let mut stage = crate::render::StageView::new(assets).with_mode(mode);
    if let Some(name) = options.up {
        let up = mocap::UpAxis::from_name(name).ok_or_else(|| format!("--up: expected y or z, found `{name}`"))?;
        stage.set_up_axis(up);
    }
    if let Some(name) = options.trail {
        if !stage.set_trail(name) {
            return Err(format!("--trail {name}: no clip in {} has that joint", shown(files)));
        }
    }
    if let Some(name) = options.interpolation {
        stage.set_interpolation(interpolation(name)?);
    }
    if let Some(name) = options.animation {
        if !stage.set_animation(name) {
            return Err(format!("--animation {name}: no model in {} has that animation", shown(files)));
        }
    }
    Ok((stage, orbit))
}

/// `mocap render`: `files` may hold models with their skins (`--skin` files are
/// added to the set).
pub fn render(
    files: &[PathBuf],
    shot: Shot,
    out: &Path,
    size: &str,
    options: &RenderOptions,
) -> Result<ExitCode, String> {
    let size = crate::render::parse_size(size)?;
    let (stage, orbit) = prepare(files, options)?;
    let gpu = crate::render::Gpu::new()?;
    let mut scene = mocap_render::Scene::default();
    let timeline = stage.timeline();
    match shot {
        Shot::Frame(_) | Shot::Time(_) => {
            let time = match shot {
                Shot::Time(t) if t.is_finite() => t.max(0.0),
                Shot::Time(_) => return Err("--time must be a number of seconds".into()),
                Shot::Frame(f) if f < timeline.frames().max(1) => timeline.time_of(f),
                Shot::Frame(f) => {
                    return Err(format!("frame {f} is out of range (the clip has {} frames)", timeline.frames()));
                }
                _ => 0.0,
            };
            let mut offscreen = crate::render::Offscreen::new(&gpu, size);
            stage.scene_at(time, &mut scene);
            let pixels = offscreen.draw(&gpu, &scene, &stage.camera(orbit, offscreen.size()))?;
            crate::render::write_png(out, offscreen.size(), &pixels)?;
        }
        Shot::Sequence(range) => {
            let (a, b, step) = parse_range(&range)?;
            let last = timeline.last();
            if a > last {
                return Err(format!("--frames {range}: the clip has {} frames", timeline.frames()));
            }
            std::fs::create_dir_all(out).map_err(|e| format!("{}: cannot create: {e}", out.display()))?;
            let mut offscreen = crate::render::Offscreen::new(&gpu, size);
            let camera = stage.camera(orbit, offscreen.size());
            for frame in (a..=b.min(last)).step_by(step) {
                stage.scene_at(timeline.time_of(frame), &mut scene);
                let pixels = offscreen.draw(&gpu, &scene, &camera)?;
                crate::render::write_png(&out.join(format!("frame_{frame:05}.png")), offscreen.size(), &pixels)?;
            }
        }
        Shot::Video(request) => super::video::video(&gpu, &stage, orbit, size, out, &request)?,
        Shot::Sheet(columns) => {
            let mut sheet = Sheet::new(&gpu, size, columns);
            sheet.write(&gpu, &stage, orbit, out)?;
        }
    }
    Ok(ExitCode::SUCCESS)
}

/// A contact sheet: `columns` x rows tiles of evenly spaced times over the whole
/// stage (rows follow from a 16:9 tile in the sheet's size), drawn offscreen.
pub struct Sheet {
    offscreen: crate::render::Offscreen,
    columns: u32,
    rows: u32,
}

impl Sheet {
    /// A sheet of about `size` pixels with `columns` columns (1 to 16).
    pub fn new(gpu: &crate::render::Gpu, size: [u32; 2], columns: u32) -> Sheet {
        let columns = columns.clamp(1, 16);
        let tile_w = (size[0] / columns).max(16);
        let rows = ((size[1] as f32 / (tile_w as f32 * 9.0 / 16.0)).floor() as u32).clamp(1, 16);
        let tile = [tile_w, (size[1] / rows).max(16)];
        Sheet { offscreen: crate::render::Offscreen::new(gpu, tile), columns, rows }
    }

    /// Draws `stage`'s sheet from `orbit` and writes it as the PNG `out`.
    pub fn write(
        &mut self,
        gpu: &crate::render::Gpu,
        stage: &crate::render::StageView,
        orbit: crate::render::Orbit,
        out: &Path,
    ) -> Result<(), String> {
        let tile = self.offscreen.size();
        let camera = stage.camera(orbit, tile);
        let count = (self.columns * self.rows) as usize;
        let sheet_size = [tile[0] * self.columns, tile[1] * self.rows];
        let mut sheet = vec![0u8; (sheet_size[0] * sheet_size[1] * 4) as usize];
        let mut scene = mocap_render::Scene::default();
        for n in 0..count {
            let time = if count > 1 { stage.duration() * n as f64 / (count - 1) as f64 } else { 0.0 };
            stage.scene_at(time, &mut scene);
            let pixels = self.offscreen.draw(gpu, &scene, &camera)?;
            let (x, y) = ((n as u32 % self.columns) * tile[0], (n as u32 / self.columns) * tile[1]);
            crate::render::blit(&mut sheet, sheet_size[0], &pixels, tile, x, y);
        }
        crate::render::write_png(out, sheet_size, &sheet)
    }
}
