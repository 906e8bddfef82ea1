//! A report drawn in the side panel: its text, and its tables as grids with each ranked
//! column's best and worst value highlighted.

use rerun::external::egui;

use crate::report::{Report, Table};

/// Draws a report's text with its tables as grids: the k-th table block of the markdown is the
/// report's k-th [`Table`], drawn from its cells, with the best and worst value of each ranked
/// column highlighted (green, red) from the cells' numbers. Other lines are shown as text.
pub(super) fn table_ui(ui: &mut egui::Ui, report: &Report) {
    let mut tables = report.tables.iter().enumerate();
    let mut in_block = false;
    for line in report.table.lines() {
        let t = line.trim();
        let is_row = t.starts_with('|') && t.ends_with('|') && t.len() > 1;
        if is_row && in_block {
            continue;
        }
        in_block = is_row;
        if is_row {
            match tables.next() {
                Some((id, table)) => grid_ui(ui, id, table),
                None => {
                    ui.label(egui::RichText::new(t).small().monospace());
                }
            }
        } else if !t.is_empty() {
            ui.label(egui::RichText::new(t).small());
        }
    }
}

fn grid_ui(ui: &mut egui::Ui, id: usize, table: &Table) {
    let columns = table.header.len();
    let mut marks = vec![vec![None; columns]; table.rows.len()];
    for c in table
        .lower_is_better
        .iter()
        .copied()
        .filter(|&c| c < columns)
    {
        if let Some((best, worst)) = table.best_and_worst(c) {
            for r in best {
                marks[r][c] = Some(BEST);
            }
            for r in worst {
                marks[r][c] = Some(WORST);
            }
        }
    }
    egui::Grid::new(("report", id))
        .striped(true)
        .show(ui, |ui| {
            for h in &table.header {
                ui.strong(h);
            }
            ui.end_row();
            for (r, row) in table.rows.iter().enumerate() {
                for (c, cell) in row.iter().enumerate() {
                    match marks[r].get(c).copied().flatten() {
                        Some(color) => ui.colored_label(color, &cell.text),
                        None => ui.label(&cell.text),
                    };
                }
                ui.end_row();
            }
        });
}

/// Colour of a column's best value.
pub const BEST: egui::Color32 = egui::Color32::from_rgb(90, 200, 110);

/// Colour of a column's worst value.
pub const WORST: egui::Color32 = egui::Color32::from_rgb(230, 90, 80);
