//! The ASCII form of Nastran's OUTPUT4: the header in `4I8, A8` and the values' Fortran format,
//! column headers in `3I8`, string headers on their own lines (see [`parse_op4`](super::parse_op4)).

use std::collections::BTreeSet;

use super::matrix_bytes::{entry_value, line_error as error};
use super::nastran_op4_matrix::{Found, Matrix, words_per_value};
use crate::{Error, Result, error::MatrixLineProblem};

/// Integers of fixed `width` in `line` (or, when those do not parse, blank-separated).
fn ints(line: &str, width: usize, count: usize) -> Option<Vec<i64>> {
    let chars: Vec<char> = line.chars().collect();
    let fixed: Option<Vec<i64>> = (0..count)
        .map(|k| {
            let (a, b) = (
                (k * width).min(chars.len()),
                ((k + 1) * width).min(chars.len()),
            );
            chars[a..b].iter().collect::<String>().trim().parse().ok()
        })
        .collect();
    fixed.or_else(|| {
        let v: Vec<i64> = line
            .split_whitespace()
            .map(|t| t.parse().ok())
            .collect::<Option<_>>()?;
        (v.len() == count).then_some(v)
    })
}

pub(super) fn ascii_op4(text: &str, path: &str, wanted: &str) -> Result<Found> {
    let mut lines = text.lines().enumerate().map(|(i, l)| (i + 1, l));
    let mut names = BTreeSet::new();
    while let Some((number, header)) = lines.next() {
        if header.trim().is_empty() {
            continue;
        }
        let mut reader = AsciiMatrix::of_header(header, number, path)?;
        reader.read_columns(&mut lines)?;
        if reader.name == wanted {
            return Ok(Ok(reader.matrix));
        }
        names.insert(reader.name);
    }
    Ok(Err(names))
}

/// The numbered lines of an ASCII OP4 file (1-based numbers).
trait Lines<'t>: Iterator<Item = (usize, &'t str)> {}

impl<'t, I: Iterator<Item = (usize, &'t str)>> Lines<'t> for I {}

/// One ASCII matrix being read: its header's name, layout and the values' field width, and
/// the entries read so far.
struct AsciiMatrix<'p> {
    path: &'p str,
    name: String,
    /// NCOL of the header: a column record beyond it closes the matrix.
    ncols: i64,
    /// Sparse strings with a two-word header (NROW < 0).
    bigmat: bool,
    /// Words per value (NTYPE).
    words_per_value: usize,
    /// Characters per value (the header's Fortran format).
    width: usize,
    matrix: Matrix,
}

impl<'p> AsciiMatrix<'p> {
    /// The header line `NCOL NROW NF NTYPE (4I8)`, the name (A8), the values' format.
    fn of_header(header: &str, number: usize, path: &'p str) -> Result<Self> {
        let fail = |problem| error(path, number, problem);
        let head = ints(header.get(..32).unwrap_or(header), 8, 4).ok_or_else(|| {
            fail(MatrixLineProblem::NotLayout {
                text: header.trim().into(),
                layout: "NCOL NROW NF NTYPE (4I8), the name (A8), the format",
            })
        })?;
        let name = header.get(32..40).unwrap_or("").trim().to_ascii_uppercase();
        let words_per_value = words_per_value(head[3]).map_err(fail)?;
        // The values' Fortran format, e.g. `1P,3E23.16`: values per line and width.
        let format = header.get(40..).unwrap_or("").trim().to_ascii_uppercase();
        let width = format
            .rsplit(',')
            .next()
            .and_then(|f| {
                let at = f.find(['E', 'D'])?;
                let (count, rest) = f.split_at(at);
                let width: usize = rest[1..].split('.').next()?.parse().ok()?;
                count.trim().parse::<usize>().ok().map(|_| width)
            })
            .filter(|&w| w > 0)
            .ok_or_else(|| {
                fail(MatrixLineProblem::NotAFortranFormat {
                    what: "values'",
                    text: format.into(),
                })
            })?;
        let (ncols, nrows) = (head[0], head[1]);
        Ok(Self {
            path,
            name,
            ncols,
            bigmat: nrows < 0,
            words_per_value,
            width,
            matrix: Matrix {
                rows: nrows.unsigned_abs() as usize,
                cols: ncols.max(0) as usize,
                entries: Vec::new(),
            },
        })
    }

    fn fail(&self, line: usize, problem: MatrixLineProblem) -> Error {
        error(self.path, line, problem)
    }

    fn not_layout(&self, line: usize, text: &str, layout: &'static str) -> Error {
        self.fail(
            line,
            MatrixLineProblem::NotLayout {
                text: text.trim().into(),
                layout,
            },
        )
    }

    /// The next line inside column `icol` (1-based); the file ending there is an error.
    fn line_in_column<'t>(
        &self,
        icol: i64,
        lines: &mut impl Lines<'t>,
    ) -> Result<(usize, &'t str)> {
        lines.next().ok_or_else(|| {
            self.fail(
                0,
                MatrixLineProblem::EndsInsideColumn {
                    matrix: (&self.name).into(),
                    column: icol,
                },
            )
        })
    }

    /// The column records up to the closing one (a column beyond NCOL and its one value).
    fn read_columns<'t>(&mut self, lines: &mut impl Lines<'t>) -> Result<()> {
        loop {
            let (n, line) = lines.next().ok_or_else(|| {
                self.fail(
                    0,
                    MatrixLineProblem::NoClosingRecord {
                        matrix: (&self.name).into(),
                    },
                )
            })?;
            let [icol, irow, nw] = ints(line, 8, 3)
                .and_then(|v| <[i64; 3]>::try_from(v).ok())
                .ok_or_else(|| self.not_layout(n, line, "ICOL IROW NW (3I8)"))?;
            if icol > self.ncols {
                lines.next(); // the closing record's one value
                return Ok(());
            }
            if icol < 1 {
                return Err(self.fail(
                    n,
                    MatrixLineProblem::NoSuchColumn {
                        matrix: (&self.name).into(),
                        column: icol,
                    },
                ));
            }
            if irow > 0 {
                self.values(nw.max(0) as usize, irow, icol, lines)?;
            } else {
                self.sparse_strings(nw, icol, lines)?;
            }
        }
    }

    /// A sparse column's strings, `nw` words in all: each a header (the string's length and
    /// first row) and its values.
    fn sparse_strings<'t>(&mut self, nw: i64, icol: i64, lines: &mut impl Lines<'t>) -> Result<()> {
        let mut words = nw;
        while words > 0 {
            let (h, string) = self.line_in_column(icol, lines)?;
            let (length, row, used) = if self.bigmat {
                let [l, r] = ints(string, 8, 2)
                    .and_then(|v| <[i64; 2]>::try_from(v).ok())
                    .ok_or_else(|| self.not_layout(h, string, "L+1 ROW (2I8), a bigmat string"))?;
                (l - 1, r, 2)
            } else {
                let is: i64 = string.trim().parse().map_err(|_| {
                    self.not_layout(h, string, "IS = ROW + 65536(L+1), a string's header")
                })?;
                ((is >> 16) - 1, is & 0xFFFF, 1)
            };
            if length < 1 || length + used > words {
                return Err(self.fail(
                    h,
                    MatrixLineProblem::StringTooLong {
                        words: length,
                        row,
                        column_words: nw,
                    },
                ));
            }
            self.values(length as usize / self.words_per_value, row, icol, lines)?;
            words -= length + used;
        }
        Ok(())
    }

    /// `count` values of column `icol` (1-based) from row `from_row` (1-based) on, read line
    /// by line, each `width` characters.
    fn values<'t>(
        &mut self,
        count: usize,
        from_row: i64,
        icol: i64,
        lines: &mut impl Lines<'t>,
    ) -> Result<()> {
        let (rows, col) = (self.matrix.rows, icol as usize - 1);
        let mut row = from_row;
        let mut left = count;
        while left > 0 {
            let (n, line) = self.line_in_column(icol, lines)?;
            let chars: Vec<char> = line.trim_end().chars().collect();
            let mut k = 0;
            while left > 0 && k * self.width < chars.len() {
                let token: String = chars[k * self.width..((k + 1) * self.width).min(chars.len())]
                    .iter()
                    .collect();
                let v = entry_value(&token, self.path, n)?;
                if row < 1 || row as usize > rows {
                    return Err(self.fail(
                        n,
                        MatrixLineProblem::RowOutOfRange {
                            matrix: (&self.name).into(),
                            row,
                            column: icol,
                            rows,
                        },
                    ));
                }
                if v != 0.0 {
                    self.matrix.entries.push((row as usize - 1, col, v));
                }
                row += 1;
                left -= 1;
                k += 1;
            }
            if k == 0 {
                return Err(self.fail(n, MatrixLineProblem::LineWithoutValues { column: icol }));
            }
        }
        Ok(())
    }
}
