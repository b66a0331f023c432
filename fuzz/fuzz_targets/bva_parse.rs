//! Fuzzes bVA files, and a BVA write -> read round trip of what reads. No input may panic, hang or allocate
//! without bound; what reads must survive what a user does next
//! (`mocap_fuzz::check_set`).
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    mocap_fuzz::check_set(&[("a.bva", data)]);
    if let Ok(bva) = mocap::formats::bva::parse(data) {
        let again =
            mocap::formats::bva::parse(mocap::formats::bva::write(&bva).as_bytes()).expect("rewritten BVA reads");
        assert_eq!(again.segments.len(), bva.segments.len());
    }
});
