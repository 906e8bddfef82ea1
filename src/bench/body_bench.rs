//! `flexmodes bench modes --body FILE`: the speed–accuracy chart of a user's own body. Every
//! method and kept-mode count reduces the body on the user's interfaces; each model's offline
//! time, the process's peak memory while it was built, and its frequency error and MAC
//! against the full body's own modes (solved once, shared by every point); the Pareto front;
//! and, for a band and tolerance, the smallest measured model of each method that meets it
//! beside the rule of thumb (modes up to 1.5–2× the band's top).
//!
//! Timings are wall-clock, measured in one run on this machine; reported, never asserted.

use std::time::Instant;

use serde_json::{Value, json};

use super::body_advice::{BodyAdvice, advise};
use crate::{
    Error, Progress, Result,
    analysis::pair_modes,
    bench::{pareto_flags, three_digits},
    body_file::ImportedBody,
    linalg::{peak_resident_bytes, reset_peak_resident},
    models::{
        BODY_METHODS, BodyInterfaces, BodyReducer, InterfaceResponse, InterfaceStatics, modes_up_to,
    },
    record::{Layout, LogLogChart, LogLogSeries, RecordingContent},
    reduction::{Method, ReductionError},
    report::{Report, markdown_table, sig},
    scenes::{
        body_modes::{body_boundary, default_boundary},
        method_color,
    },
};

/// Kept-mode counts tried when none are given.
pub const BODY_MODE_SWEEP: [usize; 4] = [4, 8, 16, 32];

/// Frequency errors below this are round-off, equal for the Pareto front.
pub const ROUND_OFF_ERROR: f64 = 1e-10;

/// Elastic modes compared when no band is given.
pub const BODY_COMPARED_MODES: usize = 6;

/// What to measure.
#[derive(Debug, Clone, PartialEq)]
pub struct BodyBenchParameters {
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

impl Default for BodyBenchParameters {
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
pub struct BodyBenchPoint {
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

/// The bench: JSON, the text table and the recording of the charts.
pub fn bench_body_modes(
    body: &ImportedBody,
    p: &BodyBenchParameters,
    progress: &Progress,
) -> Result<(Value, String, RecordingContent)> {
    let model = &body.model;
    let items = match &p.boundary {
        Some(b) => b.clone(),
        None => default_boundary(body)?
            .iter()
            .map(|n| n.to_string())
            .collect(),
    };
    let interfaces = BodyInterfaces {
        interface_modes: p.interface_modes,
        ..body_boundary(body, &items)?
    };
    if p.modes.is_empty() || p.modes.contains(&0) {
        return Err(Error::InvalidOption {
            scene: "bench modes".into(),
            reason: "--modes takes counts of at least 1".into(),
        });
    }
    progress.phase("full body's modes")?;
    let started = Instant::now();
    let full = modes_up_to(&body.model, p.band_hz, BODY_COMPARED_MODES, progress)?;
    let reference_s = started.elapsed().as_secs_f64();
    let full_hz = full.elastic_hz();
    let compared = match p.band_hz {
        Some(top) => full_hz.iter().take_while(|&&f| f <= top).count(),
        None => BODY_COMPARED_MODES.min(full_hz.len()),
    };
    if compared == 0 {
        return Err(ReductionError::EmptyBand {
            low_hz: 0.0,
            high_hz: p.band_hz.unwrap_or(0.0),
            what: "full body's elastic modes".into(),
        }
        .into());
    }
    // The interface response over the band, of the full body once (sparse LDLᵀ per
    // frequency, off its resonances), of each model below.
    // The elastic static compliance across the interfaces, of the full body once.
    let statics = {
        let loads =
            BodyReducer::new(model, interfaces.clone(), &full, 0.0, progress.clone())?.loads()?;
        let zero = full.modes.vectors.subcols(0, full.zero_modes);
        InterfaceStatics::of_full_body(
            model,
            loads,
            zero,
            full.modes.values[full.zero_modes],
            progress,
        )?
    };
    let frf = match p.band_hz {
        Some(top) => {
            let loads = BodyReducer::new(model, interfaces.clone(), &full, 0.0, progress.clone())?
                .loads()?;
            Some(InterfaceResponse::of_full_body(
                model, loads, top, &full_hz, progress,
            )?)
        }
        None => None,
    };
    let elastic_vectors = full
        .modes
        .vectors
        .subcols(full.zero_modes, compared)
        .to_owned();
    let mut modes = p.modes.clone();
    modes.sort_unstable();
    modes.dedup();
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
                Err(Error::Linalg(e @ crate::linalg::LinalgError::EigenCheckFailed { .. })) => {
                    refused.push((method, format!("{k} modes: {e}")));
                    continue;
                }
                Err(e) => return Err(e),
            };
            let peak_mb = if reset {
                peak_resident_bytes().map(|b| b as f64 / 1e6)
            } else {
                None
            };
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
                elastic_vectors.as_ref(),
                &full_hz[..compared],
                &(0..compared).collect::<Vec<_>>(),
                expanded.as_ref(),
                &hz[..candidates],
            );
            let min_mac = if candidates == 0 {
                0.0
            } else {
                pairs.iter().map(|q| q.mac).fold(1.0, f64::min)
            };
            let frf_error = match &frf {
                Some(response) => Some(response.error_of(model, &reduced.basis)?),
                None => None,
            };
            let static_error = statics.error_of(&reduced.basis, &reduced.modes, reduced.zero_modes);
            points.push(BodyBenchPoint {
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
            });
        }
    }
    // Listed by method, then by kept modes ascending.
    points.sort_by_key(|q| (p.methods.iter().position(|&m| m == q.method), q.modes));
    // Errors below round-off are equal: a model exact to 1e-13 is not better than one exact
    // to 2e-13.
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
    let frf_note = Some(format!(
        " Static error: the elastic static compliance across the interfaces, G = LᵀK⁺L with \
         the loads self-equilibrated by inertia relief (the full body by a fixed point on one \
         sparse Cholesky of K + σM, checked by ‖Kx − Lₑ‖ ≤ 1e-8‖Lₑ‖: {:.2} s; each model \
         from its own elastic modes), relative Frobenius difference.{}",
        statics.full_s,
        frf.as_ref()
            .map(|response| format!(" FRF error: {}.", response.describe()))
            .unwrap_or_default()
    ));
    let text = table_text(
        body,
        &items,
        (&full_hz[..compared], reference_s),
        &points,
        &refused,
        &advice,
        frf_note.as_deref(),
    );
    let json = json!({
        "scene": "bench-modes",
        "body": body.location.display().to_string(),
        "dofs": model.dof_count(),
        "boundary": items,
        "reference": {
            "zero_energy_modes": full.zero_modes,
            "hz": full_hz[..compared].iter().map(|&f| sig(f)).collect::<Vec<_>>(),
            "residuals": full.elastic_residuals()[..compared].iter().map(|&r| sig(r)).collect::<Vec<_>>(),
            "s": sig(reference_s),
        },
        "points": points.iter().map(|q| json!({
            "method": q.method.id(),
            "modes": q.modes,
            "coordinates": q.coordinates,
            "offline_s": sig(q.offline_s),
            "peak_mb": q.peak_mb.map(sig),
            "freq_rel_error": if q.freq_rel_error.is_finite() { json!(sig(q.freq_rel_error)) } else { Value::Null },
            "min_mac": sig(q.min_mac),
            "static_rel_error": sig(q.static_error),
            "frf_rel_error": q.frf_error.map(sig),
            "pareto": q.pareto,
        })).collect::<Vec<_>>(),
        "not_applicable": refused.iter().map(|(m, why)| json!({"method": m.id(), "reason": why})).collect::<Vec<_>>(),
        "advice": advice.json(),
    });
    let recording = charts(&points, &text);
    Ok((json, text, recording))
}

fn table_text(
    body: &ImportedBody,
    items: &[String],
    (compared_hz, reference_s): (&[f64], f64),
    points: &[BodyBenchPoint],
    refused: &[(Method, String)],
    advice: &BodyAdvice,
    frf_note: Option<&str>,
) -> String {
    let rows: Vec<Vec<String>> = points
        .iter()
        .map(|q| {
            vec![
                q.method.id().into(),
                q.modes.to_string(),
                q.coordinates.to_string(),
                format!("{:.3}", q.offline_s),
                q.peak_mb.map_or("–".into(), |m| format!("{m:.0}")),
                if q.freq_rel_error.is_finite() {
                    format!("{:.2e}", q.freq_rel_error)
                } else {
                    "too few modes".into()
                },
                format!("{:.4}", q.min_mac),
                format!("{:.2e}", q.static_error),
                q.frf_error.map_or("–".into(), |e| format!("{e:.2e}")),
                if q.pareto { "★" } else { "" }.to_string(),
            ]
        })
        .collect();
    let advice_rows: Vec<Vec<String>> = advice
        .smallest
        .iter()
        .map(|(m, s)| match s {
            Some((k, c, e)) => vec![
                m.id().into(),
                k.to_string(),
                c.to_string(),
                format!("{e:.2e}"),
            ],
            None => vec![
                m.id().into(),
                "none measured".into(),
                "–".into(),
                "–".into(),
            ],
        })
        .collect();
    let refused_text: String = refused
        .iter()
        .map(|(m, why)| format!("\n- {} not computed: {why}", m.id().to_uppercase()))
        .collect();
    format!(
        "Body `{}` ({} DOF), interface {}. Reference: the full body's {} lowest elastic \
         frequencies ({}; {reference_s:.2} s by the partial eigensolver, shared by every \
         point). Frequency error: the largest relative error over them, paired by order; MAC: \
         the smallest over them, each paired with the model's best-matching mode. Offline s: \
         building the model (the interior factor charged once per method), one run; peak MB: \
         the process's peak resident memory while it was built. ★: the Pareto front in \
         (offline s, frequency error equal to three significant digits, errors below 1e-10 \
         equal).{}{}{refused_text}\n\n{}\n\
         Advice for 0 to {:.4} Hz at {:.0e} relative error: the smallest measured model of \
         each method that meets it{}.\n\n{}",
        body.model.name,
        body.model.dof_count(),
        items.join(","),
        compared_hz.len(),
        compared_hz
            .iter()
            .map(|f| format!("{f:.4}"))
            .collect::<Vec<_>>()
            .join(", "),
        if items.iter().any(|i| i.starts_with("rbe2:")) {
            " The reference is the free body: a rigid (rbe2) interface stiffens its ring, so \
             the methods that tie it (GR, MT, CB, MC) converge to the tied body's frequencies, \
             above the free body's; their error floor is the interface model's, not the \
             reduction's. BH, MM and BT only load the interface and approach the free body."
        } else {
            ""
        },
        frf_note.unwrap_or(""),
        markdown_table(
            &[
                "method",
                "modes",
                "coordinates",
                "offline s",
                "peak MB",
                "freq. error",
                "min MAC",
                "static error",
                "FRF error",
                "Pareto",
            ],
            &rows,
        ),
        advice.band_hz,
        advice.tolerance,
        match advice.rule_of_thumb {
            Some((a, b)) => format!(
                "; the rule of thumb (fixed-interface modes up to 1.5–2× the band's top) keeps \
                 {a} to {b} modes"
            ),
            None => String::new(),
        },
        markdown_table(
            &["method", "modes", "coordinates", "freq. error"],
            &advice_rows,
        ),
    )
}

/// Frequency error against offline cost (log–log) per method with the Pareto front, and
/// frequency error against reduced coordinates.
fn charts(points: &[BodyBenchPoint], text: &str) -> RecordingContent {
    let mut methods: Vec<Method> = Vec::new();
    for q in points {
        if !methods.contains(&q.method) {
            methods.push(q.method);
        }
    }
    let of = |m: Method| points.iter().filter(move |q| q.method == m);
    let series = |x: fn(&BodyBenchPoint) -> f64| -> Vec<LogLogSeries> {
        methods
            .iter()
            .map(|&m| {
                let mut pts: Vec<(f64, f64)> = of(m).map(|q| (x(q), q.freq_rel_error)).collect();
                pts.sort_by(|a, b| a.0.total_cmp(&b.0));
                LogLogSeries {
                    id: m.id().into(),
                    label: m.id().to_uppercase(),
                    color: method_color(m),
                    points: pts,
                    line: true,
                }
            })
            .collect()
    };
    let mut cost = series(|q| q.offline_s);
    let mut front: Vec<(f64, f64)> = points
        .iter()
        .filter(|q| q.pareto)
        .map(|q| (q.offline_s, q.freq_rel_error))
        .collect();
    front.sort_by(|a, b| a.0.total_cmp(&b.0));
    cost.push(LogLogSeries {
        id: "pareto_front".into(),
        label: "Pareto".into(),
        color: [255, 255, 255, 255],
        points: front,
        line: true,
    });
    let mut visuals = LogLogChart {
        path: "bench/error_vs_offline".into(),
        x_unit: "offline s".into(),
        y_unit: "freq. rel. error".into(),
        series: cost,
        x_linear: false,
    }
    .visuals();
    visuals.extend(
        LogLogChart {
            path: "bench/error_vs_size".into(),
            x_unit: "coordinates".into(),
            y_unit: "freq. rel. error".into(),
            series: series(|q| q.coordinates as f64),
            x_linear: false,
        }
        .visuals(),
    );
    let mut report = Report::new("bench-modes");
    report.table = text.to_string();
    RecordingContent {
        report,
        markdown: format!(
            "# bench modes\n\nLeft: each model's largest relative frequency error against the \
             offline cost of building it (log–log), one line per method through its kept-mode \
             counts, the Pareto front in white. Right: the same error against the reduced \
             model's size. Points with zero error (exact to round-off) or too few modes have \
             no place on a log axis and are in the table only.\n\n{text}"
        ),
        visuals,
        layout: Layout::bench_charts(
            (
                "frequency error against offline s (log–log)",
                "/bench/error_vs_offline",
            ),
            (
                "frequency error against coordinates (log–log)",
                "/bench/error_vs_size",
            ),
            1.2,
        ),
        timeline: None,
        y_up: false,
    }
}
