//! The `mocap` command's library half: subcommands and headless rendering, shared
//! by the binary, its tests and its benchmarks.

pub mod commands;
pub mod render;
