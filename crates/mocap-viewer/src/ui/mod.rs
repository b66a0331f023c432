//! The egui panels, one per file.

pub mod compare_legend;
pub mod capture;
pub mod edit_menu;
pub mod hierarchy;
pub mod info;
pub mod inspector;
pub mod joint_map;
pub mod layer_window;
pub mod model_info;
pub mod overlay;
pub mod retarget_window;
pub mod side;
pub mod tentacle;
pub mod timeline;
pub mod toolbar;

/// A menu button reading `label` whose contents `contents` draws. Every menu
/// goes through this one function, so egui's generic menu code is compiled
/// once for all of them (about 4 KB of the page's download per menu otherwise).
pub fn menu(ui: &mut egui::Ui, label: &str, contents: &mut dyn FnMut(&mut egui::Ui)) {
    ui.menu_button(label, |ui| contents(ui));
}
