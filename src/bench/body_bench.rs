//! `flexmodes bench modes --body FILE`: the speed–accuracy chart of a user's own body. Every
//! method and kept-mode count reduces the body on the user's interfaces; each model's offline
//! time, the process's peak memory while it was built, and its frequency error and MAC
//! against the full body's own modes (solved once, shared by every point); the Pareto front;
//! and, for a band and tolerance, the smallest measured model of each method that meets it
//! beside the rule of thumb (modes up to 1.5–2× the band's top).
//!
//! Timings are wall-clock, measured in one run on this machine; reported, never asserted.

use serde_json::{Value, json};

use crate::{
    Progress, Result,
    body_file::ImportedBody,
    models::{BodyAdvice, BodyComparisonParameters, BodyComparisonPoint, compare_body_methods},
    record::{Layout, LogLogChart, LogLogSeries, RecordingContent, method_color},
    reduction::Method,
    report::{Report, markdown_table, sig},
};

/// The bench: JSON, the text table and the recording of the charts of
/// [`compare_body_methods`].
pub fn bench_body_modes(
    body: &ImportedBody,
    p: &BodyComparisonParameters,
    progress: &Progress,
) -> Result<(Value, String, RecordingContent)> {
    let model = &body.model;
    let c = compare_body_methods(body, p, progress)?;
    let (items, points, refused, advice) = (&c.boundary, &c.points, &c.not_applicable, &c.advice);
    let compared = c.reference_hz.len();
    let (full_hz, reference_s) = (&c.reference_hz, c.reference_s);
    let frf_note = Some(format!(
        " Static error: the elastic static compliance across the interfaces, G = L^T K⁺ L with \
         the loads self-equilibrated by inertia relief (the full body by a fixed point on one \
         sparse Cholesky of K + σM, checked by ‖Kx − Lₑ‖ ≤ 1e-8‖Lₑ‖: {:.2} s; each model \
         from its own elastic modes), relative Frobenius difference.{}",
        c.statics_full_s,
        c.frf_description
            .as_ref()
            .map(|d| format!(" FRF error: {d}."))
            .unwrap_or_default()
    ));
    let text = table_text(
        body,
        items,
        (&full_hz[..compared], reference_s),
        points,
        refused,
        advice,
        frf_note.as_deref(),
    );
    let json = json!({
        "scene": "bench-modes",
        "body": body.location.display().to_string(),
        "dofs": model.dof_count(),
        "boundary": items,
        "reference": {
            "zero_energy_modes": c.zero_modes,
            "hz": full_hz[..compared].iter().map(|&f| sig(f)).collect::<Vec<_>>(),
            "residuals": c.reference_residuals.iter().map(|&r| sig(r)).collect::<Vec<_>>(),
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
    let recording = charts(points, &text);
    Ok((json, text, recording))
}

fn table_text(
    body: &ImportedBody,
    items: &[String],
    (compared_hz, reference_s): (&[f64], f64),
    points: &[BodyComparisonPoint],
    refused: &[(Method, String)],
    advice: &BodyAdvice,
    frf_note: Option<&str>,
) -> String {
    let rows = point_rows(points);
    let advice_rows = advice_rows(advice);
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
         Advice for 0 to {:.4} Hz at {} relative error: the smallest measured model of \
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
        flexmodes_core::report::readable(advice.tolerance, 1),
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

/// One table row per measured model.
fn point_rows(points: &[BodyComparisonPoint]) -> Vec<Vec<String>> {
    points
        .iter()
        .map(|q| {
            vec![
                q.method.id().into(),
                q.modes.to_string(),
                q.coordinates.to_string(),
                format!("{:.3}", q.offline_s),
                q.peak_mb.map_or("–".into(), |m| format!("{m:.0}")),
                if q.freq_rel_error.is_finite() {
                    crate::report::sig3(q.freq_rel_error)
                } else {
                    "too few modes".into()
                },
                format!("{:.4}", q.min_mac),
                crate::report::sig3(q.static_error),
                q.frf_error.map_or("–".into(), crate::report::sig3),
                if q.pareto { "★" } else { "" }.to_string(),
            ]
        })
        .collect()
}

/// One row per method: its smallest measured model that meets the advice's tolerance.
fn advice_rows(advice: &BodyAdvice) -> Vec<Vec<String>> {
    advice
        .smallest
        .iter()
        .map(|(m, s)| match s {
            Some((k, c, e)) => vec![
                m.id().into(),
                k.to_string(),
                c.to_string(),
                crate::report::sig3(*e),
            ],
            None => vec![
                m.id().into(),
                "none measured".into(),
                "–".into(),
                "–".into(),
            ],
        })
        .collect()
}

/// Frequency error against offline cost (log–log) per method with the Pareto front, and
/// frequency error against reduced coordinates.
fn charts(points: &[BodyComparisonPoint], text: &str) -> RecordingContent {
    let mut methods: Vec<Method> = Vec::new();
    for q in points {
        if !methods.contains(&q.method) {
            methods.push(q.method);
        }
    }
    let of = |m: Method| points.iter().filter(move |q| q.method == m);
    let series = |x: fn(&BodyComparisonPoint) -> f64| -> Vec<LogLogSeries> {
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
        color: crate::record::PARETO,
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
             counts, the Pareto front in dark grey. Right: the same error against the reduced \
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
