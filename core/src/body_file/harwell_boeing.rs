//! The Harwell–Boeing exchange format (Duff, Grimes and Lewis 1989), as ANSYS `HBMAT` and
//! SciPy's `hb_write` write it: real assembled matrices, symmetric (`RSA`, one triangle) or
//! not (`RUA`), compressed columns in Fortran fixed-width fields. Optionally gzip-compressed.
//!
//! The four header lines give the card counts, the type and size, and the Fortran formats of
//! the pointers, row indices and values (`(8I10)`, `(1P,4E20.12)`, `(3D26.16)`); the fields
//! are cut by those widths, so values that touch (`1.0E+00-2.0E+00`) are read right. Every
//! error names the file and the line; nothing is returned half-read.

use super::{
    BodyFileError, MatrixMarket, MatrixMarketFormat,
    matrix_bytes::{entry_value, plain_text},
};
use crate::{Error, Result, error::MatrixLineProblem};

use super::matrix_bytes::line_error as error;

/// A Fortran edit descriptor of a repeated field: count per line and width.
#[derive(Debug, Clone, Copy, PartialEq)]
struct FieldFormat {
    per_line: usize,
    width: usize,
}

/// Parses `(8I10)`, `(1P,4E20.12)`, `(1P4E20.12)`, `(3D26.16)`, `(5F15.8)`.
fn field_format(text: &str) -> Option<FieldFormat> {
    let t = text.trim().trim_start_matches('(').trim_end_matches(')');
    let t = t.trim();
    // A scale factor `1P` (with or without a comma) changes nothing in the widths.
    let t = match t.find(['P', 'p']) {
        Some(i) if t[..i].chars().all(|c| c.is_ascii_digit()) => {
            t[i + 1..].trim_start_matches(',').trim()
        }
        _ => t,
    };
    let letter = t.find(|c: char| c.is_ascii_alphabetic())?;
    let per_line = if letter == 0 {
        1
    } else {
        t[..letter].parse().ok()?
    };
    let rest = &t[letter + 1..];
    let width_end = rest.find('.').unwrap_or(rest.len());
    let width = rest[..width_end].trim().parse().ok()?;
    (per_line > 0 && width > 0).then_some(FieldFormat { per_line, width })
}

/// Whether a field is a number of its kind (integer or real, Fortran `D` exponents allowed).
fn is_number(text: &str, real: bool) -> bool {
    if real {
        text.replace(['D', 'd'], "E").parse::<f64>().is_ok()
    } else {
        text.parse::<i64>().is_ok()
    }
}

/// One block of a Harwell–Boeing file's data: `count` values laid out by `format` over the
/// `cards` lines from `start` (0-based).
#[derive(Debug, Clone, Copy)]
struct FieldBlock {
    /// What the values are (`pointers`, `indices`, `values`), for errors.
    what: &'static str,
    start: usize,
    cards: usize,
    count: usize,
    format: FieldFormat,
    /// Real values (`D` exponents allowed) rather than integers.
    real: bool,
}

/// The fields of `block` in the `lines` of `path`, each with its 1-based line. A line whose
/// blank-separated tokens are all numbers is read by them (SciPy's `hb_write` declares `E25.16`
/// and writes 24 characters); otherwise by the format's widths (values that touch).
fn fields<'a>(lines: &[&'a str], path: &str, block: FieldBlock) -> Result<Vec<(usize, &'a str)>> {
    let FieldBlock {
        what,
        start,
        cards,
        count,
        format,
        real,
    } = block;
    let mut out = Vec::with_capacity(super::matrix_bytes::capacity_hint(count));
    for card in 0..cards {
        let index = start + card;
        let line = lines.get(index).ok_or_else(|| {
            error(
                path,
                index + 1,
                MatrixLineProblem::EndsEarly {
                    what,
                    read: out.len(),
                    expected: count,
                },
            )
        })?;
        let line = line.trim_end_matches('\r');
        let tokens: Vec<&str> = line.split_whitespace().collect();
        if !tokens.is_empty()
            && tokens.len() <= format.per_line
            && tokens.iter().all(|t| is_number(t, real))
        {
            for t in tokens {
                if out.len() == count {
                    break;
                }
                out.push((index + 1, t));
            }
            continue;
        }
        for k in 0..format.per_line {
            if out.len() == count {
                break;
            }
            let from = k * format.width;
            if from >= line.len() {
                break;
            }
            let to = (from + format.width).min(line.len());
            let field = line
                .get(from..to)
                .ok_or_else(|| error(path, index + 1, MatrixLineProblem::NotPlainText { what }))?;
            out.push((index + 1, field.trim()));
        }
    }
    if out.len() != count {
        return Err(error(
            path,
            start + cards,
            MatrixLineProblem::CountMismatch {
                what,
                found: out.len(),
                lines: cards,
                expected: count,
            },
        ));
    }
    Ok(out)
}

fn header_int(
    line: &str,
    field: usize,
    path: &str,
    number: usize,
    what: &'static str,
) -> Result<usize> {
    let text = line
        .get(14 * field..(14 * field + 14).min(line.len()))
        .unwrap_or("");
    text.trim().parse().map_err(|_| {
        error(
            path,
            number,
            MatrixLineProblem::NotANumber {
                field: what,
                text: text.trim().into(),
                expected: "a count",
            },
        )
    })
}

/// Whether the type field (line 3, columns 1–3) of a Harwell–Boeing file names a symmetric
/// matrix; only real (R..) assembled (..A) matrices describe a body.
fn symmetric_kind(line: &str, path: &str) -> Result<bool> {
    let kind = line.get(..3).unwrap_or("").to_ascii_uppercase();
    let mut chars = kind.chars();
    let (value_type, structure, assembly) = (chars.next(), chars.next(), chars.next());
    let unsupported = |needs| {
        error(
            path,
            3,
            MatrixLineProblem::Unsupported {
                field: "type",
                value: kind.into(),
                needs,
            },
        )
    };
    if value_type != Some('R') {
        return Err(unsupported("only real matrices (R..) describe a body"));
    }
    let symmetric = match structure {
        Some('S') | Some('H') => true,
        Some('U') => false,
        _ => {
            return Err(unsupported(
                "a body's matrix is symmetric (S) or stored whole (U)",
            ));
        }
    };
    if assembly != Some('A') {
        return Err(unsupported(
            "only assembled matrices (..A) are read, not elemental",
        ));
    }
    Ok(symmetric)
}

/// A Harwell–Boeing file's header: its cards per block (pointers, indices, values, right-hand
/// sides), the matrix kind, its size and stored entries, and the three blocks' formats.
struct Header {
    ptr_cards: usize,
    ind_cards: usize,
    val_cards: usize,
    rhs_cards: usize,
    symmetric: bool,
    rows: usize,
    cols: usize,
    nnz: usize,
    formats: [FieldFormat; 3],
}

/// The header of the file `path` from its first four `lines`.
fn header(lines: &[&str], path: &str) -> Result<Header> {
    let cards = |field| header_int(lines[1], field, path, 2, "card count");
    let (ptr_cards, ind_cards, val_cards) = (cards(1)?, cards(2)?, cards(3)?);
    let rhs_cards = if lines[1].len() > 56 { cards(4)? } else { 0 };
    let symmetric = symmetric_kind(lines[2], path)?;
    let dims = |field| header_int(&lines[2][..lines[2].len().min(70)], field, path, 3, "size");
    let (rows, cols, nnz) = (dims(1)?, dims(2)?, dims(3)?);
    let format = |from: usize, to: usize, what: &'static str| {
        let text = lines[3].get(from..to.min(lines[3].len())).unwrap_or("");
        field_format(text).ok_or_else(|| {
            error(
                path,
                4,
                MatrixLineProblem::NotAFortranFormat {
                    what,
                    text: text.trim().into(),
                },
            )
        })
    };
    let (ptr_format, ind_format, val_format) = (
        format(0, 16, "pointer")?,
        format(16, 32, "index")?,
        format(32, 52, "value")?,
    );
    Ok(Header {
        ptr_cards,
        ind_cards,
        val_cards,
        rhs_cards,
        symmetric,
        rows,
        cols,
        nnz,
        formats: [ptr_format, ind_format, val_format],
    })
}

/// The column pointers (1-based) checked before any is followed: the first 1, the last
/// `nnz` + 1, never decreasing, so they stay within the entries read. Errors name the
/// pointers' first line (`at`).
fn check_pointers(pointers: &[usize], nnz: usize, (path, at): (&str, usize)) -> Result<()> {
    let cols = pointers.len() - 1;
    if pointers.first() != Some(&1) || pointers.last() != Some(&(nnz + 1)) {
        return Err(error(
            path,
            at,
            MatrixLineProblem::PointerRange {
                first: pointers.first().copied(),
                last: pointers.last().copied(),
                expected_last: nnz + 1,
            },
        ));
    }
    // Every pointer checked before any is followed: with the first 1 and the last nnz + 1, a
    // sequence that never decreases stays within the nnz entries read.
    if let Some(j) = (0..cols).find(|&j| pointers[j + 1] < pointers[j]) {
        return Err(error(
            path,
            at,
            MatrixLineProblem::PointerDecreases {
                column: j + 1,
                from: pointers[j],
                to: pointers[j + 1],
            },
        ));
    }
    Ok(())
}

/// A field's text and its line (1-based).
type Field<'a> = (usize, &'a str);

/// A field that must be an integer (`what` names it), at its line of `path`.
fn integer_field(path: &str, (line, text): (usize, &str), what: &'static str) -> Result<usize> {
    text.parse().map_err(|_| {
        error(
            path,
            line,
            MatrixLineProblem::NotANumber {
                field: what,
                text: text.into(),
                expected: "an integer",
            },
        )
    })
}

/// The entries (0-based) of the columns `pointers` delimit, from the `indices` and `values`
/// fields read (each with its line); a row outside the `rows` × `cols` matrix is named.
fn column_entries(
    pointers: &[usize],
    (indices, values): (&[Field<'_>], &[Field<'_>]),
    (rows, cols): (usize, usize),
    path: &str,
) -> Result<Vec<(usize, usize, f64)>> {
    let nnz = indices.len();
    let integer = |field, what| integer_field(path, field, what);
    let mut entries = Vec::with_capacity(super::matrix_bytes::capacity_hint(nnz));
    for j in 0..cols {
        let (from, to) = (pointers[j], pointers[j + 1]);
        for p in from - 1..to - 1 {
            let (line, _) = indices[p];
            let row = integer(indices[p], "row index")?;
            if row == 0 || row > rows {
                return Err(Error::BodyFile(BodyFileError::MatrixIndexOutOfRange {
                    path: path.into(),
                    line,
                    row,
                    col: j + 1,
                    rows,
                    cols,
                }));
            }
            let (line, text) = values[p];
            let value = entry_value(text, path, line)?;
            entries.push((row - 1, j, value));
        }
    }
    Ok(entries)
}

/// Parses Harwell–Boeing bytes (plain or gzip) named `path` in error messages.
pub fn parse_harwell_boeing(bytes: &[u8], path: &str) -> Result<MatrixMarket> {
    let text = plain_text(bytes, path)?;
    let lines: Vec<&str> = text.lines().collect();
    if lines.len() < 4 {
        return Err(error(
            path,
            lines.len(),
            MatrixLineProblem::HeaderShort { lines: lines.len() },
        ));
    }
    let header = header(&lines, path)?;
    let (rows, cols, nnz, symmetric) = (header.rows, header.cols, header.nnz, header.symmetric);
    let [ptr_format, ind_format, val_format] = header.formats;
    let (ptr_cards, ind_cards, val_cards) = (header.ptr_cards, header.ind_cards, header.val_cards);
    let rhs_cards = header.rhs_cards;
    let start = 4 + usize::from(rhs_cards > 0);
    let integer = |field, what| integer_field(path, field, what);
    let pointers = fields(
        &lines,
        path,
        FieldBlock {
            what: "pointers",
            start,
            cards: ptr_cards,
            count: cols + 1,
            format: ptr_format,
            real: false,
        },
    )?
    .into_iter()
    .map(|f| integer(f, "pointer"))
    .collect::<Result<Vec<usize>>>()?;
    let indices = fields(
        &lines,
        path,
        FieldBlock {
            what: "indices",
            start: start + ptr_cards,
            cards: ind_cards,
            count: nnz,
            format: ind_format,
            real: false,
        },
    )?;
    let values = fields(
        &lines,
        path,
        FieldBlock {
            what: "values",
            start: start + ptr_cards + ind_cards,
            cards: val_cards,
            count: nnz,
            format: val_format,
            real: true,
        },
    )?;
    check_pointers(&pointers, nnz, (path, start + 1))?;
    let entries = column_entries(&pointers, (&indices, &values), (rows, cols), path)?;
    if val_cards == 0 && nnz > 0 {
        return Err(error(
            path,
            2,
            MatrixLineProblem::Unsupported {
                field: "value card count",
                value: "0".into(),
                needs: "a pattern-only file (no values) describes no body",
            },
        ));
    }
    Ok(MatrixMarket {
        rows,
        cols,
        format: MatrixMarketFormat::Coordinate,
        symmetric,
        entries,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 3 × 3 symmetric matrix written the way ANSYS HBMAT does (RSA, lower triangle), with
    /// values that touch and a `1P` scale factor.
    const RSA: &str = "\
test matrix                                                             key     
             5             1             1             3             0
RSA                        3             3             5             0
(4I14)          (5I14)          (1P,2E13.5)         
             1             3             5             6
             1             2             2             3             3
  4.00000E+00 -1.00000E+00
  4.00000E+00-1.00000E+00
  4.00000E+00
";

    #[test]
    fn reads_a_symmetric_file_with_touching_values() {
        let m = parse_harwell_boeing(RSA.as_bytes(), "t.rsa").unwrap();
        assert!(m.symmetric);
        assert_eq!((m.rows, m.cols), (3, 3));
        assert_eq!(
            m.entries,
            vec![
                (0, 0, 4.0),
                (1, 0, -1.0),
                (1, 1, 4.0),
                (2, 1, -1.0),
                (2, 2, 4.0)
            ]
        );
        assert_eq!(
            field_format("(1P4E20.12)"),
            Some(FieldFormat {
                per_line: 4,
                width: 20
            })
        );
        assert_eq!(
            field_format("(8I10)"),
            Some(FieldFormat {
                per_line: 8,
                width: 10
            })
        );
    }

    /// Damaged files are named errors with the line: a complex type, a row out of range, a
    /// value that is not a number, a file cut short.
    #[test]
    fn damaged_files_name_file_and_line() {
        let complex = RSA.replacen("RSA", "CSA", 1);
        let e = parse_harwell_boeing(complex.as_bytes(), "t.rsa").unwrap_err();
        assert!(e.to_string().contains("t.rsa:3"), "{e}");
        let out_of_range = RSA.replacen(
            "             1             2             2             3             3",
            "             1             2             2             3             9",
            1,
        );
        let e = parse_harwell_boeing(out_of_range.as_bytes(), "t.rsa").unwrap_err();
        assert!(e.to_string().contains("t.rsa:6"), "{e}");
        let not_a_number = RSA.replacen(
            "  4.00000E+00 -1.00000E+00",
            "  4.00000E+00 -1.0000xE+00",
            1,
        );
        let e = parse_harwell_boeing(not_a_number.as_bytes(), "t.rsa").unwrap_err();
        assert!(e.to_string().contains("t.rsa:7"), "{e}");
        let cut: String = RSA.lines().take(7).collect::<Vec<_>>().join("\n");
        let e = parse_harwell_boeing(cut.as_bytes(), "t.rsa").unwrap_err();
        assert!(
            matches!(
                e,
                Error::BodyFile(BodyFileError::MatrixLine {
                    line: 8,
                    problem: MatrixLineProblem::EndsEarly {
                        what: "values",
                        read: 2,
                        expected: 5
                    },
                    ..
                })
            ),
            "{e}"
        );
    }
}
