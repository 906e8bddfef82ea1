//! A body's response across its interfaces over a band, of the full body once and of any
//! reduced model against it: $H(\omega) = L^T(K - \omega^2M)^{-1}L$ with $L$ the interface
//! loads (a unit force per plain interface DOF, six per master) and its work-conjugate
//! displacements as outputs.

use std::time::Instant;

use faer::{Mat, MatRef};

use crate::{
    Progress, Result,
    analysis::{
        FrequencyResponse, RESONANCE_CLEARANCE, ZeroEnergyCount, count_zero_energy_modes,
        full_dynamic_compliance, off_resonance_frequencies, reduced_dynamic_compliance,
    },
    fem::FeModel,
    linalg::{GeneralizedEigen, LinalgError, SymbolicFactor, SymmetricFactor, nested_dissection},
    reduction::{Basis, InterfaceLoads, ReductionError},
};

/// Frequencies at which the response is compared over a band.
pub const RESPONSE_POINTS: usize = 24;

/// The full body's interface response over a band.
#[derive(Debug, Clone)]
pub struct InterfaceResponse {
    /// The loads (inputs and collocated outputs).
    pub loads: InterfaceLoads,
    /// The full body's response, at [`RESPONSE_POINTS`] frequencies over (0, top] at least
    /// [`RESONANCE_CLEARANCE`] from every one of its natural frequencies given.
    pub full: FrequencyResponse,
    /// Wall time of the full body's response, s.
    pub full_s: f64,
}

impl InterfaceResponse {
    /// The full body's response to `loads` up to `top_hz`, away from `natural_hz` (its
    /// elastic frequencies in the band and above it).
    pub fn of_full_body(
        model: &FeModel,
        loads: InterfaceLoads,
        top_hz: f64,
        natural_hz: &[f64],
        progress: &Progress,
    ) -> Result<Self> {
        let hz = off_resonance_frequencies(top_hz, RESPONSE_POINTS, natural_hz);
        let started = Instant::now();
        let full = full_dynamic_compliance(model, loads.matrix.as_ref(), &hz, progress)?;
        Ok(Self {
            loads,
            full,
            full_s: started.elapsed().as_secs_f64(),
        })
    }

    /// The response of the reduced model of `basis` at the same frequencies.
    pub fn of_model(&self, model: &FeModel, basis: &Basis) -> Result<FrequencyResponse> {
        reduced_dynamic_compliance(model, basis, self.loads.matrix.as_ref(), &self.full.hz)
    }

    /// The model's largest magnitude error against the full body over the band, per channel
    /// relative to the channel's peak
    /// ([`FrequencyResponse::relative_magnitude_error`]).
    pub fn error_of(&self, model: &FeModel, basis: &Basis) -> Result<f64> {
        self.of_model(model, basis)?
            .relative_magnitude_error(&self.full)
    }

    /// What was compared, in words, for tables.
    pub fn describe(&self) -> String {
        format!(
            "the interface response H = L^T (K − ω²M)⁻¹ L of the {} interface loads, undamped, at \
             {} frequencies over (0, {:.4}] Hz at least {:.0} % from every full-body resonance \
             (the full body by a sparse LDL^T per frequency, every solve refined to a residual \
             of 1e-9: {:.2} s); per channel the largest magnitude difference over the band \
             relative to the channel's peak, the largest channel",
            self.loads.count(),
            self.full.hz.len(),
            self.full.hz.last().copied().unwrap_or(0.0),
            100.0 * RESONANCE_CLEARANCE,
            self.full_s
        )
    }
}

/// Most elastic modes [`modes_up_to`] solves for before it gives up.
pub const MOST_BAND_MODES: usize = 400;

/// The body's zero-energy modes and enough elastic ones: every one up to `band_hz` and the
/// next above it (doubling the count from 12 until one lies above), or `elastic` of them when
/// no band is given.
pub fn modes_up_to(
    model: &FeModel,
    band_hz: Option<f64>,
    elastic: usize,
    progress: &Progress,
) -> Result<ZeroEnergyCount> {
    let Some(top) = band_hz else {
        return count_zero_energy_modes(model, elastic);
    };
    let mut wanted = elastic.max(12);
    loop {
        progress.phase(&format!("full body: lowest {wanted} elastic modes"))?;
        let full = count_zero_energy_modes(model, wanted)?;
        let hz = full.elastic_hz();
        if hz.last().is_some_and(|&f| f > top) || hz.len() < wanted {
            return Ok(full);
        }
        if wanted >= MOST_BAND_MODES {
            return Err(ReductionError::TooManyModes {
                requested: 2 * wanted,
                available: MOST_BAND_MODES,
            }
            .into());
        }
        wanted *= 2;
    }
}

/// Shift of $K + \sigma M$, as a fraction of the lowest elastic eigenvalue, used to reach
/// $K^+$ by the fixed-point iteration of [`InterfaceStatics::of_full_body`].
const STATIC_SHIFT: f64 = 1e-3;

/// Largest iterations of that fixed point (each gains a factor $\sigma/(\omega_1^2+\sigma)$).
const STATIC_ITERATIONS: usize = 12;

/// A free body's elastic static compliance across its interfaces, $G = L^T K^+ L_e$: the
/// loads made self-equilibrated by inertia relief, $L_e = (I - M\Phi_r\Phi_r^T)L$, the
/// response taken $M$-orthogonal to the rigid motions $\Phi_r$ (its zero-energy modes).
#[derive(Debug, Clone)]
pub struct InterfaceStatics {
    /// The loads.
    pub loads: InterfaceLoads,
    /// The full body's $G$, loads × loads.
    pub full: Mat<f64>,
    /// Wall time, s.
    pub full_s: f64,
}

impl InterfaceStatics {
    /// $G$ of the full body: $x = K^+ L_e$ by the fixed point
    /// $x \leftarrow (K + \sigma M)^{-1}(L_e + \sigma M x)$ on one sparse Cholesky of
    /// $K + \sigma M$ ($\sigma$ = `STATIC_SHIFT` of the lowest elastic eigenvalue
    /// `lowest`), until the update is below 1e-12 of $x$; `zero` are the body's
    /// mass-normalised zero-energy modes.
    pub fn of_full_body(
        model: &FeModel,
        loads: InterfaceLoads,
        zero: MatRef<'_, f64>,
        lowest: f64,
        progress: &Progress,
    ) -> Result<Self> {
        progress.phase("full body's static compliance")?;
        let started = Instant::now();
        let sigma = STATIC_SHIFT * lowest;
        let shifted = model.k.shifted(&model.m, -sigma);
        let coords = model.dof_positions();
        let order = nested_dissection(shifted.as_faer(), &coords);
        let symbolic = SymbolicFactor::analyse_ordered(shifted.as_faer(), order.as_deref())?;
        let factor = SymmetricFactor::sparse(shifted.as_faer(), &symbolic, "K + σM")?;
        let project_loads = |b: Mat<f64>| {
            // b − MΦ_r Φ_rᵀ b
            let mz = model.m.mul(zero);
            let c = zero.transpose() * &b;
            b - &mz * &c
        };
        let project_motion = |x: Mat<f64>| {
            // x − Φ_r Φ_rᵀ M x
            let c = zero.transpose() * model.m.mul(x.as_ref());
            x - zero * &c
        };
        let le = project_loads(loads.matrix.clone());
        let mut x = project_motion(factor.solve(le.as_ref()));
        let mut converged = false;
        for _ in 0..STATIC_ITERATIONS {
            let rhs = &le + model.m.mul(x.as_ref()) * sigma;
            let next = project_motion(factor.solve(rhs.as_ref()));
            let change = (&next - &x).norm_l2() / next.norm_l2().max(f64::MIN_POSITIVE);
            x = next;
            if change <= 1e-12 {
                converged = true;
                break;
            }
        }
        // The check: K x = L_e, by a sparse product.
        let residual = (model.k.mul(x.as_ref()) - &le).norm_l2() / le.norm_l2();
        if !converged || residual.is_nan() || residual > 1e-8 {
            return Err(LinalgError::SolveInaccurate {
                matrix: "K (inertia-relief static compliance)".into(),
                residual,
                tolerance: 1e-8,
            }
            .into());
        }
        Ok(Self {
            full: loads.matrix.transpose() * &x,
            loads,
            full_s: started.elapsed().as_secs_f64(),
        })
    }

    /// The same compliance of a reduced model from its own modes: the elastic ones
    /// ($\lambda$ above the zero-energy count `zero_modes`), $G_r = \sum (L^T\Psi v)(v^T\Psi^T
    /// L)/\lambda$, and its relative difference from the full body's (Frobenius).
    pub fn error_of(&self, basis: &Basis, modes: &GeneralizedEigen, zero_modes: usize) -> f64 {
        let lr = basis.psi.transpose() * &self.loads.matrix;
        let p = lr.ncols();
        let mut g = Mat::<f64>::zeros(p, p);
        for (k, &lambda) in modes.values.iter().enumerate().skip(zero_modes) {
            let a = lr.transpose() * modes.vectors.col(k);
            for i in 0..p {
                for j in 0..p {
                    g[(i, j)] += a[i] * a[j] / lambda;
                }
            }
        }
        (&g - &self.full).norm_l2() / self.full.norm_l2()
    }
}
