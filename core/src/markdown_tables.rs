//! Markdown tables fitted to a panel's width: a table wider than the room it is drawn in is
//! written as a list, one item per row, which wraps, instead of a grid cut at the panel's edge
//! (the viewer's text panel shows no scroll bar until hovered, so a cut table looks whole).

/// Points one character of panel text takes: the viewer's proportional font at its text
/// size, 5.3–5.6 points for digits and lowercase, rounded up for capitals and symbols
/// (measured on the explorer's screenshots at 1 280 × 800).
pub const CHAR_POINTS: f64 = 6.5;

/// Points a table column adds around its text (cell padding and rule; measured, 14 points).
pub const COLUMN_PADDING: f64 = 16.0;

/// Points a text panel keeps free at its edges (margins and scroll bar).
pub const PANEL_MARGIN: f64 = 28.0;

/// The width a table takes, points: each column as wide as its longest cell (header
/// included) at [`CHAR_POINTS`] per character, plus [`COLUMN_PADDING`].
pub fn table_width<S: AsRef<str>>(header: &[S], rows: &[Vec<S>]) -> f64 {
    let columns = header
        .len()
        .max(rows.iter().map(Vec::len).max().unwrap_or(0));
    (0..columns)
        .map(|c| {
            let longest = std::iter::once(header.get(c))
                .chain(rows.iter().map(|r| r.get(c)))
                .flatten()
                .map(|s| s.as_ref().chars().count())
                .max()
                .unwrap_or(0);
            longest as f64 * CHAR_POINTS + COLUMN_PADDING
        })
        .sum()
}

/// One row as a list item: the first cell in bold, then each further cell after its column
/// title: `- **CB (90 × 18)** — Hz: 7.5, 9.3`. Empty cells are left out.
pub fn row_as_list_item<S: AsRef<str>>(header: &[S], row: &[S]) -> String {
    let mut item = match row.first().map(|s| s.as_ref().trim()) {
        Some(first) if !first.is_empty() => format!("- **{first}**"),
        _ => "-".to_string(),
    };
    let rest: Vec<String> = row
        .iter()
        .enumerate()
        .skip(1)
        .filter(|(_, cell)| !cell.as_ref().trim().is_empty())
        .map(|(c, cell)| {
            let title = header.get(c).map_or("", |h| h.as_ref().trim());
            if title.is_empty() {
                cell.as_ref().trim().to_string()
            } else {
                format!("{title}: {}", cell.as_ref().trim())
            }
        })
        .collect();
    if !rest.is_empty() {
        item.push_str(" — ");
        item.push_str(&rest.join(" · "));
    }
    item
}

/// `markdown` with every table wider than `width` points (by [`table_width`]) written as a
/// list ([`row_as_list_item`]); narrower tables and all other text unchanged.
pub fn fit_tables(markdown: &str, width: f64) -> String {
    let lines: Vec<&str> = markdown.split('\n').collect();
    let mut out: Vec<String> = Vec::with_capacity(lines.len());
    let mut i = 0;
    while i < lines.len() {
        let end = (i..lines.len())
            .find(|&j| !is_table_line(lines[j]))
            .unwrap_or(lines.len());
        let is_table = end >= i + 2 && is_separator(lines[i + 1]);
        if !is_table {
            out.push(lines[i].to_string());
            i += 1;
            continue;
        }
        let header = cells(lines[i]);
        let rows: Vec<Vec<String>> = lines[i + 2..end].iter().map(|l| cells(l)).collect();
        if table_width(&header, &rows) <= width {
            out.extend(lines[i..end].iter().map(|l| l.to_string()));
        } else {
            out.extend(rows.iter().map(|r| row_as_list_item(&header, r)));
        }
        i = end;
    }
    out.join("\n")
}

fn is_table_line(line: &str) -> bool {
    let t = line.trim();
    t.len() >= 2 && t.starts_with('|') && t.ends_with('|')
}

fn is_separator(line: &str) -> bool {
    is_table_line(line)
        && cells(line)
            .iter()
            .all(|c| !c.is_empty() && c.chars().all(|ch| matches!(ch, '-' | ':')))
}

fn cells(line: &str) -> Vec<String> {
    let t = line.trim();
    let inner = &t[1..t.len() - 1];
    inner.split('|').map(|c| c.trim().to_string()).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::report::markdown_table;

    fn freq_table(models: usize, freqs: usize) -> String {
        let rows: Vec<Vec<String>> = (0..models)
            .map(|m| {
                let hz: Vec<String> = (0..freqs)
                    .map(|k| format!("{:.5}", 7.0 + k as f64))
                    .collect();
                vec![format!("M{m} (90 × 18, 6 rigid)"), hz.join(", ")]
            })
            .collect();
        markdown_table(&["model", "Hz"], &rows)
    }

    #[test]
    fn a_wide_table_becomes_one_list_item_per_row_and_a_narrow_one_stays() {
        for models in [1, 3, 5] {
            let table = freq_table(models, 8);
            let md = format!("Before.\n\n{table}\nAfter.");
            let width = table_width(
                &["model", "Hz"],
                &[vec!["M0 (90 × 18, 6 rigid)", &"7.00000, ".repeat(8)]],
            );
            // Too narrow: a list, every row kept in order, nothing else touched.
            let fitted = fit_tables(&md, width - 1.0);
            let items: Vec<&str> = fitted.lines().filter(|l| l.starts_with("- ")).collect();
            assert_eq!(items.len(), models, "{fitted}");
            for (m, item) in items.iter().enumerate() {
                assert!(
                    item.starts_with(&format!(
                        "- **M{m} (90 × 18, 6 rigid)** — Hz: 7.00000, 8.00000"
                    )),
                    "{item}"
                );
            }
            assert!(!fitted.contains('|'), "{fitted}");
            assert!(
                fitted.starts_with("Before.\n\n") && fitted.ends_with("After."),
                "{fitted}"
            );
            // Wide enough: unchanged.
            assert_eq!(fit_tables(&md, width + 200.0), md);
        }
    }

    #[test]
    fn the_width_grows_with_the_longest_cell_of_each_column() {
        let narrow = table_width(&["a", "b"], &[vec!["x", "y"]]);
        assert_eq!(narrow, 2.0 * (CHAR_POINTS + COLUMN_PADDING));
        let wide = table_width(&["a", "b"], &[vec!["x", "y"], vec!["xxxx", "y"]]);
        assert_eq!(wide - narrow, 3.0 * CHAR_POINTS);
    }

    #[test]
    fn text_with_pipes_that_is_no_table_is_left_alone() {
        for md in [
            "| a lone line |",
            "|a|\nno separator |x|\n",
            "a | b\n|---|\n",
        ] {
            assert_eq!(fit_tables(md, 1.0), md);
        }
    }

    #[test]
    fn a_list_item_skips_empty_cells_and_names_each_value_by_its_column() {
        let item = row_as_list_item(&["method", "error", "time, s"], &["CB", "", "0.12"]);
        assert_eq!(item, "- **CB** — time, s: 0.12");
        assert_eq!(row_as_list_item(&["a"], &[""]), "-");
    }
}
