//! The NIST Matrix Market exchange format (`.mtx`, optionally gzip-compressed): read real
//! `coordinate` and `array` matrices, general or symmetric, and write them back.
//!
//! Every FE code can write it (Abaqus `*MATRIX GENERATE` through a converter, ANSYS `HBMAT`
//! via SciPy, Code_Aster `IMPR_RESU`, scikit-fem and SciPy `mmwrite` directly), and SciPy,
//! Julia's `MatrixMarket.jl` and MATLAB's `mmread.m` read what [`write_array`] and
//! [`write_coordinate_symmetric`] produce. The reader is lenient where exporters differ
//! (upper-case keywords, blank lines, comments between entries, Fortran `D` exponents,
//! `integer` and `double` fields, duplicate coordinate entries summed) and strict where a
//! mistake would change the body: every error names the file and the line.

use super::{BodyFileError, matrix_bytes::plain_bytes};
use std::{
    fs,
    io::{BufRead, BufReader, Write},
    path::Path,
};

use faer::MatRef;

use crate::atomic_file::write_atomically;
use crate::{Error, Result, error::MatrixLineProblem};

/// How the entries of a Matrix Market file are stored.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MatrixMarketFormat {
    /// `coordinate`: one `row col value` line per stored entry (1-based indices).
    Coordinate,
    /// `array`: every entry (the lower triangle for symmetric), column-major.
    Array,
}

/// A real matrix read from a Matrix Market file.
#[derive(Debug, Clone, PartialEq)]
pub struct MatrixMarket {
    /// Rows.
    pub rows: usize,
    /// Columns.
    pub cols: usize,
    /// Storage of the file.
    pub format: MatrixMarketFormat,
    /// Whether the file said `symmetric` (only one triangle stored).
    pub symmetric: bool,
    /// Stored entries as `(row, col, value)`, 0-based, in file order. For a symmetric file
    /// each off-diagonal entry appears once, as stored; [`Self::expanded`] adds its mirror.
    pub entries: Vec<(usize, usize, f64)>,
}

impl MatrixMarket {
    /// Every entry of the matrix, a symmetric file's mirrored entries included.
    pub fn expanded(&self) -> Vec<(usize, usize, f64)> {
        let mut out = Vec::with_capacity(self.entries.len() * if self.symmetric { 2 } else { 1 });
        for &(i, j, v) in &self.entries {
            out.push((i, j, v));
            if self.symmetric && i != j {
                out.push((j, i, v));
            }
        }
        out
    }
}

/// Reads a Matrix Market file from disk; gzip is recognised by its magic bytes, whatever the
/// file is called.
pub fn read_matrix_market(path: &Path) -> Result<MatrixMarket> {
    let bytes = fs::read(path).map_err(|source| Error::Io {
        path: path.to_path_buf(),
        source,
    })?;
    parse_matrix_market(&bytes, &path.display().to_string())
}

/// Parses Matrix Market bytes (plain or gzip) named `name` in error messages.
pub fn parse_matrix_market(bytes: &[u8], name: &str) -> Result<MatrixMarket> {
    parse_text(BufReader::new(&*plain_bytes(bytes, name)?), name)
}

fn line_error(name: &str, line: usize, problem: MatrixLineProblem) -> Error {
    Error::BodyFile(BodyFileError::MatrixLine {
        path: name.into(),
        line,
        problem,
    })
}

/// The error of a value `text` on line `no` that is not a real number.
fn not_a_real(name: &str, no: usize, text: &str) -> Error {
    line_error(
        name,
        no,
        MatrixLineProblem::NotANumber {
            field: "value",
            text: text.into(),
            expected: "a real number",
        },
    )
}

/// A real number; Fortran writers' `1.0D+03` is accepted.
fn parse_value(token: &str) -> Option<f64> {
    token
        .parse::<f64>()
        .ok()
        .or_else(|| token.replace(['D', 'd'], "E").parse::<f64>().ok())
}

fn parse_text(reader: impl BufRead, name: &str) -> Result<MatrixMarket> {
    let mut lines = reader.lines().enumerate().map(|(k, l)| (k + 1, l));
    let (header_no, format, symmetric) = parse_header(&mut lines, name)?;
    let size = parse_size_line(&mut lines, name, header_no, format, symmetric)?;
    let entries = match format {
        MatrixMarketFormat::Coordinate => coordinate_entries(&mut lines, name, &size, symmetric)?,
        MatrixMarketFormat::Array => array_entries(&mut lines, name, &size, symmetric)?,
    };
    if let Some((no, line)) = next_data_line(&mut lines, name)? {
        return Err(line_error(
            name,
            no,
            MatrixLineProblem::TooMany {
                what: match format {
                    MatrixMarketFormat::Coordinate => "entries",
                    MatrixMarketFormat::Array => "values",
                },
                expected: size.count,
                text: line.trim().into(),
            },
        ));
    }
    Ok(MatrixMarket {
        rows: size.rows,
        cols: size.cols,
        format,
        symmetric,
        entries,
    })
}

/// A Matrix Market file's numbered lines.
type NumberedLines<'a> = dyn Iterator<Item = (usize, std::io::Result<String>)> + 'a;

/// The next line that is neither blank nor a comment, with its number.
fn next_data_line(lines: &mut NumberedLines<'_>, name: &str) -> Result<Option<(usize, String)>> {
    for (no, line) in lines {
        // Lines of bytes in memory fail only where they are not UTF-8.
        let line = line.map_err(|_| line_error(name, no, MatrixLineProblem::NotText))?;
        let t = line.trim();
        if t.is_empty() || t.starts_with('%') {
            continue;
        }
        return Ok(Some((no, line)));
    }
    Ok(None)
}

/// The header, the first line: `%%MatrixMarket matrix <format> <field> <symmetry>`; its line
/// number, the format and whether the matrix is symmetric.
fn parse_header(
    lines: &mut NumberedLines<'_>,
    name: &str,
) -> Result<(usize, MatrixMarketFormat, bool)> {
    let (header_no, header) = match lines.next() {
        Some((no, Ok(l))) => (no, l),
        Some((no, Err(_))) => return Err(line_error(name, no, MatrixLineProblem::NotText)),
        None => {
            return Err(Error::BodyFile(BodyFileError::MatrixMarketHeader {
                path: name.into(),
                line: 1,
                problem: MatrixLineProblem::EmptyFile,
            }));
        }
    };
    let words: Vec<String> = header
        .split_whitespace()
        .map(|w| w.to_ascii_lowercase())
        .collect();
    let bad_header = |problem| {
        Error::BodyFile(BodyFileError::MatrixMarketHeader {
            path: name.into(),
            line: header_no,
            problem,
        })
    };
    if words.len() != 5 || words[0] != "%%matrixmarket" || words[1] != "matrix" {
        return Err(bad_header(MatrixLineProblem::NotLayout {
            text: header.trim().into(),
            layout: "%%MatrixMarket matrix <format> <field> <symmetry>",
        }));
    }
    let unsupported = |field, value: &str, needs| {
        bad_header(MatrixLineProblem::Unsupported {
            field,
            value: value.into(),
            needs,
        })
    };
    let format = match words[2].as_str() {
        "coordinate" => MatrixMarketFormat::Coordinate,
        "array" => MatrixMarketFormat::Array,
        other => return Err(unsupported("format", other, "coordinate or array")),
    };
    match words[3].as_str() {
        "real" | "double" | "integer" => {}
        other => {
            return Err(unsupported(
                "field",
                other,
                "a stiffness or mass must be real",
            ));
        }
    }
    let symmetric = match words[4].as_str() {
        "general" => false,
        "symmetric" => true,
        other => return Err(unsupported("symmetry", other, "general or symmetric")),
    };
    Ok((header_no, format, symmetric))
}

/// What the size line says: the matrix' rows and columns and the entries that follow.
struct SizeLine {
    /// Its line number.
    line: usize,
    rows: usize,
    cols: usize,
    /// Entries (coordinate) or values (array) that follow.
    count: usize,
}

/// The size line after the header: `rows cols entries` (coordinate) or `rows cols` (array).
fn parse_size_line(
    lines: &mut NumberedLines<'_>,
    name: &str,
    header_no: usize,
    format: MatrixMarketFormat,
    symmetric: bool,
) -> Result<SizeLine> {
    let (size_no, size_line) = next_data_line(lines, name)?
        .ok_or_else(|| line_error(name, header_no + 1, MatrixLineProblem::SizeLineMissing))?;
    let (expected_sizes, layout) = match format {
        MatrixMarketFormat::Coordinate => (3, "rows cols entries"),
        MatrixMarketFormat::Array => (2, "rows cols"),
    };
    let not_layout = || {
        line_error(
            name,
            size_no,
            MatrixLineProblem::NotLayout {
                text: size_line.trim().into(),
                layout,
            },
        )
    };
    let sizes: Vec<usize> = size_line
        .split_whitespace()
        .map(|t| t.parse::<usize>())
        .collect::<std::result::Result<_, _>>()
        .map_err(|_| not_layout())?;
    if sizes.len() != expected_sizes {
        return Err(not_layout());
    }
    let (rows, cols) = (sizes[0], sizes[1]);
    if symmetric && rows != cols {
        return Err(line_error(
            name,
            size_no,
            MatrixLineProblem::NotSquare { rows, cols },
        ));
    }
    let count = match format {
        MatrixMarketFormat::Coordinate => Some(sizes[2]),
        MatrixMarketFormat::Array if symmetric => rows.checked_mul(rows + 1).map(|n| n / 2),
        MatrixMarketFormat::Array => rows.checked_mul(cols),
    }
    .ok_or_else(|| {
        line_error(
            name,
            size_no,
            MatrixLineProblem::SizeOverflow { rows, cols },
        )
    })?;
    Ok(SizeLine {
        line: size_no,
        rows,
        cols,
        count,
    })
}

/// The next data line while the size line promises more `what` (entries or values) than the
/// `read` so far: a file that ends first is an error at the size line.
fn promised_line(
    lines: &mut NumberedLines<'_>,
    name: &str,
    size: &SizeLine,
    read: usize,
    what: &'static str,
) -> Result<(usize, String)> {
    next_data_line(lines, name)?.ok_or_else(|| {
        line_error(
            name,
            size.line,
            MatrixLineProblem::EndsEarly {
                what,
                read,
                expected: size.count,
            },
        )
    })
}

/// `v` read from `token` on line `no`, when finite.
fn finite_value(v: f64, name: &str, no: usize, token: &str) -> Result<f64> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(Error::BodyFile(BodyFileError::NonFiniteEntry {
            path: name.into(),
            line: no,
            value: token.into(),
        }))
    }
}

/// The `row col value` lines of a coordinate file, 0-based; an upper-triangle entry of a
/// symmetric file is stored as its lower-triangle twin.
fn coordinate_entries(
    lines: &mut NumberedLines<'_>,
    name: &str,
    size: &SizeLine,
    symmetric: bool,
) -> Result<Vec<(usize, usize, f64)>> {
    let (rows, cols, count) = (size.rows, size.cols, size.count);
    let mut entries = Vec::with_capacity(super::matrix_bytes::capacity_hint(count));
    while entries.len() < count {
        let (no, line) = promised_line(lines, name, size, entries.len(), "entries")?;
        let t: Vec<&str> = line.split_whitespace().collect();
        if t.len() != 3 {
            return Err(line_error(
                name,
                no,
                MatrixLineProblem::NotLayout {
                    text: line.trim().into(),
                    layout: "row col value",
                },
            ));
        }
        let index = |s: &str| {
            s.parse::<usize>().map_err(|_| {
                line_error(
                    name,
                    no,
                    MatrixLineProblem::NotANumber {
                        field: "index",
                        text: s.into(),
                        expected: "a positive integer",
                    },
                )
            })
        };
        let (i, j) = (index(t[0])?, index(t[1])?);
        if i == 0 || j == 0 || i > rows || j > cols {
            return Err(Error::BodyFile(BodyFileError::MatrixIndexOutOfRange {
                path: name.into(),
                line: no,
                row: i,
                col: j,
                rows,
                cols,
            }));
        }
        let v = parse_value(t[2]).ok_or_else(|| not_a_real(name, no, t[2]))?;
        let v = finite_value(v, name, no, t[2])?;
        // Some writers store the upper triangle of a `symmetric` file: the same matrix.
        let (i, j) = if symmetric && j > i { (j, i) } else { (i, j) };
        entries.push((i - 1, j - 1, v));
    }
    Ok(entries)
}

/// The values of an array file, column-major; a symmetric array lists column j from row j
/// down.
fn array_entries(
    lines: &mut NumberedLines<'_>,
    name: &str,
    size: &SizeLine,
    symmetric: bool,
) -> Result<Vec<(usize, usize, f64)>> {
    let (rows, count) = (size.rows, size.count);
    let mut entries = Vec::with_capacity(super::matrix_bytes::capacity_hint(count));
    let (mut i, mut j) = (0usize, 0usize);
    while entries.len() < count {
        let (no, line) = promised_line(lines, name, size, entries.len(), "values")?;
        for token in line.split_whitespace() {
            if entries.len() == count {
                return Err(line_error(
                    name,
                    no,
                    MatrixLineProblem::TooMany {
                        what: "values",
                        expected: count,
                        text: token.into(),
                    },
                ));
            }
            let v = parse_value(token).ok_or_else(|| not_a_real(name, no, token))?;
            entries.push((i, j, finite_value(v, name, no, token)?));
            i += 1;
            if i == rows {
                j += 1;
                i = if symmetric { j } else { 0 };
            }
        }
    }
    Ok(entries)
}

/// Writes a dense matrix as `array real general` (column-major), or `array real symmetric`
/// (the lower triangle) when `symmetric`. Values are printed in Rust's shortest
/// round-trip form, so reading the file back gives the same `f64`s.
pub fn write_array(path: &Path, a: MatRef<'_, f64>, symmetric: bool, comment: &str) -> Result<()> {
    write_atomically(path, |w| {
        writeln!(
            w,
            "%%MatrixMarket matrix array real {}",
            if symmetric { "symmetric" } else { "general" }
        )?;
        for c in comment.lines() {
            writeln!(w, "% {c}")?;
        }
        writeln!(w, "{} {}", a.nrows(), a.ncols())?;
        for j in 0..a.ncols() {
            let start = if symmetric { j } else { 0 };
            for i in start..a.nrows() {
                writeln!(w, "{:e}", a[(i, j)])?;
            }
        }
        Ok(())
    })
}

/// Writes the lower triangle `(row, col, value)` entries (0-based, `row ≥ col`) of an `n × n`
/// symmetric matrix as `coordinate real symmetric`.
pub fn write_coordinate_symmetric(
    path: &Path,
    n: usize,
    lower: &[(usize, usize, f64)],
    comment: &str,
) -> Result<()> {
    write_atomically(path, |w| {
        write_coordinate_symmetric_to(w, n, lower, comment)
    })
}

/// [`write_coordinate_symmetric`] into any writer (a gzip encoder, a buffer).
pub fn write_coordinate_symmetric_to(
    w: &mut dyn Write,
    n: usize,
    lower: &[(usize, usize, f64)],
    comment: &str,
) -> std::io::Result<()> {
    writeln!(w, "%%MatrixMarket matrix coordinate real symmetric")?;
    for c in comment.lines() {
        writeln!(w, "% {c}")?;
    }
    writeln!(w, "{n} {n} {}", lower.len())?;
    for &(i, j, v) in lower {
        debug_assert!(i >= j);
        writeln!(w, "{} {} {v:e}", i + 1, j + 1)?;
    }
    Ok(())
}
