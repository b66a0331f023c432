//! What every fuzz target checks, shared: a set of files read through
//! `mocap::load` (the page's and the CLI's entry) either reads, and then survives
//! what a user does next, or fails with a message that names one of its files.

/// Reads `files` (name, bytes) as one dropped set and checks every result.
pub fn check_set(files: &[(&str, &[u8])]) {
    let inputs: Vec<mocap::Input> = files.iter().map(|&(name, bytes)| mocap::Input { name, bytes }).collect();
    for result in mocap::load(&inputs) {
        match result {
            Ok(loaded) => exercise(&loaded.asset),
            Err(e) => {
                let message = e.to_string();
                assert!(
                    files.iter().any(|(name, _)| message.starts_with(&format!("{name}:"))),
                    "the message names no file: {message}"
                );
            }
        }
    }
}

/// Bounds, a sampled pose and a BVH write -> read round trip for a clip; the mesh
/// and skin of a model.
pub fn exercise(asset: &mocap::Asset) {
    match asset {
        mocap::Asset::Clip(clip) => {
            let _ = clip.bounds();
            let _ = clip.units();
            let mut out = Vec::new();
            clip.sample_world_positions_into(clip.duration() * 0.37, mocap::Interpolation::Linear, &mut out);
            let text = mocap::formats::bvh::write(clip);
            let again = mocap::formats::bvh::parse(text.as_bytes()).expect("rewritten clip parses");
            assert_eq!(again.frame_count(), clip.frame_count());
        }
        mocap::Asset::Model(model) => {
            let _ = model.mesh.height();
            let _ = model.skin.as_ref().map(|s| s.image.pixel(0, 0));
        }
    }
}

/// A valid MD2 model (one triangle, two frames, made here) for the image targets:
/// an image dropped with it is its skin.
pub fn tiny_md2() -> Vec<u8> {
    let triangle = |y: f32| {
        vec![
            mocap::glam::Vec3::new(0.0, y, 0.0),
            mocap::glam::Vec3::new(10.0, y, 0.0),
            mocap::glam::Vec3::new(0.0, 20.0 + y, 0.0),
        ]
    };
    let frames = vec![("stand1".to_owned(), triangle(0.0)), ("stand2".to_owned(), triangle(2.0))];
    let md2 = mocap::formats::md2::build(&frames, &[[0, 1, 2]]).expect("a valid model");
    mocap::formats::md2::write(&md2)
}
