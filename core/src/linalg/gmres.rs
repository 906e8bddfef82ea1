//! Right-preconditioned restarted GMRES (Saad and Schultz 1986) for a nonsymmetric system
//! $Ax = b$ whose symmetric positive definite part $P$ is factored once: the effective matrix
//! of a body on a spinning frame, $P + E(t)$, where $E$ holds the gyroscopic (skew) and
//! centrifugal terms that change every step while $P = c_m M + c_k K$ does not.
//!
//! With $y = P x$ the iteration solves $A P^{-1} y = b$ over the Krylov space of $AP^{-1}$;
//! when $\|P^{-1}E\| < 1$ its eigenvalues cluster about 1 and a handful of iterations reach
//! round-off. The returned $x$ is checked against the true residual, as a normwise backward
//! error: $\|b - Ax\| \le \tau (\|b\| + \||A||x|\|)$, never against the recurrence's
//! estimate alone (an ill-conditioned $A$ cannot give a smaller residual relative to $\|b\|$
//! alone than its round-off $\varepsilon\||A||x|\|$).

use crate::error::{LinalgError, MatrixLabel};
use crate::linalg::Result;

/// What a solve took.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct GmresStatistics {
    /// Products with $A$ (each with one solve with $P$).
    pub iterations: usize,
    /// The final backward error $\|b - Ax\| / (\|b\| + \||A||x|\|)$.
    pub residual: f64,
}

/// The stopping rule of a solve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GmresParameters {
    /// Backward error to meet.
    pub tolerance: f64,
    /// Products with $A$ allowed.
    pub max_iterations: usize,
}

impl Default for GmresParameters {
    fn default() -> Self {
        Self {
            tolerance: 1e-11,
            max_iterations: 200,
        }
    }
}

/// Krylov vectors kept before a restart.
const RESTART: usize = 30;

fn norm(x: &[f64]) -> f64 {
    x.iter().map(|v| v * v).sum::<f64>().sqrt()
}

fn dot(x: &[f64], y: &[f64]) -> f64 {
    x.iter().zip(y).map(|(a, b)| a * b).sum()
}

/// Solves $Ax = b$ to the backward error `tolerance`, starting from `x0`, with `apply`
/// computing $Ax$, `precondition` computing $P^{-1}y$ and `abs_norm` computing
/// $\||A||x|\|$. `what` names the matrix in the
/// error: [`LinalgError::SolveInaccurate`] with the residual reached when the allowed
/// products did not meet the tolerance (or the products were not finite).
pub fn preconditioned_gmres(
    what: impl Into<MatrixLabel>,
    mut apply: impl FnMut(&[f64]) -> Vec<f64>,
    mut precondition: impl FnMut(&[f64]) -> Vec<f64>,
    mut abs_norm: impl FnMut(&[f64]) -> f64,
    b: &[f64],
    x0: Vec<f64>,
    parameters: GmresParameters,
) -> Result<(Vec<f64>, GmresStatistics)> {
    let GmresParameters {
        tolerance,
        max_iterations,
    } = parameters;
    let n = b.len();
    assert_eq!(
        x0.len(),
        n,
        "GMRES: start vector of {} for {n} rows",
        x0.len()
    );
    let b_norm = norm(b);
    let mut stats = GmresStatistics::default();
    if b_norm == 0.0 {
        return Ok((vec![0.0; n], stats));
    }
    let mut x = x0;
    let what = what.into();
    let inaccurate = |residual: f64| LinalgError::SolveInaccurate {
        matrix: what.clone(),
        residual,
        tolerance,
    };
    loop {
        let ax = apply(&x);
        let r: Vec<f64> = b.iter().zip(&ax).map(|(b, a)| b - a).collect();
        let beta = norm(&r);
        stats.residual = beta / b_norm;
        if !stats.residual.is_finite() {
            return Err(inaccurate(f64::INFINITY));
        }
        if stats.residual > tolerance {
            stats.residual = beta / (b_norm + abs_norm(&x));
        }
        if stats.residual <= tolerance {
            return Ok((x, stats));
        }
        if stats.iterations >= max_iterations {
            return Err(inaccurate(stats.residual));
        }
        // Arnoldi on A P⁻¹ with Givens rotations of the Hessenberg matrix.
        let m = RESTART.min(max_iterations - stats.iterations);
        let mut v: Vec<Vec<f64>> = vec![r.iter().map(|x| x / beta).collect()];
        let mut z: Vec<Vec<f64>> = Vec::with_capacity(m);
        let mut h = vec![vec![0.0; m]; m + 1];
        let (mut cs, mut sn) = (vec![0.0; m], vec![0.0; m]);
        let mut g = vec![0.0; m + 1];
        g[0] = beta;
        let mut k = 0;
        while k < m {
            let zk = precondition(&v[k]);
            let mut w = apply(&zk);
            z.push(zk);
            stats.iterations += 1;
            // Modified Gram–Schmidt, twice for orthogonality at round-off.
            for _ in 0..2 {
                for (i, vi) in v.iter().enumerate() {
                    let c = dot(&w, vi);
                    h[i][k] += c;
                    w.iter_mut().zip(vi).for_each(|(w, v)| *w -= c * v);
                }
            }
            let w_norm = norm(&w);
            h[k + 1][k] = w_norm;
            apply_rotations(&mut h, (&cs, &sn), k);
            let d = h[k][k].hypot(h[k + 1][k]);
            if d == 0.0 || !d.is_finite() {
                return Err(inaccurate(stats.residual));
            }
            cs[k] = h[k][k] / d;
            sn[k] = h[k + 1][k] / d;
            h[k][k] = d;
            h[k + 1][k] = 0.0;
            g[k + 1] = -sn[k] * g[k];
            g[k] *= cs[k];
            let breakdown = w_norm == 0.0;
            if !breakdown {
                v.push(w.iter().map(|x| x / w_norm).collect());
            }
            k += 1;
            if g[k].abs() <= 0.5 * tolerance * b_norm || breakdown {
                break;
            }
        }
        // x += Σ y_i z_i with H y = g (upper triangular, k × k).
        add_correction(&mut x, (&h, &g), &z[..k]);
    }
}

/// The Givens rotations so far (`cs`, `sn`) applied to column `k` of the Hessenberg matrix.
fn apply_rotations(h: &mut [Vec<f64>], (cs, sn): (&[f64], &[f64]), k: usize) {
    for i in 0..k {
        let t = cs[i] * h[i][k] + sn[i] * h[i + 1][k];
        h[i + 1][k] = -sn[i] * h[i][k] + cs[i] * h[i + 1][k];
        h[i][k] = t;
    }
}

/// $x \mathrel{+}= \sum_i y_iz_i$ with $Hy = g$ ($H$ upper triangular, as many rows as `z`).
fn add_correction(x: &mut [f64], (h, g): (&[Vec<f64>], &[f64]), z: &[Vec<f64>]) {
    let k = z.len();
    let mut y = vec![0.0; k];
    for i in (0..k).rev() {
        let s: f64 = (i + 1..k).map(|j| h[i][j] * y[j]).sum();
        y[i] = (g[i] - s) / h[i][i];
    }
    for (yi, zi) in y.iter().zip(z) {
        x.iter_mut().zip(zi).for_each(|(x, z)| *x += yi * z);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A tridiagonal SPD part plus a skew part of size `eps`: GMRES with the SPD part as the
    /// preconditioner meets the tolerance, and the answer satisfies the original system.
    #[test]
    fn solves_spd_plus_skew_to_the_tolerance() {
        for n in [5usize, 40, 200] {
            for eps in [0.0, 0.1, 0.6] {
                let p = |x: &[f64]| -> Vec<f64> {
                    (0..n)
                        .map(|i| {
                            let l = if i > 0 { x[i - 1] } else { 0.0 };
                            let r = if i + 1 < n { x[i + 1] } else { 0.0 };
                            4.0 * x[i] - l - r
                        })
                        .collect()
                };
                let a = |x: &[f64]| -> Vec<f64> {
                    let mut y = p(x);
                    for i in 0..n {
                        let l = if i > 0 { x[i - 1] } else { 0.0 };
                        let r = if i + 1 < n { x[i + 1] } else { 0.0 };
                        y[i] += eps * (r - l);
                    }
                    y
                };
                // P⁻¹ by the Thomas algorithm.
                let solve_p = |y: &[f64]| -> Vec<f64> {
                    let (mut c, mut d) = (vec![0.0; n], vec![0.0; n]);
                    for i in 0..n {
                        let den = 4.0 + if i > 0 { c[i - 1] } else { 0.0 };
                        c[i] = -1.0 / den;
                        d[i] = (y[i] + if i > 0 { d[i - 1] } else { 0.0 }) / den;
                    }
                    let mut x = vec![0.0; n];
                    for i in (0..n).rev() {
                        x[i] = d[i] - c[i] * if i + 1 < n { x[i + 1] } else { 0.0 };
                    }
                    x
                };
                let b: Vec<f64> = (0..n).map(|i| ((i * 7 % 11) as f64) - 5.0).collect();
                let (x, stats) = preconditioned_gmres(
                    "test",
                    a,
                    solve_p,
                    |_| 0.0,
                    &b,
                    vec![0.0; n],
                    GmresParameters {
                        tolerance: 1e-12,
                        max_iterations: 200,
                    },
                )
                .unwrap();
                let r: Vec<f64> = a(&x).iter().zip(&b).map(|(a, b)| a - b).collect();
                assert!(norm(&r) <= 1e-12 * norm(&b), "n {n} eps {eps}");
                assert!(stats.residual <= 1e-12);
                if eps == 0.0 {
                    assert_eq!(stats.iterations, 1, "P⁻¹ is exact");
                }
            }
        }
    }

    #[test]
    fn reports_the_residual_when_it_cannot_converge() {
        // A = -P: the preconditioned operator is -I, solvable in one step; with one
        // iteration allowed and a wrong preconditioner (the zero map) it cannot be.
        let b = vec![1.0, 2.0, 3.0];
        let err = preconditioned_gmres(
            "stuck",
            |x| x.iter().map(|v| 2.0 * v).collect(),
            |_| vec![0.0; 3],
            |_| 0.0,
            &b,
            vec![0.0; 3],
            GmresParameters {
                tolerance: 1e-10,
                max_iterations: 3,
            },
        )
        .unwrap_err();
        assert!(err.to_string().contains("stuck"), "{err}");
    }
}
