//! Things made in code rather than read: the generated [`body`] mesh around a
//! skeleton and the [`demo`] characters.

pub mod body;
pub mod demo;
