//! Comparing two takes ([`compare`]): a prediction against ground truth, two
//! captures of one move. Clip `b` is sampled at clip `a`'s frame times; both
//! are measured in metres with Y up (each by its own unit and up axis), joints
//! paired by index on the same skeleton, else by the retargeting name map
//! ([`crate::ops::retarget::map_joints`]); End Sites are left out. Errors come
//! back in `a`'s file units and in metres.
//!
//! Inputs: two clips, an [`Align`] rule and explicit joint pairs. Output: a
//! [`Report`] (MPJPE, per-joint mean and max, per-frame error, per-joint angle
//! differences). Flat arrays, one pass over the frames; nothing recurses.

use crate::glam::{Mat3, Quat, Vec3};
use crate::model::clip::Clip;
use crate::runtime::fk::local_to_model;
use crate::runtime::pose::LocalPose;
use crate::runtime::sample::Interpolation;

/// How the second take is placed on the first before measuring.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Align {
    /// As captured.
    #[default]
    None,
    /// Each frame: both roots moved to the origin and `b` turned about the up
    /// axis so its root faces as `a`'s does (translation and heading removed).
    Root,
    /// Each frame: the rigid motion (rotation and translation, Kabsch/Horn)
    /// that best fits `b`'s joints onto `a`'s.
    Procrustes,
    /// Once for the whole take: `b` moved so its first frame's root lies on
    /// `a`'s, turned to `a`'s first heading.
    RootOnce,
    /// Once for the whole take: the one rigid motion that best fits all of
    /// `b`'s frames onto `a`'s.
    ProcrustesOnce,
}

impl Align {
    /// `none`, `root`, `procrustes`, `root-once` or `procrustes-once`.
    pub fn from_name(name: &str) -> Option<Align> {
        match name {
            "none" => Some(Align::None),
            "root" => Some(Align::Root),
            "procrustes" => Some(Align::Procrustes),
            "root-once" => Some(Align::RootOnce),
            "procrustes-once" => Some(Align::ProcrustesOnce),
            _ => None,
        }
    }
}

/// One joint's error over the take.
#[derive(Clone, Debug, PartialEq)]
pub struct JointError {
    /// The joint's name in `a`.
    pub name: String,
    /// Mean distance, `a`'s file units.
    pub mean: f32,
    /// Largest distance, `a`'s file units.
    pub max: f32,
    /// Mean angle between the two joints' local rotations in degrees, when both
    /// clips share the skeleton; `None` otherwise.
    pub angle: Option<f32>,
}

/// What [`compare`] measures.
#[derive(Clone, Debug, PartialEq)]
pub struct Report {
    /// Mean per-joint position error over every frame and compared joint, in
    /// `a`'s file units.
    pub mpjpe: f32,
    /// The same in metres.
    pub mpjpe_m: f32,
    /// Per joint (End Sites left out), in `a`'s joint order.
    pub joints: Vec<JointError>,
    /// Per frame of `a`: the mean error over the joints, `a`'s units.
    pub frames: Vec<f32>,
    /// The frame with the largest error.
    pub worst_frame: usize,
}

/// Why two clips cannot be compared.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum CompareError {
    /// No joint of one matches a joint of the other.
    #[error("the two skeletons share no joint (give a map: A_JOINT=B_JOINT pairs)")]
    NoJoints,
    /// A clip without frames.
    #[error("a clip has no frames")]
    Empty,
    /// The name map failed.
    #[error("{0}")]
    Map(String),
}

/// Compares `b` with `a` (see the module documentation); `map` gives
/// `(a_joint, b_joint)` pairs first when the skeletons differ.
pub fn compare(a: &Clip, b: &Clip, align: Align, map: &[(String, String)]) -> Result<Report, CompareError> {
    if a.frame_count() == 0 || b.frame_count() == 0 {
        return Err(CompareError::Empty);
    }
    let (sa, sb) = (a.skeleton(), b.skeleton());
    let same = sa.len() == sb.len() && sa.joints().iter().zip(sb.joints()).all(|(x, y)| x.name == y.name && x.parent == y.parent);
    let pairs: Vec<(usize, usize)> = if same && map.is_empty() {
        (0..sa.len()).map(|j| (j, j)).collect()
    } else {
        crate::ops::retarget::map_joints(sa, sb, map).map_err(|e| CompareError::Map(e.to_string()))?
    };
    let pairs: Vec<(usize, usize)> = pairs.into_iter().filter(|&(ja, _)| !sa.is_end_site(ja)).collect();
    if pairs.is_empty() {
        return Err(CompareError::NoJoints);
    }
    let mut ctx =
        Context { a, b, pairs: &pairs, align, same, exact: (b.frame_time() - a.frame_time()).abs() < 1e-12, once: None };
    ctx.once = match align {
        Align::RootOnce => Some(root_once(&ctx)),
        Align::ProcrustesOnce => Some(procrustes_once(&ctx)?),
        _ => None,
    };
    // Frames in pieces, measured on every core, merged in order.
    let ranges: Vec<std::ops::Range<usize>> =
        (0..a.frame_count()).step_by(PIECE).map(|s| s..(s + PIECE).min(a.frame_count())).collect();
    let n = pairs.len();
    let mut sums = vec![0.0f64; n];
    let mut maxes = vec![0.0f32; n];
    let mut angles = vec![0.0f64; n];
    let mut frames = Vec::with_capacity(a.frame_count());
    for part in crate::runtime::parallel::map(ranges, |r| measure(&ctx, r)) {
        let part = part.ok_or(CompareError::Empty)?;
        for k in 0..n {
            sums[k] += part.sums[k];
            maxes[k] = maxes[k].max(part.maxes[k]);
            angles[k] += part.angles[k];
        }
        frames.extend(part.frames);
    }
    let count = a.frame_count() as f64;
    let joints: Vec<JointError> = pairs
        .iter()
        .enumerate()
        .map(|(k, &(ja, _))| JointError {
            name: sa.joints().get(ja).map(|j| j.name.clone()).unwrap_or_default(),
            mean: (sums[k] / count) as f32,
            max: maxes[k],
            angle: same.then(|| (angles[k] / count) as f32),
        })
        .collect();
    let mpjpe = (sums.iter().sum::<f64>() / (count * n as f64)) as f32;
    let ma = a.units().meters_per_unit();
    let worst_frame = frames.iter().enumerate().fold(0, |best, (i, e)| if *e > frames[best] { i } else { best });
    Ok(Report { mpjpe, mpjpe_m: mpjpe * ma, joints, frames, worst_frame })
}

/// Frames measured per piece of work.
const PIECE: usize = 1024;

/// What every piece of [`compare`] reads.
struct Context<'a> {
    a: &'a Clip,
    b: &'a Clip,
    pairs: &'a [(usize, usize)],
    align: Align,
    same: bool,
    /// Same frame times: `b`'s own frames, not samples that round.
    exact: bool,
    /// The rigid motion every frame of `b` is moved by (the `-once` alignments).
    once: Option<Rigid>,
}

/// A rigid motion: `p` goes to `rotation * (p - from) + to`.
#[derive(Clone, Copy, Debug)]
struct Rigid {
    from: Vec3,
    to: Vec3,
    rotation: Quat,
}

/// Both takes posed at frame `f` of `a`: the paired joints' positions (metres,
/// Y up) and each take's root transform in the same space.
struct Poser<'a> {
    ctx: &'a Context<'a>,
    la: LocalPose,
    lb: LocalPose,
    ta: Vec<crate::runtime::fk::Transform>,
    tb: Vec<crate::runtime::fk::Transform>,
    scratch: crate::runtime::sample::SampleScratch,
    xa: Vec<Vec3>,
    xb: Vec<Vec3>,
}

impl<'a> Poser<'a> {
    fn new(ctx: &'a Context<'a>) -> Poser<'a> {
        let n = ctx.pairs.len();
        Poser {
            ctx,
            la: LocalPose::default(),
            lb: LocalPose::default(),
            ta: Vec::new(),
            tb: Vec::new(),
            scratch: Default::default(),
            xa: vec![Vec3::ZERO; n],
            xb: vec![Vec3::ZERO; n],
        }
    }

    /// Poses frame `f`.
    fn at(&mut self, f: usize) {
        let (a, b) = (self.ctx.a, self.ctx.b);
        a.local_pose_into(f, &mut self.la);
        if self.ctx.exact && f < b.frame_count() {
            b.local_pose_into(f, &mut self.lb);
        } else {
            b.sample_local_into(a.timeline().time_of(f), Interpolation::Linear, &mut self.scratch, &mut self.lb);
        }
        local_to_model(a.skeleton(), &self.la, &mut self.ta);
        local_to_model(b.skeleton(), &self.lb, &mut self.tb);
        let (ma, mb) = (a.units().meters_per_unit(), b.units().meters_per_unit());
        let (ua, ub) = (a.up_axis(), b.up_axis());
        for (k, &(ja, jb)) in self.ctx.pairs.iter().enumerate() {
            self.xa[k] = self.ta.get(ja).map_or(Vec3::ZERO, |t| ua.to_y_up(t.translation) * ma);
            self.xb[k] = self.tb.get(jb).map_or(Vec3::ZERO, |t| ub.to_y_up(t.translation) * mb);
        }
    }

    /// `a`'s root and the joint of `b` paired with it (else `b`'s root):
    /// positions (metres, Y up) and the heading `b` turns by to face as `a`.
    fn roots(&self) -> (Vec3, Vec3, f32) {
        let (a, b) = (self.ctx.a, self.ctx.b);
        let (ma, mb) = (a.units().meters_per_unit(), b.units().meters_per_unit());
        let (ua, ub) = (a.up_axis(), b.up_axis());
        let root = a.skeleton().roots().next().unwrap_or(0);
        let paired = self.ctx.pairs.iter().find(|(ja, _)| *ja == root).map_or(0, |&(_, jb)| jb);
        let (ta, tb) = (self.ta.get(root), self.tb.get(paired));
        let root_a = ta.map_or(Vec3::ZERO, |t| ua.to_y_up(t.translation) * ma);
        let root_b = tb.map_or(Vec3::ZERO, |t| ub.to_y_up(t.translation) * mb);
        let turn = heading(ua.rotation() * ta.map_or(Quat::IDENTITY, |t| t.rotation))
            - heading(ub.rotation() * tb.map_or(Quat::IDENTITY, |t| t.rotation));
        (root_a, root_b, turn)
    }
}

/// `b`'s first root onto `a`'s, turned to `a`'s first heading.
fn root_once(ctx: &Context<'_>) -> Rigid {
    let mut poser = Poser::new(ctx);
    poser.at(0);
    let (root_a, root_b, turn) = poser.roots();
    Rigid { from: root_b, to: root_a, rotation: Quat::from_rotation_y(turn) }
}

/// The one rigid motion that best fits every frame of `b` onto `a` (Horn's
/// method on the cross-covariance summed over all frames).
fn procrustes_once(ctx: &Context<'_>) -> Result<Rigid, CompareError> {
    let ranges: Vec<std::ops::Range<usize>> =
        (0..ctx.a.frame_count()).step_by(PIECE).map(|s| s..(s + PIECE).min(ctx.a.frame_count())).collect();
    // Per piece: sum of a, sum of b, sum of b a^T, count.
    let parts = crate::runtime::parallel::map(ranges, |range| {
        let mut poser = Poser::new(ctx);
        let (mut sa, mut sb, mut m, mut n) = ([0.0f64; 3], [0.0f64; 3], [[0.0f64; 3]; 3], 0.0f64);
        for f in range {
            poser.at(f);
            for (p, q) in poser.xa.iter().zip(&poser.xb) {
                let (p, q) = (p.to_array().map(f64::from), q.to_array().map(f64::from));
                for i in 0..3 {
                    sa[i] += p[i];
                    sb[i] += q[i];
                    for j in 0..3 {
                        m[i][j] += q[i] * p[j];
                    }
                }
                n += 1.0;
            }
        }
        (sa, sb, m, n)
    });
    let (mut sa, mut sb, mut m, mut n) = ([0.0f64; 3], [0.0f64; 3], [[0.0f64; 3]; 3], 0.0f64);
    for part in parts {
        let (pa, pb, pm, pn) = part.ok_or(CompareError::Empty)?;
        for i in 0..3 {
            sa[i] += pa[i];
            sb[i] += pb[i];
            for j in 0..3 {
                m[i][j] += pm[i][j];
            }
        }
        n += pn;
    }
    let n = n.max(1.0);
    let (ca, cb) = (sa.map(|x| x / n), sb.map(|x| x / n));
    // Centred: sum (b - cb)(a - ca)^T = sum b a^T - n cb ca^T.
    let mut s = [[0.0f64; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            s[i][j] = m[i][j] - n * cb[i] * ca[j];
        }
    }
    let to = Vec3::new(ca[0] as f32, ca[1] as f32, ca[2] as f32);
    let from = Vec3::new(cb[0] as f32, cb[1] as f32, cb[2] as f32);
    Ok(Rigid { from, to, rotation: horn(s) })
}

/// One piece's sums: per pair the distances' sum and largest, the angles'
/// sum; per frame the mean distance.
struct Partial {
    sums: Vec<f64>,
    maxes: Vec<f32>,
    angles: Vec<f64>,
    frames: Vec<f32>,
}

/// Measures frames `range` of `a` (see [`compare`]).
fn measure(ctx: &Context<'_>, range: std::ops::Range<usize>) -> Partial {
    let per_unit = 1.0 / ctx.a.units().meters_per_unit().max(f32::MIN_POSITIVE);
    let n = ctx.pairs.len();
    let mut part = Partial { sums: vec![0.0; n], maxes: vec![0.0; n], angles: vec![0.0; n], frames: Vec::with_capacity(range.len()) };
    let mut poser = Poser::new(ctx);
    for f in range {
        poser.at(f);
        let roots = poser.roots();
        let (xa, xb) = (&mut poser.xa, &mut poser.xb);
        if let Some(r) = ctx.once {
            for q in xb.iter_mut() {
                *q = r.rotation * (*q - r.from) + r.to;
            }
        }
        match ctx.align {
            Align::None | Align::RootOnce | Align::ProcrustesOnce => {}
            Align::Root => {
                let (root_a, root_b, turn) = roots;
                let r = Quat::from_rotation_y(turn);
                for k in 0..n {
                    xa[k] -= root_a;
                    xb[k] = r * (xb[k] - root_b);
                }
            }
            Align::Procrustes => fit(xa, xb),
        }
        let mut frame_sum = 0.0f64;
        for k in 0..n {
            let d = xa[k].distance(xb[k]) * per_unit;
            part.sums[k] += f64::from(d);
            part.maxes[k] = part.maxes[k].max(d);
            frame_sum += f64::from(d);
        }
        part.frames.push((frame_sum / n.max(1) as f64) as f32);
        if ctx.same {
            for (k, &(ja, jb)) in ctx.pairs.iter().enumerate() {
                if let (Some(x), Some(y)) = (poser.la.rotation.get(ja), poser.lb.rotation.get(jb)) {
                    part.angles[k] += f64::from(turn(*x, *y).to_degrees());
                }
            }
        }
    }
    part
}

/// The angle of the rotation from `x` to `y` in radians (by atan2, exact
/// near zero where acos is not).
fn turn(x: Quat, y: Quat) -> f32 {
    let d = x.conjugate() * y;
    2.0 * Vec3::new(d.x, d.y, d.z).length().atan2(d.w.abs())
}

/// The heading (angle about +Y) of a rotation's forward (+Z) axis.
fn heading(q: Quat) -> f32 {
    let f = q * Vec3::Z;
    f.x.atan2(f.z)
}

/// Moves `b` onto `a` by the best rigid motion (Horn's quaternion method:
/// the largest eigenvector of the 4x4 symmetric matrix, by Jacobi rotations).
fn fit(a: &[Vec3], b: &mut [Vec3]) {
    let n = a.len().max(1) as f32;
    let ca = a.iter().copied().sum::<Vec3>() / n;
    let cb = b.iter().copied().sum::<Vec3>() / n;
    // Cross-covariance S = sum (b - cb)(a - ca)^T.
    let mut s = [[0.0f64; 3]; 3];
    for (p, q) in a.iter().zip(b.iter()) {
        let (p, q) = (*p - ca, *q - cb);
        let (p, q) = ([p.x, p.y, p.z], [q.x, q.y, q.z]);
        for i in 0..3 {
            for j in 0..3 {
                s[i][j] += f64::from(q[i]) * f64::from(p[j]);
            }
        }
    }
    let r = Mat3::from_quat(horn(s));
    for q in b.iter_mut() {
        *q = r * (*q - cb) + ca;
    }
}

/// The rotation that best turns the centred points `b` onto `a` given their
/// cross-covariance `s` = sum of b a^T (Horn's quaternion method).
fn horn(s: [[f64; 3]; 3]) -> Quat {
    let [[sxx, sxy, sxz], [syx, syy, syz], [szx, szy, szz]] = s;
    let mut m = [
        [sxx + syy + szz, syz - szy, szx - sxz, sxy - syx],
        [syz - szy, sxx - syy - szz, sxy + syx, szx + sxz],
        [szx - sxz, sxy + syx, -sxx + syy - szz, syz + szy],
        [sxy - syx, szx + sxz, syz + szy, -sxx - syy + szz],
    ];
    let v = largest_eigenvector(&mut m);
    Quat::from_xyzw(v[1] as f32, v[2] as f32, v[3] as f32, v[0] as f32).normalize()
}

/// The eigenvector of the largest eigenvalue of a symmetric 4x4 matrix
/// (cyclic Jacobi; `m` is overwritten).
fn largest_eigenvector(m: &mut [[f64; 4]; 4]) -> [f64; 4] {
    let mut v = [[0.0f64; 4]; 4];
    for (i, row) in v.iter_mut().enumerate() {
        row[i] = 1.0;
    }
    for _ in 0..50 {
        let off: f64 = (0..4).flat_map(|i| (0..4).filter(move |&j| j != i).map(move |j| (i, j))).map(|(i, j)| m[i][j] * m[i][j]).sum();
        if off < 1e-22 {
            break;
        }
        for p in 0..3 {
            for q in p + 1..4 {
                if m[p][q].abs() < 1e-300 {
                    continue;
                }
                let theta = (m[q][q] - m[p][p]) / (2.0 * m[p][q]);
                let sign = if theta >= 0.0 { 1.0 } else { -1.0 };
                let t = sign / (theta.abs() + (theta * theta + 1.0).sqrt());
                let c = 1.0 / (t * t + 1.0).sqrt();
                let s = t * c;
                for k in 0..4 {
                    let (mkp, mkq) = (m[k][p], m[k][q]);
                    m[k][p] = c * mkp - s * mkq;
                    m[k][q] = s * mkp + c * mkq;
                }
                for k in 0..4 {
                    let (mpk, mqk) = (m[p][k], m[q][k]);
                    m[p][k] = c * mpk - s * mqk;
                    m[q][k] = s * mpk + c * mqk;
                }
                for row in v.iter_mut() {
                    let (vp, vq) = (row[p], row[q]);
                    row[p] = c * vp - s * vq;
                    row[q] = s * vp + c * vq;
                }
            }
        }
    }
    let best = (0..4).max_by(|&i, &j| m[i][i].total_cmp(&m[j][j])).unwrap_or(0);
    [v[0][best], v[1][best], v[2][best], v[3][best]]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_fit_undoes_a_rigid_motion() {
        let a: Vec<Vec3> = vec![Vec3::new(0.0, 0.0, 0.0), Vec3::new(1.0, 0.2, 0.0), Vec3::new(0.0, 1.0, 0.3), Vec3::new(0.4, 0.1, 1.0)];
        let r = Quat::from_euler(crate::glam::EulerRot::YXZ, 0.7, -0.3, 0.2);
        let mut b: Vec<Vec3> = a.iter().map(|p| r * *p + Vec3::new(3.0, -1.0, 2.0)).collect();
        fit(&a, &mut b);
        for (p, q) in a.iter().zip(&b) {
            assert!(p.distance(*q) < 1e-4, "{p} {q}");
        }
    }

    #[test]
    fn alignment_names() {
        assert_eq!(Align::from_name("procrustes"), Some(Align::Procrustes));
        assert_eq!(Align::from_name("root"), Some(Align::Root));
        assert_eq!(Align::from_name("x"), None);
    }
}
