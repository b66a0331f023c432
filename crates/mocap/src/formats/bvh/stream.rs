//! [`Stream`]: a BVH file read while it arrives. Bytes are pushed as they come
//! (a browser reading a dropped file, a network download); once the header is
//! there, every whole line of motion rows is parsed at once, so that when the
//! last bytes arrive little is left to do. The result is the same as [`parse`]
//! of the whole file, bit for bit, warnings and errors included: whatever is
//! unusual (a malformed row, a header the first bytes did not settle, a
//! skeleton without channels) is left to [`parse`] at the end.
//!
//! [`parse`]: super::parse

use super::header::{self, Header};
use super::rows::RowBuilder;
use crate::error::ParseError;
use crate::model::clip::Clip;

/// Header parses tried on a growing prefix before leaving the file to
/// [`super::parse`] (each one reads the whole header again).
const HEADER_TRIES: u32 = 4;

/// Bytes enough to tell whether a file is BVH at all (its first word).
const SNIFF_BYTES: usize = 64;

/// A BVH file being read (see the module documentation).
#[derive(Default)]
pub struct Stream {
    bytes: Vec<u8>,
    state: State,
    /// Where the search for `Frame Time` goes on (where it was found, once it is).
    searched: usize,
    /// Line feeds after `Frame Time`, counted up to `counted` (each byte looked
    /// at once: a file whose rows end in lone CRs has none).
    line_feeds: usize,
    counted: usize,
    header_tries: u32,
}

#[derive(Default)]
enum State {
    /// The header is not complete yet.
    #[default]
    Header,
    /// The header is read: rows are parsed up to `next`, a line start.
    Rows { header: Box<Header>, builder: RowBuilder, next: usize },
    /// [`super::parse`] reads the whole file at the end.
    Whole,
}

impl Stream {
    /// An empty stream with room for `capacity` bytes (at most 256 MB reserved;
    /// the bytes decide the length).
    pub fn with_capacity(capacity: usize) -> Stream {
        let mut bytes = Vec::new();
        let _ = bytes.try_reserve_exact(capacity.min(256 << 20));
        Stream { bytes, ..Stream::default() }
    }

    /// Appends `chunk` and parses what it completes.
    pub fn push(&mut self, chunk: &[u8]) {
        let start = self.bytes.len();
        self.bytes.extend_from_slice(chunk);
        // Where the search for the last line feed starts: the rows' start when
        // they begin in this push, else the new bytes.
        let mut search_from = start;
        if matches!(self.state, State::Header) {
            search_from = 0;
            // Not BVH (as far as the first bytes tell): nothing to look for.
            if self.bytes.len() >= SNIFF_BYTES && !super::sniff(&self.bytes) {
                self.state = State::Whole;
                return;
            }
            self.try_header();
        }
        if let State::Rows { builder, next, .. } = &mut self.state {
            // Whole lines only: up to the last line feed (a CRLF is never cut).
            // Bytes of earlier pushes hold none after `next`: only new ones are
            // searched (each byte once, even where lines end in lone CRs).
            let rest = self.bytes.get(*next..).unwrap_or(&[]);
            let new = search_from.saturating_sub(*next);
            if let Some(end) = rest.get(new..).and_then(|r| memchr::memrchr(b'\n', r)).map(|i| i + new) {
                let piece = &rest[..=end];
                let first_rows = builder.is_empty();
                if builder.push(piece).is_some() {
                    *next += piece.len();
                    if first_rows {
                        // Room for the rest of the file's announced size.
                        builder.reserve_for(self.bytes.capacity().saturating_sub(self.bytes.len()), piece.len());
                    }
                } else {
                    self.state = State::Whole;
                }
            }
        }
    }

    /// Asks for room for `additional` more bytes; an error (and nothing
    /// reserved) where memory is short.
    pub fn try_reserve(&mut self, additional: usize) -> Result<(), std::collections::TryReserveError> {
        self.bytes.try_reserve(additional)
    }

    /// The bytes pushed so far.
    pub fn bytes(&self) -> &[u8] {
        &self.bytes
    }

    /// Whether the bytes look like BVH (see [`super::sniff`]).
    pub fn is_bvh(&self) -> bool {
        super::sniff(&self.bytes)
    }

    /// The bytes pushed, for reading them some other way.
    pub fn into_bytes(self) -> Vec<u8> {
        self.bytes
    }

    /// Reads the header once the bytes hold it and the first row's first line:
    /// after `Frame Time`, a row value followed by a line feed.
    fn try_header(&mut self) {
        let Some(found) = find_ignore_case(&self.bytes, self.searched, b"frame time") else {
            // Keep the last few bytes: the words may straddle two pushes.
            self.searched = self.bytes.len().saturating_sub(b"frame time".len());
            return;
        };
        self.searched = found;
        let from = self.counted.max(found);
        self.line_feeds += memchr::memchr_iter(b'\n', self.bytes.get(from..).unwrap_or(&[])).count();
        self.counted = self.bytes.len();
        // The Frame Time line and at least one more.
        if self.line_feeds < 2 {
            return;
        }
        if self.header_tries >= HEADER_TRIES {
            self.state = State::Whole;
            return;
        }
        self.header_tries += 1;
        let Ok(header) = header::parse_header(&self.bytes) else {
            self.state = State::Whole;
            return;
        };
        let width = header.skeleton.channel_count();
        match header.data {
            // The first row's first value is whole (a line feed follows it).
            Some((start, line, column))
                if width > 0 && self.bytes.get(start..).is_some_and(|r| memchr::memchr(b'\n', r).is_some()) =>
            {
                self.state = State::Rows {
                    header: Box::new(header),
                    builder: RowBuilder::new(line, column, width),
                    next: start,
                };
            }
            // Not enough yet (the rows have not begun), or nothing to stream.
            None if self.header_tries < HEADER_TRIES => {}
            _ => self.state = State::Whole,
        }
    }

    /// The clip, once every byte is pushed: the same as [`super::parse`] of
    /// [`Stream::bytes`].
    pub fn finish(self) -> Result<Clip, ParseError> {
        let Stream { bytes, state, .. } = self;
        let State::Rows { header, mut builder, next } = state else {
            return super::parse(&bytes);
        };
        // The header as the whole file has it must be the one the rows began
        // from (a prefix can end where a later header line would have gone on).
        let Ok(whole) = header::parse_header(&bytes) else {
            return super::parse(&bytes);
        };
        if whole.data != header.data
            || whole.frame_time != header.frame_time
            || whole.declared_frames != header.declared_frames
        {
            return super::parse(&bytes);
        }
        if bytes.get(next..).is_some_and(|rest| !rest.is_empty() && builder.push(rest).is_none()) {
            return super::parse(&bytes);
        }
        super::assemble(whole, builder.finish())
    }
}

/// Where `needle` (lower-case ASCII) first occurs in `hay` from `from` on, in
/// any case.
fn find_ignore_case(hay: &[u8], from: usize, needle: &[u8]) -> Option<usize> {
    let first = needle.first()?;
    let hay_from = hay.get(from..)?;
    memchr::memchr2_iter(*first, first.to_ascii_uppercase(), hay_from)
        .map(|i| from + i)
        .find(|&i| hay.get(i..i + needle.len()).is_some_and(|w| w.eq_ignore_ascii_case(needle)))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// What a clip is made of, comparable bit for bit.
    fn summary(result: &Result<Clip, ParseError>) -> String {
        match result {
            Err(e) => format!("error {e}"),
            Ok(clip) => {
                let joints: Vec<String> = clip
                    .skeleton()
                    .joints()
                    .iter()
                    .map(|j| format!("{} {:?} {:?}", j.name, j.offset, j.channels))
                    .collect();
                let data: Vec<u32> = clip.motion().data().iter().map(|v| v.to_bits()).collect();
                let warnings: Vec<String> =
                    clip.warnings.iter().map(|w| format!("{:?} {}", w.line, w.message)).collect();
                format!(
                    "{joints:?} {} {} {data:?} {warnings:?}",
                    clip.frame_count(),
                    clip.motion().frame_time().to_bits()
                )
            }
        }
    }

    fn streamed(bytes: &[u8], piece: usize) -> Result<Clip, ParseError> {
        let mut stream = Stream::with_capacity(bytes.len());
        for chunk in bytes.chunks(piece.max(1)) {
            stream.push(chunk);
        }
        assert_eq!(stream.bytes(), bytes);
        stream.finish()
    }

    fn check(name: &str, bytes: &[u8]) {
        let expected = summary(&super::super::parse(bytes));
        for piece in [1, 2, 3, 5, 16, 64, 257, 4096, bytes.len().max(1)] {
            assert_eq!(summary(&streamed(bytes, piece)), expected, "{name}, pieces of {piece} bytes");
        }
    }

    const WALK: &[u8] = include_bytes!("../../../../../data/walk.bvh");

    #[test]
    fn streamed_files_read_as_parse_reads_them() {
        let walk = String::from_utf8_lossy(WALK).into_owned();
        check("walk.bvh", WALK);
        check("CRLF", walk.replace('\n', "\r\n").as_bytes());
        check("lone CR", walk.replace('\n', "\r").as_bytes());
        check("no final line break", walk.trim_end().as_bytes());
        check("blank lines among the rows", walk.replacen("\n0", "\n\n  \n0", 3).as_bytes());
        check(
            "Frames after Frame Time",
            walk.replacen("Frames:", "Framez:", 1)
                .replacen("Frame Time:", "Frames: 67\nFrame Time:", 1)
                .replacen("Framez:", "Frame Time:", 1)
                .as_bytes(),
        );
        check("decimal commas", walk.replacen(" 0.", " 0,", 2).as_bytes());
        check("NaN", walk.replacen(" 0.", " nan ", 1).as_bytes());
        check("a short row", format!("{walk}1 2 3\n").as_bytes());
        check("a long row", walk.replacen("\n", " 1\n", walk.lines().count() - 3).as_bytes());
        check("a word in a row", format!("{walk}x\n").as_bytes());
        check("header only", &WALK[..walk.find("MOTION").unwrap_or(0)]);
        check(
            "no rows",
            &WALK[..walk.find("Frame Time").and_then(|i| walk[i..].find('\n').map(|j| i + j + 1)).unwrap_or(0)],
        );
        check("truncated in a row", &WALK[..WALK.len() - 7]);
        check("empty", b"");
        check("not BVH", b"hello\nframe time\n1\n2\n");
        check("not BVH, long", format!("{}\n{walk}", "x".repeat(100)).as_bytes());
        check("BVH after much white space", format!("{}{walk}", " \n".repeat(100)).as_bytes());
        check(
            "no channels",
            b"HIERARCHY\nROOT a\n{\nOFFSET 0 0 0\nCHANNELS 0\n}\nMOTION\nFrames: 2\nFrame Time: 0.1\n\n\n",
        );
    }

    proptest::proptest! {
        #[test]
        fn any_cut_of_walk_reads_the_same(len in 0usize..4000, piece in 1usize..600) {
            let bytes = &WALK[..len.min(WALK.len())];
            proptest::prop_assert_eq!(summary(&streamed(bytes, piece)), summary(&super::super::parse(bytes)));
        }
    }

    #[test]
    fn rows_are_parsed_as_they_arrive() {
        let mut stream = Stream::with_capacity(WALK.len());
        let half = WALK.len() / 2;
        stream.push(&WALK[..half]);
        let State::Rows { next, .. } = &stream.state else { panic!("the rows began") };
        assert!(*next > half - 400, "rows up to the last whole line were parsed ({next} of {half})");
        stream.push(&WALK[half..]);
        assert_eq!(summary(&stream.finish()), summary(&super::super::parse(WALK)));
    }
}
