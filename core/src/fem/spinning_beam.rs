//! A slender cantilever on a turning hub (Kane, Ryan & Banerjee 1987; Lin's thesis §1, refs.
//! [16], [18]): planar Euler–Bernoulli elements, axial displacement $u$ linear and
//! transverse displacement $v$ cubic (Hermite) in each element, consistent mass, the root
//! clamped at the hub radius $r$ on the spin axis' normal.
//!
//! The beam lies along the frame's $x$ axis; the frame turns about a unit axis $e$ through
//! the hub's centre, either normal to the beam's plane (**lagwise**: $v$ lies in the plane
//! of rotation, Kane's spin-up) or in the plane, across the beam (**flapwise**: $v$ along
//! the axis). With the displacement field $N(x)\,q$ and positions $s(x) = (r + x, 0)$ in
//! the frame, the operators of the driven frame's equations (as for a solid body: Eq. 3.14
//! with the frame's motion given) are integrated element by element,
//! $$M = \int \rho A\,N^TN, \quad G = \int \rho A\,N^T\tilde e N, \quad
//! H = \int \rho A\,N^T\tilde e^2 N, \quad Gs = \int \rho A\,N^T \tilde e s, \quad
//! Hs = \int \rho A\,N^T\tilde e^2 s,$$
//! and the geometric stiffness of an axial force $N_e$ in each element, from the quadratic
//! part of the Green–Lagrange strain $\tfrac12(u'^2 + v'^2)$,
//! $K_\sigma = \sum_e N_e \int (N_u'^TN_u' + N_v'^TN_v')\,dx$ (Cook et al., *Concepts and
//! Applications of Finite Element Analysis*, §18.3).

use nalgebra::{DMatrix, DVector};

use crate::{Error, Result, error::LinalgError};

/// The beam's data. Defaults: Kane et al. (1987), read from the embedded
/// `assets/papers/kane-1987-beam.toml`.
#[derive(Debug, Clone, PartialEq, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpinningBeamParameters {
    /// Length $L$, m.
    pub length: f64,
    /// Bending stiffness $EI$, N m².
    pub bending_stiffness: f64,
    /// Axial stiffness $EA$, N.
    pub axial_stiffness: f64,
    /// Mass per length $\rho A$, kg/m.
    pub mass_per_length: f64,
    /// Distance $r$ from the spin axis to the root, m.
    pub hub_radius: f64,
    /// Elements along the beam.
    pub elements: usize,
}

impl Default for SpinningBeamParameters {
    fn default() -> Self {
        crate::assets::parameters("papers/kane-1987-beam.toml")
    }
}

impl SpinningBeamParameters {
    /// $\sqrt{EI / (\rho A L^4)}$, rad/s: the frequency unit of the dimensionless speed
    /// $\lambda = \Omega/\text{unit}$ and frequency $\mu = \omega/\text{unit}$ of the
    /// rotating-beam tables.
    pub fn frequency_unit(&self) -> f64 {
        (self.bending_stiffness / (self.mass_per_length * self.length.powi(4))).sqrt()
    }
}

/// Where the spin axis lies against the beam's plane.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BendingPlane {
    /// The axis normal to the plane: bending in the plane of rotation (lag, edgewise).
    Lagwise,
    /// The axis in the plane, across the beam: bending out of the plane of rotation (flap).
    Flapwise,
}

/// Free DOF per node: $u$ (m), $v$ (m), $\theta = v'$ (rad).
pub const BEAM_NODE_DOF: usize = 3;

/// The assembled beam, root clamped: node $j = 1..n_e$ carries DOF $3(j-1) + (0, 1, 2)$.
#[derive(Debug, Clone)]
pub struct SpinningBeam {
    /// The data it was built from.
    pub parameters: SpinningBeamParameters,
    /// The plane the beam bends in against the spin axis.
    pub plane: BendingPlane,
    /// Mass, kg.
    pub m: DMatrix<f64>,
    /// Elastic stiffness, N/m.
    pub k: DMatrix<f64>,
    /// Gyroscopic $G$ (skew), kg.
    pub g: DMatrix<f64>,
    /// Centrifugal $H$ (symmetric, negative semi-definite), kg.
    pub h: DMatrix<f64>,
    /// $Gs$, kg m.
    pub g_s: DVector<f64>,
    /// $Hs$, kg m.
    pub h_s: DVector<f64>,
    /// The load of a unit acceleration along the frame's $x$ and $y$ (in the beam's plane),
    /// $\int\rho A N^T e_a$, kg.
    pub unit_gravity: [DVector<f64>; 2],
}

/// Gauss–Legendre points and weights on [0, 1] (4 points: exact to degree 7, the highest
/// product here being cubic × cubic × linear).
const GAUSS: [(f64, f64); 4] = [
    (0.069_431_844_202_973_71, 0.173_927_422_568_726_93),
    (0.330_009_478_207_571_9, 0.326_072_577_431_273_07),
    (0.669_990_521_792_428_1, 0.326_072_577_431_273_07),
    (0.930_568_155_797_026_3, 0.173_927_422_568_726_93),
];

/// The element's shape functions at $\xi \in [0,1]$ for DOF $(u_a, v_a, \theta_a, u_b, v_b,
/// \theta_b)$: values and $x$-derivatives of the axial row $N_u$ and transverse row $N_v$,
/// and $N_v''$.
struct Shapes {
    nu: [f64; 6],
    nv: [f64; 6],
    du: [f64; 6],
    dv: [f64; 6],
    ddv: [f64; 6],
}

fn shapes(xi: f64, le: f64) -> Shapes {
    let (x2, x3) = (xi * xi, xi * xi * xi);
    let nu = [1.0 - xi, 0.0, 0.0, xi, 0.0, 0.0];
    let nv = [
        0.0,
        1.0 - 3.0 * x2 + 2.0 * x3,
        le * (xi - 2.0 * x2 + x3),
        0.0,
        3.0 * x2 - 2.0 * x3,
        le * (x3 - x2),
    ];
    let du = [-1.0 / le, 0.0, 0.0, 1.0 / le, 0.0, 0.0];
    let dv = [
        0.0,
        (-6.0 * xi + 6.0 * x2) / le,
        1.0 - 4.0 * xi + 3.0 * x2,
        0.0,
        (6.0 * xi - 6.0 * x2) / le,
        3.0 * x2 - 2.0 * xi,
    ];
    let ddv = [
        0.0,
        (-6.0 + 12.0 * xi) / (le * le),
        (-4.0 + 6.0 * xi) / le,
        0.0,
        (6.0 - 12.0 * xi) / (le * le),
        (6.0 * xi - 2.0) / le,
    ];
    Shapes {
        nu,
        nv,
        du,
        dv,
        ddv,
    }
}

/// The element's global DOF: node $e$ (the root for $e = 0$, clamped: `None`) and node $e+1$.
fn element_dofs(e: usize) -> [Option<usize>; 6] {
    std::array::from_fn(|a| {
        let node = e + a / 3;
        (node > 0).then(|| BEAM_NODE_DOF * (node - 1) + a % 3)
    })
}

fn outer_add(out: &mut [[f64; 6]; 6], a: &[f64; 6], b: &[f64; 6], s: f64) {
    for i in 0..6 {
        for j in 0..6 {
            out[i][j] += s * a[i] * b[j];
        }
    }
}

impl SpinningBeam {
    /// Assembles the beam of `p` bending in `plane`.
    pub fn new(p: &SpinningBeamParameters, plane: BendingPlane) -> Self {
        let ne = p.elements.max(1);
        let n = BEAM_NODE_DOF * ne;
        let le = p.length / ne as f64;
        let rho = p.mass_per_length;
        let mut m = DMatrix::zeros(n, n);
        let mut k = DMatrix::zeros(n, n);
        let mut g = DMatrix::zeros(n, n);
        let mut h = DMatrix::zeros(n, n);
        let mut g_s = DVector::zeros(n);
        let mut h_s = DVector::zeros(n);
        let mut unit_gravity = [DVector::zeros(n), DVector::zeros(n)];
        for e in 0..ne {
            let (mut me, mut ke, mut ge, mut he) =
                ([[0.0; 6]; 6], [[0.0; 6]; 6], [[0.0; 6]; 6], [[0.0; 6]; 6]);
            let (mut gse, mut hse, mut gx, mut gy) = ([0.0; 6], [0.0; 6], [0.0; 6], [0.0; 6]);
            for (xi, w) in GAUSS {
                let s = shapes(xi, le);
                let dx = w * le;
                // Distance from the spin axis, m.
                let radius = p.hub_radius + (e as f64 + xi) * le;
                outer_add(&mut me, &s.nu, &s.nu, rho * dx);
                outer_add(&mut me, &s.nv, &s.nv, rho * dx);
                outer_add(&mut ke, &s.du, &s.du, p.axial_stiffness * dx);
                outer_add(&mut ke, &s.ddv, &s.ddv, p.bending_stiffness * dx);
                // ẽ² takes the axial component to minus itself in both planes; the
                // transverse one only when the axis is normal to the plane.
                outer_add(&mut he, &s.nu, &s.nu, -rho * dx);
                for a in 0..6 {
                    hse[a] -= rho * dx * s.nu[a] * radius;
                    gx[a] += rho * dx * s.nu[a];
                    gy[a] += rho * dx * s.nv[a];
                }
                if plane == BendingPlane::Lagwise {
                    outer_add(&mut he, &s.nv, &s.nv, -rho * dx);
                    // ẽ(x, y) = (−y, x): Nᵀẽ N = N_vᵀN_u − N_uᵀN_v.
                    outer_add(&mut ge, &s.nv, &s.nu, rho * dx);
                    outer_add(&mut ge, &s.nu, &s.nv, -rho * dx);
                    for (g, nv) in gse.iter_mut().zip(&s.nv) {
                        *g += rho * dx * nv * radius;
                    }
                }
            }
            let dofs = element_dofs(e);
            for (a, da) in dofs.iter().enumerate() {
                let Some(i) = *da else { continue };
                g_s[i] += gse[a];
                h_s[i] += hse[a];
                unit_gravity[0][i] += gx[a];
                unit_gravity[1][i] += gy[a];
                for (b, db) in dofs.iter().enumerate() {
                    let Some(j) = *db else { continue };
                    m[(i, j)] += me[a][b];
                    k[(i, j)] += ke[a][b];
                    g[(i, j)] += ge[a][b];
                    h[(i, j)] += he[a][b];
                }
            }
        }
        Self {
            parameters: p.clone(),
            plane,
            m,
            k,
            g,
            h,
            g_s,
            h_s,
            unit_gravity,
        }
    }

    /// Free DOF.
    pub fn dim(&self) -> usize {
        self.m.nrows()
    }

    /// The axial force $N_e = EA\,(u_b - u_a)/\ell_e$ in each element (N) of the
    /// displacements `u`: the element stresses of a static load case.
    pub fn axial_forces(&self, u: &DVector<f64>) -> Vec<f64> {
        let p = &self.parameters;
        let ne = p.elements.max(1);
        let le = p.length / ne as f64;
        (0..ne)
            .map(|e| {
                let dofs = element_dofs(e);
                let at = |a: usize| dofs[a].map_or(0.0, |i| u[i]);
                p.axial_stiffness * (at(3) - at(0)) / le
            })
            .collect()
    }

    /// The geometric stiffness $\sum_e N_e \int (N_u'^TN_u' + N_v'^TN_v')\,dx$ of the
    /// element axial forces `forces` (N/m).
    pub fn geometric_stiffness(&self, forces: &[f64]) -> DMatrix<f64> {
        let p = &self.parameters;
        let ne = p.elements.max(1);
        assert_eq!(forces.len(), ne, "one axial force per element");
        let le = p.length / ne as f64;
        let n = self.dim();
        let mut kg = DMatrix::zeros(n, n);
        for (e, &force) in forces.iter().enumerate() {
            let mut ke = [[0.0; 6]; 6];
            for (xi, w) in GAUSS {
                let s = shapes(xi, le);
                outer_add(&mut ke, &s.du, &s.du, force * w * le);
                outer_add(&mut ke, &s.dv, &s.dv, force * w * le);
            }
            let dofs = element_dofs(e);
            for (a, da) in dofs.iter().enumerate() {
                let Some(i) = *da else { continue };
                for (b, db) in dofs.iter().enumerate() {
                    let Some(j) = *db else { continue };
                    kg[(i, j)] += ke[a][b];
                }
            }
        }
        kg
    }

    /// The geometric stiffness of each unit load of a frame turning about the spin axis
    /// ($\dot\theta^2$: $-Hs$; $\ddot\theta$: $-Gs$; gravity along the frame's $x$, $y$;
    /// $z$, out of the beam's plane, is not modelled): each load solved statically on the
    /// clamped beam, $Ku_i = f_i$ (Cholesky, its residual checked), its element axial forces
    /// made into [`Self::geometric_stiffness`]. A case that stresses no element axially (the
    /// tangential load of $\ddot\theta$ on a straight beam) gives `None`.
    pub fn unit_geometric_stiffnesses(&self) -> Result<[Option<DMatrix<f64>>; 5]> {
        let chol = self.k.clone().cholesky().ok_or_else(|| {
            Error::Linalg(LinalgError::NotPositiveDefinite {
                matrix: "stiffness of the clamped spinning beam".into(),
            })
        })?;
        let loads: [Option<DVector<f64>>; 5] = [
            Some(-&self.h_s),
            Some(-&self.g_s),
            Some(self.unit_gravity[0].clone()),
            Some(self.unit_gravity[1].clone()),
            None,
        ];
        let mut cases: [Option<DMatrix<f64>>; 5] = Default::default();
        for (case, load) in cases.iter_mut().zip(loads) {
            let Some(f) = load else { continue };
            let u = chol.solve(&f);
            let residual = (&self.k * &u - &f).amax();
            let scale = (self.k.abs() * u.abs()).amax() + f.amax();
            if residual.is_nan() || residual > 1e-10 * scale.max(f64::MIN_POSITIVE) {
                return Err(LinalgError::SolveInaccurate {
                    matrix: "stiffness of the clamped spinning beam".into(),
                    residual: residual / scale,
                    tolerance: 1e-10,
                }
                .into());
            }
            let forces = self.axial_forces(&u);
            if forces.iter().any(|&n| n != 0.0) {
                *case = Some(self.geometric_stiffness(&forces));
            }
        }
        Ok(cases)
    }

    /// The transverse displacement $v$ of the tip (DOF index).
    pub fn tip_deflection_dof(&self) -> usize {
        self.dim() - 2
    }

    /// Node positions in the frame, m (the root first).
    pub fn node_positions(&self) -> Vec<[f64; 3]> {
        let p = &self.parameters;
        let ne = p.elements.max(1);
        (0..=ne)
            .map(|j| [p.hub_radius + p.length * j as f64 / ne as f64, 0.0, 0.0])
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The mass integrates to ρAL on each direction; K holds rigid translations along the
    /// beam only through the clamp (positive definite); G is skew, H symmetric and, for the
    /// lagwise plane, −M.
    #[test]
    fn operators_have_their_symmetries() {
        for elements in [1, 3, 20] {
            let p = SpinningBeamParameters {
                elements,
                ..Default::default()
            };
            let b = SpinningBeam::new(&p, BendingPlane::Lagwise);
            let mass = p.mass_per_length * p.length;
            // A unit axial translation of the free nodes (the root held) is 1 along the
            // beam but on the first element, where it rises as ξ: ∫ρA ξ² = ρA ℓ/3 there.
            let ones = DVector::from_fn(b.dim(), |i, _| if i % 3 == 0 { 1.0 } else { 0.0 });
            let carried = (ones.transpose() * &b.m * &ones)[(0, 0)];
            let le = p.length / elements as f64;
            let expected = mass - 2.0 * p.mass_per_length * le / 3.0;
            assert!(
                (carried - expected).abs() < 1e-12 * mass,
                "{carried} {expected}"
            );
            assert!((&b.g + b.g.transpose()).amax() < 1e-14 * b.m.amax());
            assert!((&b.h + &b.m).amax() < 1e-14 * b.m.amax());
            assert!(b.k.clone().cholesky().is_some());
            let flap = SpinningBeam::new(&p, BendingPlane::Flapwise);
            assert_eq!(flap.g.amax(), 0.0);
            assert!((&flap.h - flap.h.transpose()).amax() == 0.0);
        }
    }

    /// The centrifugal tension of the static solution, K u = −Ω² Hs: at the root it is the
    /// whole beam's centrifugal force ρAΩ²((r+L)² − r²)/2 (the element's average, within the
    /// element's quadratic variation), falling to the tip.
    #[test]
    fn centrifugal_axial_force_is_the_beams_inertia() {
        let p = SpinningBeamParameters {
            hub_radius: 1.5,
            elements: 40,
            ..Default::default()
        };
        let b = SpinningBeam::new(&p, BendingPlane::Lagwise);
        let u = b.k.clone().cholesky().unwrap().solve(&(-&b.h_s));
        let forces = b.axial_forces(&u);
        let (r, l, rho) = (p.hub_radius, p.length, p.mass_per_length);
        let exact = |x: f64| rho * ((r + l).powi(2) - (r + x).powi(2)) / 2.0;
        let le = l / 40.0;
        for (e, f) in forces.iter().enumerate() {
            // Nodal values of a bar under a consistent load are exact: the element's force
            // is the mean of the exact one over the element.
            let (a, c) = (e as f64 * le, (e + 1) as f64 * le);
            let mean =
                rho / 2.0 * ((r + l).powi(2) - ((r + c).powi(3) - (r + a).powi(3)) / (3.0 * le));
            assert!((f - mean).abs() < 1e-9 * exact(0.0), "{e}: {f} {mean}");
        }
    }
}
