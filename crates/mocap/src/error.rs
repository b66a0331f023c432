//! Errors and warnings from the readers.

use serde::{Deserialize, Serialize};
use std::fmt;

/// A reader error with its position in the file: 1-based line and byte column in
/// text formats (shown `line:column: message`); in binary formats line 0 and a
/// message that starts with the byte offset (shown `byte N: message`).
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{}{message}", if *line == 0 { String::new() } else { format!("{line}:{column}: ") })]
pub struct ParseError {
    /// 1-based line; 0 in binary formats (the message gives the byte offset).
    pub line: u32,
    /// 1-based column (bytes); 0 in binary formats.
    pub column: u32,
    /// What was wrong, and what was expected.
    pub message: String,
}

impl ParseError {
    /// Builds an error at a position.
    pub fn new(line: u32, column: u32, message: impl Into<String>) -> ParseError {
        ParseError { line, column, message: message.into() }
    }

    /// An error in a binary file at byte `offset` (0-based): shown `byte N: message`.
    pub fn at_byte(offset: usize, message: impl std::fmt::Display) -> ParseError {
        ParseError { line: 0, column: 0, message: format!("byte {offset}: {message}") }
    }
}

/// A non-fatal problem found while reading; the clip is still usable.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Warning {
    /// 1-based line the warning refers to, when there is one.
    pub line: Option<u32>,
    /// What was odd and what the reader did about it.
    pub message: String,
}

impl fmt::Display for Warning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.line {
            Some(line) => write!(f, "line {line}: {}", self.message),
            None => f.write_str(&self.message),
        }
    }
}

/// Failure to load a named file: a parse error or a format we do not read.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum LoadError {
    /// The file is in a known format but malformed.
    #[error("{file}:{error}")]
    Parse {
        /// The file name as given by the caller.
        file: String,
        /// Where and what.
        error: ParseError,
    },
    /// Neither the extension nor the content matches a format we read.
    #[error(
        "{file}: not a motion file or model this viewer reads (BVH, BVA, an Acclaim .asf skeleton with .amc motions, a Quake 2 .md2 model with its PCX, BMP, PNG, JPEG or TGA skin, or glTF .glb/.gltf)"
    )]
    UnknownFormat {
        /// The file name as given by the caller.
        file: String,
    },
    /// An Acclaim motion with no skeleton to read it with.
    #[error("{file}: an Acclaim motion (.amc) needs its skeleton: open it together with its .asf file{}", named.as_ref().map(|n| format!(" (the motion names {n})")).unwrap_or_default())]
    MissingSkeleton {
        /// The motion file's name.
        file: String,
        /// The skeleton file the motion's header names (`#!OML:ASF …`), if any.
        named: Option<String>,
    },
    /// An image opened without a model to put it on.
    #[error("{file}: an image is used as a model's skin: open it together with its .md2 model")]
    LoneImage {
        /// The image file's name.
        file: String,
    },
    /// The skeleton an Acclaim motion needs could not be read.
    #[error("{file}: its skeleton could not be read: {skeleton}")]
    SkeletonFailed {
        /// The motion file's name.
        file: String,
        /// Why the skeleton failed.
        skeleton: Box<LoadError>,
    },
}
