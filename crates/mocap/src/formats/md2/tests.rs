use super::*;

#[test]
fn base_names_follow_the_quake_convention() {
    for (name, base) in [
        ("run1", "run"),
        ("run6", "run"),
        ("stand01", "stand"),
        ("stand40", "stand"),
        ("pain101", "pain1"),
        ("pain201", "pain2"),
        ("death308", "death3"),
        ("crattak1", "crattak"),
        ("glide14", "glide"),
        ("jump", "jump"),
        ("", ""),
        ("123", "1"),
        ("12", "12"),
        ("a1b2", "a1b"),
    ] {
        assert_eq!(animation_base_name(name), base, "{name}");
    }
}

#[test]
fn grouping_is_by_consecutive_base_names() {
    let names = ["stand01", "stand02", "run1", "run2", "run3", "pain101", "pain102", "pain201", "stand03", "x"];
    let got: Vec<_> = group_animations(names).into_iter().map(|a| (a.name, a.first, a.last)).collect();
    let want = [("stand", 0, 1), ("run", 2, 4), ("pain1", 5, 6), ("pain2", 7, 7), ("stand", 8, 8), ("x", 9, 9)];
    assert_eq!(got, want.map(|(n, a, b)| (n.to_string(), a, b)));
    assert!(group_animations([]).is_empty());
}

#[test]
fn normal_table_is_unit_and_symmetric() {
    for (i, n) in NORMALS.iter().enumerate() {
        let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        assert!((len - 1.0).abs() < 1e-5, "{i}: {n:?}");
        // The table is closed under negation.
        assert!(NORMALS.iter().any(|m| (0..3).all(|k| (m[k] + n[k]).abs() < 1e-6)), "{i}: {n:?}");
    }
    assert_eq!(NORMALS[5], [0.0, 0.0, 1.0]);
    assert_eq!(to_y_up(NORMALS[5]), [0.0, 1.0, 0.0]);
}

#[test]
fn y_up_is_a_proper_rotation() {
    let (x, y) = (to_y_up([1.0, 0.0, 0.0]), to_y_up([0.0, 1.0, 0.0]));
    let z = to_y_up([0.0, 0.0, 1.0]);
    // x × y = z survives the mapping (right-handed stays right-handed).
    let cross = [x[1] * y[2] - x[2] * y[1], x[2] * y[0] - x[0] * y[2], x[0] * y[1] - x[1] * y[0]];
    assert_eq!(cross, z);
    assert_eq!(z, [0.0, 1.0, 0.0]);
}

#[test]
fn errors_point_at_the_byte() {
    let e = parse(b"IDP3").unwrap_err();
    assert_eq!((e.line, e.column), (0, 0), "binary: the offset is in the message");
    assert!(e.message.starts_with("byte 0: not an MD2 file"), "{e}");
    assert!(e.to_string().starts_with("byte 0: "), "shown without a line:column: {e}");
    let mut header = b"IDP2".to_vec();
    header.extend(8i32.to_le_bytes());
    let e = parse(&header).unwrap_err();
    assert!(e.message.starts_with("byte 8: the file ends inside"), "{e}");
}
