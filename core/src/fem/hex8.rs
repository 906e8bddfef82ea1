//! The 8-node trilinear brick (App. B), integrated with 2×2×2 Gauss points.

use faer::Mat;

/// Natural coordinates of the local nodes: bottom face (ζ = −1) counter-clockwise, then top.
pub const LOCAL_NODES: [[f64; 3]; 8] = [
    [-1.0, -1.0, -1.0],
    [1.0, -1.0, -1.0],
    [1.0, 1.0, -1.0],
    [-1.0, 1.0, -1.0],
    [-1.0, -1.0, 1.0],
    [1.0, -1.0, 1.0],
    [1.0, 1.0, 1.0],
    [-1.0, 1.0, 1.0],
];

/// The 12 edges of a brick as pairs of local nodes (order of [`LOCAL_NODES`]).
pub const EDGES: [(usize, usize); 12] = [
    (0, 1),
    (1, 2),
    (2, 3),
    (3, 0),
    (4, 5),
    (5, 6),
    (6, 7),
    (7, 4),
    (0, 4),
    (1, 5),
    (2, 6),
    (3, 7),
];

/// Shape functions $N_a$, their natural derivatives $\partial N_a/\partial\xi$ and the
/// Jacobian $J = \sum_a (\partial N_a/\partial\xi)\, x_a^T$ at natural point `xi` of a brick
/// with node positions `x` (local order of [`LOCAL_NODES`]).
pub(super) fn shape_at(
    xi: [f64; 3],
    x: &[[f64; 3]; 8],
) -> ([f64; 8], [[f64; 3]; 8], nalgebra::Matrix3<f64>) {
    let mut n = [0.0; 8];
    let mut dn = [[0.0; 3]; 8];
    for (a, l) in LOCAL_NODES.iter().enumerate() {
        let f = [0, 1, 2].map(|d| 1.0 + l[d] * xi[d]);
        n[a] = 0.125 * f[0] * f[1] * f[2];
        dn[a] = [
            0.125 * l[0] * f[1] * f[2],
            0.125 * l[1] * f[0] * f[2],
            0.125 * l[2] * f[0] * f[1],
        ];
    }
    let mut j = nalgebra::Matrix3::<f64>::zeros();
    for a in 0..8 {
        for r in 0..3 {
            for c in 0..3 {
                j[(r, c)] += dn[a][r] * x[a][c];
            }
        }
    }
    (n, dn, j)
}

/// Isotropic linear-elastic constitutive matrix (Voigt order xx, yy, zz, xy, yz, zx;
/// engineering shear strains). `e` in Pa.
pub(super) fn elasticity(e: f64, nu: f64) -> [[f64; 6]; 6] {
    let c = e / ((1.0 + nu) * (1.0 - 2.0 * nu));
    let mut d = [[0.0; 6]; 6];
    for i in 0..3 {
        for (j, dij) in d[i].iter_mut().take(3).enumerate() {
            *dij = c * if i == j { 1.0 - nu } else { nu };
        }
        d[i + 3][i + 3] = c * (1.0 - 2.0 * nu) / 2.0;
    }
    d
}

/// Derivatives $\partial N_a / \partial x = J^{-1}\partial N_a/\partial\xi$ and $\det J$ at
/// each of the 2×2×2 Gauss points (unit weights), in the order every brick matrix sums them.
pub(super) fn gauss_gradients(x: &[[f64; 3]; 8]) -> [([[f64; 3]; 8], f64); 8] {
    let g = 1.0 / 3.0f64.sqrt();
    let mut out = [([[0.0; 3]; 8], 0.0); 8];
    let mut p = 0;
    for &gx in &[-g, g] {
        for &gy in &[-g, g] {
            for &gz in &[-g, g] {
                let (_, dn, j) = shape_at([gx, gy, gz], x);
                let jinv = j
                    .try_inverse()
                    .unwrap_or_else(nalgebra::Matrix3::<f64>::zeros);
                let mut dx = [[0.0; 3]; 8];
                for (dxa, dna) in dx.iter_mut().zip(&dn) {
                    for (r, v) in dxa.iter_mut().enumerate() {
                        *v = (0..3).map(|c| jinv[(r, c)] * dna[c]).sum();
                    }
                }
                out[p] = (dx, j.determinant());
                p += 1;
            }
        }
    }
    out
}

/// Element stiffness (24×24, N/m) of a brick with node positions `x` (m) in the local order of
/// [`LOCAL_NODES`], Young's modulus `e` (Pa) and Poisson's ratio `nu`.
/// $K_e = \sum_g B^T D B \,\det J\, w_g$ over the 2×2×2 Gauss points.
pub fn hex8_stiffness(x: &[[f64; 3]; 8], e: f64, nu: f64) -> Mat<f64> {
    let d = elasticity(e, nu);
    let mut k = Mat::<f64>::zeros(24, 24);
    for (dx, det) in gauss_gradients(x) {
        let mut b = [[0.0; 24]; 6];
        for (a, &[nx, ny, nz]) in dx.iter().enumerate() {
            let c = 3 * a;
            b[0][c] = nx;
            b[1][c + 1] = ny;
            b[2][c + 2] = nz;
            b[3][c] = ny;
            b[3][c + 1] = nx;
            b[4][c + 1] = nz;
            b[4][c + 2] = ny;
            b[5][c] = nz;
            b[5][c + 2] = nx;
        }
        let mut db = [[0.0; 24]; 6];
        for r in 0..6 {
            for c in 0..24 {
                db[r][c] = (0..6).map(|s| d[r][s] * b[s][c]).sum();
            }
        }
        for r in 0..24 {
            for c in 0..24 {
                let v: f64 = (0..6).map(|s| b[s][r] * db[s][c]).sum();
                k[(r, c)] += v * det;
            }
        }
    }
    k
}

/// Consistent mass (24×24, kg) of a brick with node positions `x` (m) and density `rho`
/// (kg/m³): $M_e = \rho \sum_g N^T N \,\det J\, w_g$ over the 2×2×2 Gauss points, the same
/// shape function for each direction.
pub fn hex8_consistent_mass(x: &[[f64; 3]; 8], rho: f64) -> Mat<f64> {
    let g = 1.0 / 3.0f64.sqrt();
    let mut m = Mat::<f64>::zeros(24, 24);
    for &gx in &[-g, g] {
        for &gy in &[-g, g] {
            for &gz in &[-g, g] {
                let (n, _, j) = shape_at([gx, gy, gz], x);
                let det = j.determinant();
                for a in 0..8 {
                    for b in 0..8 {
                        let v = rho * n[a] * n[b] * det;
                        for d in 0..3 {
                            m[(3 * a + d, 3 * b + d)] += v;
                        }
                    }
                }
            }
        }
    }
    m
}
