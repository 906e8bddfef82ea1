//! Nastran OUTPUT4 (OP4) matrices, binary or ASCII: one named matrix picked out of the file. OP4
//! carries no DOF map: its rows are the FE code's equations, placed on the body's nodes by the
//! body file's `dof_map` (or, without one, taken as the body's node-major DOF).
//!
//! Layout (as Nastran's OUTPUT4 and NASA's pyyeti write it). Each matrix: a header
//! (`NCOL NROW NF NTYPE NAME`; NROW < 0 marks the "bigmat" sparse form), one record per column
//! with data (`ICOL IROW NW`), and a closing record with ICOL = NCOL + 1. A dense column
//! (IROW > 0) holds consecutive values from row IROW; a sparse one (IROW = 0) holds strings of
//! consecutive values, each headed by `IS = row + 65536·(L + 1)` (non-bigmat) or by the pair
//! `L + 1, row` (bigmat), L the string's length in 4-byte words. Binary files are Fortran
//! unformatted records (a 4-byte length before and after each; either byte order; 4-byte
//! integers), NTYPE 1 single and 2 double precision; ASCII files give the header in `4I8, A8`
//! followed by the values' Fortran format (`1P,3E23.16`), column headers in `3I8`, string
//! headers on their own lines. Complex matrices (NTYPE 3, 4) are refused by name. Every error
//! names the file and the line (ASCII) or the byte (binary); nothing is returned half-read.

use std::collections::BTreeSet;

use super::nastran_op4_ascii::ascii_op4;
use super::nastran_op4_matrix::{Found, Matrix, words_per_value};
use super::{
    MatrixMarket,
    matrix_bytes::{line_error as error, plain_bytes},
};
use crate::{
    Error, Result,
    error::{BodyFileError, MatrixLineProblem},
};

/// A problem at `byte` of the binary file `path`.
fn at_byte(path: &str, byte: usize, problem: MatrixLineProblem) -> Error {
    Error::BodyFile(BodyFileError::MatrixByte {
        path: path.into(),
        byte,
        problem,
    })
}

/// Parses the OP4 matrix `matrix` of the bytes named `path` (binary or ASCII, gzip allowed).
pub fn parse_op4(bytes: &[u8], path: &str, matrix: &str) -> Result<MatrixMarket> {
    let bytes = plain_bytes(bytes, path)?;
    let wanted = matrix.to_ascii_uppercase();
    let binary = bytes.len() >= 4
        && (bytes[..4] == 24i32.to_le_bytes()
            || bytes[..4] == 24i32.to_be_bytes()
            || bytes[..4] == 48i32.to_le_bytes()
            || bytes[..4] == 48i32.to_be_bytes());
    let found = if binary {
        binary_op4(&bytes, path, &wanted)?
    } else {
        let text = std::str::from_utf8(&bytes)
            .map_err(|_| error(path, 0, MatrixLineProblem::NeitherOp4NorText))?;
        ascii_op4(text, path, &wanted)?
    };
    match found {
        Ok(m) => Ok(m.into_market()),
        Err(names) => Err(error(
            path,
            0,
            MatrixLineProblem::NoSuchMatrix {
                format: "OP4",
                wanted: wanted.into(),
                found: crate::error::Name::all(names),
            },
        )),
    }
}

/// Fortran unformatted records of one byte order.
struct Records<'a> {
    bytes: &'a [u8],
    at: usize,
    little: bool,
}

impl<'a> Records<'a> {
    fn int(&self, b: &[u8]) -> i64 {
        let a = [b[0], b[1], b[2], b[3]];
        i64::from(if self.little {
            i32::from_le_bytes(a)
        } else {
            i32::from_be_bytes(a)
        })
    }

    /// The next record's body and the byte it starts at; `None` at the end of the file.
    fn next(&mut self, path: &str) -> Result<Option<(&'a [u8], usize)>> {
        if self.at == self.bytes.len() {
            return Ok(None);
        }
        let byte = self.at;
        let fail = |problem| at_byte(path, byte, problem);
        if byte + 4 > self.bytes.len() {
            return Err(fail(MatrixLineProblem::RecordCut));
        }
        let length = self.int(&self.bytes[byte..byte + 4]);
        let length = usize::try_from(length)
            .map_err(|_| fail(MatrixLineProblem::RecordLength { length }))?;
        let end = byte + 4 + length;
        if end + 4 > self.bytes.len() {
            return Err(fail(MatrixLineProblem::RecordPastEnd {
                length,
                file: self.bytes.len(),
            }));
        }
        let trailer = self.int(&self.bytes[end..end + 4]);
        if trailer != length as i64 {
            return Err(fail(MatrixLineProblem::RecordTrailer { length, trailer }));
        }
        self.at = end + 4;
        Ok(Some((&self.bytes[byte + 4..end], byte)))
    }
}

fn binary_op4(bytes: &[u8], path: &str, wanted: &str) -> Result<Found> {
    let little = bytes[..4] == 24i32.to_le_bytes() || bytes[..4] == 48i32.to_le_bytes();
    let mut records = Records {
        bytes,
        at: 0,
        little,
    };
    let mut names = BTreeSet::new();
    while let Some((header, byte)) = records.next(path)? {
        let fail = |problem| at_byte(path, byte, problem);
        if header.len() == 48 {
            return Err(fail(MatrixLineProblem::EightByteIntegers));
        }
        if header.len() != 24 {
            return Err(fail(MatrixLineProblem::HeaderLength {
                length: header.len(),
            }));
        }
        let word = |k: usize| records.int(&header[4 * k..4 * k + 4]);
        let name = String::from_utf8_lossy(&header[16..24])
            .trim()
            .to_ascii_uppercase();
        let (ncols, nrows, ntype) = (word(0), word(1), word(3));
        let wpv = words_per_value(ntype).map_err(fail)?;
        let mut matrix = BinaryMatrix {
            path,
            name,
            ncols,
            bigmat: nrows < 0,
            words_per_value: wpv,
            little,
            matrix: Matrix {
                rows: nrows.unsigned_abs() as usize,
                cols: ncols.max(0) as usize,
                entries: Vec::new(),
            },
        };
        loop {
            let (record, byte) = records.next(path)?.ok_or_else(|| {
                fail(MatrixLineProblem::NoClosingRecord {
                    matrix: (&matrix.name).into(),
                })
            })?;
            if matrix.read_column(&records, record, byte)? {
                break;
            }
        }
        if matrix.name == wanted {
            return Ok(Ok(matrix.matrix));
        }
        names.insert(matrix.name);
    }
    Ok(Err(names))
}

/// One binary matrix being read: its header's name, layout and precision, and the entries
/// read so far.
struct BinaryMatrix<'p> {
    path: &'p str,
    name: String,
    /// NCOL of the header: a column record beyond it closes the matrix.
    ncols: i64,
    /// Sparse strings with a two-word header (NROW < 0).
    bigmat: bool,
    /// Words per value (NTYPE).
    words_per_value: usize,
    /// The file's byte order.
    little: bool,
    matrix: Matrix,
}

impl BinaryMatrix<'_> {
    /// Reads the column `record` (at `byte` of the file); `true` when it is the closing one.
    fn read_column(&mut self, records: &Records<'_>, record: &[u8], byte: usize) -> Result<bool> {
        let fail = |problem| at_byte(self.path, byte, problem);
        if record.len() < 12 {
            return Err(fail(MatrixLineProblem::ColumnRecordShort {
                length: record.len(),
            }));
        }
        let w = |k: usize| records.int(&record[4 * k..4 * k + 4]);
        let (icol, irow) = (w(0), w(1));
        if icol > self.ncols {
            return Ok(true);
        }
        if icol < 1 {
            return Err(fail(MatrixLineProblem::NoSuchColumn {
                matrix: (&self.name).into(),
                column: icol,
            }));
        }
        let value_bytes = 4 * self.words_per_value;
        let data = &record[12..];
        if irow > 0 {
            if !data.len().is_multiple_of(value_bytes) {
                return Err(fail(MatrixLineProblem::PartValues { length: data.len() }));
            }
            for k in 0..data.len() / value_bytes {
                let v = self.value(record, 12 + k * value_bytes);
                self.push((irow + k as i64, icol), v, byte)?;
            }
            return Ok(false);
        }
        let mut p = 12;
        while p < record.len() {
            let head = if self.bigmat { 8 } else { 4 };
            if p + head > record.len() {
                return Err(fail(MatrixLineProblem::StringHeaderCut));
            }
            let (words, row) = if self.bigmat {
                (w(p / 4) - 1, w(p / 4 + 1))
            } else {
                let is = w(p / 4);
                ((is >> 16) - 1, is & 0xFFFF)
            };
            p += head;
            let count = usize::try_from(words).unwrap_or(usize::MAX) / self.words_per_value;
            if words < 1 || p + count * value_bytes > record.len() {
                return Err(fail(MatrixLineProblem::StringTooLong {
                    words,
                    row,
                    column_words: w(2),
                }));
            }
            for k in 0..count {
                let v = self.value(record, p + k * value_bytes);
                self.push((row + k as i64, icol), v, byte)?;
            }
            p += count * value_bytes;
        }
        Ok(false)
    }

    /// The value at `offset` of `record`, single or double precision in the file's byte order.
    fn value(&self, record: &[u8], offset: usize) -> f64 {
        let b = &record[offset..offset + 4 * self.words_per_value];
        if self.words_per_value == 1 {
            let a = [b[0], b[1], b[2], b[3]];
            f64::from(if self.little {
                f32::from_le_bytes(a)
            } else {
                f32::from_be_bytes(a)
            })
        } else {
            let mut a = [0u8; 8];
            a.copy_from_slice(b);
            if self.little {
                f64::from_le_bytes(a)
            } else {
                f64::from_be_bytes(a)
            }
        }
    }

    /// Adds the entry `v` at (`row`, `column`), both 1-based, of a record at `byte`: a row
    /// outside the matrix or a value that is not finite is named; zeros are not stored.
    fn push(&mut self, (row, column): (i64, i64), v: f64, byte: usize) -> Result<()> {
        let fail = |problem| at_byte(self.path, byte, problem);
        let rows = self.matrix.rows;
        if row < 1 || row as usize > rows {
            return Err(fail(MatrixLineProblem::RowOutOfRange {
                matrix: (&self.name).into(),
                row,
                column,
                rows,
            }));
        }
        if !v.is_finite() {
            return Err(fail(MatrixLineProblem::NonFinite {
                value: v,
                row,
                column,
            }));
        }
        if v != 0.0 {
            self.matrix
                .entries
                .push((row as usize - 1, column as usize - 1, v));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Fortran records of `words` (i32 or f64) in little-endian order.
    fn record(out: &mut Vec<u8>, body: &[u8]) {
        out.extend((body.len() as i32).to_le_bytes());
        out.extend(body);
        out.extend((body.len() as i32).to_le_bytes());
    }
    fn ints(v: &[i32]) -> Vec<u8> {
        v.iter().flat_map(|x| x.to_le_bytes()).collect()
    }
    fn doubles(v: &[f64]) -> Vec<u8> {
        v.iter().flat_map(|x| x.to_le_bytes()).collect()
    }

    /// A 3 × 3 matrix `A`: column 1 dense, column 3 as one bigmat string, then the close.
    fn binary(bigmat: bool, ntype: i32) -> Vec<u8> {
        let mut out = Vec::new();
        let rows = if bigmat { -3 } else { 3 };
        record(
            &mut out,
            &[ints(&[3, rows, 6, ntype]), b"A       ".to_vec()].concat(),
        );
        record(
            &mut out,
            &[ints(&[1, 1, 4]), doubles(&[2.0, -1.0])].concat(),
        );
        let head = if bigmat {
            ints(&[5, 2])
        } else {
            ints(&[2 + (5 << 16)])
        };
        let words = if bigmat { 6 } else { 5 };
        record(
            &mut out,
            &[ints(&[3, 0, words]), head, doubles(&[-1.0, 4.0])].concat(),
        );
        record(&mut out, &[ints(&[4, 1, 2]), doubles(&[1.0])].concat());
        out
    }

    #[test]
    fn reads_dense_and_string_columns_in_both_sparse_forms() {
        for bigmat in [true, false] {
            let m = parse_op4(&binary(bigmat, 2), "a.op4", "a").unwrap();
            assert_eq!((m.rows, m.cols), (3, 3));
            assert_eq!(
                m.entries,
                vec![(0, 0, 2.0), (1, 0, -1.0), (1, 2, -1.0), (2, 2, 4.0)]
            );
        }
        let ascii = r#"
       3      -3       6       2A       1P,3E23.16
       1       1       2
 2.0000000000000000E+00-1.0000000000000000E+00
       3       0       6
       5       2
-1.0000000000000000E+00 4.0000000000000000E+00
       4       1       1
 1.0000000000000000E+00
"#
        .trim_start_matches('\n');
        let m = parse_op4(ascii.as_bytes(), "a.op4", "A").unwrap();
        assert_eq!(
            m.entries,
            vec![(0, 0, 2.0), (1, 0, -1.0), (1, 2, -1.0), (2, 2, 4.0)]
        );
        let bad = ascii.replace("-1.0000000000000000E+00 4.0", "-1.0000000000000000X+00 4.0");
        let e = parse_op4(bad.as_bytes(), "a.op4", "A")
            .unwrap_err()
            .to_string();
        assert!(e.contains("a.op4:6:") && e.contains("not a real"), "{e}");
    }

    /// An ASCII OP4 whose columns are cut short, overrun or never closed: each a named error
    /// with its matrix, column and line (the non-bigmat string header `IS` too).
    #[test]
    fn ascii_columns_cut_short_name_matrix_column_and_line() {
        let ascii = [
            "       3       3       6       2A       1P,3E23.16",
            "       1       1       2",
            " 2.0000000000000000E+00-1.0000000000000000E+00",
            "       3       0       5",
            "     327682",
            "-1.0000000000000000E+00 4.0000000000000000E+00",
            "       4       1       1",
            " 1.0000000000000000E+00",
        ];
        let text = |lines: &[&str]| lines.join("\n");
        let problem = |lines: &[&str]| match parse_op4(text(lines).as_bytes(), "a.op4", "A") {
            Err(Error::BodyFile(BodyFileError::MatrixLine { line, problem, .. })) => {
                (line, problem)
            }
            other => panic!("{other:?}"),
        };
        // IS = ROW + 65536 (L + 1): row 2, two double-precision values (four words).
        let m = parse_op4(text(&ascii).as_bytes(), "a.op4", "A").unwrap();
        assert_eq!(
            m.entries,
            vec![(0, 0, 2.0), (1, 0, -1.0), (1, 2, -1.0), (2, 2, 4.0)]
        );
        let matrix = crate::error::Name::from("A");
        assert_eq!(
            problem(&ascii[..5]),
            (
                0,
                MatrixLineProblem::EndsInsideColumn {
                    matrix: matrix.clone(),
                    column: 3
                }
            )
        );
        assert_eq!(
            problem(&ascii[..2]),
            (
                0,
                MatrixLineProblem::EndsInsideColumn {
                    matrix: matrix.clone(),
                    column: 1
                }
            )
        );
        assert_eq!(
            problem(&ascii[..6]),
            (
                0,
                MatrixLineProblem::NoClosingRecord {
                    matrix: matrix.clone()
                }
            )
        );
        let mut overrun = ascii;
        overrun[1] = "       1       3       2";
        assert_eq!(
            problem(&overrun),
            (
                3,
                MatrixLineProblem::RowOutOfRange {
                    matrix: matrix.clone(),
                    row: 4,
                    column: 1,
                    rows: 3
                }
            )
        );
        let mut empty = ascii;
        empty[2] = "";
        assert_eq!(
            problem(&empty),
            (3, MatrixLineProblem::LineWithoutValues { column: 1 })
        );
        let mut column0 = ascii;
        column0[1] = "       0       1       2";
        assert_eq!(
            problem(&column0),
            (
                2,
                MatrixLineProblem::NoSuchColumn {
                    matrix: matrix.clone(),
                    column: 0
                }
            )
        );
    }

    #[test]
    fn names_what_it_cannot_read() {
        let e = parse_op4(&binary(true, 4), "a.op4", "A")
            .unwrap_err()
            .to_string();
        assert!(e.contains("complex"), "{e}");
        let e = parse_op4(&binary(true, 2), "a.op4", "KAAX")
            .unwrap_err()
            .to_string();
        assert!(e.contains("the file's OP4 matrices: A"), "{e}");
        let mut cut = binary(false, 2);
        cut.truncate(cut.len() - 6);
        let e = parse_op4(&cut, "a.op4", "A").unwrap_err().to_string();
        assert!(e.contains("runs past the end"), "{e}");
        let mut wrong = binary(false, 2);
        let at = 4 + 24 + 4 + 4 + 4; // the first column record's row
        wrong[at..at + 4].copy_from_slice(&7i32.to_le_bytes());
        let e = parse_op4(&wrong, "a.op4", "A").unwrap_err().to_string();
        assert!(e.contains("row 7") && e.contains("byte 32"), "{e}");
    }
}
