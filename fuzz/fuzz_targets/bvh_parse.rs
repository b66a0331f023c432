//! Fuzzes the BVH reader: no input may panic, hang or allocate without bound; what
//! parses must also survive FK, bounds and a write → parse round trip, and reading
//! it as it arrives (`bvh::Stream`) must give what `parse` gives.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    // Read as it arrives, in pieces sized by the first byte: what parse gives.
    let whole = mocap::formats::bvh::parse(data);
    let mut stream = mocap::formats::bvh::Stream::with_capacity(data.len());
    data.chunks(usize::from(data.first().copied().unwrap_or(1)).max(1)).for_each(|c| stream.push(c));
    let outcome = |r: &Result<mocap::Clip, mocap::ParseError>| {
        r.as_ref()
            .map(|c| (c.frame_count(), c.motion().data().iter().map(|v| v.to_bits()).collect::<Vec<_>>()))
            .map_err(|e| e.to_string())
    };
    assert!(outcome(&whole) == outcome(&stream.finish()), "streamed differs from parse");
    if let Ok(clip) = whole {
        let _ = clip.bounds();
        let _ = clip.units();
        let mut out = Vec::new();
        clip.sample_world_positions_into(clip.duration() * 0.37, mocap::Interpolation::Linear, &mut out);
        let text = mocap::formats::bvh::write(&clip);
        let again = mocap::formats::bvh::parse(text.as_bytes()).expect("rewritten clip parses");
        assert_eq!(again.frame_count(), clip.frame_count());
        assert_eq!(again.skeleton().len(), clip.skeleton().len());
    }
});
