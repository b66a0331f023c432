//! A model's facts: counts from its file, skins (with a thumbnail of the one in
//! use), the animation playing and the key frame drawn.

use crate::character::Character;
use mocap::Model;
use std::sync::Arc;

/// Largest side of the skin thumbnail in points.
const THUMBNAIL: f32 = 160.0;

/// Shows the model section for character `c`, whose model is `model`.
pub fn show(ui: &mut egui::Ui, c: &Character, model: &Model) {
    ui.heading("Model");
    let mesh = &model.mesh;
    let counts = mesh.source_counts;
    egui::Grid::new("model").num_columns(2).striped(true).show(ui, |ui| {
        let mut row = |k: &str, v: String| {
            ui.label(k);
            ui.label(v);
            ui.end_row();
        };
        row("Vertices", counts.vertices.to_string());
        row("Triangles", counts.triangles.to_string());
        row("Tex coords", format!("{} (skin {}×{})", counts.tex_coords, mesh.skin_size[0], mesh.skin_size[1]));
        row("Key frames", mesh.frame_count().to_string());
        row("Animations", mesh.animations().len().to_string());
        let (first, last) = model.range();
        row("Animation", format!("{} (frames {first}–{last})", model.animation_name()));
        if let Some(at) = c.extra.morph {
            let shown = if at.blend > 0.0 && at.frame1 != at.frame0 {
                format!("{} → {} ({:.0}%)", model.frame_name(at.frame0), model.frame_name(at.frame1), at.blend * 100.0)
            } else {
                model.frame_name(at.frame0).to_owned()
            };
            row("Frame", format!("{} · {shown}", at.frame0));
        }
        let named = if mesh.skins.is_empty() { "(none named)".to_owned() } else { mesh.skins.join("\n") };
        row("Skins named", named);
        row(
            "Skin used",
            model.skin.as_ref().map_or("none (neutral material)".to_owned(), |s| {
                format!("{} ({}×{})", s.name, s.image.width, s.image.height)
            }),
        );
    });
    if let Some(skin) = &model.skin {
        thumbnail(ui, skin);
    }
}

/// The skin in use, scaled to fit [`THUMBNAIL`]; its texture is made once per image.
fn thumbnail(ui: &mut egui::Ui, skin: &mocap::model::mesh::Skin) {
    let id = egui::Id::unique(("skin-thumbnail", Arc::as_ptr(&skin.image) as usize));
    let cached: Option<egui::TextureHandle> = ui.ctx().data(|d| d.get_temp(id));
    let texture = cached.unwrap_or_else(|| {
        let size = [skin.image.width as usize, skin.image.height as usize];
        let image = egui::ColorImage::from_rgba_unmultiplied(size, &skin.image.pixels);
        let handle = ui.ctx().load_texture(skin.name.clone(), image, egui::TextureOptions::LINEAR);
        ui.ctx().data_mut(|d| d.insert_temp(id, handle.clone()));
        handle
    });
    let [w, h] = texture.size().map(|v| v.max(1) as f32);
    let scale = (THUMBNAIL / w.max(h)).min(2.0);
    ui.add(egui::Image::new(&texture).fit_to_exact_size(egui::vec2(w * scale, h * scale))).on_hover_text(&skin.name);
}
