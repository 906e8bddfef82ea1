//! A reduced body on a driven frame (or a small full one such as a beam), dense: every
//! operator projected on Ψ, the geometric stiffnesses of the frame's loads among them
//! ([`super::DrivenFrameBody`] holds it).

use nalgebra::{DMatrix, DVector};

use super::{combination::Combination, frame_stiffening::FrameStiffening};

/// A reduced body, or a small full one, dense: every operator projected on Ψ.
#[derive(Debug, Clone)]
pub struct DenseDriven {
    pub(super) m: DMatrix<f64>,
    pub(super) k: DMatrix<f64>,
    pub(super) g: DMatrix<f64>,
    pub(super) h: DMatrix<f64>,
    /// The geometric stiffnesses of the unit frame loads, if the body has them.
    pub(super) stiffening: Option<FrameStiffening>,
    /// With stiffening: $H + K_{\sigma,1}$ (both scale with $\dot\theta^2$, so the
    /// integrators' combinations take them as one matrix), and the other cases.
    pub(super) folded: Option<(DMatrix<f64>, FrameStiffening)>,
}

impl DenseDriven {
    pub(super) fn new(
        m: DMatrix<f64>,
        k: DMatrix<f64>,
        g: DMatrix<f64>,
        h: DMatrix<f64>,
        stiffening: Option<FrameStiffening>,
    ) -> Self {
        let folded = stiffening.as_ref().and_then(|s| {
            let rate_squared = s.case(0)?;
            Some((&h + rate_squared, s.without_case(0)))
        });
        Self {
            m,
            k,
            g,
            h,
            stiffening,
            folded,
        }
    }

    /// The matrix that goes with $c_h$ and the stiffening cases still to add: $H +
    /// K_{\sigma,1}$ when the combination scales $K_{\sigma,1}$ as it scales $H$ (the
    /// integrators' always do), else $H$ and every case.
    pub(super) fn centrifugal(&self, c: &Combination) -> (&DMatrix<f64>, Option<&FrameStiffening>) {
        match &self.folded {
            Some((h_sigma, rest)) if c.sigma[0] == c.h => (h_sigma, Some(rest)),
            _ => (&self.h, self.stiffening.as_ref()),
        }
    }

    /// $(c_m M + c_k K + c_g G + c_h H + \sum c_{\sigma,i}K_{\sigma,i})\,x$ by one product
    /// per nonzero coefficient (no combined matrix per call: the integrators apply it several
    /// times a step).
    pub(super) fn mul(&self, c: Combination, x: &[f64]) -> Vec<f64> {
        let x = DVector::from_column_slice(x);
        let mut y = DVector::zeros(x.len());
        let (h, rest) = self.centrifugal(&c);
        for (coefficient, matrix) in [(c.m, &self.m), (c.k, &self.k), (c.g, &self.g), (c.h, h)] {
            if coefficient != 0.0 {
                y.gemv(coefficient, matrix, &x, 1.0);
            }
        }
        if let Some(s) = rest {
            s.add_mul(&c.sigma, &x, &mut y);
        }
        y.as_slice().to_vec()
    }

    pub(super) fn combine(&self, c: Combination) -> DMatrix<f64> {
        let (h, rest) = self.centrifugal(&c);
        let mut a = &self.m * c.m + &self.k * c.k + &self.g * c.g + h * c.h;
        if let Some(s) = rest {
            s.add_to(&c.sigma, &mut a);
        }
        a
    }
}
