//! The implicit generalized-α scheme of Chung and Hulbert (1993) in the form of Arnold and
//! Brüls (2007) for the floating-frame equations, with fixed steps.
//!
//! The unknown of a step is $\dot v_{n+1}$, the accelerations that satisfy the equations of
//! motion at $t_{n+1}$: $\dot v_{n+1} = f(t_{n+1}, q_{n+1}, v_{n+1})$, where $f$ is
//! [`System::accelerations`] (constraints at acceleration level, index 1). An auxiliary
//! acceleration $a$ carries the numerical damping,
//! $(1-\alpha_m)a_{n+1} + \alpha_m a_n = (1-\alpha_f)\dot v_{n+1} + \alpha_f\dot v_n$, and
//! $$\Delta_{n} = h v_n + h^2(\tfrac12-\beta)a_n + h^2\beta a_{n+1},\quad
//! v_{n+1} = v_n + h(1-\gamma)a_n + h\gamma a_{n+1},$$
//! with $q_{n+1} = q_n \oplus \Delta_n$ (translations and modal coordinates added, each body
//! turned by the body-axis rotation vector, so Euler parameters stay unit). For a spectral
//! radius $\rho_\infty \in [0, 1]$ at infinite frequency,
//! $\alpha_m = \frac{2\rho_\infty-1}{\rho_\infty+1}$, $\alpha_f =
//! \frac{\rho_\infty}{\rho_\infty+1}$,
//! $\gamma = \tfrac12-\alpha_m+\alpha_f$, $\beta = \tfrac14(\gamma+\tfrac12)^2$: second order,
//! unconditionally stable for linear systems; $\rho_\infty = 1$ is the trapezoidal rule, which
//! keeps the energy of an undamped linear system.
//!
//! Newton's method solves for $\dot v_{n+1}$ with the iteration matrix
//! $J = I - \frac{1-\alpha_f}{1-\alpha_m}\left(h^2\beta F_q + h\gamma F_v\right)$, where
//! $F_q$, $F_v$ are finite-difference derivatives of $f$ with respect to position increments
//! and velocities. $J$ is kept across steps (the stiff part, $M^{-1}K$, is constant) and
//! rebuilt only when the iterations stall. They stop when the correction is below 1e-10 of
//! the largest acceleration, or, from the third on, below 1e-8 and no longer halving: the
//! round-off floor of a large stiff model's accelerations. Positions and velocities are
//! projected onto the constraints after every step as with the explicit scheme.

use super::DynamicsError;
use super::projection_factors::ProjectionFactors;
use crate::error::DivergenceCause;
use std::time::Instant;

use faer::{
    Mat,
    linalg::solvers::{PartialPivLu, Solve},
};
use nalgebra::{DMatrix, DVector};

use super::{
    IntegratorParameters, Simulation, State, System, evaluation_workspace::EvaluationWorkspace,
    simulation::sample,
};
use crate::{Error, Progress, Result};

/// Newton iterations per step before the iteration matrix is rebuilt (and, with a fresh one,
/// before the step fails).
const MAX_NEWTON_ITERATIONS: usize = 12;
/// Convergence: the Newton correction below this fraction of the largest acceleration.
const NEWTON_TOLERANCE: f64 = 1e-10;
/// Convergence at the round-off floor: from the third iteration on, a correction below this
/// fraction that is no longer half the one before has stopped contracting. A large stiff model
/// (the 16 × 8 × 4 slab without reduction, 2 301 coordinates) evaluates its accelerations
/// only to about 2e-10 of their size, so [`NEWTON_TOLERANCE`] is out of its reach there; a
/// model whose iterations still contract keeps to [`NEWTON_TOLERANCE`].
const NEWTON_FLOOR: f64 = 1e-8;

/// The four parameters of the scheme.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GeneralizedAlphaCoefficients {
    /// $\alpha_m$.
    pub alpha_m: f64,
    /// $\alpha_f$.
    pub alpha_f: f64,
    /// $\gamma$.
    pub gamma: f64,
    /// $\beta$.
    pub beta: f64,
}

impl GeneralizedAlphaCoefficients {
    /// Chung and Hulbert's optimal coefficients for the spectral radius $\rho_\infty$.
    pub fn from_spectral_radius(rho: f64) -> Self {
        let alpha_m = (2.0 * rho - 1.0) / (rho + 1.0);
        let alpha_f = rho / (rho + 1.0);
        let gamma = 0.5 - alpha_m + alpha_f;
        Self {
            alpha_m,
            alpha_f,
            gamma,
            beta: 0.25 * (gamma + 0.5).powi(2),
        }
    }
}

/// Steps whose lengths differ by less than this fraction share one factorisation.
const SAME_STEP: f64 = 1e-9;
/// Factorisations kept for different step lengths (a step that does not divide the output
/// interval alternates between two or three lengths).
const KEPT_FACTORS: usize = 4;

/// The derivatives the iteration matrix is built from, and its inverses for the step lengths
/// met since they were taken.
///
/// $J = I - c\,(h^2\beta F_q + h\gamma F_v)$ is close to the identity (the step resolves
/// the model's motion), so its inverse is formed once from a partial-pivoting LU and checked,
/// $\|JJ^{-1} - I\|_{\max} \le 10^{-10}$: a Newton correction is then one product of
/// $n_v^2$ operations, without the triangular solves' per-call overhead on the few dozen
/// coordinates of a reduced model. A $J$ whose inverse fails the check keeps its LU.
struct IterationMatrix {
    /// $F_q$ and $F_v$ (nv × nv each).
    f_q: Mat<f64>,
    f_v: Mat<f64>,
    /// $(h, J(h)^{-1})$, newest last.
    factors: Vec<(f64, IterationInverse)>,
}

/// $J^{-1}$ applied to a residual: explicitly, or by the LU when the explicit inverse failed
/// its check.
enum IterationInverse {
    Explicit(DMatrix<f64>),
    Lu(PartialPivLu<f64>),
}

impl IterationInverse {
    fn new(j: Mat<f64>) -> Self {
        let nv = j.nrows();
        let lu = j.partial_piv_lu();
        let inverse = lu.solve(Mat::<f64>::identity(nv, nv));
        let product = &j * &inverse;
        let defect = (0..nv)
            .flat_map(|r| (0..nv).map(move |k| (r, k)))
            .map(|(r, k)| (product[(r, k)] - if r == k { 1.0 } else { 0.0 }).abs())
            .fold(0.0f64, f64::max);
        if defect <= 1e-10 {
            Self::Explicit(DMatrix::from_fn(nv, nv, |r, k| inverse[(r, k)]))
        } else {
            Self::Lu(lu)
        }
    }

    /// `out` = $J^{-1}$ `r`.
    fn apply(&self, r: &DVector<f64>, out: &mut DVector<f64>) {
        match self {
            Self::Explicit(inverse) => out.gemv(1.0, inverse, r, 0.0),
            Self::Lu(lu) => {
                let dx = lu.solve(Mat::from_fn(r.len(), 1, |i, _| r[i]));
                for (o, i) in out.iter_mut().zip(0..) {
                    *o = dx[(i, 0)];
                }
            }
        }
    }
}

impl IterationMatrix {
    fn new(f_q: Mat<f64>, f_v: Mat<f64>) -> Self {
        Self {
            f_q,
            f_v,
            factors: Vec::new(),
        }
    }

    /// $J(h)^{-1}$: a kept one for the same step length, else a new one.
    fn for_step(&mut self, h: f64, c: &GeneralizedAlphaCoefficients) -> &IterationInverse {
        let kept = self
            .factors
            .iter()
            .position(|&(k, _)| (k - h).abs() <= SAME_STEP * h);
        let index = match kept {
            Some(i) => i,
            None => {
                if self.factors.len() == KEPT_FACTORS {
                    self.factors.remove(0);
                }
                let nv = self.f_q.nrows();
                let ratio = (1.0 - c.alpha_f) / (1.0 - c.alpha_m);
                let j = Mat::from_fn(nv, nv, |r, k| {
                    let identity = if r == k { 1.0 } else { 0.0 };
                    identity
                        - ratio
                            * (h * h * c.beta * self.f_q[(r, k)] + h * c.gamma * self.f_v[(r, k)])
                });
                self.factors.push((h, IterationInverse::new(j)));
                self.factors.len() - 1
            }
        };
        &self.factors[index].1
    }
}

/// Finite-difference derivatives of the accelerations at `(t, s)` with respect to position
/// increments and velocities. The base point is evaluated here: after a projection the state
/// is no longer the one the step's accelerations belong to.
fn derivatives(
    sys: &System,
    t: f64,
    s: &State,
    ws: &mut EvaluationWorkspace,
) -> Result<(Mat<f64>, Mat<f64>)> {
    let nv = sys.nv();
    sys.accelerations_in(t, s, ws)?;
    let f0 = ws.solution().clone();
    let mut f_q = Mat::zeros(nv, nv);
    let mut f_v = Mat::zeros(nv, nv);
    for j in 0..nv {
        let eps = 1e-7;
        let mut dx = DVector::zeros(nv);
        dx[j] = eps;
        let mut moved = s.clone();
        sys.apply_increment(&mut moved, &dx);
        sys.accelerations_in(t, &moved, ws)?;
        for i in 0..nv {
            f_q[(i, j)] = (ws.solution()[i] - f0[i]) / eps;
        }
        let eps_v = 1e-7 * s.v[j].abs().max(1.0);
        let mut faster = s.clone();
        faster.v[j] += eps_v;
        sys.accelerations_in(t, &faster, ws)?;
        for i in 0..nv {
            f_v[(i, j)] = (ws.solution()[i] - f0[i]) / eps_v;
        }
    }
    Ok((f_q, f_v))
}

/// The scheme's coefficients for the spectral radius `rho` (in [0, 1]) with a positive,
/// finite `step`; either out of range is named.
fn checked_coefficients(step: f64, rho: f64) -> Result<GeneralizedAlphaCoefficients> {
    if !(step > 0.0 && step.is_finite()) {
        return Err(DynamicsError::InvalidStep { step }.into());
    }
    if !(0.0..=1.0).contains(&rho) {
        return Err(DynamicsError::InvalidSpectralRadius { rho }.into());
    }
    Ok(GeneralizedAlphaCoefficients::from_spectral_radius(rho))
}

/// Integrates `sys` with generalized-α steps of `step` seconds (shortened only to land on
/// output times) and spectral radius `rho`; see the module documentation. Same outputs and
/// divergence checks as the explicit scheme; `rejected` counts rebuilt iteration matrices.
pub(crate) fn integrate(
    sys: &System,
    initial: &State,
    p: &IntegratorParameters,
    step: f64,
    rho: f64,
    progress: &Progress,
) -> Result<Simulation> {
    let c = checked_coefficients(step, rho)?;
    let clock = Instant::now();
    let mut ws = EvaluationWorkspace::new(sys);
    let mut s = initial.clone();
    sys.project(0.0, &mut s, &mut ws, ProjectionFactors::Fresh)?;
    let mut samples = vec![sample(sys, 0.0, &s)];
    let mut t = 0.0f64;
    sys.accelerations_in(t, &s, &mut ws)?;
    let mut vdot = ws.solution().clone();
    let mut a = vdot.clone();
    let (f_q, f_v) = derivatives(sys, t, &s, &mut ws)?;
    let mut matrix = IterationMatrix::new(f_q, f_v);
    let mut buffers = NewtonBuffers::new(&s);
    let (mut steps, mut rebuilt, mut newton) = (0usize, 0usize, 0usize);
    let mut next_output = p.output_interval;
    while t < p.end_time - 1e-12 {
        if steps > p.max_steps {
            return Err(Error::Dynamics(DynamicsError::Diverged {
                time: t,
                cause: DivergenceCause::TooManySteps {
                    max_steps: p.max_steps,
                },
            }));
        }
        let target = next_output.min(p.end_time);
        let h = step.min(target - t);
        let t1 = t + h;
        let mut fresh = false;
        loop {
            let start = StepStart {
                s: &s,
                vdot: &vdot,
                a: &a,
                h,
                t1,
            };
            let inverse = matrix.for_step(h, &c);
            match start.solve(sys, &c, inverse, &mut newton, &mut ws, &mut buffers) {
                Ok(()) => break,
                Err(_) if !fresh => {
                    // Rebuild the iteration matrix at the start of the step and try again.
                    let (f_q, f_v) = derivatives(sys, t, &s, &mut ws)?;
                    matrix = IterationMatrix::new(f_q, f_v);
                    rebuilt += 1;
                    fresh = true;
                }
                Err(residual) => {
                    return Err(Error::Dynamics(DynamicsError::NewtonFailed {
                        time: t1,
                        iterations: MAX_NEWTON_ITERATIONS,
                        residual,
                    }));
                }
            }
        }
        let s1 = &mut buffers.s1;
        if !(s1.q.iter().chain(s1.v.iter())).all(|v| v.is_finite() && v.abs() <= p.divergence_bound)
        {
            return Err(Error::Dynamics(DynamicsError::Diverged {
                time: t1,
                cause: DivergenceCause::StateBeyondBound {
                    bound: p.divergence_bound,
                },
            }));
        }
        // The last Newton evaluation was at this end state but for the last correction (at
        // most 1e-10 of the accelerations, times h²β): its factors project it, checked.
        sys.project(t1, s1, &mut ws, ProjectionFactors::LastEvaluationChecked)?;
        t = t1;
        steps += 1;
        std::mem::swap(&mut s, &mut buffers.s1);
        std::mem::swap(&mut a, &mut buffers.a1);
        std::mem::swap(&mut vdot, &mut buffers.x);
        if (t - target).abs() < 1e-12 {
            samples.push(sample(sys, target, &s));
            progress.advance(t)?;
            next_output += p.output_interval;
        }
    }
    Ok(Simulation {
        samples,
        steps,
        rejected: rebuilt,
        newton_iterations: newton,
        evaluations: ws.evaluations,
        wall_time_s: clock.elapsed().as_secs_f64(),
    })
}

/// Where a step starts: $t_n$, $q_n$, $v_n$, $\dot v_n$, $a_n$.
struct StepStart<'a> {
    s: &'a State,
    vdot: &'a DVector<f64>,
    a: &'a DVector<f64>,
    /// The step's size and its end time, s.
    h: f64,
    t1: f64,
}

/// The buffers of a step's Newton iterations, reused from step to step: an iteration
/// allocates nothing.
struct NewtonBuffers {
    /// The state at the end of the step for the current accelerations.
    s1: State,
    /// $a_{n+1}$ for them.
    a1: DVector<f64>,
    /// $\Delta_n$.
    increment: DVector<f64>,
    /// The iterate $\dot v_{n+1}$.
    x: DVector<f64>,
    /// $x - f(x)$, then the correction.
    residual: DVector<f64>,
    correction: DVector<f64>,
}

impl NewtonBuffers {
    fn new(s: &State) -> Self {
        let nv = s.v.len();
        Self {
            s1: s.clone(),
            a1: DVector::zeros(nv),
            increment: DVector::zeros(nv),
            x: DVector::zeros(nv),
            residual: DVector::zeros(nv),
            correction: DVector::zeros(nv),
        }
    }
}

impl StepStart<'_> {
    /// $a_{n+1}$, $q_{n+1}$ and $v_{n+1}$ for the accelerations `b.x` $= \dot v_{n+1}$, into
    /// `b.a1` and `b.s1`.
    fn advance(&self, sys: &System, c: &GeneralizedAlphaCoefficients, b: &mut NewtonBuffers) {
        let h = self.h;
        let (hb, hh, hg) = (h * h * c.beta, h * h * (0.5 - c.beta), h * (1.0 - c.gamma));
        for i in 0..b.x.len() {
            let a1 = (b.x[i] * (1.0 - c.alpha_f) + self.vdot[i] * c.alpha_f
                - self.a[i] * c.alpha_m)
                / (1.0 - c.alpha_m);
            b.a1[i] = a1;
            b.increment[i] = self.s.v[i] * h + self.a[i] * hh + a1 * hb;
            b.s1.v[i] = self.s.v[i] + self.a[i] * hg + a1 * (h * c.gamma);
        }
        b.s1.q.copy_from(&self.s.q);
        sys.apply_increment(&mut b.s1, &b.increment);
    }

    /// Newton's iterations from the guess $\dot v_{n+1} = \dot v_n$, in `b` (`b.x`, and the
    /// end state in `b.s1`, `b.a1`), or the last correction's size when they do not converge
    /// in [`MAX_NEWTON_ITERATIONS`].
    fn solve(
        &self,
        sys: &System,
        c: &GeneralizedAlphaCoefficients,
        inverse: &IterationInverse,
        count: &mut usize,
        ws: &mut EvaluationWorkspace,
        b: &mut NewtonBuffers,
    ) -> std::result::Result<(), f64> {
        b.x.copy_from(self.vdot);
        let mut correction = f64::INFINITY;
        for iteration in 0..MAX_NEWTON_ITERATIONS {
            let previous = correction;
            *count += 1;
            self.advance(sys, c, b);
            if sys.accelerations_in(self.t1, &b.s1, ws).is_err() {
                return Err(f64::INFINITY);
            }
            let f = ws.solution();
            for ((r, x), f) in b.residual.iter_mut().zip(b.x.iter()).zip(f.iter()) {
                *r = x - f;
            }
            inverse.apply(&b.residual, &mut b.correction);
            let scale = b.x.amax().max(f.amax()).max(1e-12);
            correction = b.correction.amax() / scale;
            if !correction.is_finite() {
                return Err(f64::INFINITY);
            }
            b.x -= &b.correction;
            if newton_converged(iteration, correction, previous) {
                self.advance(sys, c, b);
                return Ok(());
            }
        }
        Err(correction)
    }
}

/// Whether Newton's iterations stop after iteration `iteration` (from 0) with the relative
/// `correction`, `previous` the one before: below [`NEWTON_TOLERANCE`], or, from the third
/// on, below [`NEWTON_FLOOR`] and no longer halving (the accelerations' round-off floor).
fn newton_converged(iteration: usize, correction: f64, previous: f64) -> bool {
    correction <= NEWTON_TOLERANCE
        || (iteration >= 2 && correction <= NEWTON_FLOOR && correction > 0.5 * previous)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The iterations stop at the tolerance when they contract, and at the floor only when
    /// they have stopped contracting: a run that still halves goes on to 1e-10.
    #[test]
    fn newton_stops_at_the_tolerance_or_where_it_stalls_on_round_off() {
        let stop = |corrections: &[f64]| {
            let mut previous = f64::INFINITY;
            corrections.iter().enumerate().position(|(i, &c)| {
                let done = newton_converged(i, c, previous);
                previous = c;
                done
            })
        };
        // Contracting by 10 per iteration: the tolerance, not the floor, ends it.
        assert_eq!(
            stop(&[1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10]),
            Some(8)
        );
        // Halving below the floor: still contracting, it goes on.
        let halving: Vec<f64> = (0..12).map(|k| 4e-9 * 0.45f64.powi(k)).collect();
        assert_eq!(stop(&halving), Some(5));
        // The 16 x 8 x 4 slab's NR: stuck near 2e-10 (the failure before the floor).
        assert_eq!(stop(&[3e-3, 4e-7, 2.1e-10, 2.07e-10, 2.2e-10]), Some(3));
        // Stuck above the floor: never converged.
        assert_eq!(stop(&[1e-6, 9e-7, 9e-7, 9e-7]), None);
        // The first two iterations never stop at the floor.
        assert_eq!(stop(&[5e-9, 5e-9, 5e-9]), Some(2));
    }
}
