//! The failures scene's case of a body's own inertia loads: CalculiX's lever spun up, CB k
//! without and with the loads' residual vectors against the full body, and the a-priori
//! estimate beside each history error.

use crate::record::{RESIDUAL_VECTORS, method_color};
use crate::scenes::failures::failure_cases::Failure;
use crate::{
    Progress, Result,
    models::{INERTIA_LOAD_MODES, InertiaLoadStudy, inertia_load_study},
    record::{LogLogChart, LogLogSeries},
    reduction::Method,
    report::{readable, sig},
};
use serde_json::json;

/// CB k on the spun lever without and with the inertia-load residual vectors.
pub(super) fn inertia_load_failure(progress: &Progress) -> Result<Failure> {
    let study = inertia_load_study(progress)?;
    let without = study.reduced(false);
    let with = study.reduced(true);
    let per_run = |runs: &[&crate::models::DrivenRun]| {
        runs.iter()
            .map(|r| {
                json!({
                    "modes": r.modes,
                    "coordinates": r.coordinates,
                    "residual_vectors": r.residual_vectors,
                    "history_error": r.history_error.map(sig),
                    "reaction_error": r.reaction_error.map(sig),
                    "estimate": r.estimate_max().map(sig),
                })
            })
            .collect::<Vec<_>>()
    };
    let InertiaLoadStudy {
        body: (name, dof),
        rate: (rate, ramp),
        ..
    } = &study;
    let json = json!({
        "body": name,
        "dof": dof,
        "rate_rad_s": rate,
        "ramp_s": ramp,
        "without_residual_vectors": per_run(&without),
        "with_residual_vectors": per_run(&with),
    });
    let chart = inertia_load_chart(&without, &with);
    let point = |runs: &[&crate::models::DrivenRun], k: usize| {
        runs.iter()
            .find(|r| r.modes == k)
            .map(|r| {
                (
                    r.history_error.unwrap_or(f64::NAN),
                    r.estimate_max().unwrap_or(f64::NAN),
                    r.residual_vectors,
                )
            })
            .unwrap_or((f64::NAN, f64::NAN, 0))
    };
    let first = INERTIA_LOAD_MODES[0];
    let last = INERTIA_LOAD_MODES[INERTIA_LOAD_MODES.len() - 1];
    let (e0, p0, _) = point(&without, first);
    let (e1, p1, _) = point(&without, last);
    let (r0, q0, rv) = point(&with, first);
    let (r1, q1, _) = point(&with, last);
    let what = format!(
        "CalculiX's lever ({dof} DOF, root clamped) spun up to {rate} rad/s in {ramp} s: the \
         tip's history error against NR is {} with CB {first} and {} with CB {last} \
         (a-priori estimate {} and {}); with the {rv} residual vectors of the frame's unit \
         inertia loads it is {} with CB {first} and {} with CB {last} (estimate {} and {})",
        readable(e0, 2),
        readable(e1, 2),
        readable(p0, 2),
        readable(p1, 2),
        readable(r0, 2),
        readable(r1, 2),
        readable(q0, 2),
        readable(q1, 2),
    );
    Ok(Failure {
        json,
        line: [
            format!("A spun arm's own inertia loads with CB k alone (k = {first}…{last})"),
            what,
            "the arm stretches quasi-statically under its centrifugal load Ω²M r; that shape \
             is no low fixed-interface mode (CB's Φ_N, Eq. 6.18) and the clamped root has no \
             constraint mode to carry it. The static responses K_ii⁻¹ f of the frame's unit \
             inertia loads, M-orthogonalised to the kept modes (residual vectors: Dickens, \
             Nakagawa & Wittbrodt's modal truncation augmentation), hold it; the estimate is \
             the share of those responses outside the basis (energy norm)"
                .into(),
        ],
        visuals: chart.visuals(),
    })
}

/// History error and a-priori estimate against k, without (CB's colour) and with residual
/// vectors: errors as lines, estimates as points.
fn inertia_load_chart(
    without: &[&crate::models::DrivenRun],
    with: &[&crate::models::DrivenRun],
) -> LogLogChart {
    let series =
        |id: &str, label: &str, color, runs: &[&crate::models::DrivenRun], estimate| LogLogSeries {
            id: id.into(),
            label: label.into(),
            color,
            points: runs
                .iter()
                .filter_map(|r| {
                    let y = if estimate {
                        r.estimate_max()
                    } else {
                        r.history_error
                    }?;
                    Some((r.modes as f64, y))
                })
                .collect(),
            line: !estimate,
        };
    let cb = method_color(Method::CraigBampton);
    LogLogChart {
        path: "charts/inertia_loads".into(),
        x_unit: "CB's fixed-interface modes k".into(),
        y_unit: "tip history error (line), estimate (points)".into(),
        series: vec![
            series("cb", "CB k", cb, without, false),
            series("cb_estimate", "", cb, without, true),
            series("cb_rv", "CB k + RV", RESIDUAL_VECTORS, with, false),
            series("cb_rv_estimate", "", RESIDUAL_VECTORS, with, true),
        ],
        x_linear: false,
    }
}
