//! Acclaim ASF (skeleton) and AMC (motion): pure parsers from bytes into
//! format-specific structs.
//!
//! [`parse_asf`] reads a skeleton into an [`Asf`]; [`parse_amc`] reads a motion
//! into an [`Amc`] given the row layout of a skeleton ([`Asf::amc_layout`]). Both
//! accept LF, CRLF and lone-CR line endings, a UTF-8 byte-order mark, tabs, `#`
//! comments and numbers in scientific notation (`3.64024e-015`). Problems that leave
//! the data usable become [`Warning`]s; the rest are [`ParseError`]s with a 1-based
//! line and byte column.
//!
//! ```
//! let asf = b":root\n order TX TY TZ RX RY RZ\n axis XYZ\n position 0 0 0\n orientation 0 0 0\n\
//! :bonedata\n begin\n  id 1\n  name spine\n  direction 0 1 0\n  length 2\n  axis 0 0 0 XYZ\n  dof rx\n end\n\
//! :hierarchy\n begin\n  root spine\n end\n";
//! let skeleton = mocap::formats::acclaim::parse_asf(asf).unwrap();
//! let amc = b":FULLY-SPECIFIED\n:DEGREES\n1\nroot 0 0 0 0 0 0\nspine 45\n";
//! let motion = mocap::formats::acclaim::parse_amc(amc, &skeleton.amc_layout()).unwrap();
//! assert_eq!(motion.frame_count, 1);
//! assert_eq!(motion.data[6], 45.0);
//! ```

mod amc;
mod asf;
mod text;

mod model;

pub use amc::{Amc, parse_amc, sniff_amc};
pub use asf::{Asf, AsfBone, AsfRoot, AsfUnits, parse_asf, sniff_asf};
pub use model::{AMC_FRAME_TIME, AcclaimSkeleton, axis_frame, skeleton};

pub use crate::error::{ParseError, Warning};

pub use crate::model::channel::AngleUnit;

/// One Acclaim degree of freedom, as in `dof` and `order` lines.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Dof {
    /// Translation along X.
    Tx,
    /// Translation along Y.
    Ty,
    /// Translation along Z.
    Tz,
    /// Rotation about X.
    Rx,
    /// Rotation about Y.
    Ry,
    /// Rotation about Z.
    Rz,
    /// Change of bone length.
    L,
}

impl Dof {
    /// Reads a degree of freedom by name, in any case (`TX`, `rx`, `l`).
    pub fn from_name(name: &[u8]) -> Option<Dof> {
        let dof = match name {
            [a, b] => match (a.to_ascii_lowercase(), b.to_ascii_lowercase()) {
                (b't', b'x') => Dof::Tx,
                (b't', b'y') => Dof::Ty,
                (b't', b'z') => Dof::Tz,
                (b'r', b'x') => Dof::Rx,
                (b'r', b'y') => Dof::Ry,
                (b'r', b'z') => Dof::Rz,
                _ => return None,
            },
            [b'l' | b'L'] => Dof::L,
            _ => return None,
        };
        Some(dof)
    }

    /// The lower-case name as written in ASF files (`tx`, `rx`, `l`).
    pub fn name(self) -> &'static str {
        match self {
            Dof::Tx => "tx",
            Dof::Ty => "ty",
            Dof::Tz => "tz",
            Dof::Rx => "rx",
            Dof::Ry => "ry",
            Dof::Rz => "rz",
            Dof::L => "l",
        }
    }
}

/// Axis order of an `axis` line, e.g. `XYZ`: the first letter is applied first
/// (extrinsic). Holds the three axes with 0 = X, 1 = Y, 2 = Z; always a permutation.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct AxisOrder(pub [u8; 3]);

impl Default for AxisOrder {
    /// `XYZ`.
    fn default() -> AxisOrder {
        AxisOrder([0, 1, 2])
    }
}

impl AxisOrder {
    /// Reads an order such as `XYZ` or `zyx`: three distinct letters X, Y, Z in any case.
    pub fn from_name(name: &[u8]) -> Option<AxisOrder> {
        let [a, b, c] = name else { return None };
        let axis = |l: &u8| match l.to_ascii_uppercase() {
            b'X' => Some(0u8),
            b'Y' => Some(1),
            b'Z' => Some(2),
            _ => None,
        };
        let order = [axis(a)?, axis(b)?, axis(c)?];
        (order[0] != order[1] && order[0] != order[2] && order[1] != order[2]).then_some(AxisOrder(order))
    }

    /// The order as upper-case letters, e.g. `"XYZ"`.
    pub fn name(self) -> String {
        self.0.iter().map(|&a| char::from(b"XYZ".get(usize::from(a)).copied().unwrap_or(b'?'))).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::PathBuf;

    /// The example of the module documentation (doctests are not part of `--lib` runs).
    #[test]
    fn module_example() {
        let asf = b":root\n order TX TY TZ RX RY RZ\n axis XYZ\n position 0 0 0\n orientation 0 0 0\n\
:bonedata\n begin\n  id 1\n  name spine\n  direction 0 1 0\n  length 2\n  axis 0 0 0 XYZ\n  dof rx\n end\n\
:hierarchy\n begin\n  root spine\n end\n";
        let skeleton = parse_asf(asf).unwrap();
        let amc = b":FULLY-SPECIFIED\n:DEGREES\n1\nroot 0 0 0 0 0 0\nspine 45\n";
        let motion = parse_amc(amc, &skeleton.amc_layout()).unwrap();
        assert_eq!(motion.frame_count, 1);
        assert_eq!(motion.data[6], 45.0);
    }

    /// Every prefix and many one-byte edits of valid files: errors, never panics.
    #[test]
    fn truncated_and_edited_inputs_do_not_panic() {
        let asf: &[u8] = b"# c\r\n:version 1\n:units\n angle rad\n:documentation\n doc\n:root\n order TX RX\n axis XYZ\n position 0 0 0\n orientation 0 0 0\n\
:bonedata\n begin\n  id 1\n  name a\n  direction 0 1 0\n  length 1\n  axis 0 0 0 XYZ\n  dof rx l\n  limits (-1 1)\n (-inf inf)\n end\n\
 begin\n  name b\n  dof ry\n end\n:hierarchy\n begin\n  root a\n  a b\n end\n";
        let amc: &[u8] =
            b":FULLY-SPECIFIED\r\n:DEGREES\r\n1\r\nroot 1 2\r\na 3 4e-015\r\nb 5\r\n2\r\nb 6\r\nroot 7 8\r\n";
        let layout = [("root", 2), ("a", 2), ("b", 1)];
        let edits: [&[u8]; 8] = [b"", b" ", b"\n", b"\r", b"(", b")", b":", b"#"];
        let mut buf = Vec::new();
        for src in [asf, amc] {
            for cut in 0..=src.len() {
                let head = src.get(..cut).unwrap_or(src);
                let _ = parse_asf(head);
                let _ = parse_amc(head, &layout);
                let _ = (sniff_asf(head), sniff_amc(head));
                for edit in edits {
                    buf.clear();
                    buf.extend_from_slice(head);
                    buf.extend_from_slice(edit);
                    buf.extend_from_slice(src.get(cut + 1..).unwrap_or(&[]));
                    let _ = parse_asf(&buf);
                    let _ = parse_amc(&buf, &layout);
                }
            }
        }
        assert!(parse_asf(asf).is_ok());
        assert_eq!(parse_amc(amc, &layout).map(|m| m.frame_count), Ok(2));
    }

    #[test]
    fn dof_and_axis_names() {
        assert_eq!(Dof::from_name(b"TX"), Some(Dof::Tx));
        assert_eq!(Dof::from_name(b"rz"), Some(Dof::Rz));
        assert_eq!(Dof::from_name(b"l"), Some(Dof::L));
        assert_eq!(Dof::from_name(b"L"), Some(Dof::L));
        assert_eq!(Dof::from_name(b"rw"), None);
        assert_eq!(Dof::from_name(b""), None);
        assert_eq!(AxisOrder::from_name(b"XYZ"), Some(AxisOrder([0, 1, 2])));
        assert_eq!(AxisOrder::from_name(b"zxy"), Some(AxisOrder([2, 0, 1])));
        assert_eq!(AxisOrder::from_name(b"XXZ"), None);
        assert_eq!(AxisOrder::from_name(b"XY"), None);
        assert_eq!(AxisOrder([1, 2, 0]).name(), "YZX");
    }

    /// The `asf_amc` folder of the shared corpus: `$MOCAP_CORPUS/asf_amc`, else the
    /// first `shared/corpus/asf_amc` found walking up from this crate.
    fn corpus_dir() -> Option<PathBuf> {
        if let Some(dir) = std::env::var_os("MOCAP_CORPUS") {
            let dir = PathBuf::from(dir).join("asf_amc");
            return dir.is_dir().then_some(dir);
        }
        PathBuf::from(env!("CARGO_MANIFEST_DIR"))
            .ancestors()
            .map(|a| a.join("shared/corpus/asf_amc"))
            .find(|d| d.is_dir())
    }

    fn read(path: &std::path::Path) -> Vec<u8> {
        std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
    }

    #[test]
    fn corpus_files_parse() {
        let Some(dir) = corpus_dir() else {
            if std::env::var_os("MOCAP_SKIP_CORPUS").is_some_and(|v| v == "1") {
                return;
            }
            panic!(
                "corpus folder shared/corpus/asf_amc not found: set MOCAP_CORPUS to the corpus folder, or MOCAP_SKIP_CORPUS=1 to skip"
            );
        };
        let mut asf_count = 0;
        let mut amc_count = 0;
        for sub in ["cmu", "handmade"] {
            let Ok(entries) = std::fs::read_dir(dir.join(sub)) else { continue };
            let mut paths: Vec<PathBuf> = entries.filter_map(|e| e.ok().map(|e| e.path())).collect();
            paths.sort();
            for path in &paths {
                let name = path.file_name().and_then(|n| n.to_str()).unwrap_or("").to_owned();
                if name.ends_with(".asf") {
                    let asf = parse_asf(&read(path)).unwrap_or_else(|e| panic!("{name}:{e}"));
                    assert!(sniff_asf(&read(path)), "{name}");
                    asf_count += 1;
                    for (i, bone) in asf.bones.iter().enumerate() {
                        assert!(bone.parent.is_none_or(|p| p < i), "{name}: parent after child");
                    }
                } else if name.ends_with(".amc") {
                    let skeleton_name = format!("{}.asf", name.split('_').next().unwrap_or(""));
                    let asf = parse_asf(&read(&path.with_file_name(&skeleton_name)))
                        .unwrap_or_else(|e| panic!("{skeleton_name}:{e}"));
                    let bytes = read(path);
                    assert!(sniff_amc(&bytes), "{name}");
                    let amc = parse_amc(&bytes, &asf.amc_layout()).unwrap_or_else(|e| panic!("{name}:{e}"));
                    assert!(amc.warnings.is_empty(), "{name}: {:?}", amc.warnings);
                    assert!(amc.fully_specified);
                    assert_eq!(amc.angle, AngleUnit::Degrees);
                    assert_eq!(amc.first_frame_number, Some(1));
                    assert_eq!(amc.data.len(), amc.frame_count * asf.amc_width());
                    let want = match name.as_str() {
                        "01_01.amc" => Some(2751),
                        "01_06.amc" => Some(5133),
                        "02_01.amc" => Some(343),
                        _ => None,
                    };
                    if let Some(want) = want {
                        assert_eq!(amc.frame_count, want, "{name}");
                    }
                    amc_count += 1;
                }
            }
        }
        assert!(
            asf_count >= 3 && amc_count >= 3,
            "found {asf_count} ASF and {amc_count} AMC files in {}",
            dir.display()
        );

        let one = parse_asf(&read(&dir.join("cmu/01.asf"))).unwrap_or_else(|e| panic!("01.asf:{e}"));
        assert_eq!(one.bones.len(), 30);
        assert_eq!(one.version.as_deref(), Some("1.10"));
        assert_eq!(one.name.as_deref(), Some("VICON"));
        assert_eq!(one.units.length, Some(0.45));
        assert_eq!(one.units.angle, AngleUnit::Degrees);
        assert_eq!(one.root.order, vec![Dof::Tx, Dof::Ty, Dof::Tz, Dof::Rx, Dof::Ry, Dof::Rz]);
        assert!(one.documentation.starts_with(".ast/.asf automatically generated"));
        assert!(one.warnings.is_empty(), "{:?}", one.warnings);
        let lfoot = one.bones.iter().find(|b| b.name == "lfoot").expect("lfoot");
        assert_eq!(lfoot.dofs, vec![Dof::Rx, Dof::Rz]);
        assert_eq!(lfoot.limits, vec![(-45.0, 90.0), (-70.0, 20.0)]);
        assert_eq!(lfoot.axis, [-90.0, 7.62852e-16, 20.0]);
        let ltibia = one.bones.iter().position(|b| b.name == "ltibia");
        assert_eq!(lfoot.parent, ltibia);
        // Root (6) plus 62 bone values per frame.
        assert_eq!(one.amc_width(), 62);
        let amc =
            parse_amc(&read(&dir.join("cmu/01_01.amc")), &one.amc_layout()).unwrap_or_else(|e| panic!("01_01.amc:{e}"));
        assert_eq!(amc.data.get(..3), Some(&[9.37216, 17.8693, -17.3198][..]));
        let rclavicle = one.amc_layout().iter().take_while(|(n, _)| *n != "rclavicle").map(|(_, w)| w).sum::<usize>();
        assert_eq!(amc.data.get(rclavicle..rclavicle + 2), Some(&[3.64024e-15, -6.75868e-15][..]));

        let simple =
            parse_asf(&read(&dir.join("handmade/simple_test.asf"))).unwrap_or_else(|e| panic!("simple_test.asf:{e}"));
        assert_eq!(simple.bones.len(), 1);
        assert!(simple.bones[0].dofs.is_empty());
        assert!(simple.bones[0].limits.is_empty());
        assert_eq!(simple.bones[0].parent, None);
        assert_eq!(simple.documentation, "Test documentation.\nThis file contains 2 bones.");
    }
}
