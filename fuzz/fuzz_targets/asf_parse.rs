//! Fuzzes aSF skeletons, alone (their rest pose) and with a motion that uses them. No input may panic, hang or allocate
//! without bound; what reads must survive what a user does next
//! (`mocap_fuzz::check_set`).
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    mocap_fuzz::check_set(&[("a.asf", data)]);
    mocap_fuzz::check_set(&[
        ("a.asf", data),
        ("a_01.amc", b":FULLY-SPECIFIED\n:DEGREES\n1\nroot 0 0 0 0 0 0\n2\nroot 1 2 3 4 5 6\n"),
    ]);
});
