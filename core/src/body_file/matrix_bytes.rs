//! The bytes of a matrix file as its readers see them: gzip undone (recognised by its magic
//! bytes, whatever the file is called), and, for the line-oriented formats, checked as text.

use std::{borrow::Cow, io::Read};

use super::BodyFileError;
use crate::{Error, Result, error::MatrixLineProblem};

/// Items reserved ahead for a count read from a file: a vector grows with what the file
/// actually holds, so a header promising 2³² entries allocates nothing it does not read.
pub(super) fn capacity_hint(count: usize) -> usize {
    count.min(1 << 16)
}

/// A line of a matrix file that does not parse (line 0: the file as a whole).
pub(super) fn line_error(path: &str, line: usize, problem: MatrixLineProblem) -> Error {
    Error::BodyFile(BodyFileError::MatrixLine {
        path: path.into(),
        line,
        problem,
    })
}

/// `bytes` decompressed when they are a gzip stream, else as they are.
pub(super) fn plain_bytes<'a>(bytes: &'a [u8], path: &str) -> Result<Cow<'a, [u8]>> {
    if !bytes.starts_with(&[0x1f, 0x8b]) {
        return Ok(Cow::Borrowed(bytes));
    }
    let mut out = Vec::new();
    flate2::read::MultiGzDecoder::new(bytes)
        .read_to_end(&mut out)
        .map_err(|source| {
            Error::BodyFile(BodyFileError::GzipDamaged {
                path: path.into(),
                source,
            })
        })?;
    Ok(Cow::Owned(out))
}

/// [`plain_bytes`] as UTF-8 text.
pub(super) fn plain_text(bytes: &[u8], path: &str) -> Result<String> {
    String::from_utf8(plain_bytes(bytes, path)?.into_owned())
        .map_err(|_| line_error(path, 0, MatrixLineProblem::NotText))
}

/// A real as Fortran and Nastran write it: `1.5`, `1.5E+3`, `1.5D+3`, or the exponent without
/// its letter (`1.5+3`, `-.5-2`; Fortran drops the `E` of a three-digit exponent).
pub(super) fn fortran_real(text: &str) -> Option<f64> {
    let t = text.trim().replace(['D', 'd'], "E");
    if let Ok(v) = t.parse::<f64>() {
        return Some(v);
    }
    // The exponent without its letter: a sign after the first character, not after an E.
    let bytes = t.as_bytes();
    let at = (1..bytes.len()).rev().find(|&i| {
        (bytes[i] == b'+' || bytes[i] == b'-') && !matches!(bytes[i - 1], b'E' | b'e')
    })?;
    format!("{}E{}", &t[..at], &t[at..]).parse().ok()
}

/// A matrix entry's value `text` at `path`:`line`: a real number ([`fortran_real`]) and
/// finite, or the named error.
pub(super) fn entry_value(text: &str, path: &str, line: usize) -> Result<f64> {
    let v = fortran_real(text).ok_or_else(|| {
        line_error(
            path,
            line,
            MatrixLineProblem::NotANumber {
                field: "value",
                text: text.trim().into(),
                expected: "a real number",
            },
        )
    })?;
    if !v.is_finite() {
        return Err(Error::BodyFile(BodyFileError::NonFiniteEntry {
            path: path.into(),
            line,
            value: text.trim().into(),
        }));
    }
    Ok(v)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reals_as_fortran_and_nastran_write_them() {
        for (t, v) in [
            ("1.5+3", 1.5e3),
            ("-.5-2", -0.5e-2),
            ("2.D-1", 0.2),
            ("7.", 7.0),
            ("1.0-300", 1e-300),
        ] {
            assert_eq!(fortran_real(t), Some(v), "{t}");
        }
        assert_eq!(fortran_real("x1"), None);
        assert!(
            entry_value("inf", "k", 3)
                .unwrap_err()
                .to_string()
                .contains("k:3")
        );
        assert!(entry_value("NaN", "k", 4).is_err());
    }
}
