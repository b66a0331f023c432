//! The ASF skeleton reader.

use super::text::{Cursor, Token, binary_kind, decode_name, parse_f32, parse_i64, trim_blanks};
use super::{AngleUnit, AxisOrder, Dof};
use crate::error::{ParseError, Warning};
use std::collections::HashMap;

/// The `:units` section.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct AsfUnits {
    /// `mass`, when given.
    pub mass: Option<f32>,
    /// `length`: the factor lengths are multiplied by (CMU files use 0.45), when given.
    pub length: Option<f32>,
    /// `angle deg` or `angle rad`; degrees when absent.
    pub angle: AngleUnit,
    /// Other keys with the rest of their line (values joined by one space).
    pub other: Vec<(String, String)>,
}

/// The `:root` section.
#[derive(Clone, Debug, PartialEq)]
pub struct AsfRoot {
    /// `order`: the root's degrees of freedom in the order of the AMC values.
    pub order: Vec<Dof>,
    /// `axis`: the order of the orientation rotations.
    pub axis: AxisOrder,
    /// `position`.
    pub position: [f32; 3],
    /// `orientation` (in the file's angle unit).
    pub orientation: [f32; 3],
}

impl Default for AsfRoot {
    fn default() -> AsfRoot {
        AsfRoot { order: Vec::new(), axis: AxisOrder::default(), position: [0.0; 3], orientation: [0.0; 3] }
    }
}

/// One `begin … end` block of `:bonedata`, with its parent from `:hierarchy`.
#[derive(Clone, Debug, PartialEq)]
pub struct AsfBone {
    /// `id`, when given.
    pub id: Option<i64>,
    /// `name`.
    pub name: String,
    /// `direction`: the bone's direction in the global frame.
    pub direction: [f32; 3],
    /// `length` (multiply by [`AsfUnits::length`] for the file's scale).
    pub length: f32,
    /// The three angles of `axis` (in the file's angle unit).
    pub axis: [f32; 3],
    /// The rotation order of `axis`.
    pub axis_order: AxisOrder,
    /// `dof`, in the order of the AMC values; empty when there is no `dof` line.
    pub dofs: Vec<Dof>,
    /// `limits`: one `(min, max)` per dof (`inf`/`-inf` as infinities); empty when there
    /// is no `limits` line.
    pub limits: Vec<(f32, f32)>,
    /// `bodymass`, when given.
    pub bodymass: Option<f32>,
    /// `cofmass`, when given.
    pub cofmass: Option<f32>,
    /// Line of the bone's `begin`.
    pub line: u32,
    /// Index of the parent in [`Asf::bones`] (always smaller than this bone's); `None`
    /// for a child of the root.
    pub parent: Option<usize>,
}

/// A parsed ASF skeleton.
#[derive(Clone, Debug, PartialEq)]
pub struct Asf {
    /// `:version`, when given.
    pub version: Option<String>,
    /// `:name`, when given.
    pub name: Option<String>,
    /// `:units`.
    pub units: AsfUnits,
    /// `:documentation`: its lines trimmed and joined with `\n`.
    pub documentation: String,
    /// `:root`.
    pub root: AsfRoot,
    /// The bones, every parent before its children: in `:bonedata` order when that
    /// already holds, otherwise reordered.
    pub bones: Vec<AsfBone>,
    /// Non-fatal problems.
    pub warnings: Vec<Warning>,
}

impl Asf {
    /// The AMC row layout of this skeleton: `("root", root dofs)` then each bone with
    /// its dof count, in [`Asf::bones`] order. Pass it to [`super::parse_amc`].
    pub fn amc_layout(&self) -> Vec<(&str, usize)> {
        std::iter::once(("root", self.root.order.len()))
            .chain(self.bones.iter().map(|b| (b.name.as_str(), b.dofs.len())))
            .collect()
    }

    /// The number of values in one AMC frame (root dofs plus every bone's dofs).
    pub fn amc_width(&self) -> usize {
        self.root.order.len() + self.bones.iter().map(|b| b.dofs.len()).sum::<usize>()
    }

    /// The index of the bone called `name` in [`Asf::bones`] (linear search).
    pub fn bone_index(&self, name: &str) -> Option<usize> {
        self.bones.iter().position(|b| b.name == name)
    }
}

/// The section keywords that may start an ASF file.
const SECTIONS: [&str; 7] = [":version", ":name", ":units", ":documentation", ":root", ":bonedata", ":hierarchy"];

/// True when `bytes` look like an ASF skeleton: the first token that is not a comment
/// is one of the section keywords (`:version`, `:name`, `:units`, `:documentation`,
/// `:root`, `:bonedata`, `:hierarchy`, any case).
pub fn sniff_asf(bytes: &[u8]) -> bool {
    let head = bytes.get(..4096).unwrap_or(bytes);
    Cursor::new(head).next_token().is_some_and(|t| SECTIONS.iter().any(|s| t.is(s)))
}

fn error_at(token: &Token, message: impl Into<String>) -> ParseError {
    ParseError::new(token.line, token.column, message)
}

/// A `parent child` pair of `:hierarchy`, with its tokens.
struct Edge<'a> {
    parent: Token<'a>,
    child: Token<'a>,
}

/// Where the parser is.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Section {
    None,
    Units,
    Root,
    Bonedata,
    Hierarchy,
    Unknown,
}

struct Parser<'a> {
    cursor: Cursor<'a>,
    version: Option<String>,
    name: Option<String>,
    units: AsfUnits,
    documentation: String,
    root: Option<AsfRoot>,
    bones: Vec<AsfBone>,
    /// Each bone's `name` token.
    name_tokens: Vec<Token<'a>>,
    names: HashMap<&'a [u8], usize>,
    edges: Vec<Edge<'a>>,
    has_hierarchy: bool,
    warnings: Vec<Warning>,
}

/// Parses an ASF skeleton.
pub fn parse_asf(bytes: &[u8]) -> Result<Asf, ParseError> {
    if let Some(kind) = binary_kind(bytes) {
        return Err(ParseError::new(1, 1, format!("not an Acclaim skeleton: {kind}")));
    }
    let mut p = Parser {
        cursor: Cursor::new(bytes),
        version: None,
        name: None,
        units: AsfUnits::default(),
        documentation: String::new(),
        root: None,
        bones: Vec::new(),
        name_tokens: Vec::new(),
        names: HashMap::new(),
        edges: Vec::new(),
        has_hierarchy: false,
        warnings: Vec::new(),
    };
    p.sections()?;
    p.finish()
}

/// Reads the tokens left on `line` and joins them with one space.
fn rest_joined(cursor: &mut Cursor, line: u32) -> String {
    let mut parts = Vec::new();
    while let Some(t) = cursor.next_on_line(line) {
        parts.push(decode_name(t.text));
    }
    parts.join(" ")
}

impl<'a> Parser<'a> {
    fn next_or_eof(&mut self, what: &str) -> Result<Token<'a>, ParseError> {
        self.cursor.next_token().ok_or_else(|| {
            let (line, column) = self.cursor.position();
            ParseError::new(line, column, format!("unexpected end of file: expected {what}"))
        })
    }

    /// A finite number.
    fn number(&mut self, what: &str) -> Result<f32, ParseError> {
        let t = self.next_or_eof(what)?;
        match parse_f32(t.text) {
            Some(v) if v.is_finite() => Ok(v),
            Some(_) => Err(error_at(&t, format!("expected {what} (a finite number), found `{}`", t.show()))),
            None => Err(error_at(&t, format!("expected {what} (a number), found `{}`", t.show()))),
        }
    }

    fn vec3(&mut self, what: &str) -> Result<[f32; 3], ParseError> {
        let mut v = [0.0; 3];
        for (slot, axis) in v.iter_mut().zip(["x", "y", "z"]) {
            *slot = self.number(&format!("the {axis} value of {what}"))?;
        }
        Ok(v)
    }

    fn sections(&mut self) -> Result<(), ParseError> {
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

    /// One `begin … end` block.
    fn bone(&mut self, begin: &Token<'a>) -> Result<(), ParseError> {
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

    /// Resolves `:hierarchy` into parents and orders the bones parents first.
    fn finish(self) -> Result<Asf, ParseError> {
        let Some(root) = self.root else {
            let (line, column) = self.cursor.position();
            return Err(ParseError::new(line, column, "no :root section: expected `:root` before the end of the file"));
        };
        let n = self.bones.len();
        // parent[j]: None = not given yet; Some(None) = root; Some(Some(p)) = bone p.
        let mut parent: Vec<Option<Option<usize>>> = vec![None; n];
        let mut parent_token: Vec<Option<Token>> = vec![None; n];
        let mut has_children = vec![false; n];
        let lookup = |t: &Token| -> Result<Option<usize>, ParseError> {
            if t.is("root") {
                return Ok(None);
            }
            match self.names.get(t.text) {
                Some(&i) => Ok(Some(i)),
                None => Err(error_at(
                    t,
                    format!("unknown bone `{}` in :hierarchy: no bone of that name in :bonedata", t.show()),
                )),
            }
        };
        for edge in &self.edges {
            let p = lookup(&edge.parent)?;
            let Some(c) = lookup(&edge.child)? else {
                return Err(error_at(&edge.child, "`root` cannot be the child of a bone in :hierarchy"));
            };
            if let Some(p) = p {
                if p == c {
                    return Err(error_at(
                        &edge.child,
                        format!("bone `{}` is listed as its own child: a cycle in :hierarchy", edge.child.show()),
                    ));
                }
                if let Some(flag) = has_children.get_mut(p) {
                    *flag = true;
                }
            }
            if let (Some(Some(_)), Some(Some(first))) = (parent.get(c), parent_token.get(c)) {
                return Err(error_at(
                    &edge.child,
                    format!(
                        "bone `{}` is given two parents: `{}` (line {}) and `{}`",
                        edge.child.show(),
                        first_parent_name(&self.edges, first),
                        first.line,
                        edge.parent.show()
                    ),
                ));
            }
            if let (Some(slot), Some(tok)) = (parent.get_mut(c), parent_token.get_mut(c)) {
                *slot = Some(p);
                *tok = Some(edge.child);
            }
        }
        for (j, p) in parent.iter().enumerate() {
            if p.is_none() {
                let Some(t) = self.name_tokens.get(j) else { continue };
                let message = if !self.has_hierarchy {
                    format!("bone `{}` has no parent: the file has no :hierarchy section", t.show())
                } else if has_children.get(j).copied().unwrap_or(false) {
                    format!(
                        "bone `{}` has children in :hierarchy but no parent: it is not reachable from root",
                        t.show()
                    )
                } else {
                    format!(
                        "bone `{}` is not in :hierarchy: expected a line such as `root {}` naming its parent",
                        t.show(),
                        t.show()
                    )
                };
                return Err(error_at(t, message));
            }
        }
        // Parents first, keeping the :bonedata order where it already holds: for each
        // bone, walk up to the first placed ancestor, then place the walked path
        // top-down. Every bone is walked once: linear time, no recursion.
        let mut state = vec![0u8; n]; // 0 unplaced, 1 on the current path, 2 placed
        let mut order: Vec<usize> = Vec::with_capacity(n);
        let mut path: Vec<usize> = Vec::new();
        for start in 0..n {
            let mut cur = start;
            loop {
                match state.get(cur) {
                    Some(2) | None => break,
                    Some(1) => {
                        let at =
                            parent_token.get(cur).copied().flatten().or_else(|| self.name_tokens.get(cur).copied());
                        let name = self.bones.get(cur).map_or("", |b| b.name.as_str());
                        let message = format!(
                            "bone `{name}` is in a cycle in :hierarchy (it is its own ancestor): it is not reachable from root"
                        );
                        return Err(at.map_or_else(
                            || ParseError::new(1, 1, message.clone()),
                            |t| error_at(&t, message.clone()),
                        ));
                    }
                    _ => {}
                }
                if let Some(s) = state.get_mut(cur) {
                    *s = 1;
                }
                path.push(cur);
                match parent.get(cur).copied().flatten().flatten() {
                    Some(p) => cur = p,
                    None => break,
                }
            }
            while let Some(b) = path.pop() {
                if let Some(s) = state.get_mut(b) {
                    *s = 2;
                }
                order.push(b);
            }
        }
        let mut new_index = vec![0usize; n];
        for (new, &old) in order.iter().enumerate() {
            if let Some(slot) = new_index.get_mut(old) {
                *slot = new;
            }
        }
        let mut slots: Vec<Option<AsfBone>> = self.bones.into_iter().map(Some).collect();
        let mut bones = Vec::with_capacity(n);
        for &old in &order {
            if let Some(mut bone) = slots.get_mut(old).and_then(Option::take) {
                bone.parent = parent.get(old).copied().flatten().flatten().and_then(|p| new_index.get(p).copied());
                bones.push(bone);
            }
        }
        Ok(Asf {
            version: self.version,
            name: self.name,
            units: self.units,
            documentation: self.documentation,
            root,
            bones,
            warnings: self.warnings,
        })
    }
}

/// The parent named on the hierarchy line of `child_token` (for messages).
fn first_parent_name(edges: &[Edge], child_token: &Token) -> String {
    edges
        .iter()
        .find(|e| e.child.line == child_token.line && e.child.column == child_token.column)
        .map_or_else(String::new, |e| e.parent.show())
}

fn unterminated(begin: &Token, found: &str) -> ParseError {
    error_at(
        begin,
        format!("`begin` at line {} has no `end`: expected `end` before the next section, {found}", begin.line),
    )
}

#[cfg(test)]
mod tests {
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
        let mut wmv =
            vec![0x30, 0x26, 0xB2, 0x75, 0x8E, 0x66, 0xCF, 0x11, 0xA6, 0xD9, 0x00, 0xAA, 0x00, 0x62, 0xCE, 0x6C];
        wmv.extend_from_slice(&[0x84, 0x01, 0, 0, 0, 0, 0, 0]);
        let e = parse_asf(&wmv).unwrap_err();
        assert_eq!(
            e,
            ParseError::new(1, 1, "not an Acclaim skeleton: this looks like a Windows Media (.asf) video file")
        );
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
}
