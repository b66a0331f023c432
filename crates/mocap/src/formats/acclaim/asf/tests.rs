use super::*;

const SMALL: &str = "# AST/ASF test skeleton
:version 1.10
:name TEST
:units
  mass 1.0
  length 0.45
  angle deg
  time 120 fps
:documentation
   Line one.
   Line two.
:root
   axis XYZ
   order TX TY TZ RX RY RZ
   position 0 0 1
   orientation 0 0 0
:bonedata
  begin
 id 1
 name hip
 direction 0 -1 0
 length 2.5
 axis 0 0 20\tXYZ
 dof rx ry rz
 limits (-160.0 20.0)
        (-inf inf)
        (-60.0 70.0)
  end
  begin
 id 2
 name knee
 direction 0 -1 0
 length 3e0
 axis 0 0 7.62852e-016 ZYX
 dof RX l
 limits (-10 170) (0 inf)
 bodymass 2.5
 cofmass 0.5
  end
:hierarchy
  begin
root hip
hip knee
  end
";

fn check_small(asf: &Asf) {
    assert_eq!(asf.version.as_deref(), Some("1.10"));
    assert_eq!(asf.name.as_deref(), Some("TEST"));
    assert_eq!(
        asf.units,
        AsfUnits {
            mass: Some(1.0),
            length: Some(0.45),
            angle: AngleUnit::Degrees,
            other: vec![("time".into(), "120 fps".into())]
        }
    );
    assert_eq!(asf.documentation, "Line one.\nLine two.");
    assert_eq!(
        asf.root,
        AsfRoot {
            order: vec![Dof::Tx, Dof::Ty, Dof::Tz, Dof::Rx, Dof::Ry, Dof::Rz],
            axis: AxisOrder([0, 1, 2]),
            position: [0.0, 0.0, 1.0],
            orientation: [0.0; 3]
        }
    );
    assert_eq!(asf.bones.len(), 2);
    let hip = &asf.bones[0];
    assert_eq!((hip.id, hip.name.as_str(), hip.line, hip.parent), (Some(1), "hip", 18, None));
    assert_eq!(hip.direction, [0.0, -1.0, 0.0]);
    assert_eq!(hip.length, 2.5);
    assert_eq!(hip.axis, [0.0, 0.0, 20.0]);
    assert_eq!(hip.dofs, vec![Dof::Rx, Dof::Ry, Dof::Rz]);
    assert_eq!(hip.limits, vec![(-160.0, 20.0), (f32::NEG_INFINITY, f32::INFINITY), (-60.0, 70.0)]);
    assert_eq!((hip.bodymass, hip.cofmass), (None, None));
    let knee = &asf.bones[1];
    assert_eq!((knee.id, knee.name.as_str(), knee.line, knee.parent), (Some(2), "knee", 29, Some(0)));
    assert_eq!(knee.length, 3.0);
    assert_eq!(knee.axis, [0.0, 0.0, 7.62852e-16]);
    assert_eq!(knee.axis_order, AxisOrder([2, 1, 0]));
    assert_eq!(knee.dofs, vec![Dof::Rx, Dof::L]);
    assert_eq!(knee.limits, vec![(-10.0, 170.0), (0.0, f32::INFINITY)]);
    assert_eq!((knee.bodymass, knee.cofmass), (Some(2.5), Some(0.5)));
    assert!(asf.warnings.is_empty(), "{:?}", asf.warnings);
    assert_eq!(asf.amc_layout(), vec![("root", 6), ("hip", 3), ("knee", 2)]);
    assert_eq!(asf.amc_width(), 11);
    assert_eq!(asf.bone_index("knee"), Some(1));
}

#[test]
fn small_skeleton_with_lf_crlf_and_cr() {
    check_small(&parse_asf(SMALL.as_bytes()).unwrap());
    check_small(&parse_asf(SMALL.replace('\n', "\r\n").as_bytes()).unwrap());
    check_small(&parse_asf(SMALL.replace('\n', "\r").as_bytes()).unwrap());
    let mut bom = b"\xEF\xBB\xBF".to_vec();
    bom.extend_from_slice(SMALL.as_bytes());
    check_small(&parse_asf(&bom).unwrap());
    assert!(sniff_asf(SMALL.as_bytes()));
    assert!(sniff_asf(&bom));
    assert!(!sniff_asf(b"HIERARCHY\nROOT a\n"));
    assert!(!sniff_asf(b"# only a comment\n"));
}

const ROOT: &str = ":root\n order TX TY TZ RX RY RZ\n axis XYZ\n position 0 0 0\n orientation 0 0 0\n";

/// Parses `ROOT` + `rest`, expecting an error.
fn fail(rest: &str) -> ParseError {
    match parse_asf(format!("{ROOT}{rest}").as_bytes()) {
        Ok(asf) => panic!("expected an error, parsed {asf:?}"),
        Err(e) => e,
    }
}

fn at(e: &ParseError, line: u32, column: u32, words: &str) {
    assert_eq!((e.line, e.column), (line, column), "{e}");
    assert!(e.message.contains(words), "`{}` does not say `{words}`", e.message);
}

/// A bone block (starting on line 7 when it follows `ROOT` and `:bonedata`).
const BONE_A: &str = " begin\n  name a\n  direction 0 1 0\n  length 1\n  axis 0 0 0 XYZ\n  dof rx ry\n end\n";

#[test]
fn missing_root() {
    let e = parse_asf(b":bonedata\n begin\n  name a\n end\n:hierarchy\n begin\n  root a\n end\n").unwrap_err();
    at(&e, 9, 1, "no :root section");
    let e = parse_asf(b"").unwrap_err();
    at(&e, 1, 1, "no :root section");
}

#[test]
fn unknown_keyword_in_bone() {
    let e = fail(":bonedata\n begin\n  name a\n  colour red\n end\n");
    at(&e, 9, 3, "unknown keyword `colour` of bone `a`: expected id, name");
}

#[test]
fn not_a_number() {
    let e = fail(":bonedata\n begin\n  name a\n  length 1.5.2\n end\n");
    at(&e, 9, 10, "expected the bone length (a number), found `1.5.2`");
    let e = fail(":bonedata\n begin\n  name a\n  direction 0 x 0\n end\n");
    at(&e, 9, 15, "expected the y value of direction (a number), found `x`");
    let e = fail(":bonedata\n begin\n  name a\n  id one\n end\n");
    at(&e, 9, 6, "bone id (an integer)");
    let e = fail(":bonedata\n begin\n  name a\n  length nan\n end\n");
    at(&e, 9, 10, "finite number");
    let e = fail(":bonedata\n begin\n  name a\n  direction 0 inf 0\n end\n");
    at(&e, 9, 15, "finite number");
    let e = fail(":bonedata\n begin\n  name a\n  dof rx\n  limits (0 nan)\n end\n");
    at(&e, 10, 13, "maximum of a limit pair");
    let e = parse_asf(b":units\n  length x\n").unwrap_err();
    at(&e, 2, 10, "expected the length unit");
    let e = parse_asf(b":root\n position 0 0\n orientation 0 0 0\n").unwrap_err();
    at(&e, 3, 2, "the z value of the root position (a number), found `orientation`");
}

#[test]
fn limits_count_must_match_dofs() {
    let e = fail(":bonedata\n begin\n  name a\n  dof rx ry\n  limits (0 1)\n end\n");
    at(&e, 10, 3, "bone `a` has 2 degrees of freedom but `limits` gives 1 (min max) pairs");
    let e = fail(":bonedata\n begin\n  name a\n  dof rx\n  limits (0 1) (2 3)\n end\n");
    at(&e, 10, 3, "has 1 degrees of freedom but `limits` gives 2");
    let e = fail(":bonedata\n begin\n  name a\n  dof rx\n  limits 0 1\n end\n");
    at(&e, 10, 10, "expected `(`");
    let e = fail(":bonedata\n begin\n  name a\n  dof rx\n  limits (0 1\n end\n");
    at(&e, 11, 2, "expected `)` to close a limit pair, found `end`");
}

#[test]
fn duplicate_bone_name() {
    let e = fail(&format!(":bonedata\n{BONE_A}{BONE_A}"));
    at(&e, 15, 8, "duplicate bone name `a`: a bone of that name begins at line 7");
}

#[test]
fn hierarchy_names_unknown_bone() {
    let e = fail(&format!(":bonedata\n{BONE_A}:hierarchy\n begin\n  root a\n  a b\n end\n"));
    at(&e, 17, 5, "unknown bone `b` in :hierarchy");
    let e = fail(&format!(":bonedata\n{BONE_A}:hierarchy\n begin\n  root a\n  x a\n end\n"));
    at(&e, 17, 3, "unknown bone `x`");
}

#[test]
fn bone_with_two_parents() {
    let b = BONE_A.replace("name a", "name b");
    let e = fail(&format!(":bonedata\n{BONE_A}{b}:hierarchy\n begin\n  root a b\n  a b\n end\n"));
    at(&e, 24, 5, "bone `b` is given two parents: `root` (line 23) and `a`");
}

#[test]
fn cycle_is_an_error() {
    let b = BONE_A.replace("name a", "name b");
    let e = fail(&format!(":bonedata\n{BONE_A}{b}:hierarchy\n begin\n  a b\n  b a\n end\n"));
    assert_eq!(e.line, 24, "{e}");
    assert!(e.message.contains("cycle"), "{e}");
    let e = fail(&format!(":bonedata\n{BONE_A}:hierarchy\n begin\n  a a\n end\n"));
    at(&e, 16, 5, "its own child");
    let e = fail(&format!(":bonedata\n{BONE_A}:hierarchy\n begin\n  a root\n end\n"));
    at(&e, 16, 5, "`root` cannot be the child");
}

#[test]
fn bone_missing_from_hierarchy() {
    let b = BONE_A.replace("name a", "name b");
    let e = fail(&format!(":bonedata\n{BONE_A}{b}:hierarchy\n begin\n  root a\n end\n"));
    at(&e, 15, 8, "bone `b` is not in :hierarchy");
    let e = fail(&format!(":bonedata\n{BONE_A}{b}:hierarchy\n begin\n  root a\n  b\n end\n"));
    at(&e, 15, 8, "bone `b` is not in :hierarchy");
    let e = fail(&format!(":bonedata\n{BONE_A}"));
    at(&e, 8, 8, "no :hierarchy section");
    let c = BONE_A.replace("name a", "name c");
    let e = fail(&format!(":bonedata\n{BONE_A}{b}{c}:hierarchy\n begin\n  root a\n  b c\n end\n"));
    at(&e, 15, 8, "bone `b` has children in :hierarchy but no parent");
}

#[test]
fn bone_without_name() {
    let e = fail(":bonedata\n begin\n  id 1\n end\n");
    at(&e, 7, 2, "bone without a `name`");
}

#[test]
fn unterminated_begin() {
    let e = fail(":bonedata\n begin\n  name a\n  dof rx\n");
    at(&e, 7, 2, "`begin` at line 7 has no `end`");
    let e = fail(":bonedata\n begin\n  name a\n begin\n  name b\n end\n");
    at(&e, 7, 2, "found `begin` at line 9");
    let e = fail(":bonedata\n begin\n  name a\n:hierarchy\n begin\n  root a\n end\n");
    at(&e, 7, 2, "found `:hierarchy` at line 9");
    let e = fail(&format!(":bonedata\n{BONE_A}:hierarchy\n begin\n  root a\n"));
    at(&e, 15, 2, "`begin` at line 15 has no `end`");
}

#[test]
fn other_syntax_errors() {
    let e = fail(":bonedata\n name a\n");
    at(&e, 7, 2, "expected `begin`");
    let e = parse_asf(b"hello\n:root\n").unwrap_err();
    at(&e, 1, 1, "expected a section keyword");
    let e = fail(":bonedata\n begin\n  name a\n  dof rx rw\n end\n");
    at(&e, 9, 10, "degree of freedom");
    let e = fail(":bonedata\n begin\n  name a\n  axis 0 0 0 XXY\n end\n");
    at(&e, 9, 14, "axis order");
    let e = fail(":bonedata\n begin\n  name root\n end\n");
    at(&e, 8, 8, "cannot be called `root`");
    let e = parse_asf(format!("{ROOT}{ROOT}").as_bytes()).unwrap_err();
    at(&e, 6, 1, "a second :root");
    let e = parse_asf(b":root\n colour red\n").unwrap_err();
    at(&e, 2, 2, "unknown keyword `colour` in :root");
    let e = parse_asf(b":units\n angle grad\n").unwrap_err();
    at(&e, 2, 8, "expected `deg` or `rad`");
}

#[test]
fn windows_media_and_binary_files() {
    let mut wmv = vec![0x30, 0x26, 0xB2, 0x75, 0x8E, 0x66, 0xCF, 0x11, 0xA6, 0xD9, 0x00, 0xAA, 0x00, 0x62, 0xCE, 0x6C];
    wmv.extend_from_slice(&[0x84, 0x01, 0, 0, 0, 0, 0, 0]);
    let e = parse_asf(&wmv).unwrap_err();
    assert_eq!(e, ParseError::new(1, 1, "not an Acclaim skeleton: this looks like a Windows Media (.asf) video file"));
    let e = parse_asf(b"\x7fELF\x02\x01\x01\0\0\0").unwrap_err();
    assert_eq!(e, ParseError::new(1, 1, "not an Acclaim skeleton: binary data"));
    assert!(!sniff_asf(&wmv));
}

#[test]
fn warnings_and_lenient_forms() {
    let src = format!(
        "{ROOT}:bonedata\n begin\n  name a\n  length 2\n  axis 0 0 0\n end\n begin\n  name b\n  length 0\n end\n:skin\n whatever 1 2\n:hierarchy\n begin\n  root a b\n end\n"
    );
    let asf = parse_asf(src.as_bytes()).unwrap();
    let lines: Vec<Option<u32>> = asf.warnings.iter().map(|w| w.line).collect();
    assert_eq!(lines, vec![Some(10), Some(7), Some(16)], "{:?}", asf.warnings);
    assert!(asf.warnings[0].message.contains("without an order"));
    assert!(asf.warnings[1].message.contains("zero direction"));
    assert!(asf.warnings[2].message.contains("unknown section `:skin`"));
    assert_eq!(asf.bones[0].axis_order, AxisOrder([0, 1, 2]));
    assert!(asf.bones[1].dofs.is_empty() && asf.bones[1].limits.is_empty());
    // `:units angle rad`, keywords in upper case, tabs, comments after values.
    let asf = parse_asf(b":UNITS\n\tANGLE\trad # radians\n:ROOT\n ORDER tx ty tz\n").unwrap();
    assert_eq!(asf.units.angle, AngleUnit::Radians);
    assert_eq!(asf.root.order, vec![Dof::Tx, Dof::Ty, Dof::Tz]);
    assert!(asf.bones.is_empty());
}

#[test]
fn bones_are_reordered_parents_first() {
    let bone = |n: &str| BONE_A.replace("name a", &format!("name {n}"));
    let src = format!(
        "{ROOT}:bonedata\n{}{}{}{}:hierarchy\n begin\n  root c\n  c b d\n  b a\n end\n",
        bone("a"),
        bone("b"),
        bone("c"),
        bone("d")
    );
    let asf = parse_asf(src.as_bytes()).unwrap();
    let names: Vec<&str> = asf.bones.iter().map(|b| b.name.as_str()).collect();
    assert_eq!(names, ["c", "b", "a", "d"]);
    let parents: Vec<Option<usize>> = asf.bones.iter().map(|b| b.parent).collect();
    assert_eq!(parents, [None, Some(0), Some(1), Some(0)]);
    assert_eq!(asf.bones[2].line, 7);
    // Already parents-first: the :bonedata order is kept even if :hierarchy lists
    // children in another order.
    let src = format!(
        "{ROOT}:bonedata\n{}{}{}:hierarchy\n begin\n  root a\n  a c b\n end\n",
        bone("a"),
        bone("b"),
        bone("c")
    );
    let names: Vec<String> = parse_asf(src.as_bytes()).unwrap().bones.into_iter().map(|b| b.name).collect();
    assert_eq!(names, ["a", "b", "c"]);
}

#[test]
fn deep_chain_without_recursion() {
    const N: usize = 100_000;
    let mut src = String::from(ROOT);
    src.push_str(":bonedata\n");
    // Children first, so every bone has to be moved.
    for i in (0..N).rev() {
        src.push_str(&format!("begin\nname b{i}\ndirection 0 1 0\nlength 1\naxis 0 0 0 XYZ\ndof rx\nend\n"));
    }
    src.push_str(":hierarchy\nbegin\nroot b0\n");
    for i in 1..N {
        src.push_str(&format!("b{} b{i}\n", i - 1));
    }
    src.push_str("end\n");
    let asf = parse_asf(src.as_bytes()).unwrap();
    assert_eq!(asf.bones.len(), N);
    assert_eq!(asf.bones[0].name, "b0");
    assert_eq!(asf.bones[0].parent, None);
    assert_eq!(asf.bones[N - 1].name, format!("b{}", N - 1));
    assert!(asf.bones.iter().enumerate().skip(1).all(|(i, b)| b.parent == Some(i - 1)));
}
