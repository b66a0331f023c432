//! Fuzzes the asset store (`formats::store`): no input may panic, hang or
//! allocate without bound; what reads must hold together (its model's checks
//! passed), store again and read back the same, and survive what a user does next
//! (`mocap_fuzz::exercise`).
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    // Past the header, so that most inputs reach the body.
    let mut bytes = mocap::formats::store::MAGIC.to_vec();
    bytes.extend_from_slice(&1u32.to_le_bytes());
    bytes.extend_from_slice(data);
    for input in [data, bytes.as_slice()] {
        match mocap::formats::store::parse(input) {
            Ok(asset) => {
                let stored = mocap::formats::store::write(&asset);
                let again = mocap::formats::store::parse(&stored).expect("a stored asset reads");
                // Debug, not ==: a NaN in the motion comes back as itself, which == never calls equal.
                assert_eq!(format!("{again:?}"), format!("{asset:?}"), "stored again, read back the same");
                assert_eq!(mocap::formats::store::write(&again), stored, "and the same bytes");
                // BVH cannot hold every clip the model can (one without joints, the
                // frames of one without channels, a joint with an empty name: no reader
                // makes those, the store keeps them): `exercise`, whose last step is a BVH
                // round trip, is for the clips whose BVH reads back; the others get the
                // rest of it here.
                match asset.clip() {
                    Some(c) if !bvh_reads_back(c) => {
                        let _ = (c.bounds(), c.units(), c.up_axis());
                        let mut out = Vec::new();
                        c.sample_world_positions_into(c.duration() * 0.37, mocap::Interpolation::Linear, &mut out);
                    }
                    _ => mocap_fuzz::exercise(&asset),
                }
            }
            Err(e) => assert!(e.message.starts_with("byte "), "an unlocated message: {e}"),
        }
    }
});

/// Whether `clip` written as BVH reads back with its frames.
fn bvh_reads_back(clip: &mocap::Clip) -> bool {
    let text = mocap::formats::bvh::write(clip);
    mocap::formats::bvh::parse(text.as_bytes()).is_ok_and(|again| again.frame_count() == clip.frame_count())
}
