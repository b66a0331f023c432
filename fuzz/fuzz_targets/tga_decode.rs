//! Fuzzes tGA skins, decoded alone and dropped with a model. No input may panic, hang or allocate
//! without bound; what reads must survive what a user does next
//! (`mocap_fuzz::check_set`).
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let _ = mocap::formats::image::decode(mocap::formats::image::ImageFormat::Tga, data);
    mocap_fuzz::check_set(&[("skin.tga", data), ("a.md2", &mocap_fuzz::tiny_md2())]);
});
