//! Numeric results of a scene: the `report --json` object and the human table.

use serde_json::{Map, Value, json};

/// `{"scene": ID, "parameters": {...}, "results": {...}}` plus a markdown table for people.
#[derive(Debug, Clone, PartialEq)]
pub struct Report {
    /// Scene id.
    pub scene: String,
    /// The parameters the scene ran with.
    pub parameters: Map<String, Value>,
    /// Results; the documented keys (docs/scenes.md, docs/bodies.md) are stable.
    pub results: Map<String, Value>,
    /// The result table in markdown (printed by `report`, shown in the `scene` panel).
    pub table: String,
    /// The result tables with their numbers, for panels that rank them (the explorer
    /// highlights the best and worst value of each ranked column).
    pub tables: Vec<Table>,
}

/// A piece of a report's text: prose (markdown) or one of its tables with its numbers.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Block<'a> {
    /// Text between tables.
    Text(&'a str),
    /// A table.
    Table(&'a Table),
}

/// One cell of a result table: its text and, where it stands for a number, the number.
#[derive(Debug, Clone, PartialEq)]
pub struct Cell {
    /// What is printed.
    pub text: String,
    /// The number it stands for (`None` for labels, and for reference rows that are not
    /// ranked, such as NR's zero error against itself).
    pub value: Option<f64>,
}

impl Cell {
    /// A text cell.
    pub fn text(text: impl Into<String>) -> Self {
        Self {
            text: text.into(),
            value: None,
        }
    }

    /// A number printed as `text`.
    pub fn number(value: f64, text: impl Into<String>) -> Self {
        Self {
            text: text.into(),
            value: Some(value),
        }
    }
}

/// A result table: header, rows, and the columns in which a lower value is better.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Table {
    /// Column titles.
    pub header: Vec<String>,
    /// Rows of cells (as many as the header).
    pub rows: Vec<Vec<Cell>>,
    /// Columns ranked lower-is-better (errors, defects).
    pub lower_is_better: Vec<usize>,
}

impl Table {
    /// An empty table with a header.
    pub fn new(header: &[&str]) -> Self {
        Self {
            header: header.iter().map(|h| h.to_string()).collect(),
            ..Default::default()
        }
    }

    /// A table of text rows (nothing ranked).
    pub fn from_text(header: &[&str], rows: &[Vec<String>]) -> Self {
        let mut t = Self::new(header);
        t.rows = rows
            .iter()
            .map(|r| r.iter().map(|c| Cell::text(c.clone())).collect())
            .collect();
        t
    }

    /// Marks columns in which a lower value is better.
    pub fn rank_lower(mut self, columns: &[usize]) -> Self {
        self.lower_is_better = columns.to_vec();
        self
    }

    /// Appends a row.
    pub fn push(&mut self, row: Vec<Cell>) {
        self.rows.push(row);
    }

    /// The table in markdown.
    pub fn markdown(&self) -> String {
        let header: Vec<&str> = self.header.iter().map(String::as_str).collect();
        let rows: Vec<Vec<String>> = self
            .rows
            .iter()
            .map(|r| r.iter().map(|c| c.text.clone()).collect())
            .collect();
        markdown_table(&header, &rows)
    }

    /// The rows with the best (lowest) and worst (highest) value of a ranked column, among
    /// the cells that carry a number, each with the rows that print the same text (ties as
    /// the reader sees them: CB and MC whose errors agree to the printed digits are both
    /// best); `None` when the column is not ranked, fewer than two rows carry a number or
    /// they all print alike.
    pub fn best_and_worst(&self, column: usize) -> Option<(Vec<usize>, Vec<usize>)> {
        if !self.lower_is_better.contains(&column) {
            return None;
        }
        let vals: Vec<(usize, f64, &str)> = self
            .rows
            .iter()
            .enumerate()
            .filter_map(|(r, row)| {
                let cell = row.get(column)?;
                Some((r, cell.value?, cell.text.as_str()))
            })
            .filter(|(_, v, _)| v.is_finite())
            .collect();
        if vals.len() < 2 {
            return None;
        }
        let best = vals.iter().min_by(|a, b| a.1.total_cmp(&b.1))?.2;
        let worst = vals.iter().max_by(|a, b| a.1.total_cmp(&b.1))?.2;
        let printing = |text: &str| -> Vec<usize> {
            vals.iter()
                .filter(|(_, _, t)| *t == text)
                .map(|&(r, _, _)| r)
                .collect()
        };
        (best != worst).then(|| (printing(best), printing(worst)))
    }
}

impl Report {
    /// An empty report for a scene.
    pub fn new(scene: &str) -> Self {
        Self {
            scene: scene.into(),
            parameters: Map::new(),
            results: Map::new(),
            table: String::new(),
            tables: Vec::new(),
        }
    }

    /// Keeps `table` for ranking panels and returns its markdown for the text.
    pub fn add_table(&mut self, table: Table) -> String {
        let md = table.markdown();
        self.tables.push(table);
        md
    }

    /// The report's text as typed blocks, in order: the text between tables, and each of
    /// [`Self::tables`] where its markdown (as [`Self::add_table`] rendered it) stands in
    /// [`Self::table`]. A table the text does not show is not a block.
    pub fn blocks(&self) -> Vec<Block<'_>> {
        let mut blocks = Vec::new();
        let mut rest = self.table.as_str();
        for table in &self.tables {
            let md = table.markdown();
            let Some(at) = rest.find(md.trim_end()) else {
                continue;
            };
            if !rest[..at].trim().is_empty() {
                blocks.push(Block::Text(rest[..at].trim()));
            }
            blocks.push(Block::Table(table));
            rest = &rest[at + md.trim_end().len()..];
        }
        if !rest.trim().is_empty() {
            blocks.push(Block::Text(rest.trim()));
        }
        blocks
    }

    /// The JSON object of `report --json`.
    pub fn to_json(&self) -> Value {
        json!({
            "scene": self.scene,
            "parameters": Value::Object(self.parameters.clone()),
            "results": Value::Object(self.results.clone()),
        })
    }

    /// A result by dotted key (`reduced_hz.cb`).
    pub fn result(&self, dotted: &str) -> Option<&Value> {
        let mut parts = dotted.split('.');
        let mut v = self.results.get(parts.next()?)?;
        for p in parts {
            v = v.get(p)?;
        }
        Some(v)
    }

    /// A numeric array result by dotted key.
    pub fn result_vec(&self, dotted: &str) -> Option<Vec<f64>> {
        self.result(dotted)?
            .as_array()?
            .iter()
            .map(Value::as_f64)
            .collect()
    }
}

/// Rounds for JSON/markdown output without losing the digits the thesis prints (9 significant).
pub fn sig(x: f64) -> f64 {
    if x == 0.0 || !x.is_finite() {
        return x;
    }
    let digits = 9 - x.abs().log10().ceil() as i32;
    let f = 10f64.powi(digits.clamp(-300, 300));
    (x * f).round() / f
}

/// Rounds each entry with [`sig`].
pub fn sig_vec(v: &[f64]) -> Vec<f64> {
    v.iter().map(|&x| sig(x)).collect()
}

/// Relative eigen-residual above which a printed frequency is flagged in text reports.
pub const RESIDUAL_FLAG: f64 = 1e-6;

/// What a text report says of the residuals of the frequencies it prints: the largest, or
/// each frequency whose residual is above [`RESIDUAL_FLAG`], flagged.
pub fn residual_note(hz: &[f64], residuals: &[f64]) -> String {
    let worst = residuals.iter().copied().fold(0.0f64, f64::max);
    let flagged: Vec<String> = hz
        .iter()
        .zip(residuals)
        .filter(|(_, r)| **r > RESIDUAL_FLAG || r.is_nan())
        .map(|(f, r)| format!("{} Hz ({r})", sig6(*f), r = crate::report::readable(r, 2)))
        .collect();
    // The first few name the trouble; a model of a thousand flagged pairs is one line.
    const NAMED: usize = 6;
    if flagged.is_empty() {
        format!(
            "relative residuals ≤ {worst}",
            worst = crate::report::readable(worst, 2)
        )
    } else if flagged.len() <= NAMED {
        format!(
            "**residual above {RESIDUAL_FLAG}, not to be trusted:** {}",
            flagged.join(", "),
            RESIDUAL_FLAG = crate::report::readable(RESIDUAL_FLAG, 1)
        )
    } else {
        format!(
            "**residual above {RESIDUAL_FLAG} in {} of {} pairs (worst {worst}), not to \
             be trusted:** {}, …",
            flagged.len(),
            hz.len(),
            flagged[..NAMED].join(", "),
            worst = crate::report::readable(worst, 2),
            RESIDUAL_FLAG = crate::report::readable(RESIDUAL_FLAG, 1)
        )
    }
}

/// A markdown table with a header row.
pub fn markdown_table(header: &[&str], rows: &[Vec<String>]) -> String {
    let mut s = format!(
        "| {} |\n|{}\n",
        header.join(" | "),
        "---|".repeat(header.len())
    );
    for r in rows {
        s.push_str(&format!("| {} |\n", r.join(" | ")));
    }
    s
}

/// Formats a list of frequencies with `digits` significant digits.
pub fn fmt_hz(v: &[f64]) -> String {
    v.iter().map(|f| sig6(*f)).collect::<Vec<_>>().join(", ")
}

/// Six significant digits, as the thesis prints: fixed-point from 1e-3 up to 1e6
/// (`0.0193103`, `2478.27`), scientific outside it (`3.33519e-21`, `1.23457e7`), where a
/// fixed-point number would be a run of zeros a person has to count.
pub fn sig6(x: f64) -> String {
    readable(x, 6)
}

/// Three significant digits, read as [`sig6`] prints: fixed-point from 1e-3 up to 1e6
/// (`2.54`, `0.0103`, `1450`), scientific outside it (`7.23e-5`): a table's errors and
/// angles, where `2.54e0` made a reader convert.
pub fn sig3(x: f64) -> String {
    readable(x, 3)
}

/// `digits` significant digits (at least 1), fixed-point from 1e-3 up to 1e6, scientific
/// outside it; the magnitude is the one after rounding (9.9999999 to six digits is 10.0000).
/// Every number a sentence prints goes through it (`0.023`, not `2.3e-2`).
pub fn readable(x: impl std::borrow::Borrow<f64>, digits: usize) -> String {
    let x = *x.borrow();
    if x == 0.0 || !x.is_finite() {
        return if x == 0.0 { "0".into() } else { format!("{x}") };
    }
    let after = digits.max(1) - 1;
    let scientific = format!("{x:.after$e}");
    let mag: i32 = scientific
        .rsplit('e')
        .next()
        .and_then(|e| e.parse().ok())
        .expect("`{:e}` ends in its exponent");
    if !(-3..6).contains(&mag) {
        return scientific;
    }
    let decimals = (after as i32 - mag).max(0) as usize;
    format!("{x:.decimals$}")
}

/// Five significant digits in MATLAB's `short g` manner (`2.5e+05`, `416.07`).
pub fn sig5(x: f64) -> f64 {
    if x == 0.0 || !x.is_finite() {
        return x;
    }
    let digits = 5 - x.abs().log10().ceil() as i32;
    let f = 10f64.powi(digits.clamp(-300, 300));
    (x * f).round() / f
}

#[cfg(test)]
mod tests {
    use super::*;

    fn error_table(errors: &[f64]) -> Table {
        let mut t = Table::new(&["method", "error"]).rank_lower(&[1]);
        for (k, &e) in errors.iter().enumerate() {
            t.push(vec![
                Cell::text(format!("m{k}")),
                Cell::number(e, format!("{e:.4}")),
            ]);
        }
        t
    }

    #[test]
    fn three_digits_read_as_a_person_writes_them() {
        for (x, printed) in [
            (2.5432, "2.54"),
            (0.010312, "0.0103"),
            (1450.2, "1450"),
            (7.2345e-5, "7.23e-5"),
            (9.996, "10.0"),
            (2.5e7, "2.50e7"),
            (0.0, "0"),
        ] {
            assert_eq!(sig3(x), printed, "{x}");
        }
    }

    #[test]
    fn six_digits_read_without_counting_zeros() {
        for (x, printed) in [
            (2478.2736, "2478.27"),
            (0.019310345, "0.0193103"),
            (0.001, "0.00100000"),
            (0.000999999, "9.99999e-4"),
            (3.335191e-21, "3.33519e-21"),
            (-5.293964e-23, "-5.29396e-23"),
            (999_999.4, "999999"),
            (9.99999999, "10.0000"),
            (999_999.7, "1.00000e6"),
            (1_234_567.0, "1.23457e6"),
            (0.0, "0"),
        ] {
            assert_eq!(sig6(x), printed, "{x}");
        }
        // No printed number has more than 8 leading zeros after the point.
        for e in -30..30 {
            let s = sig6(1.234567 * 10f64.powi(e));
            assert!(!s.contains("0.000"), "{s}");
        }
    }

    #[test]
    fn rows_that_print_alike_rank_alike() {
        // 0.023 61 and 0.023 59 both print 0.0236: both best, though the second is lower.
        let t = error_table(&[0.5, 0.02361, 0.02359, 1.2]);
        assert_eq!(t.best_and_worst(1), Some((vec![1, 2], vec![3])));
        // A tie for worst as well.
        let t = error_table(&[1.20001, 0.1, 1.2]);
        assert_eq!(t.best_and_worst(1), Some((vec![1], vec![0, 2])));
        // All alike: nothing to rank; the text column never is.
        assert_eq!(error_table(&[0.1, 0.10001]).best_and_worst(1), None);
        assert_eq!(error_table(&[0.1, 0.2]).best_and_worst(0), None);
    }
}

#[cfg(test)]
mod block_tests {
    use super::*;

    #[test]
    fn blocks_follow_the_text_and_its_tables_in_order() {
        let mut report = Report::new("test");
        let a = report.add_table(Table::from_text(&["x"], &[vec!["1".into()]]));
        let b = report.add_table(Table::from_text(
            &["y", "z"],
            &[vec!["2".into(), "3".into()]],
        ));
        report.table = format!("## First\n\n{a}\nbetween\n\n{b}\nafter");
        let blocks = report.blocks();
        assert_eq!(blocks.len(), 5, "{blocks:?}");
        assert_eq!(blocks[0], Block::Text("## First"));
        assert_eq!(blocks[1], Block::Table(&report.tables[0]));
        assert_eq!(blocks[2], Block::Text("between"));
        assert_eq!(blocks[3], Block::Table(&report.tables[1]));
        assert_eq!(blocks[4], Block::Text("after"));
        // A table the text does not show is left out; the text stays whole.
        report.table = format!("only {b}");
        let blocks = report.blocks();
        assert_eq!(
            blocks,
            vec![Block::Text("only"), Block::Table(&report.tables[1])]
        );
    }
}
