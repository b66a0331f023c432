//! The egui panels, one per file.

pub mod capture;
pub mod edit_menu;
pub mod hierarchy;
pub mod info;
pub mod inspector;
pub mod layer_window;
pub mod model_info;
pub mod overlay;
pub mod side;
pub mod tentacle;
pub mod timeline;
pub mod toolbar;
