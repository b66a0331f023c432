//! The sections of an ASF file, and what `:units`, `:root` and `:documentation`
//! hold (`:bonedata` blocks are read by `bones`, `:hierarchy` lines are kept as
//! edges for `hierarchy`).

use super::super::text::{Token, decode_name, parse_f32, trim_blanks};
use super::{AngleUnit, AsfRoot, AxisOrder, Dof, Edge, Parser, Section, error_at, rest_joined, unterminated};
use crate::error::{ParseError, Warning};

impl<'a> Parser<'a> {
    /// Reads the file section by section.
    pub(super) fn sections(&mut self) -> Result<(), ParseError> {
        let mut section = Section::None;
        let mut hierarchy_begin: Option<Token<'a>> = None;
        while let Some(token) = self.cursor.next_token() {
            if token.text.first() == Some(&b':') {
                if let Some(begin) = hierarchy_begin.take() {
                    return Err(unterminated(&begin, &format!("found `{}` at line {}", token.show(), token.line)));
                }
                section = self.section(&token)?;
                continue;
            }
            match section {
                Section::None => {
                    return Err(error_at(
                        &token,
                        format!(
                            "expected a section keyword (:version, :name, :units, :documentation, :root, :bonedata or :hierarchy), found `{}`",
                            token.show()
                        ),
                    ));
                }
                Section::Unknown => {}
                Section::Units => self.unit(&token)?,
                Section::Root => self.root_item(&token)?,
                Section::Bonedata => {
                    if !token.is("begin") {
                        return Err(error_at(
                            &token,
                            format!(
                                "expected `begin` (a bone) or a section keyword in :bonedata, found `{}`",
                                token.show()
                            ),
                        ));
                    }
                    self.bone(&token)?;
                }
                Section::Hierarchy => {
                    if hierarchy_begin.is_none() {
                        if !token.is("begin") {
                            return Err(error_at(
                                &token,
                                format!("expected `begin` in :hierarchy, found `{}`", token.show()),
                            ));
                        }
                        hierarchy_begin = Some(token);
                    } else if token.is("end") {
                        hierarchy_begin = None;
                    } else {
                        let mut any = false;
                        while let Some(child) = self.cursor.next_on_line(token.line) {
                            self.edges.push(Edge { parent: token, child });
                            any = true;
                        }
                        if !any {
                            self.warnings.push(Warning {
                                line: Some(token.line),
                                message: format!("hierarchy line names `{}` with no children", token.show()),
                            });
                        }
                    }
                }
            }
        }
        if let Some(begin) = hierarchy_begin {
            return Err(unterminated(&begin, "reached the end of the file"));
        }
        Ok(())
    }

    fn section(&mut self, token: &Token<'a>) -> Result<Section, ParseError> {
        let section = if token.is(":version") {
            self.version = Some(rest_joined(&mut self.cursor, token.line)).filter(|s| !s.is_empty());
            Section::None
        } else if token.is(":name") {
            self.name = Some(rest_joined(&mut self.cursor, token.line)).filter(|s| !s.is_empty());
            Section::None
        } else if token.is(":units") {
            Section::Units
        } else if token.is(":documentation") {
            self.documentation();
            Section::None
        } else if token.is(":root") {
            if self.root.is_some() {
                return Err(error_at(token, "a second :root section: an ASF file has one"));
            }
            self.root = Some(AsfRoot::default());
            Section::Root
        } else if token.is(":bonedata") {
            Section::Bonedata
        } else if token.is(":hierarchy") {
            if self.has_hierarchy {
                return Err(error_at(token, "a second :hierarchy section: an ASF file has one"));
            }
            self.has_hierarchy = true;
            Section::Hierarchy
        } else {
            self.warnings.push(Warning {
                line: Some(token.line),
                message: format!("unknown section `{}` skipped", token.show()),
            });
            Section::Unknown
        };
        Ok(section)
    }

    /// Free text up to the next line that starts with `:`; `#` lines are comments.
    fn documentation(&mut self) {
        let mut lines: Vec<String> = Vec::new();
        let first = trim_blanks(self.cursor.take_line());
        if !first.is_empty() {
            lines.push(decode_name(first));
        }
        while !self.cursor.at_end() {
            match self.cursor.first_on_line() {
                Some(b':') => break,
                Some(b'#') => {
                    self.cursor.take_line();
                }
                _ => lines.push(decode_name(trim_blanks(self.cursor.take_line()))),
            }
        }
        self.documentation = lines.join("\n").trim().to_owned();
    }

    fn unit(&mut self, key: &Token<'a>) -> Result<(), ParseError> {
        if key.is("mass") || key.is("length") {
            let t = self
                .cursor
                .next_on_line(key.line)
                .ok_or_else(|| error_at(key, format!("expected a number after `{}`", key.show())))?;
            let v = parse_f32(t.text).filter(|v| v.is_finite()).ok_or_else(|| {
                error_at(&t, format!("expected the {} unit (a finite number), found `{}`", key.show(), t.show()))
            })?;
            if key.is("mass") {
                self.units.mass = Some(v);
            } else {
                self.units.length = Some(v);
            }
        } else if key.is("angle") {
            let t = self
                .cursor
                .next_on_line(key.line)
                .ok_or_else(|| error_at(key, "expected `deg` or `rad` after `angle`"))?;
            self.units.angle = if t.is("deg") || t.is("degree") || t.is("degrees") {
                AngleUnit::Degrees
            } else if t.is("rad") || t.is("radian") || t.is("radians") {
                AngleUnit::Radians
            } else {
                return Err(error_at(&t, format!("expected `deg` or `rad` after `angle`, found `{}`", t.show())));
            };
        } else {
            let value = rest_joined(&mut self.cursor, key.line);
            self.units.other.push((decode_name(key.text), value));
        }
        // Anything else on the line is ignored with a warning.
        if let Some(extra) = self.cursor.next_on_line(key.line) {
            self.warnings.push(Warning {
                line: Some(extra.line),
                message: format!("extra `{}` after the `{}` unit ignored", extra.show(), key.show()),
            });
            while self.cursor.next_on_line(key.line).is_some() {}
        }
        Ok(())
    }

    fn root_item(&mut self, key: &Token<'a>) -> Result<(), ParseError> {
        let mut root = self.root.take().unwrap_or_default();
        let result = self.root_value(key, &mut root);
        self.root = Some(root);
        result
    }

    fn root_value(&mut self, key: &Token<'a>, root: &mut AsfRoot) -> Result<(), ParseError> {
        if key.is("order") {
            root.order.clear();
            while let Some(t) = self.cursor.next_on_line(key.line) {
                let dof = Dof::from_name(t.text).ok_or_else(|| {
                    error_at(
                        &t,
                        format!(
                            "expected a degree of freedom (TX TY TZ RX RY RZ) in the root order, found `{}`",
                            t.show()
                        ),
                    )
                })?;
                root.order.push(dof);
            }
        } else if key.is("axis") {
            let t = self.next_or_eof("the root axis order (e.g. XYZ)")?;
            root.axis = AxisOrder::from_name(t.text)
                .ok_or_else(|| error_at(&t, format!("expected an axis order such as XYZ, found `{}`", t.show())))?;
        } else if key.is("position") {
            root.position = self.vec3("the root position")?;
        } else if key.is("orientation") {
            root.orientation = self.vec3("the root orientation")?;
        } else {
            return Err(error_at(
                key,
                format!("unknown keyword `{}` in :root: expected order, axis, position or orientation", key.show()),
            ));
        }
        Ok(())
    }
}
