//! The ASF skeleton reader.

use super::text::{binary_kind, decode_name, parse_f32, parse_i64, trim_blanks, Cursor, Token};
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
        std::iter::once(("root", self.root.order.len())).chain(self.bones.iter().map(|b| (b.name.as_str(), b.dofs.len()))).collect()
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
                    return Err(error_at(&token, format!("expected a section keyword (:version, :name, :units, :documentation, :root, :bonedata or :hierarchy), found `{}`", token.show())));
                }
                Section::Unknown => {}
                Section::Units => self.unit(&token)?,
                Section::Root => self.root_item(&token)?,
                Section::Bonedata => {
                    if !token.is("begin") {
                        return Err(error_at(&token, format!("expected `begin` (a bone) or a section keyword in :bonedata, found `{}`", token.show())));
                    }
                    self.bone(&token)?;
                }
                Section::Hierarchy => {
                    if hierarchy_begin.is_none() {
                        if !token.is("begin") {
                            return Err(error_at(&token, format!("expected `begin` in :hierarchy, found `{}`", token.show())));
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
                            self.warnings.push(Warning { line: Some(token.line), message: format!("hierarchy line names `{}` with no children", token.show()) });
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
            self.warnings.push(Warning { line: Some(token.line), message: format!("unknown section `{}` skipped", token.show()) });
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
            let t = self.cursor.next_on_line(key.line).ok_or_else(|| error_at(key, format!("expected a number after `{}`", key.show())))?;
            let v = parse_f32(t.text)
                .filter(|v| v.is_finite())
                .ok_or_else(|| error_at(&t, format!("expected the {} unit (a finite number), found `{}`", key.show(), t.show())))?;
            if key.is("mass") {
                self.units.mass = Some(v);
            } else {
                self.units.length = Some(v);
            }
        } else if key.is("angle") {
            let t = self.cursor.next_on_line(key.line).ok_or_else(|| error_at(key, "expected `deg` or `rad` after `angle`"))?;
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
            self.warnings.push(Warning { line: Some(extra.line), message: format!("extra `{}` after the `{}` unit ignored", extra.show(), key.show()) });
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
                let dof = Dof::from_name(t.text).ok_or_else(|| error_at(&t, format!("expected a degree of freedom (TX TY TZ RX RY RZ) in the root order, found `{}`", t.show())))?;
                root.order.push(dof);
            }
        } else if key.is("axis") {
            let t = self.next_or_eof("the root axis order (e.g. XYZ)")?;
            root.axis = AxisOrder::from_name(t.text).ok_or_else(|| error_at(&t, format!("expected an axis order such as XYZ, found `{}`", t.show())))?;
        } else if key.is("position") {
            root.position = self.vec3("the root position")?;
        } else if key.is("orientation") {
            root.orientation = self.vec3("the root orientation")?;
        } else {
            return Err(error_at(key, format!("unknown keyword `{}` in :root: expected order, axis, position or orientation", key.show())));
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
                bone.id = Some(parse_i64(t.text).ok_or_else(|| error_at(&t, format!("expected the bone id (an integer), found `{}`", t.show())))?);
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
                        bone.axis_order = AxisOrder::from_name(t.text).ok_or_else(|| error_at(&t, format!("expected an axis order such as XYZ after the axis angles, found `{}`", t.show())))?;
                    }
                    None => self.warnings.push(Warning { line: Some(key.line), message: "`axis` line without an order (e.g. XYZ): using XYZ".into() }),
                }
            } else if key.is("dof") {
                bone.dofs.clear();
                while let Some(t) = self.cursor.next_on_line(key.line) {
                    let dof = Dof::from_name(t.text).ok_or_else(|| error_at(&t, format!("expected a degree of freedom (tx ty tz rx ry rz l), found `{}`", t.show())))?;
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
                    format!("unknown keyword `{}`{context}: expected id, name, direction, length, axis, dof, limits, bodymass, cofmass or end", key.show()),
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
            return Err(error_at(&name_token, "a bone cannot be called `root`: that name is the root in :hierarchy and AMC files"));
        }
        if let Some(&first) = self.names.get(name_token.text) {
            let line = self.bones.get(first).map_or(0, |b| b.line);
            return Err(error_at(&name_token, format!("duplicate bone name `{}`: a bone of that name begins at line {line}", name_token.show())));
        }
        if bone.direction == [0.0; 3] && bone.length != 0.0 {
            self.warnings.push(Warning { line: Some(begin.line), message: format!("bone `{}` has length {} but a zero direction vector: it points nowhere", bone.name, bone.length) });
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
                Some(t) if limits.is_empty() => return Err(error_at(&t, format!("expected `(` to start a (min max) limit pair, found `{}`", t.show()))),
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
        parse_f32(t.text).filter(|v| !v.is_nan()).ok_or_else(|| error_at(&t, format!("expected {what} (a number, `inf` or `-inf`), found `{}`", t.show())))
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
                None => Err(error_at(t, format!("unknown bone `{}` in :hierarchy: no bone of that name in :bonedata", t.show()))),
            }
        };
        for edge in &self.edges {
            let p = lookup(&edge.parent)?;
            let Some(c) = lookup(&edge.child)? else {
                return Err(error_at(&edge.child, "`root` cannot be the child of a bone in :hierarchy"));
            };
            if let Some(p) = p {
                if p == c {
                    return Err(error_at(&edge.child, format!("bone `{}` is listed as its own child: a cycle in :hierarchy", edge.child.show())));
                }
                if let Some(flag) = has_children.get_mut(p) {
                    *flag = true;
                }
            }
            if let (Some(Some(_)), Some(Some(first))) = (parent.get(c), parent_token.get(c)) {
                return Err(error_at(
                    &edge.child,
                    format!("bone `{}` is given two parents: `{}` (line {}) and `{}`", edge.child.show(), first_parent_name(&self.edges, first), first.line, edge.parent.show()),
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
                    format!("bone `{}` has children in :hierarchy but no parent: it is not reachable from root", t.show())
                } else {
                    format!("bone `{}` is not in :hierarchy: expected a line such as `root {}` naming its parent", t.show(), t.show())
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
                        let at = parent_token.get(cur).copied().flatten().or_else(|| self.name_tokens.get(cur).copied());
                        let name = self.bones.get(cur).map_or("", |b| b.name.as_str());
                        let message = format!("bone `{name}` is in a cycle in :hierarchy (it is its own ancestor): it is not reachable from root");
                        return Err(at.map_or_else(|| ParseError::new(1, 1, message.clone()), |t| error_at(&t, message.clone())));
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
        Ok(Asf { version: self.version, name: self.name, units: self.units, documentation: self.documentation, root, bones, warnings: self.warnings })
    }
}

/// The parent named on the hierarchy line of `child_token` (for messages).
fn first_parent_name(edges: &[Edge], child_token: &Token) -> String {
    edges.iter().find(|e| e.child.line == child_token.line && e.child.column == child_token.column).map_or_else(String::new, |e| e.parent.show())
}

fn unterminated(begin: &Token, found: &str) -> ParseError {
    error_at(begin, format!("`begin` at line {} has no `end`: expected `end` before the next section, {found}", begin.line))
}

