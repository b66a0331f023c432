//! The BVH header: the HIERARCHY section and the MOTION lines before the rows.

pub(crate) use crate::formats::text::decode_name;

use super::cursor::{Cursor, Token};
use crate::error::{ParseError, Warning};
use crate::model::channel::Channel;
use crate::model::skeleton::{EulerConvention, Joint, Skeleton};
use glam::Vec3;

/// Everything before the motion rows.
pub(crate) struct Header {
    /// The joints in file order.
    pub skeleton: Skeleton,
    /// What `Frames:` said, and its line.
    pub declared_frames: Option<(u64, u32)>,
    /// What `Frame Time:` said, and its line.
    pub frame_time: Option<(f64, u32)>,
    /// Where the rows start: byte offset, line, and column of that offset.
    pub data: Option<(usize, u32, u32)>,
    /// Whether a MOTION keyword was seen.
    pub has_motion: bool,
    /// Non-fatal problems.
    pub warnings: Vec<Warning>,
}

fn error_at(token: &Token, message: impl Into<String>) -> ParseError {
    ParseError::new(token.line, token.column, message)
}

fn end_of_file(cursor: &Cursor, what: &str) -> ParseError {
    let (line, column) = cursor.position();
    ParseError::new(line, column, format!("unexpected end of file: expected {what}"))
}

/// Parses one float token (exponents, leading `+`, `-0` accepted).
pub(crate) fn parse_f32(token: &Token) -> Option<f32> {
    match fast_float2::parse_partial::<f32, _>(token.text) {
        Ok((v, used)) if used == token.text.len() => Some(v),
        _ => None,
    }
}

/// The start of the warning for a top-level `JOINT`.
const JOINT_AS_ROOT: &str = "the skeleton's root is written JOINT";

struct Builder<'a> {
    cursor: Cursor<'a>,
    joints: Vec<Joint>,
    /// Open joints, innermost last, with whether each has had its OFFSET.
    stack: Vec<(usize, bool)>,
    warnings: Vec<Warning>,
}

/// Parses the header of a BVH file.
pub(crate) fn parse_header(src: &[u8]) -> Result<Header, ParseError> {
    let mut b = Builder { cursor: Cursor::new(src), joints: Vec::new(), stack: Vec::new(), warnings: Vec::new() };
    let first = b.cursor.next_token().ok_or_else(|| ParseError::new(1, 1, "empty file: expected HIERARCHY"))?;
    if !first.is("HIERARCHY") {
        return Err(error_at(
            &first,
            format!("expected HIERARCHY at the start of a BVH file, found `{}`", first.show()),
        ));
    }
    loop {
        let Some(token) = b.cursor.next_token() else {
            if let Some(&(open, _)) = b.stack.last() {
                let name = b.joints.get(open).map_or("", |j| j.name.as_str()).to_owned();
                return Err(end_of_file(&b.cursor, &format!("`}}` to close joint `{name}`")));
            }
            if b.joints.is_empty() {
                return Err(end_of_file(&b.cursor, "ROOT"));
            }
            b.warnings.push(Warning {
                line: None,
                message: "no MOTION section: showing the skeleton in its rest pose".into(),
            });
            return b.finish(None, None, None, false);
        };
        if b.stack.is_empty() {
            if token.is("ROOT") {
                b.open_joint(&token, None, false, None)?;
            } else if token.is("JOINT") {
                // Some Mixamo-to-BVH converters write the root as `JOINT`. With no joint
                // open it can only be a root, so it reads as one, with a warning.
                if !b.warnings.iter().any(|w| w.message.starts_with(JOINT_AS_ROOT)) {
                    b.warnings.push(Warning {
                        line: Some(token.line),
                        message: format!("{JOINT_AS_ROOT}; read as the root (BVH writes ROOT there)"),
                    });
                }
                b.open_joint(&token, None, false, None)?;
            } else if token.is("MOTION") {
                if b.joints.is_empty() {
                    return Err(error_at(&token, "expected ROOT before MOTION: the file has no skeleton"));
                }
                return b.motion_header();
            } else if token.is("HIERARCHY") {
                return Err(error_at(
                    &token,
                    "a second HIERARCHY section: a BVH file has one (several skeletons are several ROOTs in it)",
                ));
            } else {
                let what = if b.joints.is_empty() { "ROOT" } else { "ROOT or MOTION" };
                return Err(error_at(&token, format!("expected {what}, found `{}`", token.show())));
            }
        } else {
            b.joint_item(&token)?;
        }
    }
}

impl<'a> Builder<'a> {
    fn finish(
        self,
        declared_frames: Option<(u64, u32)>,
        frame_time: Option<(f64, u32)>,
        data: Option<(usize, u32, u32)>,
        has_motion: bool,
    ) -> Result<Header, ParseError> {
        // Joints were pushed parent-first with End Sites channel-free, so this holds;
        // a non-finite OFFSET is the one thing the file can still get wrong.
        let skeleton = Skeleton::new(self.joints, EulerConvention::Intrinsic)
            .map_err(|e| ParseError::new(1, 1, format!("{e}")))?;
        Ok(Header { skeleton, declared_frames, frame_time, data, has_motion, warnings: self.warnings })
    }

    fn current(&self) -> Option<usize> {
        self.stack.last().map(|&(j, _)| j)
    }

    /// One item inside an open joint's braces.
    fn joint_item(&mut self, token: &Token<'a>) -> Result<(), ParseError> {
        let Some(current) = self.current() else { return Ok(()) };
        let in_end_site = self.joints.get(current).is_some_and(Joint::is_end_site);
        if token.is("OFFSET") {
            let mut v = [0.0f32; 3];
            for (axis, slot) in v.iter_mut().enumerate() {
                let t = self.cursor.next_token().ok_or_else(|| end_of_file(&self.cursor, "an OFFSET value"))?;
                *slot = parse_f32(&t).ok_or_else(|| {
                    error_at(
                        &t,
                        format!(
                            "expected the {} value of OFFSET (a number), found `{}`",
                            ["x", "y", "z"][axis],
                            t.show()
                        ),
                    )
                })?;
            }
            if let Some(joint) = self.joints.get_mut(current) {
                joint.offset = Vec3::from(v);
            }
            if let Some(top) = self.stack.last_mut() {
                top.1 = true;
            }
        } else if token.is("CHANNELS") {
            if in_end_site {
                return Err(error_at(token, "an End Site has no CHANNELS"));
            }
            self.channels(token, current)?;
        } else if token.is("JOINT") {
            if in_end_site {
                return Err(error_at(token, "an End Site cannot contain a JOINT"));
            }
            self.open_joint(token, Some(current), false, None)?;
        } else if token.is("End") || token.is("EndSite") {
            if in_end_site {
                return Err(error_at(token, "an End Site cannot contain another End Site"));
            }
            let mut glued_name = None;
            if token.is("End") {
                let site = self.cursor.next_token().ok_or_else(|| end_of_file(&self.cursor, "`Site` after `End`"))?;
                let starts_with_site = site.text.get(..4).is_some_and(|w| w.eq_ignore_ascii_case(b"Site"));
                if !starts_with_site {
                    return Err(error_at(&site, format!("expected `Site` after `End`, found `{}`", site.show())));
                }
                // `End Site4`: a suffix glued to `Site` names the End Site.
                if site.text.len() > 4 {
                    glued_name = Some(decode_name(site.text));
                }
            }
            self.open_joint(token, Some(current), true, glued_name)?;
        } else if token.is("}") {
            self.close_joint(token);
        } else {
            let what = if in_end_site { "OFFSET or `}`" } else { "OFFSET, CHANNELS, JOINT, End Site or `}`" };
            return Err(error_at(token, format!("expected {what}, found `{}`", token.show())));
        }
        Ok(())
    }

    fn channels(&mut self, token: &Token<'a>, current: usize) -> Result<(), ParseError> {
        let count_token = self.cursor.next_token().ok_or_else(|| end_of_file(&self.cursor, "the channel count"))?;
        let count: u32 = std::str::from_utf8(count_token.text).ok().and_then(|s| s.parse().ok()).ok_or_else(|| {
            error_at(&count_token, format!("expected a channel count after CHANNELS, found `{}`", count_token.show()))
        })?;
        if self.joints.get(current).is_some_and(|j| !j.channels.is_empty()) {
            return Err(error_at(token, "a second CHANNELS line for the same joint"));
        }
        let mut channels = Vec::new();
        for _ in 0..count {
            let t = self.cursor.next_token().ok_or_else(|| end_of_file(&self.cursor, "a channel name"))?;
            let channel = Channel::from_name(t.text).ok_or_else(|| {
                error_at(&t, format!("expected a channel name (Xposition, Yposition, Zposition, Xrotation, Yrotation or Zrotation; CHANNELS said {count}), found `{}`", t.show()))
            })?;
            channels.push(channel);
        }
        if let Some(joint) = self.joints.get_mut(current) {
            joint.channels = channels;
        }
        Ok(())
    }

    /// Reads a name (rest of the line, or the next token), the `{`, and opens a joint.
    fn open_joint(
        &mut self,
        keyword: &Token<'a>,
        parent: Option<usize>,
        end_site: bool,
        glued_name: Option<String>,
    ) -> Result<(), ParseError> {
        let name_token = self.cursor.rest_of_line();
        let name = match (name_token, end_site) {
            (Some(t), _) => decode_name(t.text),
            (None, true) => glued_name.unwrap_or_else(|| {
                let parent_name = parent.and_then(|p| self.joints.get(p)).map_or("", |j| j.name.as_str());
                format!("{parent_name}_End")
            }),
            (None, false) => {
                // The name may be on the next line; it must not be a brace.
                match self.cursor.peek_token() {
                    Some(t) if t.text != b"{" && t.text != b"}" => {
                        self.cursor.next_token();
                        decode_name(t.text)
                    }
                    _ => {
                        return Err(error_at(
                            keyword,
                            format!("expected a joint name after {}", String::from_utf8_lossy(keyword.text)),
                        ));
                    }
                }
            }
        };
        let open =
            self.cursor.next_token().ok_or_else(|| end_of_file(&self.cursor, &format!("`{{` after `{name}`")))?;
        if open.text != b"{" {
            return Err(error_at(&open, format!("expected `{{` after joint name `{name}`, found `{}`", open.show())));
        }
        self.joints.push(if end_site {
            Joint::end_site(name, parent, Vec3::ZERO)
        } else {
            Joint::new(name, parent, Vec3::ZERO, Vec::new())
        });
        self.stack.push((self.joints.len() - 1, false));
        Ok(())
    }

    fn close_joint(&mut self, token: &Token) {
        if let Some((joint, false)) = self.stack.pop() {
            let name = self.joints.get(joint).map_or("", |j| j.name.as_str());
            self.warnings.push(Warning {
                line: Some(token.line),
                message: format!("joint `{name}` has no OFFSET; using 0 0 0"),
            });
        }
    }

    /// `Frames:` and `Frame Time:` in any order and case, then the first row.
    fn motion_header(mut self) -> Result<Header, ParseError> {
        let mut frames = None;
        let mut frame_time = None;
        loop {
            let Some(t) = self.cursor.peek_token() else {
                return self.finish(frames, frame_time, None, true);
            };
            let lower = t.text.to_ascii_lowercase();
            if lower.starts_with(b"frames") && (lower.len() == 6 || lower[6] == b':') {
                self.cursor.next_token();
                let value = self.header_value(&t, &lower[6..], "Frames:")?;
                // A whole number; "120.0" (some exporters) is accepted too.
                // Too many digits for u64 saturates: only the rows count anyway.
                let n = std::str::from_utf8(value.text).ok().and_then(|s| {
                    let all_digits = !s.is_empty() && s.bytes().all(|b| b.is_ascii_digit());
                    s.parse::<u64>().ok().or_else(|| all_digits.then_some(u64::MAX)).or_else(|| {
                        s.parse::<f64>().ok().filter(|f| f.fract() == 0.0 && *f >= 0.0 && *f < 1e19).map(|f| f as u64)
                    })
                });
                let n = n.ok_or_else(|| {
                    error_at(
                        &value,
                        format!("expected a whole number of frames after Frames:, found `{}`", value.show()),
                    )
                })?;
                frames = Some((n, t.line));
            } else if lower == b"frame" {
                self.cursor.next_token();
                let time =
                    self.cursor.next_token().ok_or_else(|| end_of_file(&self.cursor, "`Time:` after `Frame`"))?;
                let lt = time.text.to_ascii_lowercase();
                if !(lt.starts_with(b"time") && (lt.len() == 4 || lt[4] == b':')) {
                    return Err(error_at(&time, format!("expected `Time:` after `Frame`, found `{}`", time.show())));
                }
                let value = self.header_value(&time, &lt[4..], "Frame Time:")?;
                let v = fast_float2::parse::<f64, _>(value.text).ok();
                let v = v.ok_or_else(|| {
                    error_at(&value, format!("expected a number after Frame Time:, found `{}`", value.show()))
                })?;
                frame_time = Some((v, t.line));
            } else {
                return self.finish(frames, frame_time, Some((t.start, t.line, t.column)), true);
            }
        }
    }

    /// The value after a header keyword: glued (`Frames:12`), or the next token after
    /// an optional lone `:`.
    fn header_value(&mut self, keyword: &Token<'a>, tail: &[u8], what: &str) -> Result<Token<'a>, ParseError> {
        if tail.len() > 1 {
            let skip = 1 + keyword.text.len() - tail.len();
            return Ok(Token {
                text: &keyword.text[skip..],
                start: keyword.start + skip,
                line: keyword.line,
                column: keyword.column + skip as u32,
            });
        }
        let mut value =
            self.cursor.next_token().ok_or_else(|| end_of_file(&self.cursor, &format!("a value after {what}")))?;
        if tail.is_empty() && value.text == b":" {
            value =
                self.cursor.next_token().ok_or_else(|| end_of_file(&self.cursor, &format!("a value after {what}")))?;
        }
        Ok(value)
    }
}
