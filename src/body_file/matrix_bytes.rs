//! The bytes of a matrix file as its readers see them: gzip undone (recognised by its magic
//! bytes, whatever the file is called), and, for the line-oriented formats, checked as text.

use std::{borrow::Cow, io::Read};

use super::BodyFileError;
use crate::{Error, Result};

fn damaged(path: &str, reason: String) -> Error {
    line_error(path, 0, reason)
}

/// A line of a matrix file that does not parse (line 0: the file as a whole).
pub(super) fn line_error(path: &str, line: usize, reason: impl Into<String>) -> Error {
    Error::BodyFile(BodyFileError::MatrixMarketLine {
        path: path.into(),
        line,
        reason: reason.into(),
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
        .map_err(|e| damaged(path, format!("the gzip stream is damaged: {e}")))?;
    Ok(Cow::Owned(out))
}

/// [`plain_bytes`] as UTF-8 text.
pub(super) fn plain_text(bytes: &[u8], path: &str) -> Result<String> {
    String::from_utf8(plain_bytes(bytes, path)?.into_owned())
        .map_err(|_| damaged(path, "the file is not text".into()))
}
