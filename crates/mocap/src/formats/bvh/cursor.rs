//! A byte cursor for the BVH header: whitespace-separated tokens with line and column,
//! braces as tokens of their own, and "rest of the line" names.

pub(crate) use crate::formats::text::{Token, bom_len, is_blank, line_break_len, show_bytes};

/// Walks the header, keeping line and column.
#[derive(Clone)]
pub(crate) struct Cursor<'a> {
    src: &'a [u8],
    pos: usize,
    line: u32,
    line_start: usize,
}

impl<'a> Cursor<'a> {
    /// Starts at the beginning, skipping a UTF-8 byte-order mark.
    pub fn new(src: &'a [u8]) -> Cursor<'a> {
        let pos = bom_len(src);
        Cursor { src, pos, line: 1, line_start: 0 }
    }

    /// Current line and column (1-based).
    pub fn position(&self) -> (u32, u32) {
        (self.line, self.column_at(self.pos))
    }

    fn column_at(&self, pos: usize) -> u32 {
        u32::try_from(pos.saturating_sub(self.line_start) + 1).unwrap_or(u32::MAX)
    }

    fn newline(&mut self) {
        self.line = self.line.saturating_add(1);
        self.line_start = self.pos;
    }

    /// Skips blanks and line breaks (LF, CRLF and lone CR all end a line).
    pub fn skip_whitespace(&mut self) {
        while let Some(&b) = self.src.get(self.pos) {
            match b {
                b'\n' | b'\r' => {
                    self.pos += line_break_len(self.src, self.pos);
                    self.newline();
                }
                b if is_blank(b) => self.pos += 1,
                _ => break,
            }
        }
    }

    /// The next token, or `None` at the end of the input.
    pub fn next_token(&mut self) -> Option<Token<'a>> {
        self.skip_whitespace();
        let start = self.pos;
        let first = *self.src.get(start)?;
        let end = if first == b'{' || first == b'}' {
            start + 1
        } else {
            let mut end = start;
            while let Some(&b) = self.src.get(end) {
                if is_blank(b) || b == b'\n' || b == b'\r' || b == b'{' || b == b'}' {
                    break;
                }
                end += 1;
            }
            end
        };
        self.pos = end;
        Some(Token { text: &self.src[start..end], start, line: self.line, column: self.column_at(start) })
    }

    /// The next token without consuming it.
    pub fn peek_token(&self) -> Option<Token<'a>> {
        self.clone().next_token()
    }

    /// The rest of the current line up to a `{` (not consumed) or the line end,
    /// trimmed; `None` when that is empty. Used for names, which may hold spaces.
    pub fn rest_of_line(&mut self) -> Option<Token<'a>> {
        while self.src.get(self.pos).is_some_and(|&b| is_blank(b)) {
            self.pos += 1;
        }
        let start = self.pos;
        let mut end = start;
        while let Some(&b) = self.src.get(end) {
            if b == b'\n' || b == b'\r' || b == b'{' || b == b'}' {
                break;
            }
            end += 1;
        }
        self.pos = end;
        let mut trimmed = end;
        while trimmed > start && is_blank(self.src[trimmed - 1]) {
            trimmed -= 1;
        }
        (trimmed > start).then(|| Token {
            text: &self.src[start..trimmed],
            start,
            line: self.line,
            column: self.column_at(start),
        })
    }
}
