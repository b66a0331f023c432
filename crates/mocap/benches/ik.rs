//! `cargo bench -p mocap --bench ik`: IK solves per second for each solver on a
//! 3-bone and a 10-bone chain (a chain of joints along +Y, bent a little), each
//! solve from the same starting pose toward targets moving around a sphere inside
//! the chain's reach. The two-bone solver runs on two bones.

use mocap::LocalPose;
use mocap::glam::Vec3;
use mocap::runtime::ik::{self, Chain, Options};
use std::time::Instant;

fn chain_clip(n: usize) -> mocap::Clip {
    let mut text = String::from("HIERARCHY\nROOT j0\n{\nOFFSET 0 0 0\nCHANNELS 3 Zrotation Xrotation Yrotation\n");
    for i in 1..n {
        text.push_str(&format!("JOINT j{i}\n{{\nOFFSET 0 1 0\nCHANNELS 3 Zrotation Xrotation Yrotation\n"));
    }
    text.push_str("End Site\n{\nOFFSET 0 1 0\n}\n");
    text.push_str(&"}\n".repeat(n));
    text.push_str("MOTION\nFrames: 1\nFrame Time: 0.1\n");
    for i in 0..n {
        text.push_str(&format!("{} 4 0 ", 5.0 + i as f32));
    }
    text.push('\n');
    mocap::formats::bvh::parse(text.as_bytes()).expect("chain")
}

fn main() {
    println!("IK solves per second (targets inside reach, tolerance 1e-4, at most 32 passes):");
    for bones in [2usize, 3, 10] {
        let clip = chain_clip(bones);
        let skeleton = clip.skeleton();
        let mut start_pose = LocalPose::default();
        clip.local_pose_into(0, &mut start_pose);
        let chain = Chain::up_from(skeleton, skeleton.len() - 1, bones).expect("chain");
        let options = Options::default();
        let targets: Vec<Vec3> = (0..256)
            .map(|i| {
                let a = i as f32 * 0.37;
                Vec3::new(a.sin() * (a * 0.3).cos(), (a * 0.7).cos(), a.cos() * (a * 0.3).sin()).normalize_or_zero()
                    * bones as f32
                    * 0.7
            })
            .collect();
        let mut solvers: Vec<(&str, Box<dyn Fn(&mut LocalPose, Vec3) -> ik::Solve>)> = vec![
            ("ccd", Box::new(|p: &mut LocalPose, t: Vec3| ik::ccd(skeleton, p, &chain, t, &options))),
            ("fabrik", Box::new(|p: &mut LocalPose, t: Vec3| ik::fabrik(skeleton, p, &chain, t, &options))),
        ];
        if bones == 2 {
            solvers.insert(
                0,
                (
                    "two_bone",
                    Box::new(|p: &mut LocalPose, t: Vec3| {
                        ik::two_bone(skeleton, p, &chain, t, Vec3::Z * 5.0, &options)
                    }),
                ),
            );
        }
        for (name, solve) in solvers {
            let mut pose = start_pose.clone();
            let mut reached = 0usize;
            let runs = 20_000usize;
            let start = Instant::now();
            for i in 0..runs {
                pose.rotation.copy_from_slice(&start_pose.rotation);
                let s = solve(&mut pose, targets[i % targets.len()]);
                reached += usize::from(s.reached);
            }
            let secs = start.elapsed().as_secs_f64();
            println!(
                "{name:<8} {bones:>2} bones: {:>10.0} solves/s ({:.0}% reached the tolerance)",
                runs as f64 / secs,
                100.0 * reached as f64 / runs as f64
            );
        }
    }
}
