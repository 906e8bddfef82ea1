//! Generalized-α (Chung and Hulbert 1993) for the linear, time-varying equations of a body on
//! a driven frame, $M\ddot u + C(t)\dot u + K(t)u = f(t)$ with $C = 2\dot\theta G$ and
//! $K(t) = K + \ddot\theta G + \dot\theta^2 H + K_\sigma(t)$ ([`DrivenFrameBody`]; $K_\sigma$
//! the geometric stiffness of the frame's loads, [`super::FrameStiffening`], if the body
//! carries it).
//!
//! The balance holds at $t_{n+1-\alpha_f}$ with the accelerations at $t_{n+1-\alpha_m}$:
//! $M a_{n+1-\alpha_m} + C v_{n+1-\alpha_f} + K u_{n+1-\alpha_f} = f(t_{n+1-\alpha_f})$,
//! $x_{n+1-\alpha} = (1-\alpha)x_{n+1} + \alpha x_n$, with Newmark's updates
//! $u_{n+1} = u_n + hv_n + h^2((\tfrac12-\beta)a_n + \beta a_{n+1})$,
//! $v_{n+1} = v_n + h((1-\gamma)a_n + \gamma a_{n+1})$; the coefficients are those of
//! [`GeneralizedAlphaCoefficients::from_spectral_radius`]. Each step solves one linear system
//! in $a_{n+1}$ whose matrix is $(1-\alpha_m)M + (1-\alpha_f)(\gamma h C + \beta h^2 K(t))$:
//! its constant part $(1-\alpha_m)M + (1-\alpha_f)\beta h^2 K$ is factored once.
//!
//! The body starts from rest in static equilibrium under the loads at $t = 0$ ($Ku_0 =
//! f(0)$, gravity only for a spin-up), so nothing but the motion excites it.

use std::time::Instant;

use nalgebra::Vector3;

use super::{
    GeneralizedAlphaCoefficients, Shake, SpinUp, combination::Combination,
    driven_frame_body::DrivenFrameBody, stiffening_coefficients,
};
use crate::{Progress, Result};

/// The steps of a driven integration.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DrivenIntegration {
    /// Step h, s.
    pub step: f64,
    /// End time, s.
    pub end: f64,
    /// Spectral radius at infinite frequency, $\rho_\infty \in [0, 1]$.
    pub spectral_radius: f64,
    /// Output every this many steps (and at the end).
    pub output_every: usize,
}

/// The driving: the frame's spin-up about an axis through its origin, a shaking of the origin,
/// and gravity in ground axes (the body's length unit per s²).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Driving {
    /// The frame's turning.
    pub spin: SpinUp,
    /// The origin's translation, if any.
    pub shake: Option<Shake>,
    /// Gravity in ground axes.
    pub gravity: Vector3<f64>,
}

impl Driving {
    /// $(\dot\theta, \ddot\theta, A^T(g - \ddot r))$ at `t`: a translation of the frame loads
    /// the body as gravity does, with the opposite sign.
    pub fn at(&self, t: f64) -> (f64, f64, Vector3<f64>) {
        let (_, rate, acceleration) = self.spin.at(t);
        let ground = self.gravity - self.shake.map_or(Vector3::zeros(), |s| s.acceleration(t));
        let g_body = if ground == Vector3::zeros() {
            ground
        } else {
            self.spin.rotation(t).inverse() * ground
        };
        (rate, acceleration, g_body)
    }
}

/// The displacements at rest in static equilibrium under the loads at t = 0 ($Ku_0 = f(0)$:
/// the frame at rest, so $K(0) = K$), and the Krylov iterations the solve took: where both
/// integrators start.
pub(super) fn static_start(
    body: &mut DrivenFrameBody,
    driving: &Driving,
) -> Result<(Vec<f64>, usize)> {
    let (rate, acceleration, g_body) = driving.at(0.0);
    let f0 = body.load(rate, acceleration, g_body);
    let stiffness = Combination {
        k: 1.0,
        g: acceleration,
        h: rate * rate,
        sigma: stiffening_coefficients(rate, acceleration, g_body),
        ..Default::default()
    };
    body.solve(stiffness, &f0, vec![0.0; body.dim()])
}

/// What an integration took.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct DrivenCost {
    /// Steps.
    pub steps: usize,
    /// Solves of the effective matrix (one per step, plus the initial static solve).
    pub solves: usize,
    /// Krylov iterations over all solves (0 for a dense body).
    pub iterations: usize,
    /// Wall time of the integration alone (the observer's time left out), s.
    pub online_s: f64,
    /// Entries of the sparse factor of the constant part (0 for a dense body).
    pub factor_nnz: usize,
}

/// Integrates `body` under `driving` from static equilibrium at rest, calling `observe(t, u,
/// v, a)` at t = 0, every `output_every` steps and at the end (its time is not counted).
pub fn integrate_driven(
    body: &mut DrivenFrameBody,
    driving: &Driving,
    steps: &DrivenIntegration,
    progress: &Progress,
    mut observe: impl FnMut(f64, &[f64], &[f64], &[f64]) -> Result<()>,
) -> Result<DrivenCost> {
    let started = Instant::now();
    let mut observer_s = 0.0;
    let n = body.dim();
    let co = GeneralizedAlphaCoefficients::from_spectral_radius(steps.spectral_radius);
    let h = steps.step;
    let count = (steps.end / h).round().max(1.0) as usize;
    let (mut u, mut iterations) = static_start(body, driving)?;
    let mut v = vec![0.0; n];
    let mut a = vec![0.0; n];
    let mut watch = |t: f64, u: &[f64], v: &[f64], a: &[f64]| -> Result<()> {
        let s = Instant::now();
        observe(t, u, v, a)?;
        observer_s += s.elapsed().as_secs_f64();
        Ok(())
    };
    watch(0.0, &u, &v, &a)?;
    progress.start_simulation(count as f64 * h)?;
    for step in 1..=count {
        let t = step as f64 * h;
        progress.advance(t)?;
        let tf = t - co.alpha_f * h;
        let (rate, acceleration, g_body) = driving.at(tf);
        let f = body.load(rate, acceleration, g_body);
        // The predictors at t_{n+1-αf} with a_{n+1} = 0.
        let v_star: Vec<f64> = v
            .iter()
            .zip(&a)
            .map(|(v, a)| v + (1.0 - co.alpha_f) * h * (1.0 - co.gamma) * a)
            .collect();
        let u_star: Vec<f64> = (0..n)
            .map(|i| u[i] + (1.0 - co.alpha_f) * (h * v[i] + h * h * (0.5 - co.beta) * a[i]))
            .collect();
        let ma = body.mul(
            Combination {
                m: co.alpha_m,
                ..Default::default()
            },
            &a,
        );
        let cv = body.mul(
            Combination {
                g: 2.0 * rate,
                ..Default::default()
            },
            &v_star,
        );
        let sigma = stiffening_coefficients(rate, acceleration, g_body);
        let ku = body.mul(
            Combination {
                k: 1.0,
                g: acceleration,
                h: rate * rate,
                sigma,
                ..Default::default()
            },
            &u_star,
        );
        let b: Vec<f64> = (0..n).map(|i| f[i] - ma[i] - cv[i] - ku[i]).collect();
        let centrifugal = (1.0 - co.alpha_f) * co.beta * h * h * rate * rate;
        let mut stiffening = sigma.map(|c| (1.0 - co.alpha_f) * co.beta * h * h * c);
        // The rate² case scales exactly as H does: the dense body adds the two as one matrix.
        stiffening[0] = centrifugal;
        let effective = Combination {
            m: 1.0 - co.alpha_m,
            k: (1.0 - co.alpha_f) * co.beta * h * h,
            g: (1.0 - co.alpha_f) * (2.0 * co.gamma * h * rate + co.beta * h * h * acceleration),
            h: centrifugal,
            sigma: stiffening,
        };
        let (a_next, its) = body.solve(effective, &b, a.clone())?;
        iterations += its;
        for i in 0..n {
            u[i] += h * v[i] + h * h * ((0.5 - co.beta) * a[i] + co.beta * a_next[i]);
            v[i] += h * ((1.0 - co.gamma) * a[i] + co.gamma * a_next[i]);
        }
        a = a_next;
        if step % steps.output_every.max(1) == 0 || step == count {
            watch(t, &u, &v, &a)?;
        }
    }
    Ok(DrivenCost {
        steps: count,
        solves: count + 1,
        iterations,
        online_s: started.elapsed().as_secs_f64() - observer_s,
        factor_nnz: body.factor_nnz(),
    })
}
