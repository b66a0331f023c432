use super::*;

const TWO: &str = "Segment: Hips\n\
Frames: 2\n\
Frame Time: 0.033333\n\
XTRAN   YTRAN   ZTRAN   XROT    YROT    ZROT    XSCALE  YSCALE  ZSCALE\n\
INCHES  INCHES  INCHES  DEGREES DEGREES DEGREES INCHES  INCHES  INCHES\n\
8.03 35.01 88.36 14.78 -164.35 -3.41 5.21 5.21 5.21\n\
7.81 35.10 86.47 12.94 -166.97 -2.35 5.21 5.21 5.21\n\
Segment: Left Upper Arm\n\
Frames: 2\n\
Frame Time: 0.033333\n\
XTRAN\tYTRAN\tZTRAN\tXROT\tYROT\tZROT\tXSCALE\tYSCALE\tZSCALE\n\
INCHES\tINCHES\tINCHES\tDEGREES\tDEGREES\tDEGREES\tINCHES\tINCHES\tINCHES\n\
1 2 3 4 5 6 7 8 9\n\
-1 -2 -3 -4 -5 -6 -7 -8 -9\n";

fn err(text: &str) -> ParseError {
    match parse(text.as_bytes()) {
        Ok(bva) => panic!("expected an error, got {bva:?}"),
        Err(e) => e,
    }
}

fn check_two(bva: &Bva) {
    assert_eq!(bva.warnings, vec![]);
    assert_eq!(bva.segments.len(), 2);
    let hips = &bva.segments[0];
    assert_eq!(hips.name, "Hips");
    assert_eq!(hips.frame_time, 0.033333);
    assert_eq!(hips.channels, BvaChannel::ALL);
    assert_eq!(hips.units[3], "DEGREES");
    assert_eq!(hips.frame_count, 2);
    assert_eq!(hips.line, 1);
    assert_eq!(hips.row(1), &[7.81, 35.10, 86.47, 12.94, -166.97, -2.35, 5.21, 5.21, 5.21]);
    assert!(hips.row(2).is_empty());
    assert!(!hips.angle_in_radians());
    let arm = &bva.segments[1];
    assert_eq!(arm.name, "Left Upper Arm");
    assert_eq!(arm.line, 8);
    assert_eq!(arm.row(0), &[1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0]);
    assert_eq!(arm.row(1), &[-1.0, -2.0, -3.0, -4.0, -5.0, -6.0, -7.0, -8.0, -9.0]);
}

#[test]
fn two_segments_lf_crlf_cr() {
    check_two(&parse(TWO.as_bytes()).unwrap());
    check_two(&parse(TWO.replace('\n', "\r\n").as_bytes()).unwrap());
    check_two(&parse(TWO.replace('\n', "\r").as_bytes()).unwrap());
}
