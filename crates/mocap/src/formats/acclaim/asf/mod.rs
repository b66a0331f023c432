//! The ASF skeleton reader: the [`Asf`] it gives and [`parse_asf`] here, with the
//! parser's state and its token helpers; the sections and the small ones in
//! `sections`, `:bonedata` blocks in `bones`, and `:hierarchy` resolved into
//! parents in `hierarchy`.

use super::text::{Cursor, Token, binary_kind, decode_name, parse_f32};
use super::{AngleUnit, AxisOrder, Dof};
use crate::error::{ParseError, Warning};
use std::collections::HashMap;

mod bones;
mod hierarchy;
mod sections;
#[cfg(test)]
mod tests;

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
}

/// A `begin` with no `end` before `found`.
fn unterminated(begin: &Token, found: &str) -> ParseError {
    error_at(
        begin,
        format!("`begin` at line {} has no `end`: expected `end` before the next section, {found}", begin.line),
    )
}
