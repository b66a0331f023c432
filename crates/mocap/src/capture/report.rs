//! What a capture says about each joint: its tracked vertices, residuals,
//! convergence and agreement with the closed form.

use super::track;

/// What happened to one joint.
#[derive(Clone, Debug, PartialEq)]
pub struct JointReport {
    /// The joint's name.
    pub name: String,
    /// The four tracked vertices and the bone they are bound to, or why the joint has none.
    pub tracked: Result<track::JointSet, String>,
    /// Largest distance from the solved joint to one of its spheres (mesh units).
    pub max_residual: f64,
    /// Mean over frames of that distance.
    pub mean_residual: f64,
    /// Frames where successive approximation did not converge, with why.
    pub failures: Vec<(usize, String)>,
    /// Largest distance between the successive and the closed-form answers.
    pub max_disagreement: f64,
    /// Frame of that largest disagreement.
    pub disagreement_frame: usize,
    /// Whether the bone leaving this joint has a tracked spin.
    pub spin: bool,
}

/// The capture's report.
#[derive(Clone, Debug, PartialEq)]
pub struct Report {
    /// Per joint, in rig order.
    pub joints: Vec<JointReport>,
    /// The model's height (mesh units), the scale of the tolerances.
    pub height: f32,
}

impl Report {
    /// A plain-text table: per joint its vertices, residuals, convergence and
    /// agreement with the closed form.
    pub fn text(&self) -> String {
        let mut out = format!(
            "{:<16} {:<24} {:>10} {:>10} {:>8} {:>12}  spin\n",
            "joint", "vertices (bone)", "max resid", "mean", "failed", "vs closed"
        );
        for j in &self.joints {
            let tracked = match &j.tracked {
                Ok(s) => format!("{:?} ({})", s.vertices, s.bone),
                Err(_) => "none".to_owned(),
            };
            out.push_str(&format!(
                "{:<16} {:<24} {:>10.4} {:>10.4} {:>8} {:>12.4}  {}\n",
                j.name,
                tracked,
                j.max_residual,
                j.mean_residual,
                j.failures.len(),
                j.max_disagreement,
                if j.spin { "yes" } else { "no" }
            ));
        }
        for j in &self.joints {
            if let Err(why) = &j.tracked {
                out.push_str(&format!("no vertex set: {why}\n"));
            }
            if let Some((f, why)) = j.failures.first() {
                out.push_str(&format!(
                    "{}: frame {f} did not converge ({why}){}\n",
                    j.name,
                    if j.failures.len() > 1 {
                        format!(" and {} more frames", j.failures.len() - 1)
                    } else {
                        String::new()
                    }
                ));
            }
        }
        out
    }
}
