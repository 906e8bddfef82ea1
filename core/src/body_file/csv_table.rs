//! The tables of a body file: node coordinates and wireframe edges, inline or in CSV files,
//! each value traced to its file and line.

use super::BodyFileError;
use super::{BodyLocation, TableOrFile};
use crate::{Error, Result, error::TableProblem, fem::NodeIndex};

/// A row of a table and its 1-based line.
pub(super) type Row<T> = (usize, Vec<T>);

/// A CSV table (or inline rows): `(line, values)` per row and the name used in messages.
/// Commas, semicolons or white space separate values; `#` starts a comment; a first line that
/// does not parse is taken as a header.
pub(super) fn read_table<T: std::str::FromStr + Copy>(
    location: &BodyLocation,
    table: &TableOrFile<T>,
    key: &str,
    body_name: &str,
) -> Result<(Vec<Row<T>>, String)> {
    match table {
        TableOrFile::Inline(rows) => Ok((
            rows.iter()
                .cloned()
                .enumerate()
                .map(|(k, r)| (k + 1, r))
                .collect(),
            format!("{body_name} [geometry] {key}"),
        )),
        TableOrFile::File(file) => {
            let (bytes, name) = location.read(Some(file))?;
            let text = String::from_utf8_lossy(&bytes);
            let mut rows = Vec::new();
            for (k, raw) in text.lines().enumerate() {
                let line = raw.split('#').next().unwrap_or("").trim();
                if line.is_empty() {
                    continue;
                }
                let values: std::result::Result<Vec<T>, _> = line
                    .split(|c: char| c == ',' || c == ';' || c.is_whitespace())
                    .filter(|t| !t.is_empty())
                    .map(|t| t.parse::<T>())
                    .collect();
                match values {
                    Ok(v) => rows.push((k + 1, v)),
                    Err(_) if rows.is_empty() && k == 0 => {} // a header
                    Err(_) => {
                        return Err(Error::BodyFile(BodyFileError::TableLine {
                            path: name.into(),
                            line: k + 1,
                            problem: TableProblem::NotNumbers { text: line.into() },
                        }));
                    }
                }
            }
            Ok((rows, name))
        }
    }
}

/// Wireframe edges from 1-based node pairs or face cycles.
pub(super) fn edges(
    location: &BodyLocation,
    table: &TableOrFile<usize>,
    node_count: usize,
    body_name: &str,
) -> Result<Vec<[usize; 2]>> {
    let (rows, name) = read_table(location, table, "edges", body_name)?;
    let mut out = Vec::new();
    for (line, row) in rows {
        if row.len() < 2 {
            return Err(Error::BodyFile(BodyFileError::TableLine {
                path: name.into(),
                line,
                problem: TableProblem::EdgeTooShort,
            }));
        }
        if let Some(&bad) = row.iter().find(|&&x| x == 0 || x > node_count) {
            return Err(Error::BodyFile(BodyFileError::TableLine {
                path: name.into(),
                line,
                problem: TableProblem::NodeOutOfRange {
                    node: bad,
                    count: node_count,
                },
            }));
        }
        // Every number is in 1..=node_count (checked above): stored nodes from here on.
        let row: Vec<usize> = row
            .iter()
            .map(|&number| NodeIndex::of_number(number).expect("checked above").get())
            .collect();
        let cycle = row.len() > 2;
        for w in row.windows(2) {
            out.push([w[0], w[1]]);
        }
        if cycle {
            out.push([row[row.len() - 1], row[0]]);
        }
    }
    Ok(out)
}
