//! Left panel: the collapsible joint tree; clicking a joint selects it.

use crate::document::Document;

/// Shows the hierarchy panel; records the label of every joint drawn in `labels`.
pub fn show(ui: &mut egui::Ui, doc: Option<&Document>, selected: &mut Option<usize>, labels: &mut Vec<String>) {
    egui::Panel::left("hierarchy").resizable(true).default_size(220.0).show(ui, |ui| {
        ui.heading("Hierarchy");
        let Some(doc) = doc else { return };
        ui.spacing_mut().indent = 10.0;
        egui::ScrollArea::both().auto_shrink([false, false]).show(ui, |ui| {
            let roots = doc.clip.skeleton.joints.iter().enumerate().filter(|(_, j)| j.parent.is_none());
            for (root, _) in roots {
                joint_row(ui, doc, root, selected, labels);
            }
        });
    });
}

fn joint_row(ui: &mut egui::Ui, doc: &Document, index: usize, selected: &mut Option<usize>, labels: &mut Vec<String>) {
    let Some(joint) = doc.clip.skeleton.joints.get(index) else { return };
    labels.push(joint.name.clone());
    let children = doc.children.get(index).map_or(&[][..], Vec::as_slice);
    let is_selected = *selected == Some(index);
    let text = if joint.end_site { egui::RichText::new(&joint.name).weak() } else { egui::RichText::new(&joint.name) };
    if children.is_empty() {
        if ui.selectable_label(is_selected, text).clicked() {
            *selected = Some(index);
        }
        return;
    }
    let id = ui.make_persistent_id(("joint", index));
    egui::collapsing_header::CollapsingState::load_with_default_open(ui.ctx(), id, true)
        .show_header(ui, |ui| {
            if ui.selectable_label(is_selected, text).clicked() {
                *selected = Some(index);
            }
        })
        .body(|ui| {
            for &child in children {
                joint_row(ui, doc, child, selected, labels);
            }
        });
}
