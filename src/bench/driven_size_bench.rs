//! `flexmodes bench simulate --body FILE --drive SET --larger FILES`: the full body's online
//! cost on a driven spin-up against its size (the same part meshed finer), beside
//! Craig–Bampton's, with the fitted growth exponents of the time per step and of the sparse
//! factor's entries.
//!
//! Timings are wall-clock seconds measured in one run on this machine; they are reported,
//! never asserted.

use serde_json::{Value, json};

use super::growth_exponent;
use crate::{
    Progress, Result,
    body_file::ImportedBody,
    dynamics::DrivenIntegration,
    models::{DrivenBodyParameters, driven_body_study},
    reduction::Method,
    report::{markdown_table, sig},
};

/// The spin-up every size runs: to the default rate in 50 ms, 50 steps of 1 ms sampled every
/// 5 — short, since the cost per step, not the history, is what is measured.
pub fn driven_size_parameters(drive: String) -> DrivenBodyParameters {
    DrivenBodyParameters {
        drive,
        ramp: 0.05,
        integration: DrivenIntegration {
            step: 1e-3,
            end: 0.05,
            spectral_radius: 0.9,
            output_every: 5,
        },
        ..Default::default()
    }
}

/// One body of the size bench.
#[derive(Debug, Clone, PartialEq)]
pub struct DrivenSizePoint {
    /// The body file.
    pub file: String,
    /// DOF of the body.
    pub dof: usize,
    /// Coordinates the full body integrates (its free DOF).
    pub free: usize,
    /// Entries of the sparse factor of (1−α_m)M + (1−α_f)βh²K.
    pub factor_nnz: usize,
    /// NR's online time per step, s.
    pub nr_step_s: f64,
    /// GMRES iterations per step.
    pub iterations_per_step: f64,
    /// Craig–Bampton's online time per step, s, and its history error against NR.
    pub cb: Option<(f64, f64)>,
}

/// Runs each body under `parameters` (the drive, the motion, the steps), the full body and CB
/// with `modes` kept modes; returns JSON and the markdown table.
pub fn bench_driven_sizes(
    files: &[String],
    parameters: &DrivenBodyParameters,
    modes: usize,
    progress: &Progress,
) -> Result<(Value, String)> {
    let mut points = Vec::new();
    for file in files {
        progress.phase(&format!("simulate {file}"))?;
        let body = ImportedBody::load(file)?;
        let study = driven_body_study(
            &body,
            parameters,
            &[Method::CraigBampton],
            &[modes],
            true,
            progress,
        )?;
        let nr = &study.runs[0];
        let steps = nr.cost.steps.max(1) as f64;
        points.push(DrivenSizePoint {
            file: file.clone(),
            dof: study.dof,
            free: nr.coordinates,
            factor_nnz: nr.cost.factor_nnz,
            nr_step_s: nr.cost.online_s / steps,
            iterations_per_step: nr.cost.iterations as f64 / steps,
            cb: study
                .runs
                .get(1)
                .map(|r| (r.cost.online_s / steps, r.history_error.unwrap_or(f64::NAN))),
        });
    }
    points.sort_by_key(|p| p.dof);
    let time_exponent = growth_exponent(
        &points
            .iter()
            .map(|p| (p.dof as f64, p.nr_step_s))
            .collect::<Vec<_>>(),
    );
    let fill_exponent = growth_exponent(
        &points
            .iter()
            .map(|p| (p.dof as f64, p.factor_nnz as f64))
            .collect::<Vec<_>>(),
    );
    let rows = point_rows(&points);
    let exponent = |e: Option<f64>| e.map_or("–".to_string(), |e| format!("{e:.2}"));
    let text = format!(
        "{}\nGrowth with DOF (least squares on log–log): NR time per step n^{}, factor entries \
         n^{}. Online times per step of generalized-α ({} s); CB with {modes} modes; history \
         error as in `simulate`.\n",
        markdown_table(
            &[
                "body",
                "DOF",
                "factor entries",
                "NR s/step",
                "GMRES its/step",
                &format!("CB {modes} s/step"),
                "NR/CB",
                "CB history error",
            ],
            &rows,
        ),
        exponent(time_exponent),
        exponent(fill_exponent),
        parameters.integration.step,
    );
    let value = json!({
        "bench": "simulate --sizes",
        "drive": parameters.drive,
        "step": parameters.integration.step,
        "end": parameters.integration.end,
        "cb_modes": modes,
        "points": points.iter().map(|p| json!({
            "file": p.file,
            "dof": p.dof,
            "free": p.free,
            "factor_nnz": p.factor_nnz,
            "nr_step_s": sig(p.nr_step_s),
            "gmres_iterations_per_step": p.iterations_per_step,
            "cb_step_s": p.cb.map(|c| sig(c.0)),
            "cb_history_error": p.cb.map(|c| c.1),
        })).collect::<Vec<_>>(),
        "nr_time_exponent": time_exponent,
        "factor_nnz_exponent": fill_exponent,
    });
    Ok((value, text))
}

/// One table row per body.
fn point_rows(points: &[DrivenSizePoint]) -> Vec<Vec<String>> {
    points
        .iter()
        .map(|p| {
            vec![
                p.file.clone(),
                p.dof.to_string(),
                p.factor_nnz.to_string(),
                format!("{}", flexmodes_core::report::readable(p.nr_step_s, 3)),
                format!("{:.2}", p.iterations_per_step),
                p.cb.map_or("–".into(), |c| {
                    flexmodes_core::report::readable(c.0, 3).to_string()
                }),
                p.cb.map_or("–".into(), |c| format!("{:.0}", p.nr_step_s / c.0)),
                p.cb.map_or("–".into(), |c| {
                    flexmodes_core::report::readable(c.1, 3).to_string()
                }),
            ]
        })
        .collect()
}
