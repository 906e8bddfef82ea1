//! The explicit Dormand–Prince scheme (its 5th-order solution, fixed steps) for a reduced body
//! on a driven frame, in first-order form $\dot u = v$,
//! $\dot v = M^{-1}(f(t) - 2\dot\theta G v - (K + \ddot\theta G + \dot\theta^2 H)u)$, from
//! static equilibrium at rest as [`super::integrate_driven`]. Its step is bounded by the
//! stability region: above [`super::critical_step`] of the model's highest frequency the
//! deflection grows without bound, and the run stops with [`DynamicsError::Diverged`] once it
//! exceeds `bound` (the body's size: no small-strain answer is left).

use std::time::Instant;

use nalgebra::{DMatrix, DVector};

use super::{
    DrivenCost, DrivenFrameBody, Driving, DynamicsError,
    combination::Combination,
    dormand_prince::{A, B5, C},
    driven_integration::static_start,
    stiffening_coefficients,
};
use crate::{Progress, Result, error::DivergenceCause};

/// The fixed steps of an explicit driven run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DrivenExplicit {
    /// Step, s.
    pub step: f64,
    /// End time, s.
    pub end: f64,
    /// Output every this many steps (and at the end).
    pub output_every: usize,
    /// Largest nodal-coordinate magnitude before the run counts as diverged (the body's
    /// length unit; for modal coordinates of mass-normalised modes a bound on their size).
    pub bound: f64,
}

/// $\dot y = [v; a(t, u, v)]$ of the reduced `body` under `driving` at `t`, $y = [u; v]$:
/// $a = M^{-1}(f - (K + \dot\Omega G + \Omega^2H + K_\sigma)u - 2\Omega Gv)$.
fn driven_derivative(
    (body, mass_inverse): (&DrivenFrameBody, &DMatrix<f64>),
    driving: &Driving,
    t: f64,
    y: &DVector<f64>,
) -> DVector<f64> {
    let n = body.dim();
    let (rate, acceleration, g_body) = driving.at(t);
    let (u, v) = (y.rows(0, n), y.rows(n, n));
    let f = body.load(rate, acceleration, g_body);
    let ku = body.mul(
        Combination {
            k: 1.0,
            g: acceleration,
            h: rate * rate,
            sigma: stiffening_coefficients(rate, acceleration, g_body),
            ..Default::default()
        },
        u.as_slice(),
    );
    let cv = body.mul(
        Combination {
            g: 2.0 * rate,
            ..Default::default()
        },
        v.as_slice(),
    );
    let rhs = DVector::from_fn(n, |i, _| f[i] - ku[i] - cv[i]);
    let a = mass_inverse * rhs;
    let mut out = DVector::zeros(2 * n);
    out.rows_mut(0, n).copy_from(&v);
    out.rows_mut(n, n).copy_from(&a);
    out
}

/// Integrates the reduced `body` under `driving` with fixed Dormand–Prince steps, calling
/// `observe(t, u, v, a)` at t = 0, every `output_every` steps and at the end. A full (sparse)
/// body is refused: its consistent mass would need a solve per stage at a step of the mesh's
/// highest frequency.
pub fn integrate_driven_explicit(
    body: &mut DrivenFrameBody,
    driving: &Driving,
    steps: &DrivenExplicit,
    progress: &Progress,
    mut observe: impl FnMut(f64, &[f64], &[f64], &[f64]) -> Result<()>,
) -> Result<DrivenCost> {
    let started = Instant::now();
    let mut observer_s = 0.0;
    let n = body.dim();
    let mass_inverse: DMatrix<f64> = body.mass_inverse()?;
    let h = steps.step;
    // The steps that reach the end (a step that divides it exactly counts once).
    let count = (steps.end / h - 1e-9).ceil().max(1.0) as usize;
    let (u0, _) = static_start(body, driving)?;
    // y = [u; v]; ẏ = [v; a(t, u, v)].
    let derivative =
        |t: f64, y: &DVector<f64>| driven_derivative((body, &mass_inverse), driving, t, y);
    let mut y = DVector::zeros(2 * n);
    y.rows_mut(0, n).copy_from_slice(&u0);
    let mut watch = |t: f64, y: &DVector<f64>, dy: &DVector<f64>| -> Result<()> {
        let s = Instant::now();
        observe(
            t,
            y.rows(0, n).as_slice(),
            y.rows(n, n).as_slice(),
            dy.rows(n, n).as_slice(),
        )?;
        observer_s += s.elapsed().as_secs_f64();
        Ok(())
    };
    watch(0.0, &y, &derivative(0.0, &y))?;
    progress.start_simulation(count as f64 * h)?;
    let mut k: Vec<DVector<f64>> = Vec::with_capacity(7);
    for step in 1..=count {
        let t0 = (step - 1) as f64 * h;
        progress.advance(t0 + h)?;
        k.clear();
        for stage in 0..6 {
            let mut ys = y.clone();
            for (j, kj) in k.iter().enumerate() {
                if A[stage][j] != 0.0 {
                    ys.axpy(h * A[stage][j], kj, 1.0);
                }
            }
            k.push(derivative(t0 + C[stage] * h, &ys));
        }
        for (j, kj) in k.iter().enumerate() {
            if B5[j] != 0.0 {
                y.axpy(h * B5[j], kj, 1.0);
            }
        }
        let t = step as f64 * h;
        let largest = y.rows(0, n).amax();
        if !(largest.is_finite() && largest <= steps.bound) {
            return Err(DynamicsError::Diverged {
                time: t,
                cause: DivergenceCause::CoordinateBeyondBound {
                    largest,
                    bound: steps.bound,
                    step: h,
                },
            }
            .into());
        }
        if step % steps.output_every.max(1) == 0 || step == count {
            watch(t, &y, &derivative(t, &y))?;
        }
    }
    Ok(DrivenCost {
        steps: count,
        solves: 1,
        iterations: 0,
        online_s: started.elapsed().as_secs_f64() - observer_s,
        factor_nnz: 0,
    })
}
