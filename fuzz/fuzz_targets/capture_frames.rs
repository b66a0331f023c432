//! Fuzzes the per-frame capture layout: read, every bone of every frame converted, written and read back. No input may panic, hang or allocate
//! without bound; what reads must survive what a user does next
//! (`mocap_fuzz::check_set`).
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Ok(frames) = mocap::capture::frames::parse(data) {
        for frame in &frames.frames {
            for b in 0..frames.bones.len() {
                let _ = frame.to_y_up(b);
            }
        }
        let again =
            mocap::capture::frames::parse(&mocap::capture::frames::write(&frames)).expect("rewritten frames read");
        assert_eq!(again.frames.len(), frames.frames.len());
    }
});
