//! BVH reader behaviour on small inline fixtures: robustness cases and error positions.

use mocap::Channel;
use mocap::formats::bvh::parse;
use mocap::glam::Vec3;

/// A one-joint file with the given channel line and rows.
fn one_joint(channels: &str, rows: &str, frames: usize) -> String {
    format!(
        "HIERARCHY\nROOT Hips\n{{\n\tOFFSET 0 0 0\n\t{channels}\n\tEnd Site\n\t{{\n\t\tOFFSET 0 1 0\n\t}}\n}}\nMOTION\nFrames: {frames}\nFrame Time: 0.5\n{rows}"
    )
}

fn err(src: &str) -> mocap::ParseError {
    match parse(src.as_bytes()) {
        Ok(_) => panic!("expected an error for:\n{src}"),
        Err(e) => e,
    }
}

#[test]
fn keywords_any_case_and_braces_on_name_lines() {
    let src = "hierarchy\nroot Hips{\n offset 1 2 3\n channels 3 xrotation YROTATION Zrotation\n end site{ offset 0 1 0 }\n}\nmotion\nframes: 1\nframe time: 0.1\n0 0 0\n";
    let clip = parse(src.as_bytes()).unwrap();
    assert_eq!(clip.skeleton().len(), 2);
    assert_eq!(clip.skeleton().joints()[0].name, "Hips");
    assert_eq!(clip.skeleton().joints()[0].offset, Vec3::new(1.0, 2.0, 3.0));
    assert_eq!(clip.skeleton().joints()[0].channels, vec![Channel::Xrotation, Channel::Yrotation, Channel::Zrotation]);
    assert!(clip.skeleton().joints()[1].is_end_site());
    assert_eq!(clip.frame_count(), 1);
    assert!(clip.warnings.is_empty(), "{:?}", clip.warnings);
}

#[test]
fn every_line_ending_and_missing_final_newline() {
    let base = one_joint("CHANNELS 3 Xposition Yposition Zposition", "1 2 3\n4 5 6", 2);
    for ending in ["\n", "\r\n", "\r"] {
        let src = base.replace('\n', ending).replace('\t', " \t ");
        let clip = parse(src.as_bytes()).unwrap_or_else(|e| panic!("{ending:?}: {e}"));
        assert_eq!(clip.frame_count(), 2, "{ending:?}");
        assert_eq!(clip.channel_values(1), &[4.0, 5.0, 6.0]);
    }
}

#[test]
fn error_lines_are_right_with_crlf_and_lone_cr() {
    let base = one_joint("CHANNELS 3 Xposition Yposition Zposition", "1 2 3\n4 5\n", 2);
    for ending in ["\n", "\r\n", "\r"] {
        let e = err(&base.replace('\n', ending));
        assert_eq!((e.line, e.column), (15, 4), "{ending:?}: {e}");
        assert!(e.message.contains("2 values, expected 3"), "{e}");
    }
}

#[test]
fn number_forms() {
    let src = one_joint(
        "CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation",
        "+1.5 -0 1e2 2.5E-1 .5 -7.\n",
        1,
    );
    let clip = parse(src.as_bytes()).unwrap();
    let row = clip.channel_values(0);
    assert_eq!(row, &[1.5, -0.0, 100.0, 0.25, 0.5, -7.0]);
    assert!(row[1].is_sign_negative());
}

#[test]
fn names_with_spaces_dots_colons_and_non_ascii() {
    let mut src = b"HIERARCHY\nROOT mixamorig:Hips\n{\nOFFSET 0 0 0\nCHANNELS 0\nJOINT Left Up.Leg  \n{\nOFFSET 0 -1 0\nJOINT K\xe9\n{\nOFFSET 0 -1 0\n}\n}\nJOINT R\xc3\xa9\n{\nOFFSET 0 1 0\nEnd Site Tip\n{\nOFFSET 0 1 0\n}\n}\n}\n".to_vec();
    src.extend_from_slice(b"MOTION\nFrames: 0\nFrame Time: 0.1\n");
    let clip = parse(&src).unwrap();
    let names: Vec<&str> = clip.skeleton().joints().iter().map(|j| j.name.as_str()).collect();
    assert_eq!(names, ["mixamorig:Hips", "Left Up.Leg", "K\u{e9}", "R\u{e9}", "Tip"]);
    assert_eq!(clip.skeleton().joints()[4].parent, Some(3));
    assert_eq!(clip.frame_count(), 0);
}

#[test]
fn unnamed_end_site_gets_parent_name_and_zero_channel_joints() {
    let src = "HIERARCHY\nROOT A\n{\nOFFSET 0 0 0\nCHANNELS 0\nEnd Site\n{\nOFFSET 0 2 0\n}\n}\nMOTION\nFrames: 3\nFrame Time: 0.1\n\n\n\n";
    let clip = parse(src.as_bytes()).unwrap();
    assert_eq!(clip.skeleton().joints()[1].name, "A_End");
    assert_eq!(clip.skeleton().channel_count(), 0);
    assert_eq!(clip.world_positions(0)[1], Vec3::new(0.0, 2.0, 0.0));
}

#[test]
fn several_roots_are_kept_with_their_own_columns() {
    let src = "HIERARCHY\nROOT A\n{\nOFFSET 0 0 0\nCHANNELS 3 Xposition Yposition Zposition\n}\nROOT B\n{\nOFFSET 0 0 0\nCHANNELS 3 Xposition Yposition Zposition\n}\nMOTION\nFrames: 1\nFrame Time: 0.1\n1 2 3 4 5 6\n";
    let clip = parse(src.as_bytes()).unwrap();
    assert_eq!(clip.skeleton().roots().count(), 2);
    assert_eq!(clip.world_positions(0), vec![Vec3::new(1.0, 2.0, 3.0), Vec3::new(4.0, 5.0, 6.0)]);
}

#[test]
fn frames_count_disagreeing_with_rows_uses_rows_and_warns() {
    let src = one_joint("CHANNELS 1 Xposition", "1\n2\n", 4_000_000_000);
    let clip = parse(src.as_bytes()).unwrap();
    assert_eq!(clip.frame_count(), 2);
    assert!(
        clip.warnings.iter().any(|w| w.message.contains("4000000000") && w.line == Some(12)),
        "{:?}",
        clip.warnings
    );
}

#[test]
fn frame_time_missing_or_zero_defaults_with_warning() {
    let zero = one_joint("CHANNELS 1 Xposition", "1\n", 1).replace("Frame Time: 0.5", "Frame Time: 0");
    let missing = one_joint("CHANNELS 1 Xposition", "1\n", 1).replace("Frame Time: 0.5\n", "");
    for src in [zero, missing] {
        let clip = parse(src.as_bytes()).unwrap();
        assert_eq!(clip.frame_time(), mocap::formats::bvh::DEFAULT_FRAME_TIME);
        assert!(clip.warnings.iter().any(|w| w.message.contains("1/30")), "{:?}", clip.warnings);
    }
}

#[test]
fn header_forms_glued_and_spaced() {
    let src = one_joint("CHANNELS 1 Xposition", "7\n", 1)
        .replace("Frames: 1\nFrame Time: 0.5", "FRAMES:1\nFrame time : 0.25");
    let clip = parse(src.as_bytes()).unwrap();
    assert_eq!((clip.frame_count(), clip.frame_time()), (1, 0.25));
}

#[test]
fn no_motion_section_is_a_rest_pose_with_warning() {
    let src = "HIERARCHY\nROOT A\n{\nOFFSET 0 0 0\nCHANNELS 3 Zrotation Xrotation Yrotation\n}\n";
    let clip = parse(src.as_bytes()).unwrap();
    assert_eq!(clip.frame_count(), 0);
    assert_eq!(clip.warnings.len(), 1);
}

#[test]
fn huge_declared_frames_do_not_allocate() {
    // Parsing must be instant and small even though the header claims billions.
    let src = one_joint(
        "CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation",
        "0 0 0 0 0 0\n0 0 0 0 0 0\n",
        4_000_000_000,
    );
    let clip = parse(src.as_bytes()).unwrap();
    assert_eq!(clip.motion().data().len(), 12);
}

#[test]
fn many_blank_lines_with_wide_rows_do_not_allocate() {
    let mut src =
        "HIERARCHY\nROOT A\n{\nOFFSET 0 0 0\nCHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation\n"
            .to_string();
    for i in 0..200 {
        src.push_str(&format!(
            "JOINT J{i}\n{{\nOFFSET 0 0 0\nCHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation\n}}\n"
        ));
    }
    src.push_str("}\nMOTION\nFrames: 1\nFrame Time: 0.1\n");
    src.push_str(&"x\n".repeat(100_000));
    let e = err(&src);
    assert!(e.message.contains("expected a number"), "{e}");
}

#[test]
fn error_cases_have_line_and_column() {
    let cases: &[(&str, u32, u32, &str)] = &[
        ("", 1, 1, "expected HIERARCHY"),
        ("HIERARCHX\n", 1, 1, "expected HIERARCHY"),
        ("HIERARCHY\nJOINTS A\n", 2, 1, "expected ROOT"),
        ("HIERARCHY\nEnd Site\n{\n}\n", 2, 1, "expected ROOT"),
        ("HIERARCHY\nROOT A\n{\nOFFSET 0 x 0\n}\n", 4, 10, "y value of OFFSET"),
        ("HIERARCHY\nROOT A\n{\nOFFSET 0 0 0\nCHANNELS 2 Xrotation Wrotation\n}\n", 5, 22, "channel name"),
        ("HIERARCHY\nROOT A\n{\nOFFSET 0 0 0\nCHANNELS three\n}\n", 5, 10, "channel count"),
        ("HIERARCHY\nROOT A\n{\nOFFSET 0 0 0\nBOGUS\n}\n", 5, 1, "expected OFFSET, CHANNELS"),
        ("HIERARCHY\nROOT A\n{\nOFFSET 0 0 0\n", 5, 1, "close joint `A`"),
        ("HIERARCHY\nROOT A\nOFFSET 0 0 0\n", 3, 1, "expected `{`"),
        ("HIERARCHY\nROOT\n{\n}\n", 2, 1, "joint name"),
        ("HIERARCHY\nROOT A\n{\nOFFSET 0 0 0\nEnd Sight\n{\n}\n}\n", 5, 5, "`Site`"),
        (
            "HIERARCHY\nROOT A\n{\nOFFSET 0 0 0\nEnd Site\n{\nCHANNELS 1 Xrotation\n}\n}\n",
            7,
            1,
            "End Site has no CHANNELS",
        ),
        ("HIERARCHY\nROOT A\n{\nOFFSET 0 0 0\n}\nHIERARCHY\n", 6, 1, "second HIERARCHY"),
        ("HIERARCHY\nROOT A\n{\nOFFSET 0 0 0\n}\nMOTION\nFrames: lots\n", 7, 9, "whole number"),
        (
            "HIERARCHY\nROOT A\n{\nOFFSET 0 0 0\n}\nMOTION\nFrames: 1\nFrame Time: soon\n",
            8,
            13,
            "number after Frame Time",
        ),
    ];
    for &(src, line, column, needle) in cases {
        let e = err(src);
        assert_eq!((e.line, e.column), (line, column), "{src:?}: {e}");
        assert!(e.message.contains(needle), "{src:?}: {e}");
    }
}

#[test]
fn row_errors_partial_too_long_and_garbage() {
    let ch = "CHANNELS 3 Xposition Yposition Zposition";
    let e = err(&one_joint(ch, "1 2 3\n1 2 3\n1 2\n", 3));
    assert_eq!((e.line, e.column), (16, 4));
    let e = err(&one_joint(ch, "1 2 3 4\n", 1));
    assert_eq!((e.line, e.column), (14, 7));
    assert!(e.message.contains("more than 3"));
    let e = err(&one_joint(ch, "1 2 3\n1 abc 3\n", 2));
    assert_eq!((e.line, e.column), (15, 3));
    assert!(e.message.contains("`abc`"), "{e}");
    let e = err(&one_joint(ch, "1 2 3\n1 2.5.5 3\n", 2));
    assert_eq!((e.line, e.column), (15, 3));
}

#[test]
fn msvc_nan_and_decimal_commas_are_read_with_warnings() {
    let clip = parse(
        one_joint("CHANNELS 3 Xposition Yposition Zposition", "1.#QNAN0 -1.#IND00 1.#INF00\n0,5 -2,25 3\n", 2)
            .as_bytes(),
    )
    .unwrap();
    let row0 = clip.channel_values(0);
    assert!(row0[0].is_nan() && row0[1].is_nan() && row0[2] == f32::INFINITY);
    assert_eq!(clip.channel_values(1), &[0.5, -2.25, 3.0]);
    assert!(
        clip.warnings.iter().any(|w| w.message.contains("decimal comma") && w.line == Some(15)),
        "{:?}",
        clip.warnings
    );
    assert!(clip.warnings.iter().any(|w| w.message.contains("NaN") && w.line == Some(14)));
    // Other junk is still an error.
    assert!(parse(one_joint("CHANNELS 1 Xposition", "1.#WAT\n", 1).as_bytes()).is_err());
    assert!(parse(one_joint("CHANNELS 1 Xposition", "1,2,3\n", 1).as_bytes()).is_err());
}

#[test]
fn non_finite_values_warn() {
    let clip = parse(one_joint("CHANNELS 3 Xposition Yposition Zposition", "1 nan 3\n", 1).as_bytes()).unwrap();
    assert!(clip.warnings.iter().any(|w| w.message.contains("NaN") && w.line == Some(14)));
}

#[test]
fn dos_eof_and_nul_padding_and_float_frame_count() {
    let mut src = one_joint("CHANNELS 1 Xposition", "1\r\n2\r\n", 2).replace("Frames: 2", "Frames: 2.0").into_bytes();
    src.extend_from_slice(b"\x1a\0\0");
    let clip = parse(&src).unwrap();
    assert_eq!(clip.frame_count(), 2);
    assert!(clip.warnings.is_empty(), "{:?}", clip.warnings);
}

#[test]
fn end_site_with_a_glued_suffix_is_a_named_end_site() {
    let src = "HIERARCHY\nROOT A\n{\nOFFSET 0 0 0\nCHANNELS 1 Xrotation\nEnd Site4\n{\nOFFSET 0 1 0\n}\n}\nMOTION\nFrames: 1\nFrame Time: 0.1\n5\n";
    let clip = parse(src.as_bytes()).unwrap();
    assert!(clip.skeleton().is_end_site(1));
    assert_eq!(clip.skeleton().joints()[1].name, "Site4");
    assert!(
        err("HIERARCHY\nROOT A\n{\nOFFSET 0 0 0\nEnd Sight\n{\nOFFSET 0 1 0\n}\n}\n")
            .message
            .contains("expected `Site` after `End`")
    );
}

#[test]
fn utf8_bom_and_leading_blank_lines() {
    let src = format!("\u{feff}\n\n{}", one_joint("CHANNELS 1 Xposition", "1\n", 1));
    assert_eq!(parse(src.as_bytes()).unwrap().frame_count(), 1);
}

#[test]
fn load_dispatch_and_error_display() {
    let e = mocap::load_one("bad.bvh", b"HIERARCHY\nROOT A\n{\nOFFSET 0 q 0\n").unwrap_err();
    assert_eq!(e.to_string(), "bad.bvh:4:10: expected the y value of OFFSET (a number), found `q`");
    assert!(matches!(mocap::load_one("x.png", b"\x89PNG"), Err(mocap::LoadError::LoneImage { .. })));
    assert!(matches!(mocap::load_one("x.exe", b"MZ\x90\0"), Err(mocap::LoadError::UnknownFormat { .. })));
    assert!(mocap::load_one("noext", one_joint("CHANNELS 0", "", 0).as_bytes()).is_ok());
    // The content decides, not the extension.
    assert_eq!(
        mocap::load_one("walk.txt", one_joint("CHANNELS 1 Xposition", "1\n", 1).as_bytes()).unwrap().frame_count(),
        1
    );
    assert_eq!(mocap::Format::detect("x.bvh", b"Segment: a\n"), Some(mocap::Format::Bva));
    assert_eq!(mocap::Format::detect("x.bvh", b":version 1.10\n"), Some(mocap::Format::Asf));
    assert_eq!(
        mocap::Format::detect("take.bvh", b"# c\n:FULLY-SPECIFIED\n:DEGREES\n1\nroot 0\n"),
        Some(mocap::Format::Amc)
    );
    assert_eq!(mocap::Format::detect("x.amc", b"HIERARCHY\n"), Some(mocap::Format::Bvh));
}

#[test]
fn big_input_parsed_in_parallel_matches_sequential_and_reports_lines() {
    // > 1 MiB so that the row parser splits into chunks.
    let ch = "CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation";
    let mut rows = String::new();
    for i in 0..60_000 {
        rows.push_str(&format!("{i} {}.25 -{i}e-3 1 2 3\r\n", i % 7));
    }
    let clip = parse(one_joint(ch, &rows, 60_000).as_bytes()).unwrap();
    assert_eq!(clip.frame_count(), 60_000);
    assert_eq!(clip.channel_values(59_999)[0], 59_999.0);
    assert_eq!(clip.channel_values(40_000)[2], -40.0);
    // An error deep in the second half still gets its exact line.
    let bad = rows.replacen("50000 ", "50000 oops ", 1);
    let e = err(&one_joint(ch, &bad, 60_000));
    assert_eq!(e.line, 14 + 50_000, "{e}");
    // With errors in several pieces, the first in the file is the one reported.
    let two = bad.replacen("20000 ", "20000 1 ", 1);
    let e = err(&one_joint(ch, &two, 60_000));
    assert_eq!((e.line, e.message.contains("more than 6 values")), (14 + 20_000, true), "{e}");
}

#[test]
fn a_root_written_joint_reads_as_the_root_with_one_warning() {
    // What some Mixamo-to-BVH converters write: `JOINT` where `ROOT` belongs, twice
    // (two skeletons), otherwise an ordinary file.
    let src = one_joint("CHANNELS 3 Xposition Yposition Zposition", "1 2 3\n4 5 6\n", 2).replacen("ROOT", "JOINT", 1);
    let two = src.replacen("MOTION", "JOINT Second\n{\n\tOFFSET 0 0 0\n}\nMOTION", 1);
    let clip = parse(two.as_bytes()).expect("a top-level JOINT is a root");
    let roots: Vec<&str> =
        clip.skeleton().joints().iter().filter(|j| j.parent.is_none()).map(|j| j.name.as_str()).collect();
    assert_eq!(roots, ["Hips", "Second"]);
    assert_eq!(clip.frame_count(), 2);
    let joint_warnings: Vec<_> = clip.warnings.iter().filter(|w| w.message.contains("written JOINT")).collect();
    assert_eq!(joint_warnings.len(), 1, "{:?}", clip.warnings);
    assert_eq!(joint_warnings[0].line, Some(2));
    // The same file with ROOT reads to the same skeleton and motion, without the warning.
    let plain = parse(src.replacen("JOINT", "ROOT", 1).as_bytes()).unwrap();
    assert!(plain.warnings.is_empty(), "{:?}", plain.warnings);
    // A JOINT inside a joint is still a child.
    assert!(parse(one_joint("CHANNELS 0", "\n", 1).replace("End Site", "JOINT Child").as_bytes()).is_ok());
}
