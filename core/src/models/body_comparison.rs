//! The speed–accuracy comparison of a user's own body (`bench modes --body`, Python's
//! `flexmodes.compare`): every method and kept-mode count reduces the body on the user's
//! interfaces; each model's offline time, the process's peak memory while it was built, its
//! frequency error and MAC against the full body's own modes (solved once, shared by every
//! point), its static compliance across the interfaces and, with a band, its interface
//! response; the Pareto front; and, for a band and tolerance, the smallest measured model of
//! each method that meets it beside the rule of thumb.
//!
//! Timings are wall-clock, measured in one run on this machine; reported, never asserted.

use std::time::Instant;

use faer::MatRef;

use super::{
    BODY_METHODS, BodyAdvice, BodyInterfaces, BodyReducer, InterfaceResponse, InterfaceStatics,
    ReducedBody, advise, modes_up_to,
};
use crate::{
    Error, Progress, Result,
    analysis::{ZeroEnergyCount, pair_modes, pareto_flags, three_digits},
    body_file::ImportedBody,
    fem::FeModel,
    linalg::{LinalgError, peak_resident_bytes, reset_peak_resident},
    reduction::{Method, ReductionError},
};

/// Kept-mode counts tried when none are given.
pub const BODY_MODE_SWEEP: [usize; 4] = [4, 8, 16, 32];

/// Frequency errors below this are round-off, equal for the Pareto front.
pub const ROUND_OFF_ERROR: f64 = 1e-10;

/// Elastic modes compared when no band is given.
pub const BODY_COMPARED_MODES: usize = 6;

/// What to measure.
#[derive(Debug, Clone, PartialEq)]
pub struct BodyComparisonParameters {
    /// Interface items as `--boundary` takes them (set names, node numbers, `rbe2:SET`).
    pub boundary: Option<Vec<String>>,
    /// Characteristic constraint modes kept (None: all).
    pub interface_modes: Option<usize>,
    /// Methods (default: all eight).
    pub methods: Vec<Method>,
    /// Kept-mode counts (default [`BODY_MODE_SWEEP`]).
    pub modes: Vec<usize>,
    /// Top of the frequency band, Hz: every full-body elastic mode up to it is compared
    /// (default: the lowest [`BODY_COMPARED_MODES`]).
    pub band_hz: Option<f64>,
    /// Largest relative frequency error a model may make in the band to be advised.
    pub tolerance: f64,
}

impl Default for BodyComparisonParameters {
    fn default() -> Self {
        Self {
            boundary: None,
            interface_modes: None,
            methods: BODY_METHODS.to_vec(),
            modes: BODY_MODE_SWEEP.to_vec(),
            band_hz: None,
            tolerance: 0.01,
        }
    }
}

/// One method and kept-mode count on the body.
#[derive(Debug, Clone, PartialEq)]
pub struct BodyComparisonPoint {
    /// Method.
    pub method: Method,
    /// Kept modes (0 for Guyan).
    pub modes: usize,
    /// Reduced coordinates.
    pub coordinates: usize,
    /// Offline wall time, s (the shared interior factor charged once per method).
    pub offline_s: f64,
    /// Peak resident memory while the model was built, MB (None: not measurable here).
    pub peak_mb: Option<f64>,
    /// Largest relative error of the compared elastic frequencies (infinite when the model
    /// has fewer elastic modes than compared).
    pub freq_rel_error: f64,
    /// Smallest MAC of the compared full modes against the model's (paired by best MAC).
    pub min_mac: f64,
    /// Relative error (Frobenius) of the elastic static compliance across the interfaces
    /// ([`InterfaceStatics`]).
    pub static_error: f64,
    /// With a band: the largest error of the interface response's magnitude over it, per
    /// channel relative to the channel's peak
    /// ([`crate::analysis::FrequencyResponse::relative_magnitude_error`]).
    pub frf_error: Option<f64>,
    /// On the Pareto front of (offline s, frequency error).
    pub pareto: bool,
}

/// What [`compare_body_methods`] measured.
#[derive(Debug, Clone, PartialEq)]
pub struct BodyComparison {
    /// The interface items used (as `--boundary` takes them).
    pub boundary: Vec<String>,
    /// Zero-energy modes of the full body.
    pub zero_modes: usize,
    /// The compared full-body elastic frequencies, Hz (checked pairs).
    pub reference_hz: Vec<f64>,
    /// Their relative residuals $\|K\phi - \lambda M\phi\| / (\lambda\|M\phi\|)$.
    pub reference_residuals: Vec<f64>,
    /// Wall time of the full body's modes, s.
    pub reference_s: f64,
    /// One point per method and kept-mode count, by method then kept modes ascending.
    pub points: Vec<BodyComparisonPoint>,
    /// Methods (or counts) that could not be built on this body, and why.
    pub not_applicable: Vec<(Method, String)>,
    /// The mode-count advice.
    pub advice: BodyAdvice,
    /// Wall time of the full body's static compliance, s.
    pub statics_full_s: f64,
    /// How the interface response was compared (with a band).
    pub frf_description: Option<String>,
}

/// A reduced model's largest relative error over the `full_hz.len()` compared elastic
/// frequencies (infinite with fewer modes) and the smallest MAC of the full body's modes
/// (`elastic_vectors`) against its expanded ones, paired by best MAC among twice as many.
fn frequency_and_mac(
    reduced: &ReducedBody,
    full_hz: &[f64],
    elastic_vectors: MatRef<'_, f64>,
) -> (f64, f64) {
    let compared = full_hz.len();
    let hz = reduced.elastic_hz();
    let freq_rel_error = if hz.len() < compared {
        f64::INFINITY
    } else {
        (0..compared)
            .map(|j| ((hz[j] - full_hz[j]) / full_hz[j]).abs())
            .fold(0.0, f64::max)
    };
    let candidates = hz.len().min(2 * compared);
    let expanded = reduced.basis.psi.as_ref()
        * reduced
            .modes
            .vectors
            .subcols(reduced.zero_modes, candidates);
    let pairs = pair_modes(
        elastic_vectors,
        full_hz,
        &(0..compared).collect::<Vec<_>>(),
        expanded.as_ref(),
        &hz[..candidates],
    );
    let min_mac = if candidates == 0 {
        0.0
    } else {
        pairs.iter().map(|q| q.mac).fold(1.0, f64::min)
    };
    (freq_rel_error, min_mac)
}

/// Marks the points on the front of offline time against frequency error. Errors below
/// round-off are equal: a model exact to 1e-13 is not better than one exact to 2e-13.
fn mark_pareto(points: &mut [BodyComparisonPoint]) {
    let flags = pareto_flags(
        &points
            .iter()
            .map(|q| {
                (
                    q.offline_s,
                    three_digits(q.freq_rel_error.max(ROUND_OFF_ERROR)),
                )
            })
            .collect::<Vec<_>>(),
    );
    for (q, f) in points.iter_mut().zip(flags) {
        q.pareto = f && q.freq_rel_error.is_finite();
    }
}

/// The interfaces compared across: `p.boundary`, or the body's own default interface nodes;
/// the items as given (node numbers or set names) and the interfaces they make.
fn comparison_interfaces(
    body: &ImportedBody,
    p: &BodyComparisonParameters,
) -> Result<(Vec<String>, BodyInterfaces)> {
    let items = match &p.boundary {
        Some(b) => b.clone(),
        None => body
            .default_interface_nodes()?
            .iter()
            .map(|n| n.to_string())
            .collect(),
    };
    let interfaces = BodyInterfaces {
        interface_modes: p.interface_modes,
        ..BodyInterfaces::of(body, &items, None)?
    };
    Ok((items, interfaces))
}

/// The interface loads, built once; with them the elastic static compliance across the
/// interfaces and, over a band, the interface response (sparse LDLᵀ per frequency, off its
/// resonances), of the full body once, of each model later.
fn interface_measures(
    model: &FeModel,
    interfaces: &BodyInterfaces,
    (full, full_hz): (&ZeroEnergyCount, &[f64]),
    band_hz: Option<f64>,
    progress: &Progress,
) -> Result<(InterfaceStatics, Option<InterfaceResponse>)> {
    let loads =
        BodyReducer::new(model, interfaces.clone(), full, 0.0, progress.clone())?.loads()?;
    let statics = InterfaceStatics::of_full_body(
        model,
        loads.clone(),
        full.modes.vectors.subcols(0, full.zero_modes),
        full.modes.values[full.zero_modes],
        progress,
    )?;
    let frf = match band_hz {
        Some(top) => Some(InterfaceResponse::of_full_body(
            model, loads, top, full_hz, progress,
        )?),
        None => None,
    };
    Ok((statics, frf))
}

/// The full body's elastic modes compared: those in the band, or the lowest
/// [`BODY_COMPARED_MODES`]; none is an error.
fn compared_modes(full_hz: &[f64], band_hz: Option<f64>) -> Result<usize> {
    let compared = match band_hz {
        Some(top) => full_hz.iter().take_while(|&&f| f <= top).count(),
        None => BODY_COMPARED_MODES.min(full_hz.len()),
    };
    if compared == 0 {
        return Err(ReductionError::EmptyBand {
            low_hz: 0.0,
            high_hz: band_hz.unwrap_or(0.0),
            what: "full body's elastic modes",
        }
        .into());
    }
    Ok(compared)
}

/// One reduced model (`method` with `k` modes, its peak memory) measured against the full
/// body: the frequency error and smallest MAC over the compared modes (`full_hz`, their
/// `elastic_vectors`), the static error across the interfaces and the FRF error over the band.
fn measure_point(
    model: &FeModel,
    (method, k, reduced, peak_mb): (Method, usize, &ReducedBody, Option<f64>),
    (full_hz, elastic_vectors): (&[f64], MatRef<'_, f64>),
    (statics, frf): (&InterfaceStatics, Option<&InterfaceResponse>),
) -> Result<BodyComparisonPoint> {
    let (freq_rel_error, min_mac) = frequency_and_mac(reduced, full_hz, elastic_vectors);
    let frf_error = match frf {
        Some(response) => Some(response.error_of(model, &reduced.basis)?),
        None => None,
    };
    let static_error = statics.error_of(&reduced.basis, &reduced.modes, reduced.zero_modes);
    Ok(BodyComparisonPoint {
        method,
        modes: k,
        coordinates: reduced.basis.size(),
        offline_s: reduced.offline_s,
        peak_mb,
        freq_rel_error,
        min_mac,
        static_error,
        frf_error,
        pareto: false,
    })
}

/// Reduces `body` by every method and kept-mode count of `p` and measures each model against
/// the full body's own checked modes.
pub fn compare_body_methods(
    body: &ImportedBody,
    p: &BodyComparisonParameters,
    progress: &Progress,
) -> Result<BodyComparison> {
    let model = &body.model;
    let (items, interfaces) = comparison_interfaces(body, p)?;
    if p.modes.is_empty() || p.modes.contains(&0) {
        return Err(ReductionError::NoKeptModes {
            counts: p.modes.clone(),
        }
        .into());
    }
    progress.phase("full body's modes")?;
    let started = Instant::now();
    let full = modes_up_to(&body.model, p.band_hz, BODY_COMPARED_MODES, progress)?;
    let reference_s = started.elapsed().as_secs_f64();
    let full_hz = full.elastic_hz();
    let compared = compared_modes(&full_hz, p.band_hz)?;
    let (statics, frf) =
        interface_measures(model, &interfaces, (&full, &full_hz), p.band_hz, progress)?;
    let elastic_vectors = full
        .modes
        .vectors
        .subcols(full.zero_modes, compared)
        .to_owned();
    let modes: std::collections::BTreeSet<usize> = p.modes.iter().copied().collect();
    let mut points = Vec::new();
    let mut refused = Vec::new();
    for &method in &p.methods {
        let mut reducer = BodyReducer::new(
            model,
            interfaces.clone(),
            &full,
            reference_s,
            progress.clone(),
        )?;
        // Largest count first: the partial eigensolvers then serve the smaller ones.
        let counts: Vec<usize> = if method == Method::Guyan {
            vec![0]
        } else {
            modes.iter().rev().copied().collect()
        };
        for k in counts {
            progress.phase(&format!("{} with {k} modes", method.id()))?;
            let reset = reset_peak_resident();
            let reduced = match reducer.reduce(method, k) {
                Ok(r) => r,
                Err(Error::Reduction(e @ ReductionError::MethodNeedsContext { .. })) => {
                    refused.push((method, e.to_string()));
                    break;
                }
                // A reduced model whose pairs fail their check is said in its row, never
                // charted, and the other methods still run.
                Err(Error::Linalg(e @ LinalgError::EigenCheckFailed { .. })) => {
                    refused.push((method, format!("{k} modes: {e}")));
                    continue;
                }
                Err(e) => return Err(e),
            };
            let peak_mb = reset
                .then(peak_resident_bytes)
                .flatten()
                .map(|b| b as f64 / 1e6);
            points.push(measure_point(
                model,
                (method, k, &reduced, peak_mb),
                (&full_hz[..compared], elastic_vectors.as_ref()),
                (&statics, frf.as_ref()),
            )?);
        }
    }
    // Listed by method, then by kept modes ascending.
    points.sort_by_key(|q| (p.methods.iter().position(|&m| m == q.method), q.modes));
    mark_pareto(&mut points);
    let advice = advise(
        &points,
        p,
        &full_hz[..compared],
        &mut BodyReducer::new(
            model,
            interfaces.clone(),
            &full,
            reference_s,
            progress.clone(),
        )?,
    )?;
    Ok(BodyComparison {
        boundary: items,
        zero_modes: full.zero_modes,
        reference_hz: full_hz[..compared].to_vec(),
        reference_residuals: full.elastic_residuals()[..compared].to_vec(),
        reference_s,
        points,
        not_applicable: refused,
        advice,
        statics_full_s: statics.full_s,
        frf_description: frf.as_ref().map(InterfaceResponse::describe),
    })
}
