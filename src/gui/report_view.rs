//! A report drawn in the side panel: its text, and its tables as grids with each ranked
//! column's best and worst value highlighted.

use rerun::external::egui;

use crate::{
    inline_markdown::{SpanStyle, inline_spans},
    markdown_tables::table_width,
    report::{Block, Report, Table},
};

/// Draws a report's text and its tables as grids (the report's own [`Block`]s), with the best
/// and worst value of each ranked column highlighted (green, red) from the cells' numbers.
pub(super) fn table_ui(ui: &mut egui::Ui, report: &Report) {
    for (id, block) in report.blocks().into_iter().enumerate() {
        match block {
            // A table wider than the panel is drawn as a list, one wrapped item per row,
            // instead of a grid cut at the panel's edge.
            Block::Table(table) => {
                let texts: Vec<Vec<&str>> = table
                    .rows
                    .iter()
                    .map(|r| r.iter().map(|c| c.text.as_str()).collect())
                    .collect();
                let header: Vec<&str> = table.header.iter().map(String::as_str).collect();
                if table_width(&header, &texts) <= f64::from(ui.available_width()) {
                    grid_ui(ui, id, table);
                } else {
                    list_ui(ui, table);
                }
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

/// The best and worst mark of every cell of a table's ranked columns.
fn marks(table: &Table) -> Vec<Vec<Option<egui::Color32>>> {
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
    marks
}

/// A table as a list: each row's first cell in bold, then its other cells after their
/// column titles, wrapped to the panel; ranked cells keep their colours.
fn list_ui(ui: &mut egui::Ui, table: &Table) {
    let marks = marks(table);
    for (r, row) in table.rows.iter().enumerate() {
        ui.horizontal_wrapped(|ui| {
            ui.spacing_mut().item_spacing.x = 0.0;
            if let Some(first) = row.first() {
                ui.label(egui::RichText::new(format!("• {} — ", first.text)).strong());
            }
            let mut sep = "";
            for (c, cell) in row.iter().enumerate().skip(1) {
                if cell.text.trim().is_empty() {
                    continue;
                }
                let title = table.header.get(c).map_or("", |h| h.as_str());
                ui.label(format!("{sep}{title}: "));
                match marks[r].get(c).copied().flatten() {
                    Some(color) => ui.colored_label(color, &cell.text),
                    None => ui.label(&cell.text),
                };
                sep = " · ";
            }
        });
    }
}

fn grid_ui(ui: &mut egui::Ui, id: usize, table: &Table) {
    let marks = marks(table);
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
