//! Fuzzes rig files (JSON): read, and what reads written and read back. No input may panic, hang or allocate
//! without bound; what reads must survive what a user does next
//! (`mocap_fuzz::check_set`).
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Ok(rig) = mocap::capture::Rig::from_json(&String::from_utf8_lossy(data)) {
        let again = mocap::capture::Rig::from_json(&rig.to_json()).expect("rewritten rig reads");
        assert_eq!(again.joints.len(), rig.joints.len());
    }
});
