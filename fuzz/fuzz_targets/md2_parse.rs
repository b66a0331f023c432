//! Fuzzes mD2 models: the reader, the loader, and capture's per-frame vertices. No input may panic, hang or allocate
//! without bound; what reads must survive what a user does next
//! (`mocap_fuzz::check_set`).
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    mocap_fuzz::check_set(&[("a.md2", data)]);
    if let Ok(md2) = mocap::formats::md2::parse(data) {
        let _ = mocap::capture::model_frames(&md2);
    }
});
