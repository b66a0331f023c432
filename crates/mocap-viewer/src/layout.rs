//! How characters are placed: side by side in lanes, or all on top of each other
//! (the core's [`mocap::stage::Layout`], shared with `mocap render`).

pub use mocap::stage::Layout;
