//! `:bonedata`: one `begin … end` block per bone, with its limits.

use super::super::text::{Token, decode_name, parse_f32, parse_i64};
use super::{AsfBone, AxisOrder, Dof, Parser, error_at, unterminated};
use crate::error::{ParseError, Warning};

impl<'a> Parser<'a> {
    /// One `begin … end` block.
    pub(super) fn bone(&mut self, begin: &Token<'a>) -> Result<(), ParseError> {
        let mut bone = AsfBone {
            id: None,
            name: String::new(),
            direction: [0.0; 3],
            length: 0.0,
            axis: [0.0; 3],
            axis_order: AxisOrder::default(),
            dofs: Vec::new(),
            limits: Vec::new(),
            bodymass: None,
            cofmass: None,
            line: begin.line,
            parent: None,
        };
        let mut name_token: Option<Token<'a>> = None;
        let mut limits_token: Option<Token<'a>> = None;
        loop {
            let Some(key) = self.cursor.next_token() else {
                return Err(unterminated(begin, "reached the end of the file"));
            };
            if key.text.first() == Some(&b':') || key.is("begin") {
                return Err(unterminated(begin, &format!("found `{}` at line {}", key.show(), key.line)));
            }
            if key.is("end") {
                break;
            } else if key.is("id") {
                let t = self.next_or_eof("the bone id")?;
                bone.id =
                    Some(parse_i64(t.text).ok_or_else(|| {
                        error_at(&t, format!("expected the bone id (an integer), found `{}`", t.show()))
                    })?);
            } else if key.is("name") {
                let t = self.next_or_eof("the bone name")?;
                bone.name = decode_name(t.text);
                name_token = Some(t);
            } else if key.is("direction") {
                bone.direction = self.vec3("direction")?;
            } else if key.is("length") {
                bone.length = self.number("the bone length")?;
            } else if key.is("axis") {
                bone.axis = self.vec3("axis")?;
                match self.cursor.next_on_line(key.line) {
                    Some(t) => {
                        bone.axis_order = AxisOrder::from_name(t.text).ok_or_else(|| {
                            error_at(
                                &t,
                                format!(
                                    "expected an axis order such as XYZ after the axis angles, found `{}`",
                                    t.show()
                                ),
                            )
                        })?;
                    }
                    None => self.warnings.push(Warning {
                        line: Some(key.line),
                        message: "`axis` line without an order (e.g. XYZ): using XYZ".into(),
                    }),
                }
            } else if key.is("dof") {
                bone.dofs.clear();
                while let Some(t) = self.cursor.next_on_line(key.line) {
                    let dof = Dof::from_name(t.text).ok_or_else(|| {
                        error_at(
                            &t,
                            format!("expected a degree of freedom (tx ty tz rx ry rz l), found `{}`", t.show()),
                        )
                    })?;
                    bone.dofs.push(dof);
                }
            } else if key.is("limits") {
                bone.limits = self.limits()?;
                limits_token = Some(key);
            } else if key.is("bodymass") {
                bone.bodymass = Some(self.number("the body mass")?);
            } else if key.is("cofmass") {
                bone.cofmass = Some(self.number("the centre of mass")?);
            } else {
                let context = name_token.map_or_else(String::new, |t| format!(" of bone `{}`", t.show()));
                return Err(error_at(
                    &key,
                    format!(
                        "unknown keyword `{}`{context}: expected id, name, direction, length, axis, dof, limits, bodymass, cofmass or end",
                        key.show()
                    ),
                ));
            }
        }
        let Some(name_token) = name_token else {
            return Err(error_at(begin, "bone without a `name` (expected `name` between `begin` and `end`)"));
        };
        if let Some(limits) = limits_token {
            if bone.limits.len() != bone.dofs.len() {
                return Err(error_at(
                    &limits,
                    format!(
                        "bone `{}` has {} degrees of freedom but `limits` gives {} (min max) pairs: expected one pair per dof",
                        bone.name,
                        bone.dofs.len(),
                        bone.limits.len()
                    ),
                ));
            }
        }
        if name_token.text.eq_ignore_ascii_case(b"root") {
            return Err(error_at(
                &name_token,
                "a bone cannot be called `root`: that name is the root in :hierarchy and AMC files",
            ));
        }
        if let Some(&first) = self.names.get(name_token.text) {
            let line = self.bones.get(first).map_or(0, |b| b.line);
            return Err(error_at(
                &name_token,
                format!("duplicate bone name `{}`: a bone of that name begins at line {line}", name_token.show()),
            ));
        }
        if bone.direction == [0.0; 3] && bone.length != 0.0 {
            self.warnings.push(Warning {
                line: Some(begin.line),
                message: format!(
                    "bone `{}` has length {} but a zero direction vector: it points nowhere",
                    bone.name, bone.length
                ),
            });
        }
        self.names.insert(name_token.text, self.bones.len());
        self.name_tokens.push(name_token);
        self.bones.push(bone);
        Ok(())
    }

    /// `(min max)` pairs, as many as follow (on any number of lines).
    fn limits(&mut self) -> Result<Vec<(f32, f32)>, ParseError> {
        let mut limits = Vec::new();
        loop {
            match self.cursor.peek_token() {
                Some(t) if t.text == b"(" => {
                    self.cursor.next_token();
                }
                Some(t) if limits.is_empty() => {
                    return Err(error_at(
                        &t,
                        format!("expected `(` to start a (min max) limit pair, found `{}`", t.show()),
                    ));
                }
                None if limits.is_empty() => {
                    self.next_or_eof("`(` to start a (min max) limit pair")?;
                }
                _ => return Ok(limits),
            }
            let min = self.limit("the minimum of a limit pair")?;
            let max = self.limit("the maximum of a limit pair")?;
            let close = self.next_or_eof("`)` to close a limit pair")?;
            if close.text != b")" {
                return Err(error_at(&close, format!("expected `)` to close a limit pair, found `{}`", close.show())));
            }
            limits.push((min, max));
        }
    }

    /// A limit: a number or ±infinity, not NaN.
    fn limit(&mut self, what: &str) -> Result<f32, ParseError> {
        let t = self.next_or_eof(what)?;
        parse_f32(t.text)
            .filter(|v| !v.is_nan())
            .ok_or_else(|| error_at(&t, format!("expected {what} (a number, `inf` or `-inf`), found `{}`", t.show())))
    }
}
