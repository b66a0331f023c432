//! The joint mapping table of the Layer and Retarget windows: a row per joint
//! that receives motion, with a menu of the joints that can drive it (proposed
//! by name across the common conventions; changeable or left out by hand).

/// One row: a joint and the joint that drives it, if any.
pub struct Row {
    /// The joint receiving motion.
    pub joint: String,
    /// The joint driving it.
    pub driver: Option<String>,
    /// The chain of the body the joint is on (`left arm`, `spine`), where the
    /// tree's shape was read ([`mocap::ops::retarget::chains`]).
    pub chain: Option<&'static str>,
}

/// Shows the table; a choice made by hand is recorded in `map` as
/// `(joint, driver)` (an empty driver leaves the joint out). `none` labels the
/// "no driver" entry; `id` keeps two tables apart.
pub fn grid(
    ui: &mut egui::Ui,
    id: &str,
    none: &str,
    rows: &[Row],
    drivers: &[String],
    map: &mut Vec<(String, String)>,
) {
    let chains = rows.iter().any(|r| r.chain.is_some());
    egui::ScrollArea::vertical().max_height(260.0).id_salt(id).show(ui, |ui| {
        egui::Grid::new((id, "grid")).striped(true).num_columns(2 + usize::from(chains)).show(ui, |ui| {
            for row in rows {
                if chains {
                    ui.label(egui::RichText::new(row.chain.unwrap_or("")).weak());
                }
                ui.label(&row.joint);
                let mut choice: Option<String> = None;
                egui::ComboBox::from_id_salt((id, row.joint.as_str()))
                    .width(150.0)
                    .selected_text(row.driver.as_deref().unwrap_or(none))
                    .show_ui(ui, |ui| {
                        if ui.selectable_label(row.driver.is_none(), none).clicked() {
                            choice = Some(String::new());
                        }
                        for n in drivers {
                            if ui.selectable_label(row.driver.as_deref() == Some(n.as_str()), n).clicked() {
                                choice = Some(n.clone());
                            }
                        }
                    });
                if let Some(choice) = choice {
                    map.retain(|(j, _)| *j != row.joint);
                    map.push((row.joint.clone(), choice));
                }
                ui.end_row();
            }
        });
    });
}
