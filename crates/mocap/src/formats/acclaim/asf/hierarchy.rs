//! `:hierarchy` resolved: every bone's parent, checked (known names, one parent
//! each, no cycles, every bone reachable from the root), and the bones put parents
//! first.

use super::super::text::Token;
use super::{Asf, AsfBone, Edge, Parser, error_at};
use crate::error::ParseError;

impl Parser<'_> {
    /// Resolves `:hierarchy` into parents and orders the bones parents first.
    pub(super) fn finish(self) -> Result<Asf, ParseError> {
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
