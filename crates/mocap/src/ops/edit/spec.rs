//! Edits written as text: one grammar for the command line, the browser and any
//! list of edits kept as strings. [`EditSpec`] reads it ([`std::str::FromStr`])
//! and writes it back ([`std::fmt::Display`]); [`Edit`] does the same for every spec
//! that needs no clip.

use super::Edit;
use crate::model::clip::{Clip, Units};
use glam::{Quat, Vec3};
use std::fmt::{self, Display, Formatter, Write as _};
use std::str::FromStr;

/// An edit as written in text: an [`Edit`], or one that is resolved against the
/// clip it applies to ([`EditSpec::resolve`]).
///
/// # Grammar
///
/// A spec is its name, then its fields, each after a colon:
///
/// | Spec | Edit |
/// |---|---|
/// | `reverse` | [`Edit::Reverse`] |
/// | `ping-pong` | [`Edit::PingPong`] |
/// | `in-place` | [`Edit::InPlace`] (turning kept) |
/// | `in-place-turning` | [`Edit::InPlace`] (turning removed too) |
/// | `trim:A:B` | [`Edit::Trim`]: keep frames A to B, inclusive |
/// | `fps:N` | [`Edit::Resample`] to N frames per second (`fps:N:cubic`: [`Edit::ResampleCubic`]) |
/// | `knit:N` | [`Edit::LoopKnit`] over the last N frames |
/// | `up:AXIS` | [`Edit::UpAxis`]: the file's up is `x`, `y`, `z`, `-x`, `-y` or `-z`; `up-z` is `up:z` |
/// | `scale:F` | [`Edit::Scale`] by F |
/// | `units:U` | [`EditSpec::Units`]: lengths from the clip's guessed unit to `m`, `dm`, `cm`, `mm` or `in` |
/// | `rename:OLD:NEW` | [`Edit::Rename`] |
/// | `remove:JOINT` | [`Edit::RemoveJoint`], its motion folded into its children |
/// | `drop:JOINT` | [`Edit::RemoveJoint`], its motion dropped |
/// | `add:PARENT:NAME:X,Y,Z` | [`Edit::AddJoint`] at that offset |
/// | `offset:NAME:X,Y,Z` | [`Edit::SetOffset`] |
/// | `channels:NAME:ORDER` | [`Edit::SetChannels`]: rotations only, in ORDER (e.g. `ZXY`) |
/// | `channels:NAME:ORDER:position` | [`Edit::SetChannels`]: position channels first |
/// | `correct:FRAME:WINDOW:POSE` | [`Edit::Correct`] |
/// | `key:FRAME:KEYS:POSE` | [`Edit::Key`]; KEYS the other keyed frames, `F,F,…` (may be empty) |
///
/// A POSE is entries separated by `;` (none at all is an empty POSE): `JOINT=X,Y,Z,W`
/// is a joint's local rotation (a quaternion, `W` last), `JOINT=X,Y,Z` its local
/// translation. Frames and counts are whole numbers; the other numbers are decimals
/// (finite), with spaces around them ignored. Names are taken as written; a
/// backslash takes the next character literally, so a name with `:`, `;`, `=`, `,`
/// or `\` in it is written with `\:`, `\;`, `\=`, `\,` or `\\`.
///
/// Reading checks the form only: whether the numbers make sense for the clip (a
/// trim within its frames, a positive rate, a joint that exists) is for
/// [`super::apply`] to say. Writing ([`Display`]) gives the spec that reads back
/// as the same value, escapes included; values no spec can hold (an up axis past 2,
/// a number that is not finite, units `cmu` or `unknown`) are written as they are
/// and do not read back.
///
/// ```
/// use mocap::ops::edit::{Edit, EditSpec};
/// let spec: EditSpec = "trim:0:9".parse().unwrap();
/// assert_eq!(spec, EditSpec::Edit(Edit::Trim { first: 0, last: 9 }));
/// assert_eq!(spec.to_string(), "trim:0:9");
/// // Edits that need no clip also read as an `Edit` directly.
/// assert_eq!("knit:4".parse::<Edit>(), Ok(Edit::LoopKnit { frames: 4 }));
/// let e = "knit:four".parse::<Edit>().unwrap_err();
/// assert_eq!(e.to_string(), "`knit:four`: expected a frame count (knit:N)");
/// ```
#[derive(Clone, Debug, PartialEq)]
pub enum EditSpec {
    /// An edit complete in itself.
    Edit(Edit),
    /// `units:U`: every length converted from the clip's guessed unit
    /// ([`Clip::units`]) to this one: an [`Edit::Scale`] once the clip is known.
    Units(Units),
}

impl EditSpec {
    /// The edit this spec makes on `clip` (only [`EditSpec::Units`] looks at it).
    pub fn resolve(&self, clip: &Clip) -> Edit {
        match self {
            EditSpec::Edit(edit) => edit.clone(),
            EditSpec::Units(target) => {
                Edit::Scale { factor: clip.units().meters_per_unit() / target.meters_per_unit() }
            }
        }
    }
}

impl From<Edit> for EditSpec {
    fn from(edit: Edit) -> EditSpec {
        EditSpec::Edit(edit)
    }
}

/// Why a string is not an edit spec ([`EditSpec`]).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SpecError {
    /// The spec as given.
    pub spec: String,
    /// What was expected where it went wrong, e.g. `a frame count` (no spec syntax
    /// around it, so a caller with its own syntax, such as a command-line flag, can
    /// show it after its own words).
    pub expected: String,
    /// The form of the spec named, e.g. `knit:N`; empty when the name is no edit's.
    pub form: &'static str,
}

impl Display for SpecError {
    fn fmt(&self, f: &mut Formatter<'_>) -> fmt::Result {
        write!(f, "`{}`: expected {}", self.spec, self.expected)?;
        if !self.form.is_empty() {
            write!(f, " ({})", self.form)?;
        }
        Ok(())
    }
}

impl std::error::Error for SpecError {}

/// The forms, for the message about a name that is no edit's.
const FORMS: &str = "reverse, ping-pong, in-place, in-place-turning, trim:A:B, fps:N, knit:N, up:AXIS, scale:F, \
     units:U, rename:OLD:NEW, remove:JOINT, drop:JOINT, add:PARENT:NAME:X,Y,Z, offset:NAME:X,Y,Z, \
     channels:NAME:ORDER[:position], correct:FRAME:WINDOW:POSE or key:FRAME:KEYS:POSE";

/// A name with a colon in it needs a backslash: said where a spec has too many fields.
const COLON: &str = "; a colon in a name is written \\:";

const TRIM: &str = "first and last frames a:b";
const NUMBER: &str = "a number";
const UP: &str = "x, y, z, -x, -y or -z";
const UNITS: &str = "m, dm, cm, mm or in";
const OFFSET: &str = "an offset x,y,z (three numbers)";
const POSE: &str = "a pose: entries JOINT=x,y,z,w (a rotation) or JOINT=x,y,z (a translation), separated by ;";

impl FromStr for EditSpec {
    type Err = SpecError;

    fn from_str(spec: &str) -> Result<EditSpec, SpecError> {
        let fields = split(spec, ':');
        let (name, args) = fields.split_first().map_or(("", &[][..]), |(n, a)| (*n, a));
        let fail =
            |expected: &str, form: &'static str| SpecError { spec: spec.to_owned(), expected: expected.into(), form };
        // The fields of a spec of `form`, `n` of them (`expected` when not).
        let fields = |n: usize, expected: &str, form: &'static str| -> Result<&[&str], SpecError> {
            if args.len() == n { Ok(args) } else { Err(fail(expected, form)) }
        };
        let named = |expected: &str| format!("{expected}{COLON}");
        let edit = match name {
            "reverse" | "ping-pong" | "in-place" | "in-place-turning" | "up-z" => {
                let form = FORM_OF_PLAIN.iter().find(|f| **f == name).copied().unwrap_or("");
                fields(0, &format!("nothing after `{name}`"), form)?;
                match name {
                    "reverse" => Edit::Reverse,
                    "ping-pong" => Edit::PingPong,
                    "in-place" => Edit::InPlace { remove_turning: false },
                    "in-place-turning" => Edit::InPlace { remove_turning: true },
                    _ => Edit::UpAxis { from: 2, negative: false },
                }
            }
            "trim" => {
                const FORM: &str = "trim:A:B";
                let a = fields(2, TRIM, FORM)?;
                let frame = |x: &str| whole(x).ok_or_else(|| fail(TRIM, FORM));
                Edit::Trim { first: frame(a[0])?, last: frame(a[1])? }
            }
            "fps" => {
                const FORM: &str = "fps:N or fps:N:cubic";
                let (a, cubic) = match args.get(1).map(|s| s.trim()) {
                    Some("cubic") => (fields(2, "a frame rate and `cubic`", FORM)?, true),
                    Some("linear") => (fields(2, "a frame rate and `linear`", FORM)?, false),
                    _ => (fields(1, "a frame rate", FORM)?, false),
                };
                let fps = decimal(a[0]).ok_or_else(|| fail(NUMBER, FORM))?;
                if cubic { Edit::ResampleCubic { fps } } else { Edit::Resample { fps } }
            }
            "knit" => {
                const FORM: &str = "knit:N";
                let a = fields(1, "a frame count", FORM)?;
                Edit::LoopKnit { frames: whole(a[0]).ok_or_else(|| fail("a frame count", FORM))? }
            }
            "up" => {
                const FORM: &str = "up:AXIS";
                let a = fields(1, UP, FORM)?;
                let t = a[0].trim().to_ascii_lowercase();
                let (negative, axis) = t.strip_prefix('-').map_or((false, t.as_str()), |a| (true, a));
                let from = ["x", "y", "z"].iter().position(|a| *a == axis).ok_or_else(|| fail(UP, FORM))?;
                Edit::UpAxis { from, negative }
            }
            "scale" => {
                const FORM: &str = "scale:F";
                let a = fields(1, NUMBER, FORM)?;
                Edit::Scale { factor: decimal(a[0]).ok_or_else(|| fail(NUMBER, FORM))? }
            }
            "units" => {
                const FORM: &str = "units:U";
                let a = fields(1, UNITS, FORM)?;
                let units = match a[0].trim() {
                    "m" => Units::Meters,
                    "dm" => Units::Decimeters,
                    "cm" => Units::Centimeters,
                    "mm" => Units::Millimeters,
                    "in" => Units::Inches,
                    _ => return Err(fail(UNITS, FORM)),
                };
                return Ok(EditSpec::Units(units));
            }
            "rename" => {
                let a = fields(2, &named("an old and a new name"), "rename:OLD:NEW")?;
                Edit::Rename { from: unescape(a[0]), to: unescape(a[1]) }
            }
            "remove" | "drop" => {
                let form = if name == "remove" { "remove:JOINT" } else { "drop:JOINT" };
                let a = fields(1, &named("one joint name"), form)?;
                Edit::RemoveJoint { name: unescape(a[0]), fold: name == "remove" }
            }
            "add" => {
                const FORM: &str = "add:PARENT:NAME:X,Y,Z";
                let a = fields(3, &named("a parent, a name and an offset"), FORM)?;
                let offset = vector::<3>(a[2]).map(Vec3::from_array).ok_or_else(|| fail(OFFSET, FORM))?;
                Edit::AddJoint { parent: unescape(a[0]), name: unescape(a[1]), offset }
            }
            "offset" => {
                const FORM: &str = "offset:NAME:X,Y,Z";
                let a = fields(2, &named("a joint name and an offset"), FORM)?;
                let offset = vector::<3>(a[1]).map(Vec3::from_array).ok_or_else(|| fail(OFFSET, FORM))?;
                Edit::SetOffset { name: unescape(a[0]), offset }
            }
            "channels" => {
                const FORM: &str = "channels:NAME:ORDER[:position]";
                let expected = named("a joint name, a rotation order and, for position channels, `position`");
                let position = match args {
                    [_, _] => false,
                    [_, _, "position"] => true,
                    [_, _, _] => return Err(fail("`position` or nothing after the rotation order", FORM)),
                    _ => return Err(fail(&expected, FORM)),
                };
                Edit::SetChannels { name: unescape(args[0]), position, order: unescape(args[1]) }
            }
            "correct" => {
                const FORM: &str = "correct:FRAME:WINDOW:POSE";
                let a = fields(3, &named("a frame, a window and a pose"), FORM)?;
                let frame = whole(a[0]).ok_or_else(|| fail("a frame number", FORM))?;
                let window = whole(a[1]).ok_or_else(|| fail("a window in frames", FORM))?;
                let (rotations, translations) = pose(a[2]).ok_or_else(|| fail(POSE, FORM))?;
                Edit::Correct { frame, rotations, translations, window }
            }
            "key" => {
                const FORM: &str = "key:FRAME:KEYS:POSE";
                let a = fields(3, &named("a frame, the other keys and a pose"), FORM)?;
                let frame = whole(a[0]).ok_or_else(|| fail("a frame number", FORM))?;
                let keys = if a[1].trim().is_empty() {
                    Vec::new()
                } else {
                    a[1].split(',')
                        .map(whole)
                        .collect::<Option<_>>()
                        .ok_or_else(|| fail("the other keyed frames f,f,… (or nothing)", FORM))?
                };
                let (rotations, translations) = pose(a[2]).ok_or_else(|| fail(POSE, FORM))?;
                Edit::Key { frame, rotations, translations, keys }
            }
            _ => return Err(fail(&format!("an edit: {FORMS}"), "")),
        };
        Ok(EditSpec::Edit(edit))
    }
}

/// The specs that are a name alone (their form is the name).
const FORM_OF_PLAIN: [&str; 5] = ["reverse", "ping-pong", "in-place", "in-place-turning", "up-z"];

impl FromStr for Edit {
    type Err = SpecError;

    /// Reads an [`EditSpec`] that needs no clip (any but `units:U`).
    fn from_str(spec: &str) -> Result<Edit, SpecError> {
        match spec.parse::<EditSpec>()? {
            EditSpec::Edit(edit) => Ok(edit),
            EditSpec::Units(_) => Err(SpecError {
                spec: spec.to_owned(),
                expected: "an edit that needs no clip (units depend on the clip's own: read an EditSpec and resolve \
                           it against the clip)"
                    .into(),
                form: "units:U",
            }),
        }
    }
}

impl Display for EditSpec {
    fn fmt(&self, f: &mut Formatter<'_>) -> fmt::Result {
        match self {
            EditSpec::Edit(edit) => edit.fmt(f),
            EditSpec::Units(units) => write!(f, "units:{}", units.name()),
        }
    }
}

impl Display for Edit {
    /// The edit's spec ([`EditSpec`]'s grammar).
    fn fmt(&self, f: &mut Formatter<'_>) -> fmt::Result {
        match self {
            Edit::Trim { first, last } => write!(f, "trim:{first}:{last}"),
            Edit::Resample { fps } => write!(f, "fps:{fps}"),
            Edit::ResampleCubic { fps } => write!(f, "fps:{fps}:cubic"),
            Edit::Reverse => f.write_str("reverse"),
            Edit::PingPong => f.write_str("ping-pong"),
            Edit::LoopKnit { frames } => write!(f, "knit:{frames}"),
            Edit::InPlace { remove_turning: false } => f.write_str("in-place"),
            Edit::InPlace { remove_turning: true } => f.write_str("in-place-turning"),
            Edit::UpAxis { from, negative } => {
                let sign = if *negative { "-" } else { "" };
                match ["x", "y", "z"].get(*from) {
                    Some(axis) => write!(f, "up:{sign}{axis}"),
                    None => write!(f, "up:{sign}{from}"),
                }
            }
            Edit::Scale { factor } => write!(f, "scale:{factor}"),
            Edit::Rename { from, to } => write!(f, "rename:{}:{}", Escaped(from), Escaped(to)),
            Edit::RemoveJoint { name, fold } => {
                write!(f, "{}:{}", if *fold { "remove" } else { "drop" }, Escaped(name))
            }
            Edit::AddJoint { parent, name, offset } => {
                write!(f, "add:{}:{}:{}", Escaped(parent), Escaped(name), Numbers(&offset.to_array()))
            }
            Edit::SetOffset { name, offset } => write!(f, "offset:{}:{}", Escaped(name), Numbers(&offset.to_array())),
            Edit::SetChannels { name, position, order } => {
                write!(f, "channels:{}:{}{}", Escaped(name), Escaped(order), if *position { ":position" } else { "" })
            }
            Edit::Correct { frame, rotations, translations, window } => {
                write!(f, "correct:{frame}:{window}:{}", Pose(rotations, translations))
            }
            Edit::Key { frame, rotations, translations, keys } => {
                write!(f, "key:{frame}:")?;
                for (i, k) in keys.iter().enumerate() {
                    write!(f, "{}{k}", if i > 0 { "," } else { "" })?;
                }
                write!(f, ":{}", Pose(rotations, translations))
            }
        }
    }
}

/// A name or other free text, with `\` before each of `\ : ; = ,`.
struct Escaped<'a>(&'a str);

impl Display for Escaped<'_> {
    fn fmt(&self, f: &mut Formatter<'_>) -> fmt::Result {
        for c in self.0.chars() {
            if matches!(c, '\\' | ':' | ';' | '=' | ',') {
                f.write_char('\\')?;
            }
            f.write_char(c)?;
        }
        Ok(())
    }
}

/// Numbers separated by commas (each the shortest text that reads back exactly).
struct Numbers<'a>(&'a [f32]);

impl Display for Numbers<'_> {
    fn fmt(&self, f: &mut Formatter<'_>) -> fmt::Result {
        for (i, x) in self.0.iter().enumerate() {
            write!(f, "{}{x}", if i > 0 { "," } else { "" })?;
        }
        Ok(())
    }
}

/// A POSE: rotations, then translations.
struct Pose<'a>(&'a [(String, Quat)], &'a [(String, Vec3)]);

impl Display for Pose<'_> {
    fn fmt(&self, f: &mut Formatter<'_>) -> fmt::Result {
        let rotations = self.0.iter().map(|(name, q)| (name, q.to_array().to_vec()));
        let translations = self.1.iter().map(|(name, t)| (name, t.to_array().to_vec()));
        for (i, (name, values)) in rotations.chain(translations).enumerate() {
            write!(f, "{}{}={}", if i > 0 { ";" } else { "" }, Escaped(name), Numbers(&values))?;
        }
        Ok(())
    }
}

/// `s` cut at each `sep` not escaped by a backslash (escapes are kept).
fn split(s: &str, sep: char) -> Vec<&str> {
    let mut out = Vec::new();
    let mut start = 0;
    let mut escaped = false;
    for (i, c) in s.char_indices() {
        if escaped {
            escaped = false;
        } else if c == '\\' {
            escaped = true;
        } else if c == sep {
            out.push(&s[start..i]);
            start = i + c.len_utf8();
        }
    }
    out.push(&s[start..]);
    out
}

/// `s` with its escapes resolved (a lone backslash at the end stays).
fn unescape(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    let mut chars = s.chars();
    while let Some(c) = chars.next() {
        out.push(if c == '\\' { chars.next().unwrap_or('\\') } else { c });
    }
    out
}

/// A whole number (frames, counts).
fn whole(s: &str) -> Option<usize> {
    s.trim().parse().ok()
}

/// A finite decimal number (`f32` or `f64`).
fn decimal<T: FromStr + Into<f64> + Copy>(s: &str) -> Option<T> {
    s.trim().parse::<T>().ok().filter(|x| (*x).into().is_finite())
}

/// `N` finite numbers separated by commas.
fn vector<const N: usize>(s: &str) -> Option<[f32; N]> {
    let values: Vec<f32> = s.split(',').map(decimal).collect::<Option<_>>()?;
    values.try_into().ok()
}

/// Rotations and translations of a POSE.
#[allow(clippy::type_complexity)]
fn pose(s: &str) -> Option<(Vec<(String, Quat)>, Vec<(String, Vec3)>)> {
    let (mut rotations, mut translations) = (Vec::new(), Vec::new());
    if s.is_empty() {
        return Some((rotations, translations));
    }
    for entry in split(s, ';') {
        let [name, values] = split(entry, '=')[..] else { return None };
        let name = unescape(name);
        if let Some(q) = vector::<4>(values) {
            rotations.push((name, Quat::from_array(q)));
        } else {
            translations.push((name, Vec3::from_array(vector::<3>(values)?)));
        }
    }
    Some((rotations, translations))
}

#[cfg(test)]
mod tests {
    use super::{Edit, EditSpec, SpecError};
    use crate::model::clip::Units;
    use glam::{Quat, Vec3};
    use proptest::prelude::*;

    fn edit(spec: &str) -> Edit {
        spec.parse().unwrap_or_else(|e| panic!("{spec}: {e}"))
    }

    #[test]
    fn the_browser_s_specs_read_as_before() {
        let name = |s: &str| s.to_owned();
        for (spec, want) in [
            ("reverse", Edit::Reverse),
            ("ping-pong", Edit::PingPong),
            ("in-place", Edit::InPlace { remove_turning: false }),
            ("in-place-turning", Edit::InPlace { remove_turning: true }),
            ("up-z", Edit::UpAxis { from: 2, negative: false }),
            ("trim:3:17", Edit::Trim { first: 3, last: 17 }),
            ("fps:60", Edit::Resample { fps: 60.0 }),
            ("fps: 29.97 ", Edit::Resample { fps: 29.97 }),
            ("fps:120:cubic", Edit::ResampleCubic { fps: 120.0 }),
            ("knit:4", Edit::LoopKnit { frames: 4 }),
            ("scale:0.01", Edit::Scale { factor: 0.01 }),
            ("rename:Head:Kopf", Edit::Rename { from: name("Head"), to: name("Kopf") }),
            ("remove:LeftForeArm", Edit::RemoveJoint { name: name("LeftForeArm"), fold: true }),
            ("drop:LeftForeArm", Edit::RemoveJoint { name: name("LeftForeArm"), fold: false }),
            (
                "add:Hips:Tail:0,-0.5, 1e-3",
                Edit::AddJoint { parent: name("Hips"), name: name("Tail"), offset: Vec3::new(0.0, -0.5, 1e-3) },
            ),
            ("offset:Head:1,2,3", Edit::SetOffset { name: name("Head"), offset: Vec3::new(1.0, 2.0, 3.0) }),
            ("channels:Head:ZXY", Edit::SetChannels { name: name("Head"), position: false, order: name("ZXY") }),
            (
                "channels:Head:YXZ:position",
                Edit::SetChannels { name: name("Head"), position: true, order: name("YXZ") },
            ),
        ] {
            assert_eq!(edit(spec), want, "{spec}");
        }
    }

    #[test]
    fn the_command_line_s_specs_read() {
        for (spec, want) in [
            ("up:z", Edit::UpAxis { from: 2, negative: false }),
            ("up:-X", Edit::UpAxis { from: 0, negative: true }),
            ("up: y", Edit::UpAxis { from: 1, negative: false }),
        ] {
            assert_eq!(edit(spec), want, "{spec}");
        }
        assert_eq!("units:cm".parse::<EditSpec>(), Ok(EditSpec::Units(Units::Centimeters)));
        assert_eq!("units:in".parse::<EditSpec>().unwrap().to_string(), "units:in");
        // Units resolve against the clip's own guess.
        let clip = super::super::new_character(10, 30.0);
        let factor = clip.units().meters_per_unit() / Units::Millimeters.meters_per_unit();
        assert_eq!(EditSpec::Units(Units::Millimeters).resolve(&clip), Edit::Scale { factor });
        assert_eq!(EditSpec::Edit(Edit::Reverse).resolve(&clip), Edit::Reverse);
    }

    #[test]
    fn names_with_separators_are_escaped() {
        let e = Edit::Rename { from: "mixamorig:Hips".into(), to: r"a\b;c=d,e".into() };
        assert_eq!(e.to_string(), r"rename:mixamorig\:Hips:a\\b\;c\=d\,e");
        assert_eq!(edit(&e.to_string()), e);
        assert_eq!(edit(r"remove:mixamorig\:Hips"), Edit::RemoveJoint { name: "mixamorig:Hips".into(), fold: true });
    }

    #[test]
    fn keys_and_corrections_are_specs_too() {
        let e = Edit::Key {
            frame: 5,
            rotations: vec![("Hips".into(), Quat::from_rotation_y(0.5)), ("Head".into(), Quat::IDENTITY)],
            translations: vec![("Hips".into(), Vec3::new(0.0, 1.0, -2.5))],
            keys: vec![0, 10],
        };
        assert_eq!(e.to_string().split(':').nth(2), Some("0,10"));
        assert!(e.to_string().ends_with(";Head=0,0,0,1;Hips=0,1,-2.5"), "{e}");
        assert_eq!(edit(&e.to_string()), e);
        let c = Edit::Correct { frame: 2, rotations: vec![], translations: vec![], window: 3 };
        assert_eq!(c.to_string(), "correct:2:3:");
        assert_eq!(edit("correct:2:3:"), c);
        assert_eq!(edit("key:1::"), Edit::Key { frame: 1, rotations: vec![], translations: vec![], keys: vec![] });
    }

    #[test]
    fn errors_name_the_spec_and_what_was_expected() {
        let error = |spec: &str| spec.parse::<Edit>().unwrap_err();
        let message = |spec: &str| error(spec).to_string();
        assert_eq!(message("knit:x"), "`knit:x`: expected a frame count (knit:N)");
        assert_eq!(message("trim:5"), "`trim:5`: expected first and last frames a:b (trim:A:B)");
        assert_eq!(message("trim:a:5"), "`trim:a:5`: expected first and last frames a:b (trim:A:B)");
        assert_eq!(message("up:q"), "`up:q`: expected x, y, z, -x, -y or -z (up:AXIS)");
        assert_eq!(message("scale:NaN"), "`scale:NaN`: expected a number (scale:F)");
        assert_eq!(message("fps:fast"), "`fps:fast`: expected a number (fps:N or fps:N:cubic)");
        assert_eq!(
            message("offset:Head:1,2"),
            "`offset:Head:1,2`: expected an offset x,y,z (three numbers) (offset:NAME:X,Y,Z)"
        );
        assert!(message("remove:a:b").contains(r"a colon in a name is written \:"));
        assert!(message("reverse:1").contains("expected nothing after `reverse`"));
        assert!(message("channels:Head:ZXY:pos").contains("`position` or nothing"));
        assert!(message("key:1:a:").contains("other keyed frames"));
        assert!(message("correct:1:2:Head=1,2").contains("a pose"));
        let unknown = error("frobnicate");
        assert_eq!(unknown.form, "");
        assert!(unknown.to_string().starts_with("`frobnicate`: expected an edit: reverse, ping-pong"), "{unknown}");
        assert_eq!(error("units:furlong").expected, "m, dm, cm, mm or in");
        assert_eq!(
            error("units:m"),
            SpecError { spec: "units:m".into(), expected: error("units:m").expected, form: "units:U" }
        );
        assert!(message("units:m").contains("resolve it against the clip"));
        assert!(message("").contains("expected an edit"));
    }

    fn finite() -> impl Strategy<Value = f32> {
        any::<f32>().prop_filter("finite", |x| x.is_finite())
    }

    fn vec3() -> impl Strategy<Value = Vec3> {
        (finite(), finite(), finite()).prop_map(|(x, y, z)| Vec3::new(x, y, z))
    }

    fn quat() -> impl Strategy<Value = Quat> {
        (finite(), finite(), finite(), finite()).prop_map(|(x, y, z, w)| Quat::from_xyzw(x, y, z, w))
    }

    fn name() -> impl Strategy<Value = String> {
        prop_oneof![any::<String>(), "[A-Za-z_:;=,\\\\ ]{0,8}"]
    }

    fn key_pose() -> impl Strategy<Value = (Vec<(String, Quat)>, Vec<(String, Vec3)>)> {
        (prop::collection::vec((name(), quat()), 0..4), prop::collection::vec((name(), vec3()), 0..4))
    }

    fn any_edit() -> impl Strategy<Value = Edit> {
        prop_oneof![
            (any::<usize>(), any::<usize>()).prop_map(|(first, last)| Edit::Trim { first, last }),
            any::<f64>().prop_filter("finite", |x| x.is_finite()).prop_map(|fps| Edit::Resample { fps }),
            any::<f64>().prop_filter("finite", |x| x.is_finite()).prop_map(|fps| Edit::ResampleCubic { fps }),
            Just(Edit::Reverse),
            Just(Edit::PingPong),
            any::<usize>().prop_map(|frames| Edit::LoopKnit { frames }),
            any::<bool>().prop_map(|remove_turning| Edit::InPlace { remove_turning }),
            (0..3usize, any::<bool>()).prop_map(|(from, negative)| Edit::UpAxis { from, negative }),
            finite().prop_map(|factor| Edit::Scale { factor }),
            (name(), name()).prop_map(|(from, to)| Edit::Rename { from, to }),
            (name(), any::<bool>()).prop_map(|(name, fold)| Edit::RemoveJoint { name, fold }),
            (name(), name(), vec3()).prop_map(|(parent, name, offset)| Edit::AddJoint { parent, name, offset }),
            (name(), vec3()).prop_map(|(name, offset)| Edit::SetOffset { name, offset }),
            (name(), any::<bool>(), name()).prop_map(|(name, position, order)| Edit::SetChannels {
                name,
                position,
                order
            }),
            (any::<usize>(), key_pose(), any::<usize>()).prop_map(|(frame, (rotations, translations), window)| {
                Edit::Correct { frame, rotations, translations, window }
            }),
            (any::<usize>(), key_pose(), prop::collection::vec(any::<usize>(), 0..4)).prop_map(
                |(frame, (rotations, translations), keys)| Edit::Key { frame, rotations, translations, keys }
            ),
        ]
    }

    /// Bit-exact comparison (`-0.0` and `0.0` differ), through the debug text.
    fn exact(e: &Edit) -> String {
        format!("{e:?}")
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(512))]
        #[test]
        fn every_edit_reads_back_from_its_spec(e in any_edit()) {
            let spec = e.to_string();
            let again: Edit = spec.parse().map_err(|err: SpecError| TestCaseError::fail(err.to_string()))?;
            prop_assert_eq!(exact(&again), exact(&e), "{}", spec);
            let as_spec: EditSpec = spec.parse().map_err(|err: SpecError| TestCaseError::fail(err.to_string()))?;
            prop_assert_eq!(as_spec.to_string(), spec);
        }

        #[test]
        fn no_string_panics_the_reader(s in any::<String>()) {
            let _ = s.parse::<EditSpec>();
        }
    }

    #[test]
    fn units_read_back() {
        for units in [Units::Meters, Units::Decimeters, Units::Centimeters, Units::Millimeters, Units::Inches] {
            let spec = EditSpec::Units(units);
            assert_eq!(spec.to_string().parse::<EditSpec>(), Ok(spec));
        }
    }
}
