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

/// A one-segment file: the header lines given, then `rows`.
const HEAD: &str = "Segment: Hips\nFrames: 1\nFrame Time: 0.5\n";
const CHANNELS: &str = "XTRAN YTRAN ZTRAN XROT YROT ZROT XSCALE YSCALE ZSCALE\n";
const UNITS: &str = "INCHES INCHES INCHES DEGREES DEGREES DEGREES INCHES INCHES INCHES\n";

fn one(rows: &str) -> String {
    format!("{HEAD}{CHANNELS}{UNITS}{rows}")
}

fn at(e: &ParseError) -> (u32, u32) {
    (e.line, e.column)
}

#[test]
fn bom_blank_lines_tabs_and_keyword_spellings() {
    let text = "\u{feff}\n  \n\tsegment:Hips  \n\n FRAMES :\t1\nframe   time:0.25\n\n\
        xtran\tytran ZTRAN XRot YROT ZROT XSCALE YSCALE ZSCALE \n\n\
        inches inches inches radians radians radians inches inches inches\n\n\
        \t1 2 3 4 5 6 7 8 9\t\n\n\
        SEGMENT  :  Left Foot\t\nFrames 0\nFrame Time 0.25\n"
        .to_owned()
        + CHANNELS
        + UNITS;
    let bva = parse(text.as_bytes()).unwrap();
    assert_eq!(
        bva.warnings,
        vec![Warning {
            line: Some(14),
            message: "segments have different frame counts (`Hips`: 1, `Left Foot`: 0)".into()
        }]
    );
    let hips = &bva.segments[0];
    assert_eq!((hips.name.as_str(), hips.line, hips.frame_time, hips.frame_count), ("Hips", 3, 0.25, 1));
    assert_eq!(hips.units[3], "radians");
    assert!(hips.angle_in_radians());
    assert_eq!(hips.row(0), &[1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0]);
    let foot = &bva.segments[1];
    assert_eq!((foot.name.as_str(), foot.line, foot.frame_count, foot.data.len()), ("Left Foot", 14, 0, 0));
    assert!(foot.row(0).is_empty());
    // Frame Time before Frames.
    let text = format!("Segment: Hips\nFrame Time: 0.25\nFrames: 0\n{CHANNELS}{UNITS}");
    let bva = parse(text.as_bytes()).unwrap();
    assert_eq!((bva.segments[0].frame_time, bva.warnings.len()), (0.25, 0));
    // No final line break.
    let bva = parse(one("1 2 3 4 5 6 7 8 9").as_bytes()).unwrap();
    assert_eq!(bva.segments[0].frame_count, 1);
}

#[test]
fn bom_counts_in_line_one_columns() {
    let e = err("\u{feff}HIERARCHY\n");
    assert_eq!(at(&e), (1, 4));
    assert_eq!(e.message, "expected Segment: at the start of a BVA file, found `HIERARCHY`");
}

#[test]
fn empty_file_is_an_error() {
    for text in ["", "\n\n \t\r\n", "\u{feff}"] {
        let e = err(text);
        assert_eq!((at(&e), e.message.as_str()), ((1, 1), "empty file: expected Segment:"), "{text:?}");
    }
}

#[test]
fn header_errors_with_positions() {
    let e = err("  Hips\n");
    assert_eq!((at(&e), e.message.as_str()), ((1, 3), "expected Segment: at the start of a BVA file, found `Hips`"));

    let e = err("Segment:  \nFrames: 1\n");
    assert_eq!((at(&e), e.message.as_str()), ((1, 11), "expected a segment name after Segment:"));

    let e = err("Segment: Hips\nFrames: many\n");
    assert_eq!(
        (at(&e), e.message.as_str()),
        ((2, 9), "segment `Hips`: expected a frame count after Frames:, found `many`")
    );

    let e = err("Segment: Hips\nFrames: -2\n");
    assert_eq!(at(&e), (2, 9));

    let e = err("Segment: Hips\nFrames:\n");
    assert_eq!((at(&e), e.message.as_str()), ((2, 8), "segment `Hips`: expected a frame count after Frames:"));

    let e = err("Segment: Hips\nFrames: 1\nFrame Time: soon\n");
    assert_eq!(
        (at(&e), e.message.as_str()),
        ((3, 13), "segment `Hips`: expected a number after Frame Time:, found `soon`")
    );
}

#[test]
fn channel_line_errors_with_positions() {
    // Missing at the end of the file: just after the last content.
    let e = err(HEAD);
    assert_eq!(
        (at(&e), e.message.as_str()),
        (
            (3, 16),
            "segment `Hips`: unexpected end of file: expected the channel line (XTRAN YTRAN ZTRAN XROT YROT ZROT XSCALE YSCALE ZSCALE)"
        )
    );
    // Missing: the units line (or anything else) where the channels should be.
    let e = err(&format!("{HEAD}{UNITS}"));
    assert_eq!(
        (at(&e), e.message.as_str()),
        (
            (4, 1),
            "segment `Hips`: expected the channel line (XTRAN YTRAN ZTRAN XROT YROT ZROT XSCALE YSCALE ZSCALE), found `INCHES`"
        )
    );
    let e = err(&format!("{HEAD}Segment: Chest\n"));
    assert_eq!(at(&e), (4, 1));
    // Unknown name.
    let e = err(&format!("{HEAD}XTRAN YTRAN ZTRAN XROT YROT ZROT XSCALE YSCALE WSCALE\n"));
    assert_eq!(
        (at(&e), e.message.as_str()),
        (
            (4, 48),
            "segment `Hips`: unknown channel `WSCALE` (expected one of XTRAN YTRAN ZTRAN XROT YROT ZROT XSCALE YSCALE ZSCALE)"
        )
    );
    // Duplicate.
    let e = err(&format!("{HEAD}XTRAN YTRAN ZTRAN XROT YROT ZROT XSCALE YSCALE XSCALE\n"));
    assert_eq!((at(&e), e.message.as_str()), ((4, 48), "segment `Hips`: channel XSCALE listed twice"));
    // Too few.
    let e = err(&format!("{HEAD}XTRAN YTRAN  \n"));
    assert_eq!(
        (at(&e), e.message.as_str()),
        (
            (4, 12),
            "segment `Hips`: channel line has 2 names, expected all 9 (XTRAN YTRAN ZTRAN XROT YROT ZROT XSCALE YSCALE ZSCALE)"
        )
    );
    // Ten names: the tenth is always a repeat.
    let e = err(&format!("{HEAD}XTRAN YTRAN ZTRAN XROT YROT ZROT XSCALE YSCALE ZSCALE XTRAN\n"));
    assert_eq!((at(&e), e.message.as_str()), ((4, 55), "segment `Hips`: channel XTRAN listed twice"));
}

#[test]
fn units_line_errors_with_positions() {
    let e = err(&format!("{HEAD}{CHANNELS}INCHES INCHES INCHES DEGREES DEGREES DEGREES INCHES INCHES\n"));
    assert_eq!(
        (at(&e), e.message.as_str()),
        ((5, 59), "segment `Hips`: units line has 8 words, expected 9, one per channel (e.g. INCHES or DEGREES)")
    );
    let e = err(&format!("{HEAD}{CHANNELS}INCHES INCHES INCHES DEGREES DEGREES DEGREES INCHES INCHES INCHES FEET\n"));
    assert_eq!(at(&e), (5, 67));
    assert!(e.message.contains("more than 9 words"), "{}", e.message);
    // A word that is not a number where the units go is taken as units.
    let e = err(&format!("{HEAD}{CHANNELS}x1 2 3 4 5 6 7 8 9 10\n"));
    assert_eq!(at(&e), (5, 20));
}

#[test]
fn row_errors_with_positions() {
    let e = err(&one("1 2 3 4 5 6 7\n"));
    assert_eq!((at(&e), e.message.as_str()), ((6, 14), "segment `Hips`: expected 9 values (XTRAN … ZSCALE), found 7"));
    let e = err(&one("1 2 3 4 5 6 7 8 9\n1 2 3 4 5 6 7 8 9 10 11\n"));
    assert_eq!((at(&e), e.message.as_str()), ((7, 19), "segment `Hips`: expected 9 values (XTRAN … ZSCALE), found 11"));
    let e = err(&one("1 2 x3 4 5 6 7 8 9\n"));
    assert_eq!((at(&e), e.message.as_str()), ((6, 5), "segment `Hips`: expected a number, found `x3`"));
    let e = err(&one("1 2 3 4 5 6 7 8 9,\n"));
    assert_eq!(at(&e), (6, 17));
    // The channel names in the message follow the file's column order.
    let text = format!("{HEAD}ZSCALE YTRAN ZTRAN XROT YROT ZROT XSCALE YSCALE XTRAN\n{UNITS}1\n");
    let e = err(&text);
    assert_eq!((at(&e), e.message.as_str()), ((6, 2), "segment `Hips`: expected 9 values (ZSCALE … XTRAN), found 1"));
    // CRLF and CR give the same positions.
    for eol in ["\r\n", "\r"] {
        let e = err(&one("1 2 x3 4 5 6 7 8 9\n").replace('\n', eol));
        assert_eq!(at(&e), (6, 5), "{eol:?}");
    }
}

#[test]
fn frames_mismatch_warns_and_uses_rows_present() {
    let text = "Segment: Hips\nFrames: 3\nFrame Time: 0.5\n".to_owned()
        + CHANNELS
        + UNITS
        + "1 2 3 4 5 6 7 8 9\n1 2 3 4 5 6 7 8 9\n";
    let bva = parse(text.as_bytes()).unwrap();
    assert_eq!(bva.segments[0].frame_count, 2);
    assert_eq!(bva.segments[0].data.len(), 18);
    assert_eq!(
        bva.warnings,
        vec![Warning {
            line: Some(2),
            message: "segment `Hips`: Frames: says 3 but the segment has 2 rows; using 2".into()
        }]
    );
}

#[test]
fn huge_frames_number_does_not_allocate_from_it() {
    let text =
        "Segment: Hips\nFrames: 4000000000\nFrame Time: 0.5\n".to_owned() + CHANNELS + UNITS + "1 2 3 4 5 6 7 8 9\n";
    let bva = parse(text.as_bytes()).unwrap();
    let hips = &bva.segments[0];
    assert_eq!(hips.frame_count, 1);
    assert!(hips.data.capacity() < 1024);
    assert_eq!(bva.warnings.len(), 1);
    // Beyond u64: saturates, still a warning and not an error.
    let text = text.replace("4000000000", "99999999999999999999999999");
    assert_eq!(parse(text.as_bytes()).unwrap().segments[0].frame_count, 1);
}

#[test]
fn frame_time_and_frames_fallbacks() {
    let cases = [
        ("Segment: Hips\nFrames: 0\n", 1, "segment `Hips`: no Frame Time: line; using 1/30 s"),
        (
            "Segment: Hips\nFrames: 0\nFrame Time: 0\n",
            3,
            "segment `Hips`: Frame Time 0 is not a positive duration; using 1/30 s",
        ),
        (
            "Segment: Hips\nFrames: 0\nFrame Time: -0.1\n",
            3,
            "segment `Hips`: Frame Time -0.1 is not a positive duration; using 1/30 s",
        ),
        (
            "Segment: Hips\nFrames: 0\nFrame Time: inf\n",
            3,
            "segment `Hips`: Frame Time inf is not a positive duration; using 1/30 s",
        ),
        ("Segment: Hips\nFrames: 0\nFrame Time:\n", 3, "segment `Hips`: Frame Time is missing; using 1/30 s"),
        ("Segment: Hips\nFrame Time: 0.5\n", 1, "segment `Hips`: no Frames: line; using the 0 rows present"),
    ];
    for (head, line, message) in cases {
        let bva = parse(format!("{head}{CHANNELS}{UNITS}").as_bytes()).unwrap();
        assert_eq!(bva.warnings, vec![Warning { line: Some(line), message: message.into() }], "{head:?}");
        let expected = if head.contains("0.5") { 0.5 } else { DEFAULT_FRAME_TIME };
        assert_eq!(bva.segments[0].frame_time, expected);
    }
}

#[test]
fn missing_units_line_defaults_by_channel_kind() {
    let text = format!("{HEAD}XROT YROT ZROT XTRAN YTRAN ZTRAN XSCALE YSCALE ZSCALE\n-1 2 3 4 5 6 7 8 9\n");
    let bva = parse(text.as_bytes()).unwrap();
    let hips = &bva.segments[0];
    assert_eq!(
        hips.units,
        ["DEGREES", "DEGREES", "DEGREES", "INCHES", "INCHES", "INCHES", "INCHES", "INCHES", "INCHES"]
    );
    assert_eq!(hips.row(0), &[-1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0]);
    assert_eq!(hips.column(BvaChannel::XTran), Some(3));
    assert_eq!(hips.column(BvaChannel::YRot), Some(1));
    assert_eq!(bva.warnings.len(), 1);
    assert_eq!(bva.warnings[0].line, Some(1));
    // No units and no rows: at the end of the file, or before the next segment.
    let text = format!("{HEAD}{CHANNELS}Segment: Chest\nFrames: 0\nFrame Time: 0.5\n{CHANNELS}");
    let bva = parse(text.as_bytes()).unwrap();
    assert_eq!(bva.segments.len(), 2);
    assert_eq!(bva.segments[1].units[0], "INCHES");
    assert!(bva.warnings.iter().any(|w| w.message.starts_with("2 segments have no units line")), "{:?}", bva.warnings);
}

#[test]
fn non_finite_values_give_one_warning() {
    let bva = parse(one("nan 2 3 4 5 6 7 8 inf\n1 2 3 -inf 5 6 7 8 9\n").as_bytes()).unwrap();
    let hips = &bva.segments[0];
    assert!(hips.data[0].is_nan());
    assert_eq!(hips.data[8], f32::INFINITY);
    assert_eq!(hips.data[12], f32::NEG_INFINITY);
    let non_finite: Vec<_> = bva.warnings.iter().filter(|w| w.message.contains("NaN")).collect();
    assert_eq!(non_finite.len(), 1);
    assert_eq!(non_finite[0].line, Some(6));
}

#[test]
fn different_frame_times_warn() {
    let text = TWO.replacen("0.033333", "0.01", 1);
    let bva = parse(text.as_bytes()).unwrap();
    assert_eq!(
        bva.warnings,
        vec![Warning {
            line: Some(8),
            message: "segments have different frame times (`Hips`: 0.01 s, `Left Upper Arm`: 0.033333 s)".into()
        }]
    );
}

#[test]
fn sniff_looks_at_the_first_word() {
    assert!(sniff(b"Segment: Hips\n"));
    assert!(sniff(b"\xEF\xBB\xBF\r\n  segment:Hips"));
    assert!(sniff(b"SEGMENT Hips"));
    assert!(sniff(b"Segment"));
    assert!(!sniff(b"Segments: 3"));
    assert!(!sniff(b"HIERARCHY\nROOT Hips"));
    assert!(!sniff(b""));
    assert!(!sniff(b"Seg"));
}

#[test]
fn channel_names() {
    for c in BvaChannel::ALL {
        assert_eq!(BvaChannel::from_name(c.name()), Some(c));
        assert_eq!(BvaChannel::from_name(&c.name().to_lowercase()), Some(c));
    }
    assert_eq!(BvaChannel::from_name("Xrot"), Some(BvaChannel::XRot));
    assert_eq!(BvaChannel::from_name("XPOSITION"), None);
    assert_eq!(BvaChannel::XRot.default_unit(), "DEGREES");
    assert_eq!(BvaChannel::ZScale.default_unit(), "INCHES");
}

#[test]
fn writes_the_standard_layout() {
    let bva = parse(TWO.as_bytes()).unwrap();
    let text = write(&bva);
    let expected_head = "Segment: Hips\nFrames: 2\nFrame Time: 0.033333\n\
        XTRAN\tYTRAN\tZTRAN\tXROT\tYROT\tZROT\tXSCALE\tYSCALE\tZSCALE\n\
        INCHES\tINCHES\tINCHES\tDEGREES\tDEGREES\tDEGREES\tINCHES\tINCHES\tINCHES\n\
        8.03\t35.01\t88.36\t14.78\t-164.35\t-3.41\t5.21\t5.21\t5.21\n";
    assert!(text.starts_with(expected_head), "{text}");
    assert!(text.contains("\n1\t2\t3\t4\t5\t6\t7\t8\t9\n"), "{text}");
    assert!(!text.contains('\r'));
    assert_eq!(parse(text.as_bytes()).unwrap(), bva);
}

fn segment(name: &str, frame_time: f64, channels: [BvaChannel; 9], data: Vec<f32>) -> Segment {
    Segment {
        name: name.into(),
        frame_time,
        channels,
        units: channels.map(|c| c.default_unit().to_owned()),
        frame_count: data.len() / 9,
        data,
        line: 0,
    }
}

fn bits(data: &[f32]) -> Vec<u32> {
    data.iter().map(|v| v.to_bits()).collect()
}

#[test]
fn awkward_floats_round_trip_bit_exact() {
    let awkward = [1e-40f32, -0.0, 1e30, 0.1, f32::MIN_POSITIVE, f32::MAX, -f32::MAX, 1.0 / 3.0, 16777217.0];
    let mut reversed = BvaChannel::ALL;
    reversed.reverse();
    let mut data = awkward.to_vec();
    data.extend(awkward.iter().map(|v| -v));
    data.extend([f32::from_bits(1), 0.0, 1e-45, 123456.79, -7.0e-39, 2.5, 1e38, -1e-38, 0.30000001]);
    let bva = Bva {
        segments: vec![
            segment("Hips", 1.0 / 120.0, BvaChannel::ALL, data.clone()),
            segment("Odd  name", 0.1 + 0.2, reversed, awkward.to_vec()),
        ],
        warnings: vec![],
    };
    let back = parse(write(&bva).as_bytes()).unwrap();
    assert_eq!(back.segments.len(), 2);
    assert_eq!(bits(&back.segments[0].data), bits(&data));
    assert_eq!(bits(&back.segments[1].data), bits(&awkward));
    assert_eq!(back.segments[0].frame_time.to_bits(), (1.0f64 / 120.0).to_bits());
    assert_eq!(back.segments[1].frame_time.to_bits(), (0.1f64 + 0.2).to_bits());
    assert_eq!(back.segments[1].channels, reversed);
    assert_eq!(back.segments[1].name, "Odd  name");
    assert!(back.segments[0].data[1].is_sign_negative());
    // Non-finite values survive too (as a warning).
    let special = segment(
        "S",
        0.5,
        BvaChannel::ALL,
        vec![f32::NAN, f32::INFINITY, f32::NEG_INFINITY, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    );
    let back = parse(write(&Bva { segments: vec![special], warnings: vec![] }).as_bytes()).unwrap();
    let row = back.segments[0].row(0);
    assert!(row[0].is_nan() && row[1] == f32::INFINITY && row[2] == f32::NEG_INFINITY);
}

#[test]
fn writer_keeps_output_parseable() {
    // Odd names and units, and a frame_count that disagrees with the data.
    let mut s = segment("  two\nlines ", 0.5, BvaChannel::ALL, vec![1.0; 18]);
    s.frame_count = 5;
    s.units[0] = "square inches".into();
    s.units[1] = String::new();
    let back = parse(write(&Bva { segments: vec![s], warnings: vec![] }).as_bytes()).unwrap();
    let s = &back.segments[0];
    assert_eq!((s.name.as_str(), s.frame_count), ("two lines", 2));
    assert_eq!((s.units[0].as_str(), s.units[1].as_str()), ("square_inches", "-"));
    assert_eq!(back.warnings, vec![]);
    // No segments: empty text (which does not parse: a BVA file needs a segment).
    assert_eq!(write(&Bva::default()), "");
}

mod prop {
    use super::super::*;
    use proptest::prelude::*;

    fn channel_order() -> impl Strategy<Value = [BvaChannel; 9]> {
        Just(BvaChannel::ALL.to_vec()).prop_shuffle().prop_map(|v| {
            let mut out = BvaChannel::ALL;
            out.copy_from_slice(&v);
            out
        })
    }

    fn value() -> impl Strategy<Value = f32> {
        use proptest::num::f32::*;
        POSITIVE | NEGATIVE | NORMAL | SUBNORMAL | ZERO | INFINITE
    }

    fn segment() -> impl Strategy<Value = Segment> {
        (
            "[A-Za-z0-9_é][A-Za-z0-9_é .:\t-]{0,12}[A-Za-z0-9_é]|[A-Za-z]",
            1e-6f64..10.0,
            channel_order(),
            // Units never start like a number (`inf`, `nan`) or a keyword (`Segment`).
            proptest::array::uniform9("[A-HJ-MO-RT-Za-hj-mo-rt-z%/_][A-Za-z%/_]{0,7}"),
            0usize..5,
        )
            .prop_flat_map(|(name, frame_time, channels, units, frames)| {
                proptest::collection::vec(value(), frames * 9).prop_map(move |data| Segment {
                    name: name.clone(),
                    frame_time,
                    channels,
                    units: units.clone(),
                    frame_count: frames,
                    data,
                    line: 0,
                })
            })
    }

    proptest! {
        #[test]
        fn write_then_parse_is_identity(mut segments in proptest::collection::vec(segment(), 1..5)) {
            // The writer's layout puts each segment 5 lines + its rows after the last.
            let mut line = 1u32;
            for s in &mut segments {
                s.line = line;
                line += 5 + s.frame_count as u32;
            }
            let bva = Bva { segments, warnings: vec![] };
            let text = write(&bva);
            let back = parse(text.as_bytes()).map_err(|e| TestCaseError::fail(format!("{e}\n{text}")))?;
            prop_assert_eq!(back.segments.len(), bva.segments.len());
            for (a, b) in bva.segments.iter().zip(&back.segments) {
                prop_assert_eq!(&a.name, &b.name);
                prop_assert_eq!(a.frame_time.to_bits(), b.frame_time.to_bits());
                prop_assert_eq!(a.channels, b.channels);
                prop_assert_eq!(&a.units, &b.units);
                prop_assert_eq!(a.frame_count, b.frame_count);
                prop_assert_eq!(a.line, b.line);
                prop_assert_eq!(super::bits(&a.data), super::bits(&b.data));
            }
            // The only warnings are about differences between segments, or non-finite data.
            for w in &back.warnings {
                prop_assert!(w.message.starts_with("segments have different") || w.message.contains("NaN"), "{}", w);
            }
        }
    }
}
