//! Fuzzes aMC motions on a fixed valid two-bone ASF skeleton. No input may panic, hang or allocate
//! without bound; what reads must survive what a user does next
//! (`mocap_fuzz::check_set`).
#![no_main]

use libfuzzer_sys::fuzz_target;

const ASF: &[u8] = b":version 1.10\n:name T\n:units\n  mass 1.0\n  length 1.0\n  angle deg\n:root\n  order TX TY TZ RX RY RZ\n  axis XYZ\n  position 0 0 0\n  orientation 0 0 0\n:bonedata\n  begin\n    id 1\n    name up\n    direction 0 1 0\n    length 10\n    axis 0 0 30 XYZ\n    dof rx ry rz\n  end\n  begin\n    id 2\n    name side\n    direction 1 0 0\n    length 5\n    axis 0 0 0 XYZ\n    dof rx rz\n  end\n:hierarchy\n  begin\n    root up\n    up side\n  end\n";

fuzz_target!(|data: &[u8]| {
    mocap_fuzz::check_set(&[("a.asf", ASF), ("a_01.amc", data)]);
});
