//! NumPy's `.npy` format (version 1.0) for dense matrices: what `numpy.load` reads without any
//! other package, at the speed of writing bytes.

use std::path::Path;

use faer::MatRef;

use crate::Result;
use crate::atomic_file::write_atomically;

/// Writes `a` as a little-endian `float64` `.npy` array of shape `(rows, cols)`, Fortran
/// (column-major) order, atomically (see [`write_atomically`]).
pub fn write_npy(path: &Path, a: MatRef<'_, f64>) -> Result<()> {
    write_atomically(path, |w| {
        w.write_all(&npy_header(a.nrows(), a.ncols()))?;
        let mut bytes = Vec::with_capacity(8 * a.nrows());
        for j in 0..a.ncols() {
            bytes.clear();
            for i in 0..a.nrows() {
                bytes.extend_from_slice(&a[(i, j)].to_le_bytes());
            }
            w.write_all(&bytes)?;
        }
        Ok(())
    })
}

/// The magic string, version 1.0, the header length and the header dictionary, padded with
/// spaces and a newline so the data starts at a multiple of 64 bytes.
pub fn npy_header(rows: usize, cols: usize) -> Vec<u8> {
    let dict = format!("{{'descr': '<f8', 'fortran_order': True, 'shape': ({rows}, {cols}), }}");
    let unpadded = 10 + dict.len() + 1;
    let total = unpadded.div_ceil(64) * 64;
    let mut header = Vec::with_capacity(total);
    header.extend_from_slice(b"\x93NUMPY\x01\x00");
    let len = u16::try_from(total - 10).expect("an npy header under 64 KiB");
    header.extend_from_slice(&len.to_le_bytes());
    header.extend_from_slice(dict.as_bytes());
    header.resize(total - 1, b' ');
    header.push(b'\n');
    header
}

/// Reads what [`write_npy`] writes: `(rows, cols, column-major values)`, or `None` when the
/// bytes are not a Fortran-order little-endian `float64` 2-D array of that layout.
pub fn read_npy(bytes: &[u8]) -> Option<(usize, usize, Vec<f64>)> {
    if bytes.len() < 10 || &bytes[..8] != b"\x93NUMPY\x01\x00" {
        return None;
    }
    let len = u16::from_le_bytes([bytes[8], bytes[9]]) as usize;
    let dict = std::str::from_utf8(bytes.get(10..10 + len)?).ok()?;
    if !dict.contains("'descr': '<f8'") || !dict.contains("'fortran_order': True") {
        return None;
    }
    let shape = dict.split("'shape': (").nth(1)?.split(')').next()?;
    let mut dims = shape.split(',').map(|s| s.trim()).filter(|s| !s.is_empty());
    let rows: usize = dims.next()?.parse().ok()?;
    let cols: usize = dims.next()?.parse().ok()?;
    let data = &bytes[10 + len..];
    if Some(data.len()) != rows.checked_mul(cols).and_then(|n| n.checked_mul(8)) {
        return None;
    }
    let values = data
        .chunks_exact(8)
        .map(|c| f64::from_le_bytes(c.try_into().expect("chunks of 8")))
        .collect();
    Some((rows, cols, values))
}
