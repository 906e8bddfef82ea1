//! Mode pairing by the modal assurance criterion and the relative frequency error
//! (Witteveen Eqs. 42–43).

use faer::{Mat, MatRef};

/// A MAC below this marks a reduced mode as inaccurate (Witteveen, p. 319).
pub const MAC_ACCURATE: f64 = 0.95;

/// $\beta = (\varphi^T\tilde\varphi)^2 / ((\varphi^T\varphi)(\tilde\varphi^T\tilde\varphi))$
/// (Eq. 43): 1 for parallel shapes, 0 for orthogonal ones; 0 when either is zero.
pub fn mac(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len(), "MAC of shapes of different lengths");
    let ab: f64 = a.iter().zip(b).map(|(x, y)| x * y).sum();
    let aa: f64 = a.iter().map(|x| x * x).sum();
    let bb: f64 = b.iter().map(|x| x * x).sum();
    if aa == 0.0 || bb == 0.0 {
        return 0.0;
    }
    ab * ab / (aa * bb)
}

/// MAC of every column of `full` against every column of `reduced` (same rows).
pub fn mac_matrix(full: MatRef<'_, f64>, reduced: MatRef<'_, f64>) -> Mat<f64> {
    assert_eq!(
        full.nrows(),
        reduced.nrows(),
        "MAC of shapes of different lengths"
    );
    let col =
        |m: MatRef<'_, f64>, j: usize| -> Vec<f64> { (0..m.nrows()).map(|i| m[(i, j)]).collect() };
    Mat::from_fn(full.ncols(), reduced.ncols(), |i, j| {
        mac(&col(full, i), &col(reduced, j))
    })
}

/// A full-model mode and the reduced mode most like it.
#[derive(Debug, Clone, PartialEq)]
pub struct ModePair {
    /// Index of the full model's mode.
    pub full: usize,
    /// Index of the reduced model's mode with the largest MAC against it.
    pub reduced: usize,
    /// Frequencies, Hz.
    pub full_hz: f64,
    /// Frequency of the paired reduced mode, Hz.
    pub reduced_hz: f64,
    /// $(\tilde f - f)/f$ (Eq. 42, signed: a Ritz model errs upwards).
    pub frequency_error: f64,
    /// The MAC of the pair.
    pub mac: f64,
}

impl ModePair {
    /// Whether the pair passes the MAC threshold 0.95.
    pub fn accurate(&self) -> bool {
        self.mac >= MAC_ACCURATE
    }
}

/// Pairs each full mode listed in `full_modes` with the reduced mode of largest MAC (ties to
/// the lower index). Pairing by best MAC instead of by mode number keeps one missing or extra
/// reduced mode from shifting every later pair; a full mode the reduced basis cannot
/// represent shows as a small MAC.
pub fn pair_modes(
    full_shapes: MatRef<'_, f64>,
    full_hz: &[f64],
    full_modes: &[usize],
    reduced_shapes: MatRef<'_, f64>,
    reduced_hz: &[f64],
) -> Vec<ModePair> {
    let macs = mac_matrix(full_shapes, reduced_shapes);
    full_modes
        .iter()
        .map(|&i| {
            let j = (0..reduced_hz.len())
                .fold(None, |best: Option<usize>, j| match best {
                    Some(b) if macs[(i, b)] >= macs[(i, j)] => Some(b),
                    _ => Some(j),
                })
                .unwrap_or(0);
            let (f, g) = (full_hz[i], reduced_hz.get(j).copied().unwrap_or(f64::NAN));
            ModePair {
                full: i,
                reduced: j,
                full_hz: f,
                reduced_hz: g,
                frequency_error: (g - f) / f,
                mac: if reduced_hz.is_empty() {
                    0.0
                } else {
                    macs[(i, j)]
                },
            }
        })
        .collect()
}
