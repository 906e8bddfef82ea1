//! Stresses of the 8-node brick and its geometric (stress) stiffness: the second variation of
//! the Green–Lagrange strain energy at a given stress, the stiffness a prestressed solid gains
//! or loses (tension stiffens, compression softens).
//!
//! At each of the 2×2×2 Gauss points the Cauchy stress of a displacement is $\sigma = DBu_e$
//! and
//! $$K_{\sigma,ab} = \sum_g \left(\nabla N_a^T\, S_g\, \nabla N_b\right) \det J_g\; I_3,$$
//! with $S_g$ the 3 × 3 stress at the point: for any displacement field $v$,
//! $v^T K_\sigma v = \int \sigma : (\nabla v^T \nabla v)\,dV$ (Bathe, *Finite Element
//! Procedures*, §6.3.3, the $\int {}^tS\,\delta{}_0\eta\,d V$ term).

use faer::Mat;

use super::hex8::{elasticity, gauss_gradients};

/// The stress (Pa, Voigt order xx, yy, zz, xy, yz, zx) at each Gauss point.
pub type GaussStresses = [[f64; 6]; 8];

/// The stresses of the displacement `u` (24 values, node-major x, y, z, m) of a brick with node
/// positions `x` (m), Young's modulus `e` (Pa) and Poisson's ratio `nu`, at its Gauss points.
pub fn hex8_stresses(x: &[[f64; 3]; 8], e: f64, nu: f64, u: &[f64; 24]) -> GaussStresses {
    let d = elasticity(e, nu);
    let mut out = [[0.0; 6]; 8];
    for (sigma, (dx, _)) in out.iter_mut().zip(gauss_gradients(x)) {
        // Displacement gradient g[i][j] = ∂u_i/∂x_j.
        let mut g = [[0.0; 3]; 3];
        for (a, dna) in dx.iter().enumerate() {
            for (i, gi) in g.iter_mut().enumerate() {
                for (j, gij) in gi.iter_mut().enumerate() {
                    *gij += u[3 * a + i] * dna[j];
                }
            }
        }
        let strain = [
            g[0][0],
            g[1][1],
            g[2][2],
            g[0][1] + g[1][0],
            g[1][2] + g[2][1],
            g[2][0] + g[0][2],
        ];
        for (s, row) in sigma.iter_mut().zip(&d) {
            *s = row.iter().zip(&strain).map(|(a, b)| a * b).sum();
        }
    }
    out
}

/// The geometric stiffness (24 × 24, N/m) of a brick with node positions `x` (m) at the Gauss
/// point stresses `stresses` (Pa, of [`hex8_stresses`]).
pub fn hex8_geometric_stiffness(x: &[[f64; 3]; 8], stresses: &GaussStresses) -> Mat<f64> {
    let mut k = Mat::<f64>::zeros(24, 24);
    for ((dx, det), s) in gauss_gradients(x).iter().zip(stresses) {
        let sm = [[s[0], s[3], s[5]], [s[3], s[1], s[4]], [s[5], s[4], s[2]]];
        for a in 0..8 {
            // S ∇N_a
            let sa: [f64; 3] = std::array::from_fn(|i| (0..3).map(|j| sm[i][j] * dx[a][j]).sum());
            for b in 0..8 {
                let v = det * (0..3).map(|i| dx[b][i] * sa[i]).sum::<f64>();
                for d in 0..3 {
                    k[(3 * a + d, 3 * b + d)] += v;
                }
            }
        }
    }
    k
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A sheared, stretched brick (not a cube, so the Jacobian is not diagonal).
    fn brick() -> [[f64; 3]; 8] {
        super::super::hex8::LOCAL_NODES.map(|[a, b, c]| {
            let (x, y, z) = (0.5 * (a + 1.0), 0.5 * (b + 1.0), 0.5 * (c + 1.0));
            [2.0 * x + 0.3 * y, 0.7 * y + 0.1 * z, 0.5 * z + 0.2 * x]
        })
    }

    /// Under a linear displacement $u = Gx$ the stress is uniform and equals $D\varepsilon(G)$;
    /// for any linear field $v = Hx$ the energy $v^TK_\sigma v$ equals
    /// $V\,\sigma:(H^TH)$ exactly (the integrand is constant).
    #[test]
    fn uniform_stress_gives_the_closed_form_energy() {
        let x = brick();
        let (e, nu) = (2.1e11, 0.3);
        let grad = [[1e-4, 2e-5, -3e-5], [0.0, -5e-5, 1e-5], [4e-5, 0.0, 2e-4]];
        let field = |g: &[[f64; 3]; 3]| -> [f64; 24] {
            std::array::from_fn(|k| {
                let (a, i) = (k / 3, k % 3);
                (0..3).map(|j| g[i][j] * x[a][j]).sum()
            })
        };
        let stresses = hex8_stresses(&x, e, nu, &field(&grad));
        let d = elasticity(e, nu);
        let strain = [
            grad[0][0],
            grad[1][1],
            grad[2][2],
            grad[0][1] + grad[1][0],
            grad[1][2] + grad[2][1],
            grad[2][0] + grad[0][2],
        ];
        let expected: [f64; 6] = std::array::from_fn(|r| (0..6).map(|c| d[r][c] * strain[c]).sum());
        for s in &stresses {
            for (a, b) in s.iter().zip(&expected) {
                assert!(
                    (a - b).abs() <= 1e-9 * expected.iter().fold(0.0f64, |m, v| m.max(v.abs()))
                );
            }
        }
        let k = hex8_geometric_stiffness(&x, &stresses);
        let h = [[0.3, -1.0, 0.2], [0.5, 0.1, -0.7], [-0.4, 0.9, 0.6]];
        let v = field(&h);
        let energy: f64 = (0..24)
            .map(|i| (0..24).map(|j| v[i] * k[(i, j)] * v[j]).sum::<f64>())
            .sum();
        let volume: f64 = gauss_gradients(&x).iter().map(|(_, det)| det).sum();
        let s = &expected;
        let sm = [[s[0], s[3], s[5]], [s[3], s[1], s[4]], [s[5], s[4], s[2]]];
        // σ : (HᵀH) = Σ_ij σ_ij Σ_k H_ki H_kj
        let closed: f64 = (0..3)
            .map(|i| {
                (0..3)
                    .map(|j| sm[i][j] * (0..3).map(|k| h[k][i] * h[k][j]).sum::<f64>())
                    .sum::<f64>()
            })
            .sum::<f64>()
            * volume;
        assert!(
            (energy - closed).abs() <= 1e-10 * closed.abs(),
            "{energy} against {closed}"
        );
        // Rigid translations carry no energy; the matrix is symmetric.
        for d in 0..3 {
            let t: [f64; 24] = std::array::from_fn(|k| if k % 3 == d { 1.0 } else { 0.0 });
            let e_t: f64 = (0..24)
                .map(|i| (0..24).map(|j| t[i] * k[(i, j)] * t[j]).sum::<f64>())
                .sum();
            assert!(e_t.abs() <= 1e-12 * closed.abs());
        }
        for i in 0..24 {
            for j in 0..24 {
                assert!((k[(i, j)] - k[(j, i)]).abs() <= 1e-12 * closed.abs());
            }
        }
    }
}
