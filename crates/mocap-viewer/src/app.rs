//! The eframe app: runs a shared [`Viewer`] each frame with eframe's wgpu state.

use crate::command::{HostRequest, OpenMode};
use crate::viewer::Viewer;
use std::cell::RefCell;
use std::rc::Rc;

/// An eframe app around a viewer that the host (e.g. JavaScript) can also reach.
pub struct ViewerApp {
    viewer: Rc<RefCell<Viewer>>,
    on_open_requested: Box<dyn FnMut(OpenMode)>,
    on_share_requested: Box<dyn FnMut()>,
    on_export_video: Option<Box<dyn FnMut()>>,
    /// Runs when the user asks for the previous session ([`HostRequest::RestorePrevious`]).
    on_restore_requested: Option<Box<dyn FnMut()>>,
    on_save_requested: Box<dyn FnMut(String, Vec<u8>)>,
    /// The panels' colour, which the window is cleared to (see [`ViewerApp::new`]).
    panel_fill: egui::Color32,
    /// Runs when the view state changed (see [`ViewerApp::on_view_change`]).
    on_view_change: Option<Box<dyn FnMut()>>,
    /// The view state at the end of the last frame.
    last_view: String,
}

impl ViewerApp {
    /// Wraps `viewer` (and installs the viewer's [`crate::fonts`] and picks the dark theme, to match the 3D view); `on_open_requested`
    /// runs when the user presses "Open…" ([`OpenMode::Replace`]) or "Add…" ([`OpenMode::Add`]).
    ///
    /// Panels are left unpainted and the window is cleared to their colour
    /// instead: a clear costs next to nothing, while egui's fill of the panels
    /// (its shader, blending) costs about as much per pixel on a software
    /// rasteriser as the whole 3D view.
    pub fn new(
        ctx: &egui::Context,
        viewer: Rc<RefCell<Viewer>>,
        on_open_requested: Box<dyn FnMut(OpenMode)>,
    ) -> ViewerApp {
        crate::fonts::install(ctx);
        ctx.set_theme(egui::ThemePreference::Dark);
        let mut panel_fill = egui::Color32::TRANSPARENT;
        ctx.style_mut_of(egui::Theme::Dark, |style| {
            panel_fill = std::mem::replace(&mut style.visuals.panel_fill, egui::Color32::TRANSPARENT)
        });
        ViewerApp {
            viewer,
            on_open_requested,
            on_share_requested: Box::new(|| {}),
            on_export_video: None,
            on_restore_requested: None,
            on_save_requested: Box::new(|_, _| {}),
            panel_fill,
            on_view_change: None,
            last_view: String::new(),
        }
    }

    /// Sets what runs after a frame whose view state ([`Viewer::view_fragment`])
    /// differs from the last frame's: a host keeping the state somewhere (the
    /// page's URL fragment) follows it without polling, so a page at rest does
    /// no work at all.
    pub fn on_view_change(mut self, f: Box<dyn FnMut()>) -> ViewerApp {
        self.on_view_change = Some(f);
        self
    }

    /// Tells the host when the view state changed.
    fn update_view(&mut self, view: Option<String>) {
        if let (Some(f), Some(view)) = (self.on_view_change.as_mut(), view)
            && view != self.last_view
        {
            self.last_view = view;
            f();
        }
    }

    /// Sets what runs when the viewer asks to save a file ([`HostRequest::Save`]:
    /// Save as BVH, Save rig): `f` gets the file's name and contents.
    pub fn on_save(mut self, f: Box<dyn FnMut(String, Vec<u8>)>) -> ViewerApp {
        self.on_save_requested = f;
        self
    }

    /// Sets what runs when the user asks for the previous session the host holds
    /// (File ▸ Restore previous session; the host reads it and restores it).
    pub fn on_restore_previous(mut self, f: Box<dyn FnMut()>) -> ViewerApp {
        self.on_restore_requested = Some(f);
        self
    }

    /// Sets what runs when the user asks to export a video (the host shows its
    /// dialog, renders with [`crate::Viewer::video_frame`] and encodes); the
    /// Export video… button shows from now on.
    pub fn on_export_video(mut self, f: Box<dyn FnMut()>) -> ViewerApp {
        self.on_export_video = Some(f);
        if let Ok(mut v) = self.viewer.try_borrow_mut() {
            let _ = v.apply(crate::Command::SetVideoExport(true));
        }
        self
    }

    /// Sets what runs when the user presses "Share" (the host builds and copies the link).
    pub fn on_share(mut self, f: Box<dyn FnMut()>) -> ViewerApp {
        self.on_share_requested = f;
        self
    }
}

impl eframe::App for ViewerApp {
    fn clear_color(&self, _visuals: &egui::Visuals) -> [f32; 4] {
        self.panel_fill.to_normalized_gamma_f32()
    }

    fn ui(&mut self, ui: &mut egui::Ui, frame: &mut eframe::Frame) {
        let (requests, view) = {
            let Ok(mut viewer) = self.viewer.try_borrow_mut() else { return };
            let mut requests = viewer.ui(ui, frame.wgpu_render_state());
            // Requests made by commands from the JS API between frames, too.
            requests.extend(viewer.take_requests());
            let view = self.on_view_change.is_some().then(|| viewer.state().view_fragment());
            (requests, view)
        };
        self.update_view(view);
        for request in requests {
            match request {
                HostRequest::Save { name, bytes } => (self.on_save_requested)(name, bytes),
                HostRequest::PickFiles(mode) => (self.on_open_requested)(mode),
                HostRequest::Share => (self.on_share_requested)(),
                HostRequest::ExportVideo => {
                    if let Some(f) = &mut self.on_export_video {
                        f();
                    }
                }
                HostRequest::RestorePrevious => {
                    if let Some(f) = &mut self.on_restore_requested {
                        f();
                    }
                }
            }
        }
    }
}
