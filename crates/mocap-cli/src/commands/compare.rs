//! `mocap compare`: two takes measured against each other ([`mocap::ops::compare`]).

use super::*;
use mocap::ops::compare::{Align, Report};

/// Runs `mocap compare A B`: a table, or JSON with `--json`.
pub fn compare(a: &Path, b: &Path, align: &str, map: Option<&Path>, as_json: bool) -> Result<ExitCode, String> {
    let align = Align::from_name(align).ok_or_else(|| format!("--align {align}: expected none, root, procrustes, root-once or procrustes-once"))?;
    let first = read_clip(&[a.to_path_buf()])?;
    let second = read_clip(&[b.to_path_buf()])?;
    let map = match map {
        Some(path) => super::retarget::read_map(path)?,
        None => Vec::new(),
    };
    let report = mocap::ops::compare::compare(&first, &second, align, &map)
        .map_err(|e| format!("{} against {}: {e}", b.display(), a.display()))?;
    let mut out = std::io::stdout().lock();
    let written = if as_json {
        writeln!(out, "{}", to_json(&report))
    } else {
        write_table(&mut out, &report, first.units().name())
    };
    written.map_err(|e| format!("stdout: {e}"))?;
    Ok(ExitCode::SUCCESS)
}

fn to_json(r: &Report) -> Value {
    let joints: Vec<Value> = r
        .joints
        .iter()
        .map(|j| json!({"name": j.name, "mean": num(j.mean), "max": num(j.max), "angle": j.angle.map_or(Value::Null, num)}))
        .collect();
    json!({
        "mpjpe": num(r.mpjpe),
        "mpjpe_m": num(r.mpjpe_m),
        "worst_frame": r.worst_frame,
        "joints": joints,
        "frames": r.frames.iter().map(|f| num(*f)).collect::<Vec<_>>(),
    })
}

fn write_table(out: &mut impl Write, r: &Report, units: &str) -> std::io::Result<()> {
    writeln!(out, "MPJPE {:.4} {units} ({:.4} m); worst frame {}", r.mpjpe, r.mpjpe_m, r.worst_frame)?;
    writeln!(out, "{:<24} {:>10} {:>10} {:>9}", "joint", "mean", "max", "angle °")?;
    for j in &r.joints {
        let angle = j.angle.map_or("-".to_string(), |a| format!("{a:.2}"));
        writeln!(out, "{:<24} {:>10.4} {:>10.4} {:>9}", j.name, j.mean, j.max, angle)?;
    }
    Ok(())
}
