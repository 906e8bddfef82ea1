//! A linear elastic body on a frame driven about a fixed axis through the frame's origin: the
//! driven interface's master, its ring clamped in the frame (nodal-fixed axes, Table 4-1,
//! at an interface instead of a node).
//!
//! With the frame turning by $\theta(t)$ about the unit axis $e$, the nodal displacements $u$
//! in the frame and a mass matrix that is the same on each direction of a node,
//! $M = M_s \otimes I_3$ (lumped, or consistent from one scalar shape function per node), the
//! kinetic energy $\tfrac12 (\dot u + \dot\theta\,E(s+u))^T M (\dot u + \dot\theta\,E(s+u))$
//! ($E = I \otimes \tilde e$, $s$ the undeformed positions about the origin; Eq. 3.14 with
//! the frame's motion given) gives Lagrange's equations
//! $$M\ddot u + 2\dot\theta\,G\dot u + (K + \ddot\theta\,G + \dot\theta^2 H)u
//! = -\ddot\theta\,Gs - \dot\theta^2 Hs + M(1 \otimes A^T g),$$
//! with $G = ME$ (skew: $M$ commutes with $E$) and $H = ME^2$ (symmetric), all restricted to
//! the DOF outside the clamped ring, and $A$ the frame's orientation (gravity $g$ turns in the
//! frame). They are exact for small strains in the frame, as the floating-frame equations
//! are; they are linear with time-varying coefficients.
//!
//! The same equations hold in reduced coordinates $u = \Psi z$ with each operator projected,
//! $\Psi^T X \Psi$. [`DrivenFrameBody`] holds either: the full body sparse (no reduction,
//! NR) or a reduced body dense.

use super::DynamicsError;
use faer::MatRef;
use nalgebra::{DMatrix, DVector, Unit, Vector3};

use super::combination::Combination;
use super::dense_driven::DenseDriven;
use super::frame_coordinates::{FrameCoordinates, PinnedRing};
use super::frame_stiffening::FrameStiffening;
use super::sparse_driven::{SparseDriven, check_isotropic, mul_mass};
use crate::{
    Error, Result,
    error::LinalgError,
    fem::FeModel,
    linalg::{
        GmresParameters, GmresStatistics, MassMatrix, SparseSymmetric, SymbolicFactor,
        preconditioned_gmres,
    },
};

/// Backward error every solve of the effective matrix meets,
/// $\|b - Ax\| \le \tau(\|b\| + \||A||x|\|)$.
pub const DRIVEN_SOLVE_TOLERANCE: f64 = 1e-11;

/// The equations' operators.
#[derive(Debug)]
enum Operators {
    Sparse(Box<SparseDriven>),
    Dense(Box<DenseDriven>),
}

/// A body on a driven frame (see the module documentation): its operators and load vectors
/// in its own coordinates (the free DOF, or the modal coordinates of a reduced body).
#[derive(Debug)]
pub struct DrivenFrameBody {
    operators: Operators,
    /// $Gs$ and $Hs$.
    g_s: Vec<f64>,
    h_s: Vec<f64>,
    /// $M(1 \otimes e_a)$ for a = x, y, z: the load of a unit acceleration of gravity.
    unit_gravity: [Vec<f64>; 3],
}

/// A driven body's dense operators in its own coordinates ([`DrivenFrameBody::dense`]), each
/// $n \times n$ or of length $n$.
#[derive(Debug, Clone)]
pub struct DenseDrivenOperators {
    /// Mass $M$.
    pub m: DMatrix<f64>,
    /// Stiffness $K$.
    pub k: DMatrix<f64>,
    /// The gyroscopic coupling $G$ (skew).
    pub g: DMatrix<f64>,
    /// The centrifugal softening $H$ (symmetric).
    pub h: DMatrix<f64>,
    /// The load $Gs$ of the body's own positions $s$.
    pub g_s: Vec<f64>,
    /// The load $Hs$.
    pub h_s: Vec<f64>,
    /// $M(1\otimes e_a)$: the loads of a unit acceleration of the frame along each axis.
    pub unit_gravity: [Vec<f64>; 3],
    /// The geometric stiffnesses of the unit frame loads, if the body has them.
    pub stiffening: Option<FrameStiffening>,
}

impl DrivenFrameBody {
    /// The full body of `model` with the DOF of `ring` (0-based DOF indices) clamped and the
    /// `pins` pinned, on a frame with its origin at `origin` (model coordinates) turning about
    /// `axis`.
    pub fn full(
        model: &FeModel,
        ring: &[usize],
        pins: Vec<PinnedRing>,
        origin: [f64; 3],
        axis: Unit<Vector3<f64>>,
    ) -> Result<Self> {
        check_isotropic(model)?;
        let n = model.dof_count();
        let coords = FrameCoordinates::new(n, ring, pins)?;
        let k_ff = coords.project(&model.k);
        let m_ff = coords.project_mass(&model.m);
        // The pattern of K + cM, the union of K's and M's (an FE code's M may hold entries
        // where its K holds none).
        let symbolic = SymbolicFactor::analyse(k_ff.shifted(&m_ff, -1.0).as_faer())?;
        let s = positions(model, origin);
        let sparse = SparseDriven {
            coords,
            k_ff,
            m: model.m.clone(),
            m_ff,
            axis: axis.into_inner(),
            symbolic,
            centrifugal: None,
            factor: None,
        };
        let g_s = sparse.frame_full(&s, false);
        let h_s = sparse.frame_full(&s, true);
        let unit_gravity = std::array::from_fn(|a| {
            let mut t = vec![0.0; n];
            t.iter_mut().skip(a).step_by(3).for_each(|x| *x = 1.0);
            sparse.restrict(&mul_mass(&sparse.m, &t))
        });
        Ok(Self {
            operators: Operators::Sparse(Box::new(sparse)),
            g_s,
            h_s,
            unit_gravity,
        })
    }

    /// A body given by its dense operators in its own coordinates (a small full body such
    /// as a beam, or a reduced one); refused unless they share one size.
    pub fn dense(operators: DenseDrivenOperators) -> Result<Self> {
        let DenseDrivenOperators {
            m,
            k,
            g,
            h,
            g_s,
            h_s,
            unit_gravity,
            stiffening,
        } = operators;
        let n = m.nrows();
        let square = [&m, &k, &g, &h].iter().all(|a| a.shape() == (n, n));
        let loads = [
            &g_s,
            &h_s,
            &unit_gravity[0],
            &unit_gravity[1],
            &unit_gravity[2],
        ]
        .iter()
        .all(|v| v.len() == n);
        if !(square && loads && stiffening.as_ref().is_none_or(|s| s.dim() == n)) {
            return Err(DynamicsError::Misuse {
                what: "a dense driven body's operators and loads share one size",
            }
            .into());
        }
        Ok(Self {
            operators: Operators::Dense(Box::new(DenseDriven::new(m, k, g, h, stiffening))),
            g_s,
            h_s,
            unit_gravity,
        })
    }

    /// Whether the body carries geometric stiffnesses of the frame's loads.
    pub fn has_stiffening(&self) -> bool {
        match &self.operators {
            Operators::Dense(d) => d.stiffening.is_some(),
            Operators::Sparse(s) => s.centrifugal.is_some(),
        }
    }

    /// Gives the full (sparse) body the geometric stiffness of the centrifugal load per unit
    /// rate², `k` on every DOF of the body (a preloaded stiffness, held DOF zero): its
    /// coefficient is $\dot\theta^2$; reduced bodies project it.
    pub fn set_centrifugal_stiffening(&mut self, k: &SparseSymmetric) -> Result<()> {
        let Operators::Sparse(s) = &mut self.operators else {
            return Err(DynamicsError::Misuse {
                what: "a preloaded stiffness is set on the full body",
            }
            .into());
        };
        if k.dim() != s.coords.dofs() {
            return Err(DynamicsError::Misuse {
                what: "a preloaded stiffness has a row per DOF of the body",
            }
            .into());
        }
        s.centrifugal = Some(s.coords.project(k));
        Ok(())
    }

    /// A copy of a dense body, with its geometric stiffnesses or without them (`false`: the
    /// linear floating-frame model of the thesis, whose spinning frequencies fall with the
    /// rate).
    pub fn dense_copy(&self, stiffening: bool) -> Result<Self> {
        let Operators::Dense(d) = &self.operators else {
            return Err(DynamicsError::Misuse {
                what: "only a dense driven body carries geometric stiffnesses",
            }
            .into());
        };
        Ok(Self {
            operators: Operators::Dense(Box::new(DenseDriven::new(
                d.m.clone(),
                d.k.clone(),
                d.g.clone(),
                d.h.clone(),
                if stiffening {
                    d.stiffening.clone()
                } else {
                    None
                },
            ))),
            g_s: self.g_s.clone(),
            h_s: self.h_s.clone(),
            unit_gravity: self.unit_gravity.clone(),
        })
    }

    /// The body reduced by `psi` (rows: the free DOF of `full`, in its order; columns: the
    /// modal coordinates): every operator and load projected, $\Psi^T X \Psi$, $\Psi^T f$,
    /// the geometric stiffnesses of a dense body too.
    pub fn reduced(full: &DrivenFrameBody, psi: MatRef<'_, f64>) -> Result<Self> {
        let sparse = match &full.operators {
            Operators::Sparse(sparse) => sparse,
            Operators::Dense(dense) => return Self::reduced_dense(full, dense, psi),
        };
        let (rows, k) = (psi.nrows(), psi.ncols());
        assert_eq!(rows, sparse.coords.dim(), "Ψ has a row per coordinate");
        let columns: Vec<Vec<f64>> = (0..k)
            .map(|c| (0..rows).map(|i| psi[(i, c)]).collect())
            .collect();
        let project = |c: Combination| {
            let images: Vec<Vec<f64>> = columns.iter().map(|x| sparse.mul(c, x)).collect();
            let mut out = DMatrix::zeros(k, k);
            for (i, xi) in columns.iter().enumerate() {
                for (j, yj) in images.iter().enumerate() {
                    out[(i, j)] = xi.iter().zip(yj).map(|(a, b)| a * b).sum();
                }
            }
            out
        };
        let one = |m, kk, g, h| Combination {
            m,
            k: kk,
            g,
            h,
            ..Default::default()
        };
        let mut m = project(one(1.0, 0.0, 0.0, 0.0));
        let mut kk = project(one(0.0, 1.0, 0.0, 0.0));
        let mut h = project(one(0.0, 0.0, 0.0, 1.0));
        let mut g = project(one(0.0, 0.0, 1.0, 0.0));
        // Exact symmetry (M, K, H) and skew symmetry (G), as the operators have.
        for mat in [&mut m, &mut kk, &mut h] {
            *mat = (&*mat + mat.transpose()) * 0.5;
        }
        g = (&g - g.transpose()) * 0.5;
        let stiffening = if sparse.centrifugal.is_some() {
            let mut c = Combination::default();
            c.sigma[0] = 1.0;
            let kg = project(c);
            Some(FrameStiffening::new([
                Some((&kg + kg.transpose()) * 0.5),
                None,
                None,
                None,
                None,
            ])?)
        } else {
            None
        };
        let project_vector =
            |v: &[f64]| -> Vec<f64> { columns.iter().map(|x| dot(x, v)).collect() };
        Ok(Self {
            operators: Operators::Dense(Box::new(DenseDriven::new(m, kk, g, h, stiffening))),
            g_s: project_vector(&full.g_s),
            h_s: project_vector(&full.h_s),
            unit_gravity: std::array::from_fn(|a| project_vector(&full.unit_gravity[a])),
        })
    }

    fn reduced_dense(
        full: &DrivenFrameBody,
        d: &DenseDriven,
        psi: MatRef<'_, f64>,
    ) -> Result<Self> {
        let n = d.m.nrows();
        if psi.nrows() != n {
            return Err(DynamicsError::Misuse {
                what: "Ψ has a row per coordinate of the dense body",
            }
            .into());
        }
        let p = DMatrix::from_fn(n, psi.ncols(), |i, j| psi[(i, j)]);
        let project = |a: &DMatrix<f64>| p.transpose() * a * &p;
        let symmetric = |a: DMatrix<f64>| (&a + a.transpose()) * 0.5;
        let g = project(&d.g);
        let vector = |v: &[f64]| -> Vec<f64> {
            (p.transpose() * DVector::from_column_slice(v))
                .as_slice()
                .to_vec()
        };
        Self::dense(DenseDrivenOperators {
            m: symmetric(project(&d.m)),
            k: symmetric(project(&d.k)),
            g: (&g - g.transpose()) * 0.5,
            h: symmetric(project(&d.h)),
            g_s: vector(&full.g_s),
            h_s: vector(&full.h_s),
            unit_gravity: std::array::from_fn(|a| vector(&full.unit_gravity[a])),
            stiffening: d.stiffening.as_ref().map(|s| s.projected(&p)),
        })
    }

    /// The combination $c_m M + c_k K + c_g G + c_h H + \sum c_{\sigma,i}K_{\sigma,i}$ as a
    /// dense matrix: a dense body's own, a sparse body's formed column by column from its
    /// products (for frequency checks of bodies of a few thousand coordinates at most).
    pub fn dense_matrix(&self, c: Combination) -> faer::Mat<f64> {
        let n = self.dim();
        if let Operators::Dense(d) = &self.operators {
            let a = d.combine(c);
            return faer::Mat::from_fn(n, n, |i, j| a[(i, j)]);
        }
        let mut a = faer::Mat::<f64>::zeros(n, n);
        let mut e = vec![0.0; n];
        for j in 0..n {
            e[j] = 1.0;
            let column = self.mul(c, &e);
            e[j] = 0.0;
            for (i, v) in column.into_iter().enumerate() {
                a[(i, j)] = v;
            }
        }
        a
    }

    /// The sparse pencil of the full body spun steadily at `rate` (rad/s), Coriolis left out:
    /// $K + \Omega^2(H + K_{\sigma,1})$ and $M$ on its coordinates (`None` for a dense body).
    pub fn spun_pencil(&self, rate: f64) -> Option<(SparseSymmetric, &MassMatrix)> {
        match &self.operators {
            Operators::Sparse(s) => Some((s.spun_stiffness(rate), &s.m_ff)),
            Operators::Dense(_) => None,
        }
    }

    /// Coordinates: free DOF or modal coordinates.
    pub fn dim(&self) -> usize {
        self.g_s.len()
    }

    /// $M^{-1}$ of a reduced (dense) body, checked ($\|MM^{-1} - I\|_{\max} \le 10^{-8}$);
    /// the full body is refused.
    pub fn mass_inverse(&self) -> Result<DMatrix<f64>> {
        let Operators::Dense(d) = &self.operators else {
            return Err(DynamicsError::ExplicitFullBody.into());
        };
        let n = d.m.nrows();
        let singular = || {
            Error::Linalg(LinalgError::SingularMatrix {
                matrix: "reduced mass of the driven body".into(),
                rcond: None,
            })
        };
        let inverse = d.m.clone().cholesky().ok_or_else(singular)?.inverse();
        let residual = (&d.m * &inverse - DMatrix::<f64>::identity(n, n)).amax();
        if residual.is_nan() || residual > 1e-8 {
            return Err(singular());
        }
        Ok(inverse)
    }

    /// Entries of the sparse factor of the constant part (the last one made; 0 for a dense
    /// body or before the first solve).
    pub fn factor_nnz(&self) -> usize {
        match &self.operators {
            Operators::Sparse(s) => s.factor.as_ref().map_or(0, |(_, f)| f.factor_nnz()),
            Operators::Dense(_) => 0,
        }
    }

    /// The coordinates of the full body (`None` for a reduced one).
    pub fn coordinates(&self) -> Option<&FrameCoordinates> {
        match &self.operators {
            Operators::Sparse(s) => Some(&s.coords),
            Operators::Dense(_) => None,
        }
    }

    /// $(c_m M + c_k K + c_g G + c_h H)\,x$.
    pub fn mul(&self, c: Combination, x: &[f64]) -> Vec<f64> {
        match &self.operators {
            Operators::Sparse(s) => s.mul(c, x),
            Operators::Dense(d) => d.mul(c, x),
        }
    }

    /// The load $-\ddot\theta Gs - \dot\theta^2 Hs + M(1\otimes g_b)$ for the frame's rate and
    /// acceleration and gravity in frame axes `g_body` (the body's length unit per s²).
    pub fn load(&self, rate: f64, acceleration: f64, g_body: Vector3<f64>) -> Vec<f64> {
        let mut f: Vec<f64> = self
            .g_s
            .iter()
            .zip(&self.h_s)
            .map(|(g, h)| -acceleration * g - rate * rate * h)
            .collect();
        for a in 0..3 {
            if g_body[a] != 0.0 {
                f.iter_mut()
                    .zip(&self.unit_gravity[a])
                    .for_each(|(f, t)| *f += g_body[a] * t);
            }
        }
        f
    }

    /// Solves $(c_m M + c_k K + c_g G + c_h H)\,x = b$ to [`DRIVEN_SOLVE_TOLERANCE`], from
    /// the guess `x0`. Sparse: GMRES preconditioned by the factor of $c_m M + c_k K$, kept
    /// while $c_m, c_k$ stay; dense: LU, checked by its residual. Returns $x$ and the Krylov
    /// iterations it took (0 for a dense body).
    pub fn solve(&mut self, c: Combination, b: &[f64], x0: Vec<f64>) -> Result<(Vec<f64>, usize)> {
        match &mut self.operators {
            Operators::Sparse(s) => {
                s.factor(c.m, c.k)?;
                let s = &**s;
                let (_, f) = s.factor.as_ref().expect("factored above");
                let n = b.len();
                let (x, stats): (Vec<f64>, GmresStatistics) = preconditioned_gmres(
                    "effective matrix of the driven body",
                    |x| s.mul(c, x),
                    |y| {
                        let z = f.solve(MatRef::from_column_major_slice(y, n, 1));
                        (0..n).map(|i| z[(i, 0)] / c.k).collect()
                    },
                    |x| s.abs_norm(c, x),
                    b,
                    x0,
                    GmresParameters {
                        tolerance: DRIVEN_SOLVE_TOLERANCE,
                        max_iterations: 200,
                    },
                )?;
                Ok((x, stats.iterations))
            }
            Operators::Dense(d) => {
                let a = d.combine(c);
                let rhs = DVector::from_column_slice(b);
                let x = a.clone().lu().solve(&rhs).ok_or_else(|| {
                    Error::Linalg(LinalgError::SingularMatrix {
                        matrix: "effective matrix of the reduced driven body".into(),
                        rcond: None,
                    })
                })?;
                let scale = rhs.norm() + (a.abs() * x.abs()).norm();
                let residual = (&a * &x - &rhs).norm() / scale.max(f64::MIN_POSITIVE);
                if residual.is_nan() || residual > DRIVEN_SOLVE_TOLERANCE {
                    return Err(LinalgError::SolveInaccurate {
                        matrix: "effective matrix of the reduced driven body".into(),
                        residual,
                        tolerance: DRIVEN_SOLVE_TOLERANCE,
                    }
                    .into());
                }
                Ok((x.as_slice().to_vec(), 0))
            }
        }
    }
}

fn dot(x: &[f64], y: &[f64]) -> f64 {
    x.iter().zip(y).map(|(a, b)| a * b).sum()
}

/// Node positions about `origin`, node-major (the body's length unit).
pub fn positions(model: &FeModel, origin: [f64; 3]) -> Vec<f64> {
    model
        .nodes
        .iter()
        .flat_map(|p| (0..3).map(move |a| p[a] - origin[a]))
        .collect()
}
