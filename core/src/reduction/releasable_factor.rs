//! The factor a shift-invert partial eigensolve runs on, held only while it is needed.
//!
//! A partial solve is followed by a Sturm count ([`crate::linalg::sturm_count`]), which forms
//! an $LDL^T$ factor of $K - \sigma' M$ on the same pattern: as many entries as the
//! $LL^T$ factor of $K - \sigma M$ the solve ran on. Held together they double the peak: on
//! the 512 250-DOF corpus link 19.4 GB, where SciPy's CHOLMOD route holds 9.0 GB. A large
//! factor is therefore released before the count and made again only when something needs it
//! after (a retry of the solve with more pairs, a second partial solve for more modes).

use std::time::Instant;

use crate::linalg::{Result, SymmetricFactor};

/// Bytes of factor values above which [`ReleasableFactor`] releases its factor before a Sturm
/// count (256 MiB, 32 M entries: a body of roughly 60–100 k DOF). A smaller factor is kept: it
/// costs little memory, and remaking it would cost more than holding it.
pub const RELEASED_FACTOR_BYTES: usize = 256 << 20;

/// A factor of $K - \sigma M$ and the means to make it again.
pub struct ReleasableFactor<'a> {
    held: Option<SymmetricFactor>,
    remake: Box<dyn Fn() -> Result<SymmetricFactor> + 'a>,
    /// Factorisations made again after a release.
    pub remade: usize,
    /// Their wall time, s.
    pub remake_s: f64,
    /// Bytes released before a Sturm count (the largest such factor).
    pub released_bytes: usize,
    /// Factors of more bytes than this are released ([`RELEASED_FACTOR_BYTES`]).
    limit: usize,
}

impl<'a> ReleasableFactor<'a> {
    /// `factor`, held, with `remake` to form it again once released.
    pub fn new(factor: SymmetricFactor, remake: impl Fn() -> Result<SymmetricFactor> + 'a) -> Self {
        Self {
            held: Some(factor),
            remake: Box::new(remake),
            remade: 0,
            remake_s: 0.0,
            released_bytes: 0,
            limit: RELEASED_FACTOR_BYTES,
        }
    }

    /// Releases factors of more than `bytes` instead of [`RELEASED_FACTOR_BYTES`] (0: every
    /// factor, as the tests of the release use).
    #[cfg(test)]
    pub fn with_limit(mut self, bytes: usize) -> Self {
        self.limit = bytes;
        self
    }

    /// The factor, made again when it was released.
    pub fn get(&mut self) -> Result<&SymmetricFactor> {
        if self.held.is_none() {
            let started = Instant::now();
            let factor = (self.remake)()?;
            self.remake_s += started.elapsed().as_secs_f64();
            self.remade += 1;
            self.held = Some(factor);
        }
        Ok(self.held.as_ref().expect("held above"))
    }

    /// Drops the factor when it holds more than the limit ([`RELEASED_FACTOR_BYTES`] unless
    /// set), before a factorisation of the same size (the Sturm count's); a smaller one stays.
    pub fn release_if_large(&mut self) {
        if let Some(f) = &self.held
            && f.factor_bytes() > self.limit
        {
            self.released_bytes = self.released_bytes.max(f.factor_bytes());
            self.held = None;
        }
    }

    /// The factor if it is still held.
    pub fn into_held(self) -> Option<SymmetricFactor> {
        self.held
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::linalg::{
        MassMatrix, PartialEigenParameters, SparseSymmetric, SymbolicFactor, generalized_eigen,
    };
    use crate::reduction::free_body_solver::{FreeBodyParameters, SturmPencil, sturm_checked};

    /// A fixed-free chain of springs and masses with a consistent-like tridiagonal mass.
    fn chain(n: usize) -> (SparseSymmetric, MassMatrix) {
        let mut k = Vec::new();
        let mut m = Vec::new();
        for i in 0..n {
            k.push((i, i, 2.0 + 0.01 * i as f64));
            m.push((i, i, 4.0));
            if i + 1 < n {
                k.extend([(i, i + 1, -1.0), (i + 1, i, -1.0)]);
                m.extend([(i, i + 1, 1.0), (i + 1, i, 1.0)]);
            }
        }
        (
            SparseSymmetric::from_triplets(n, &k),
            MassMatrix::Consistent(SparseSymmetric::from_triplets(n, &m)),
        )
    }

    #[test]
    fn a_released_factor_gives_the_same_checked_pairs_and_is_made_again_on_demand() {
        for n in [60, 240] {
            let (k, m) = chain(n);
            let shifted = k.shifted(&m, 0.0);
            let symbolic = SymbolicFactor::analyse(shifted.as_faer()).unwrap();
            let make = || SymmetricFactor::sparse(k.shifted(&m, 0.0).as_faer(), &symbolic, "K");
            let all =
                generalized_eigen(k.to_dense().as_ref(), m.to_dense().as_ref(), "chain").unwrap();
            let null = faer::Mat::<f64>::zeros(n, 0);
            let mut results = Vec::new();
            for limit in [usize::MAX, 0] {
                let mut factor = ReleasableFactor::new(make().unwrap(), make).with_limit(limit);
                let (eigen, _) = sturm_checked(
                    SturmPencil {
                        k: &k,
                        m: &m,
                        symbolic: &symbolic,
                    },
                    &mut factor,
                    0.0,
                    8,
                    null.as_ref(),
                    &PartialEigenParameters::default(),
                    FreeBodyParameters::default().sturm_retries,
                )
                .unwrap();
                assert_eq!(eigen.sturm.map(|c| c.missed()), Some(0));
                for (a, b) in eigen.values.iter().zip(&all.values) {
                    assert!((a - b).abs() <= 1e-10 * b, "{a} against {b} (n = {n})");
                }
                // Kept under the limit; released above it, and made again only when asked.
                let expected_bytes = make().unwrap().factor_bytes();
                if limit == 0 {
                    assert_eq!(factor.released_bytes, expected_bytes);
                    assert_eq!(factor.remade, 0);
                    factor.get().unwrap();
                    assert_eq!(factor.remade, 1);
                } else {
                    assert_eq!((factor.released_bytes, factor.remade), (0, 0));
                    assert!(factor.into_held().is_some());
                }
                results.push(eigen.values);
            }
            assert_eq!(
                results[0], results[1],
                "the release changes no pair (n = {n})"
            );
        }
    }
}
