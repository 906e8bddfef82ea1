//! A report drawn in the side panel: its text, and its tables as grids with each ranked
//! column's best and worst value highlighted.

use rerun::external::egui;

use crate::{
    inline_markdown::{SpanStyle, inline_spans},
    report::{Block, Report, Table},
};

/// Draws a report's text and its tables as grids (the report's own [`Block`]s), with the best
/// and worst value of each ranked column highlighted (green, red) from the cells' numbers.
pub(super) fn table_ui(ui: &mut egui::Ui, report: &Report) {
    for (id, block) in report.blocks().into_iter().enumerate() {
        match block {
            // Wide tables scroll sideways instead of being cut at the panel's edge.
            Block::Table(table) => {
                egui::ScrollArea::horizontal()
                    .id_salt(("report-table", id))
                    .show(ui, |ui| grid_ui(ui, id, table));
            }
            // The text's inline markdown drawn, not shown as markup.
            Block::Text(text) => {
                for line in text.lines().map(str::trim).filter(|l| !l.is_empty()) {
                    ui.horizontal_wrapped(|ui| {
                        ui.spacing_mut().item_spacing.x = 0.0;
                        for (span, style) in inline_spans(line) {
                            let t = egui::RichText::new(span).small();
                            ui.label(match style {
                                SpanStyle::Plain => t,
                                SpanStyle::Code => t.code(),
                                SpanStyle::Strong => t.strong(),
                            });
                        }
                    });
                }
            }
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
