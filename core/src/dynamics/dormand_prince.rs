//! The explicit Dormand–Prince 5(4) scheme with adaptive steps (or fixed ones, to verify a
//! critical step), and where its stability region ends.

use super::DynamicsError;
use super::projection_factors::ProjectionFactors;
use crate::error::DivergenceCause;
use crate::linalg::LinalgError;
use std::time::Instant;

use nalgebra::DVector;

use super::{
    IntegratorParameters, Simulation, State, System, evaluation_workspace::EvaluationWorkspace,
    simulation::sample,
};
use crate::{Error, Progress, Result};

// Dormand–Prince 5(4) tableau.
pub(super) const C: [f64; 7] = [0.0, 1.0 / 5.0, 3.0 / 10.0, 4.0 / 5.0, 8.0 / 9.0, 1.0, 1.0];
pub(super) const A: [[f64; 6]; 7] = [
    [0.0; 6],
    [1.0 / 5.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [3.0 / 40.0, 9.0 / 40.0, 0.0, 0.0, 0.0, 0.0],
    [44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0, 0.0, 0.0, 0.0],
    [
        19372.0 / 6561.0,
        -25360.0 / 2187.0,
        64448.0 / 6561.0,
        -212.0 / 729.0,
        0.0,
        0.0,
    ],
    [
        9017.0 / 3168.0,
        -355.0 / 33.0,
        46732.0 / 5247.0,
        49.0 / 176.0,
        -5103.0 / 18656.0,
        0.0,
    ],
    [
        35.0 / 384.0,
        0.0,
        500.0 / 1113.0,
        125.0 / 192.0,
        -2187.0 / 6784.0,
        11.0 / 84.0,
    ],
];
pub(super) const B5: [f64; 7] = [
    35.0 / 384.0,
    0.0,
    500.0 / 1113.0,
    125.0 / 192.0,
    -2187.0 / 6784.0,
    11.0 / 84.0,
    0.0,
];
const B4: [f64; 7] = [
    5179.0 / 57600.0,
    0.0,
    7571.0 / 16695.0,
    393.0 / 640.0,
    -92097.0 / 339200.0,
    187.0 / 2100.0,
    1.0 / 40.0,
];

/// Largest RMS of the projection's correction after a step, in units of the error tolerance
/// ($a_{tol} + r_{tol}|y_i|$ per component), for which the step's last stage (the derivative
/// at the unprojected $y_5$) is kept as the next step's first: its error is then a thousandth
/// of what the error control accepts per step.
const FSAL_CORRECTION: f64 = 1e-3;

/// Coefficients $c_k$ of the stability polynomial $R(z) = \sum_k c_k z^k$ of the 5th-order
/// solution: $c_0 = 1$, $c_k = b^T A^{k-1} \mathbb 1$ (the tableau is explicit, so the series
/// $1 + z b^T (I - zA)^{-1} \mathbb 1$ ends at $z^7$).
pub fn stability_polynomial() -> Vec<f64> {
    let mut out = vec![1.0];
    let mut v = [1.0; 7]; // A^{k-1} 1
    for _ in 1..=7 {
        out.push((0..7).map(|i| B5[i] * v[i]).sum());
        let mut next = [0.0; 7];
        for (i, n) in next.iter_mut().enumerate() {
            *n = (0..6).map(|j| A[i][j] * v[j]).sum();
        }
        v = next;
    }
    out
}

/// The state derivative $(\dot q, \dot v)$ at `(t, y)` into `out` (the state's length),
/// whose storage is reused.
fn derivative_into(
    sys: &System,
    t: f64,
    y: &DVector<f64>,
    out: &mut DVector<f64>,
    buffers: &mut Buffers,
) -> Result<()> {
    let nq = sys.nq();
    let s = &mut buffers.state;
    s.q.copy_from(&y.rows(0, nq));
    s.v.copy_from(&y.rows(nq, y.len() - nq));
    sys.accelerations_in(t, s, &mut buffers.evaluation)?;
    sys.qdot_into(s, &mut out.rows_mut(0, nq));
    let vd = buffers.evaluation.solution();
    out.rows_mut(nq, vd.len()).copy_from(vd);
    Ok(())
}

/// The state an evaluation reads and the equations of motion's buffers, kept over a run.
struct Buffers {
    state: State,
    evaluation: EvaluationWorkspace,
}

impl Buffers {
    fn new(sys: &System) -> Self {
        Self {
            state: State {
                q: DVector::zeros(sys.nq()),
                v: DVector::zeros(sys.nv()),
            },
            evaluation: EvaluationWorkspace::new(sys),
        }
    }
}

/// Where the stability region of the 5th-order solution ends on the imaginary axis: the first
/// $y > 0$ with $|R(iy)| > 1$ ($y \approx 0.997$; beyond it the growth per step is slow at
/// first, $|R(1.5i)| \approx 1.003$, and $|R(3i)| \approx 1.44$).
pub fn imaginary_stability_limit() -> f64 {
    let c = stability_polynomial();
    let modulus = |y: f64| {
        let (mut re, mut im) = (0.0, 0.0);
        for (k, ck) in c.iter().enumerate() {
            // i^k y^k
            let v = ck * y.powi(k as i32);
            match k % 4 {
                0 => re += v,
                1 => im += v,
                2 => re -= v,
                _ => im -= v,
            }
        }
        (re * re + im * im).sqrt()
    };
    // Scan for the first crossing, then bisect.
    let (mut lo, mut hi) = (1e-3, 1e-3);
    while modulus(hi) <= 1.0 + 1e-14 && hi < 10.0 {
        lo = hi;
        hi += 1e-3;
    }
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if modulus(mid) <= 1.0 + 1e-14 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    lo
}

/// The critical fixed step of the explicit scheme for an undamped system whose highest
/// circular frequency is `omega_max` (rad/s): [`imaginary_stability_limit`] / ω, s.
pub fn critical_step(omega_max: f64) -> f64 {
    imaginary_stability_limit() / omega_max
}

/// Whether every entry of `v` lies within the divergence bound of `p`.
fn within(v: &DVector<f64>, p: &IntegratorParameters) -> bool {
    v.iter().all(|x| x.abs() <= p.divergence_bound)
}

/// The stages' derivatives $k_1 \dots k_7$ and the stage state, in buffers kept over a run.
struct Stages {
    k: Vec<DVector<f64>>,
    ys: DVector<f64>,
    err: DVector<f64>,
    /// The fifth-order solution of the last attempt.
    y5: DVector<f64>,
    buffers: Buffers,
}

impl Stages {
    fn new(sys: &System) -> Self {
        let n = sys.nq() + sys.nv();
        Self {
            k: vec![DVector::zeros(n); 7],
            ys: DVector::zeros(n),
            err: DVector::zeros(n),
            y5: DVector::zeros(n),
            buffers: Buffers::new(sys),
        }
    }

    /// One step of `h` from `(t, y)` whose derivative is `k1`: the scaled error norm (the
    /// fifth-order solution is left in `y5`), or `None` when a stage state left the
    /// divergence bound. A
    /// singular system at a fixed step is divergence, reported with the step.
    fn attempt(
        &mut self,
        sys: &System,
        p: &IntegratorParameters,
        t: f64,
        h: f64,
        y: &DVector<f64>,
        k1: &DVector<f64>,
    ) -> Result<Option<f64>> {
        self.k[0].copy_from(k1);
        for stage in 1..7 {
            self.ys.copy_from(y);
            for (j, kj) in self.k[..stage].iter().enumerate() {
                if A[stage][j] != 0.0 {
                    self.ys.axpy(h * A[stage][j], kj, 1.0);
                }
            }
            // A stage far outside the bound is the step blowing up, not a state to evaluate.
            if !within(&self.ys, p) {
                return Ok(None);
            }
            let (ys, k) = (&self.ys, &mut self.k[stage]);
            match derivative_into(sys, t + C[stage] * h, ys, k, &mut self.buffers) {
                Ok(()) => {}
                // Without error control a blown-up step reaches states whose mass matrix has
                // lost definiteness in floating point: that is the divergence.
                Err(Error::Linalg(LinalgError::SingularMatrix { matrix, .. }))
                    if p.fixed_step.is_some() =>
                {
                    return Err(Error::Dynamics(DynamicsError::Diverged {
                        time: t,
                        cause: DivergenceCause::FixedStepSingular { step: h, matrix },
                    }));
                }
                Err(e) => return Err(e),
            }
        }
        // The 5th-order solution and the error norm (the caller refuses a result beyond the
        // bound or not finite).
        let y5 = &mut self.y5;
        y5.copy_from(y);
        self.err.as_mut_slice().fill(0.0);
        for (j, kj) in self.k.iter().enumerate() {
            y5.axpy(h * B5[j], kj, 1.0);
            self.err.axpy(h * (B5[j] - B4[j]), kj, 1.0);
        }
        let mut norm = 0.0;
        for i in 0..y.len() {
            let sc = p.atol + p.rtol * y[i].abs().max(y5[i].abs());
            norm += (self.err[i] / sc).powi(2);
        }
        Ok(Some((norm / y.len() as f64).sqrt()))
    }
}

/// Integrates `sys` from `initial` with Dormand–Prince 5(4) (see [`super::simulate`]).
pub(super) fn integrate(
    sys: &System,
    initial: &State,
    p: &IntegratorParameters,
    progress: &Progress,
) -> Result<Simulation> {
    let start = Instant::now();
    let nq = sys.nq();
    let mut stages = Stages::new(sys);
    // The projected initial state; then each accepted step's state, projected.
    let mut state = initial.clone();
    sys.project(
        0.0,
        &mut state,
        &mut stages.buffers.evaluation,
        ProjectionFactors::Fresh,
    )?;
    let mut samples = vec![sample(sys, 0.0, &state)];
    let mut y = DVector::zeros(nq + sys.nv());
    y.rows_mut(0, nq).copy_from(&state.q);
    y.rows_mut(nq, sys.nv()).copy_from(&state.v);
    if let Some(dt) = p.fixed_step
        && !(dt > 0.0 && dt.is_finite())
    {
        return Err(DynamicsError::InvalidStep { step: dt }.into());
    }
    let (mut t, mut h) = (0.0f64, p.output_interval.min(1e-3));
    let (mut steps, mut rejected) = (0usize, 0usize);
    let mut next_output = p.output_interval;
    let mut k1 = DVector::zeros(y.len());
    derivative_into(sys, t, &y, &mut k1, &mut stages.buffers)?;
    while t < p.end_time - 1e-12 {
        guard(&y, p, t, steps + rejected)?;
        let target = next_output.min(p.end_time);
        if let Some(dt) = p.fixed_step {
            h = dt;
        }
        h = h.min(target - t);
        let step = stages.attempt(sys, p, t, h, &y, &k1)?;
        let Some(norm) = step.filter(|norm| norm.is_finite() && within(&stages.y5, p)) else {
            if p.fixed_step.is_some() {
                return Err(diverged(
                    t,
                    DivergenceCause::FixedStepBeyondBound {
                        step: h,
                        bound: p.divergence_bound,
                    },
                ));
            }
            h *= 0.2;
            rejected += 1;
            if h < p.min_step {
                return Err(diverged(
                    t,
                    DivergenceCause::StepsCannotHold {
                        bound: p.divergence_bound,
                    },
                ));
            }
            continue;
        };
        if norm <= 1.0 || p.fixed_step.is_some() {
            t += h;
            steps += 1;
            stages.accept(sys, p, t, (&mut state, &mut y, &mut k1))?;
            if (t - target).abs() < 1e-12 {
                samples.push(sample(sys, target, &state));
                progress.advance(t)?;
                next_output += p.output_interval;
            }
        } else {
            rejected += 1;
        }
        let factor = if norm == 0.0 {
            5.0
        } else {
            0.9 * norm.powf(-0.2)
        };
        h *= factor.clamp(0.2, 5.0);
        h = h.min(p.output_interval);
        if p.fixed_step.is_none() && h < p.min_step {
            return Err(diverged(
                t,
                DivergenceCause::StepTooSmall {
                    min_step: p.min_step,
                },
            ));
        }
    }
    Ok(Simulation {
        samples,
        steps,
        rejected,
        newton_iterations: 0,
        evaluations: stages.buffers.evaluation.evaluations,
        wall_time_s: start.elapsed().as_secs_f64(),
    })
}

impl Stages {
    /// Takes the accepted step's `y5` (at `t`) as the projected `state` and the next `y`, and
    /// the derivative there into `k1`.
    fn accept(
        &mut self,
        sys: &System,
        p: &IntegratorParameters,
        t: f64,
        (state, y, k1): (&mut State, &mut DVector<f64>, &mut DVector<f64>),
    ) -> Result<()> {
        let nq = sys.nq();
        let y5 = &self.y5;
        state.q.copy_from(&y5.rows(0, nq));
        state.v.copy_from(&y5.rows(nq, sys.nv()));
        // The last stage was evaluated at y5: its factors correct the velocities.
        sys.project(
            t,
            state,
            &mut self.buffers.evaluation,
            ProjectionFactors::LastEvaluation,
        )?;
        // First same as last: the last stage is the derivative at y5. The projection
        // moves y5 by round-off after every step; only a correction within
        // FSAL_CORRECTION of the error tolerance keeps it, a larger one is re-evaluated.
        let correction = fsal_correction(y5, state, p);
        let reuse = (correction / y.len() as f64).sqrt() <= FSAL_CORRECTION;
        y.rows_mut(0, nq).copy_from(&state.q);
        y.rows_mut(nq, sys.nv()).copy_from(&state.v);
        if reuse {
            k1.copy_from(&self.k[6]);
        } else {
            derivative_into(sys, t, y, k1, &mut self.buffers)?;
        }
        Ok(())
    }
}

/// Stops a run whose state left the bound or that took more than its `attempts` allow.
fn guard(y: &DVector<f64>, p: &IntegratorParameters, t: f64, attempts: usize) -> Result<()> {
    if !within(y, p) {
        return Err(diverged(
            t,
            DivergenceCause::StateBeyondBound {
                bound: p.divergence_bound,
            },
        ));
    }
    if attempts > p.max_steps {
        return Err(diverged(
            t,
            DivergenceCause::TooManySteps {
                max_steps: p.max_steps,
            },
        ));
    }
    Ok(())
}

/// A run that diverged at `time`, and why.
fn diverged(time: f64, cause: DivergenceCause) -> Error {
    Error::Dynamics(DynamicsError::Diverged { time, cause })
}

/// The sum of squares of the projection's moves of `y5` into `state`, each scaled by its
/// error tolerance (first same as last keeps the last stage only when it is small).
fn fsal_correction(y5: &DVector<f64>, state: &State, p: &IntegratorParameters) -> f64 {
    let mut correction = 0.0;
    for (i, (&before, &after)) in y5
        .iter()
        .zip(state.q.iter().chain(state.v.iter()))
        .enumerate()
    {
        let sc = p.atol + p.rtol * y5[i].abs();
        correction += ((after - before) / sc).powi(2);
    }
    correction
}
