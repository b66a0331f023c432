//! The motion-capture viewer: an egui app with a timeline, a joint hierarchy, an
//! inspector and a 3D view drawn by `mocap-render`.
//!
//! Data flows one way: bytes → [`mocap::Clip`] (the core's loader) → a
//! [`Character`] on the [`Stage`] (colour, visibility, placement in metres) → playhead
//! ([`Playback`], one clock for all) → world transforms → scene primitives
//! ([`pose_scene`]) → GPU ([`viewport`]). [`Viewer`] holds the state; on the web,
//! [`app::ViewerApp`] runs it inside eframe.

#![warn(missing_docs)]

#[cfg(target_arch = "wasm32")]
pub mod app;
pub mod capture;
pub mod character;
pub mod command;
pub mod comparison;
pub mod drag;
pub mod fonts;
pub mod gesture;
pub mod history;
pub mod keys;
pub mod layer_dialog;
pub mod layout;
pub mod notice;
pub mod panels;
pub mod playback;
pub mod pose_scene;
pub mod quality;
pub mod retarget_dialog;
pub mod rig_edit;
pub mod selection;
pub mod session;
pub mod settings;
pub mod snapshot;
pub mod stage;
pub mod state;
pub mod tentacle;
pub mod tree;
pub mod ui;
pub mod view_state;
pub mod viewer;
pub mod viewport;

pub use character::{Character, Look};
pub use command::{Command, HostRequest, OpenMode};
pub use layout::Layout;
pub use mocap_scene::{OrbitCamera, Waypoint};
pub use notice::{Notice, Outcome};
pub use panels::Panels;
pub use playback::Playback;
pub use selection::Selection;
pub use settings::ViewSettings;
pub use snapshot::{ClipSummary, Snapshot};
pub use stage::Stage;
pub use state::AppState;
pub use view_state::ViewState;
pub use viewer::{VideoDefaults, Viewer, WARM_UP_FRAMES, WARM_UP_MAX_JOINTS};
