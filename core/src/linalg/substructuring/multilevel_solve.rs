//! The block factor of [`MultilevelSubstructures`] applied: the expansion of projected vectors
//! to the body and $K_\sigma^{-1}$.

use faer::{Mat, MatMut, MatRef, linalg::solvers::Solve};

use super::MultilevelSubstructures;
use super::multilevel_substructures::Front;
use super::substructure_front::product;
use crate::linalg::threads::par_for_flops;

impl MultilevelSubstructures {
    /// $x = T y$: the body's vectors of projected coordinates `y` (`modes()` rows), each
    /// node's $x_P = \Psi y_P + \Phi x_B$ from the root down.
    pub fn expand(&self, y: MatRef<'_, f64>) -> Mat<f64> {
        assert_eq!(y.nrows(), self.modes(), "projected coordinates");
        let s = y.ncols();
        let mut x = Mat::<f64>::zeros(self.dim, s);
        for front in self.fronts.iter().rev() {
            let p = front.unknowns.len();
            let mut x_p = Mat::<f64>::zeros(p, s);
            let kept = front.modes.ncols();
            if kept > 0 {
                product(
                    x_p.as_mut(),
                    front.modes.as_ref(),
                    y.subrows(front.first_mode, kept),
                    par_for_flops((p * kept * s) as f64),
                );
            }
            self.add_static(front, &mut x_p, &x);
            for (i, &u) in front.unknowns.iter().enumerate() {
                for c in 0..s {
                    x[(u, c)] = x_p[(i, c)];
                }
            }
        }
        x
    }

    /// $x_P \mathrel{+}= \Phi x_B$ with $x_B$ read from `x`.
    fn add_static(&self, front: &Front, x_p: &mut Mat<f64>, x: &Mat<f64>) {
        let q = front.boundary.len();
        if q == 0 {
            return;
        }
        let s = x.ncols();
        let x_b = Mat::from_fn(q, s, |i, c| x[(front.boundary[i], c)]);
        let par = par_for_flops((front.phi.nrows() * q * s) as f64);
        product(x_p.as_mut(), front.phi.as_ref(), x_b.as_ref(), par);
    }

    /// $B \leftarrow K_\sigma^{-1}B$ by the block factor: the tree's nodes up (each node's
    /// right-hand side solved by its $K_{PP}$, $\Phi^T b_P$ added to its ancestors'), then
    /// down ($x_P = K_{PP}^{-1}b_P + \Phi x_B$).
    pub fn solve_in_place(&self, mut b: MatMut<'_, f64>) {
        assert_eq!(b.nrows(), self.dim, "right-hand sides");
        let s = b.ncols();
        let mut solved: Vec<Mat<f64>> = Vec::with_capacity(self.fronts.len());
        for front in &self.fronts {
            let p = front.unknowns.len();
            let b_p = Mat::from_fn(p, s, |i, c| b[(front.unknowns[i], c)]);
            let q = front.boundary.len();
            if q > 0 {
                let mut up = Mat::<f64>::zeros(q, s);
                let par = par_for_flops((p * q * s) as f64);
                product(up.as_mut(), front.phi.transpose(), b_p.as_ref(), par);
                for (i, &v) in front.boundary.iter().enumerate() {
                    for c in 0..s {
                        b[(v, c)] += up[(i, c)];
                    }
                }
            }
            let mut z = b_p;
            front.factor.solve_in_place(z.as_mut());
            solved.push(z);
        }
        for (front, z) in self.fronts.iter().zip(solved).rev() {
            let mut x_p = z;
            let q = front.boundary.len();
            if q > 0 {
                let x_b = Mat::from_fn(q, s, |i, c| b[(front.boundary[i], c)]);
                let par = par_for_flops((front.unknowns.len() * q * s) as f64);
                product(x_p.as_mut(), front.phi.as_ref(), x_b.as_ref(), par);
            }
            for (i, &u) in front.unknowns.iter().enumerate() {
                for c in 0..s {
                    b[(u, c)] = x_p[(i, c)];
                }
            }
        }
    }
}
