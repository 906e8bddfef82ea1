//! A Nastran OUTPUT4 matrix as its binary and ASCII readers build it
//! ([`parse_op4`](super::parse_op4)).

use std::collections::BTreeSet;

use super::{MatrixMarket, MatrixMarketFormat};
use crate::error::MatrixLineProblem;

/// A matrix being read: its size and the entries so far (0-based).
pub(super) struct Matrix {
    pub(super) rows: usize,
    pub(super) cols: usize,
    pub(super) entries: Vec<(usize, usize, f64)>,
}

impl Matrix {
    pub(super) fn into_market(self) -> MatrixMarket {
        MatrixMarket {
            rows: self.rows,
            cols: self.cols,
            format: MatrixMarketFormat::Coordinate,
            // OP4 stores every column whole, a symmetric form (6) too.
            symmetric: false,
            entries: self.entries,
        }
    }
}

/// Checks a matrix's NTYPE: the 4-byte words per value (1 single, 2 double precision).
pub(super) fn words_per_value(ntype: i64) -> std::result::Result<usize, MatrixLineProblem> {
    let needs = match ntype {
        1 => return Ok(1),
        2 => return Ok(2),
        3 | 4 => "a complex matrix: a body's matrices are real (NTYPE 1 or 2)",
        _ => "NTYPE is 1 or 2 (real), 3 or 4 (complex)",
    };
    Err(MatrixLineProblem::Unsupported {
        field: "NTYPE",
        value: ntype.to_string().into(),
        needs,
    })
}

/// The wanted matrix, or the names of the matrices the file holds.
pub(super) type Found = std::result::Result<Matrix, BTreeSet<String>>;
