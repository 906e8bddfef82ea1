//! Dynamic (geometric, stress) stiffening of a body on a driven frame: the stiffness its own
//! inertia loads add through the stresses they cause (Lin's thesis §1, the effect its
//! refs. [16] Kane, Ryan & Banerjee 1987 and [18] Zhang & Huston 1996 show the linear
//! floating-frame models to miss).
//!
//! The frame's motion loads the body with inertia forces linear in a few coefficients: on a
//! frame turning about a fixed axis, $\dot\theta^2$ (centrifugal, $-\dot\theta^2 Hs$),
//! $\ddot\theta$ (tangential, $-\ddot\theta Gs$) and the three components of gravity less
//! the origin's acceleration in frame axes ($M(1\otimes g_b)$). Each unit load case $i$,
//! solved statically with the body held where the frame holds it, gives element stresses
//! $\sigma_i$ and from them a geometric stiffness $K_{\sigma,i}$ (the second variation of the
//! Green–Lagrange strain energy at those stresses). The stresses are linear in the loads,
//! so at any instant
//! $$K_\sigma(t) = \dot\theta^2 K_{\sigma,1} + \ddot\theta K_{\sigma,2} + \sum_a g_{b,a}
//! K_{\sigma,2+a},$$
//! added to the linear equations' stiffness $K + \ddot\theta G + \dot\theta^2 H$. Kept: the
//! first-order (quasi-static) prestress of those loads, as Kane et al.'s and Wallrapp and
//! Wiedemann's (2002) modal stiffening; left out: the prestress of the elastic coordinates'
//! own accelerations and of the Coriolis forces, second order in the deformation. A reduced
//! body carries $\Psi^T K_{\sigma,i}\Psi$, projected once: the online cost is one product per
//! nonzero coefficient, whatever the mesh.

use nalgebra::{DMatrix, DVector, Vector3};

use super::DynamicsError;
use crate::Result;

/// Unit load cases: $\dot\theta^2$, $\ddot\theta$, $g_x$, $g_y$, $g_z$.
pub const STIFFENING_CASES: usize = 5;

/// The cases' names, in their order.
pub const STIFFENING_CASE_NAMES: [&str; STIFFENING_CASES] =
    ["rate²", "angular acceleration", "g_x", "g_y", "g_z"];

/// The geometric stiffness of each unit frame load a body carries (`None`: the case loads
/// nothing that stresses it, or the body does not model it).
#[derive(Debug, Clone, PartialEq)]
pub struct FrameStiffening {
    dim: usize,
    cases: [Option<DMatrix<f64>>; STIFFENING_CASES],
}

/// The coefficients of the unit cases at a frame state: $(\dot\theta^2, \ddot\theta, g_b)$.
pub fn stiffening_coefficients(
    rate: f64,
    acceleration: f64,
    g_body: Vector3<f64>,
) -> [f64; STIFFENING_CASES] {
    [rate * rate, acceleration, g_body.x, g_body.y, g_body.z]
}

impl FrameStiffening {
    /// The body's unit geometric stiffnesses ($n \times n$ each, symmetric to $10^{-12}$ of
    /// their largest entry), checked: a matrix of another shape or unsymmetric, or no case at
    /// all, is [`DynamicsError::GeometricStiffnessInvalid`].
    pub fn new(cases: [Option<DMatrix<f64>>; STIFFENING_CASES]) -> Result<Self> {
        let none = DynamicsError::GeometricStiffnessInvalid {
            case: None,
            rows: 0,
            cols: 0,
            dim: 0,
            defect: 0.0,
        };
        let dim = cases
            .iter()
            .flatten()
            .map(|c| c.nrows())
            .next()
            .ok_or(none)?;
        for (c, name) in cases.iter().zip(STIFFENING_CASE_NAMES) {
            let Some(c) = c else { continue };
            let square = c.shape() == (dim, dim);
            let defect = if square {
                (c - c.transpose()).amax() / c.amax().max(f64::MIN_POSITIVE)
            } else {
                f64::NAN
            };
            if !(square && defect <= 1e-12) {
                return Err(DynamicsError::GeometricStiffnessInvalid {
                    case: Some(name),
                    rows: c.nrows(),
                    cols: c.ncols(),
                    dim,
                    defect,
                }
                .into());
            }
        }
        Ok(Self { dim, cases })
    }

    /// Coordinates.
    pub fn dim(&self) -> usize {
        self.dim
    }

    /// Case `i`'s matrix.
    pub fn case(&self, i: usize) -> Option<&DMatrix<f64>> {
        self.cases.get(i)?.as_ref()
    }

    /// The same cases but `i` (set to none).
    pub fn without_case(&self, i: usize) -> Self {
        let mut cases = self.cases.clone();
        if let Some(c) = cases.get_mut(i) {
            *c = None;
        }
        Self {
            dim: self.dim,
            cases,
        }
    }

    /// $\Psi^T K_{\sigma,i}\Psi$ for every case.
    pub fn projected(&self, psi: &DMatrix<f64>) -> Self {
        let cases = self.cases.clone().map(|c| {
            c.map(|k| {
                let r = psi.transpose() * k * psi;
                (&r + r.transpose()) * 0.5
            })
        });
        Self {
            dim: psi.ncols(),
            cases,
        }
    }

    /// $y \mathrel{+}= \sum_i c_i K_{\sigma,i}\,x$ (a product per nonzero coefficient).
    pub fn add_mul(&self, c: &[f64; STIFFENING_CASES], x: &DVector<f64>, y: &mut DVector<f64>) {
        for (ci, k) in c.iter().zip(&self.cases) {
            if let (true, Some(k)) = (*ci != 0.0, k) {
                y.gemv(*ci, k, x, 1.0);
            }
        }
    }

    /// $A \mathrel{+}= \sum_i c_i K_{\sigma,i}$.
    pub fn add_to(&self, c: &[f64; STIFFENING_CASES], a: &mut DMatrix<f64>) {
        for (ci, k) in c.iter().zip(&self.cases) {
            if let (true, Some(k)) = (*ci != 0.0, k) {
                *a += k * *ci;
            }
        }
    }

    /// $K_\sigma$ at a frame state.
    pub fn at(&self, rate: f64, acceleration: f64, g_body: Vector3<f64>) -> DMatrix<f64> {
        let mut a = DMatrix::zeros(self.dim, self.dim);
        self.add_to(&stiffening_coefficients(rate, acceleration, g_body), &mut a);
        a
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A product with the combination equals the combined matrix's; a projection on the
    /// identity changes nothing; an unsymmetric case is refused.
    #[test]
    fn products_combinations_and_projections_agree() {
        for n in [1, 4, 9] {
            let sym = |seed: f64| {
                let a = DMatrix::from_fn(n, n, |i, j| ((i * 7 + j * 3) as f64 * seed).sin());
                (&a + a.transpose()) * 0.5
            };
            let s =
                FrameStiffening::new([Some(sym(0.3)), None, Some(sym(1.1)), None, None]).unwrap();
            let c = stiffening_coefficients(3.0, -2.0, Vector3::new(0.5, 7.0, 1.0));
            let x = DVector::from_fn(n, |i, _| 1.0 + i as f64);
            let mut y = DVector::zeros(n);
            s.add_mul(&c, &x, &mut y);
            let a = s.at(3.0, -2.0, Vector3::new(0.5, 7.0, 1.0));
            assert!((&a * &x - &y).amax() <= 1e-12 * y.amax().max(1.0));
            let expected = sym(0.3) * 9.0 + sym(1.1) * 0.5;
            assert!((a - expected).amax() <= 1e-12);
            let same = s.projected(&DMatrix::identity(n, n));
            assert_eq!(same.dim(), n);
            assert!((same.case(0).unwrap() - s.case(0).unwrap()).amax() <= 1e-14);
            if n > 1 {
                let mut bad = sym(0.3);
                bad[(0, 1)] += 1.0;
                assert!(FrameStiffening::new([None, None, None, None, None]).is_err());
                let refused = FrameStiffening::new([Some(bad), None, None, None, None]);
                assert!(
                    refused
                        .unwrap_err()
                        .to_string()
                        .contains("geometric stiffness of the rate² case"),
                );
            }
        }
    }
}
