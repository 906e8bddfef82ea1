//! A driven body's study as `flexmodes simulate` prints it: the ranked table of its runs,
//! the motion in words, the final values, and the JSON.

use serde_json::json;

use crate::{
    body_file::ImportedBody,
    models::{DrivenBodyParameters, DrivenRun, DrivenStudy},
    report::{Cell, Table, sig},
};

/// The JSON value and the text of a driven body's study.
pub fn summary(
    body: &ImportedBody,
    parameters: &DrivenBodyParameters,
    study: &DrivenStudy,
) -> (serde_json::Value, String) {
    (
        summary_json(body, parameters, study),
        summary_text(body, parameters, study),
    )
}

/// The study as `flexmodes simulate` prints it: the drive and the motion, the runs' table,
/// what the columns mean, the stiffening, the explicit scheme's checks and the final values.
fn summary_text(
    body: &ImportedBody,
    parameters: &DrivenBodyParameters,
    study: &DrivenStudy,
) -> String {
    let length = &body.units.length;
    let force = &body.units.force;
    let table = runs_table(study).markdown();
    let (drive, master, ring) = &study.drive;
    let steps = study.runs.first().map_or(0, |r| r.cost.steps);
    let motion = motion_words(parameters, length);
    let mut text = format!(
        "# simulate `{}` ({} DOF): `{drive}` ({ring} nodes, master at ({}) {length}) {}; the \
         frame turns about ({}) {length}, {}; generalized-α ρ∞ = {}, {steps} steps of {} s\n\n\
         {table}\n",
        body.model.name,
        study.dof,
        master.map(sig).map(|x| x.to_string()).join(", "),
        motion.join("; "),
        study
            .axis_point
            .0
            .map(sig)
            .map(|x| x.to_string())
            .join(", "),
        study.axis_point.1,
        parameters.integration.spectral_radius,
        parameters.integration.step,
    );
    text += &format!(
        "\nHistory: the mean displacement of {} {} ({length}); history error = \
         largest difference over the largest full-body value; reaction error = largest \
         reaction-force difference over the largest elastic part of the full body's. Lowest \
         and highest Hz: the reduced model on the frame at rest, ring clamped. Online: the \
         integration alone (the outputs' reconstruction left out). A-priori estimate: the \
         largest share, in the energy norm, of the static response to the drive's own \
         inertia loads ({loads}) that the basis misses, the body held at its interfaces \
         (known before integrating). Residual vectors: {rv}.\n",
        study.output_names.join(", "),
        match parameters.axes {
            crate::dynamics::AxisKind::Mean => {
                "seen from the body's mean axes (the motion in the drive's frame less its rigid \
                 part in the mass metric, §4.2 linearised)"
            }
            _ => "in the drive's turning frame",
        },
        loads = study
            .runs
            .iter()
            .find(|r| !r.estimate.is_empty())
            .map(|r| r
                .estimate
                .iter()
                .map(|(n, _)| n.as_str())
                .collect::<Vec<_>>()
                .join(", "))
            .unwrap_or_else(|| "none".into()),
        rv = if study.residual_vectors {
            "the static responses to the frame's unit inertia loads, added to each \
             fixed-interface basis (--residual-vectors off leaves them out)"
        } else {
            "off (--residual-vectors off)"
        },
    );
    text += &stiffening_words(body, parameters, study);
    text += &stability_words(study);
    if !parameters.boundary.is_empty() && study.runs.iter().any(|r| r.method.is_some()) {
        text += &format!(
            "\nThe reduced models keep {} as interfaces (an rbe2 set as a rigid ring) while the full \
             body leaves them free: part of their history error is that ring's stiffening, \
             not the reduction.\n",
            parameters.boundary.join(", ")
        );
    }
    text += &final_values(study, force);
    text
}

/// The explicit scheme's check on each model: its critical step, and whether the run above it
/// diverged as predicted.
fn stability_words(study: &DrivenStudy) -> String {
    let mut text = String::new();
    for c in &study.stability {
        text += &format!(
            "\nExplicit Dormand–Prince on {}: highest frequency {:.6} Hz, critical step \
             {} s; the run below it ({} DP5) {}; at {} s ({:.0}× critical) {}.\n",
            c.label,
            sig(c.highest_hz),
            flexmodes_core::report::readable(c.critical_s, 4),
            c.label,
            "is bounded (its row above)",
            flexmodes_core::report::readable(c.above_step_s, 4),
            c.above_step_s / c.critical_s,
            match c.diverged_at {
                Some(t) => format!(
                    "it diverged at t = {t} s, as predicted",
                    t = flexmodes_core::report::readable(t, 5)
                ),
                None => "it did NOT diverge: the prediction is not confirmed".into(),
            }
        );
    }
    text
}

/// The study as `flexmodes simulate --json` writes it.
fn summary_json(
    body: &ImportedBody,
    parameters: &DrivenBodyParameters,
    study: &DrivenStudy,
) -> serde_json::Value {
    let (length, force) = (&body.units.length, &body.units.force);
    let (drive, master, ring) = &study.drive;
    let runs: Vec<serde_json::Value> = study.runs.iter().map(run_json).collect();
    json!({
        "body": body.model.name,
        "dof": study.dof,
        "units": {"length": length, "force": force},
        "drive": {"interface": drive, "master": master, "nodes": ring},
        "motion": {"axis": parameters.axis, "rate": parameters.rate, "ramp": parameters.ramp,
                   "axis_point": study.axis_point.0,
                   "axis_point_from": study.axis_point.1,
                   "shake": parameters.shake.map(|(d, a, f)| json!({
                       "direction": d, "amplitude_m": a, "frequency_hz": f}))},
        "gravity": parameters.gravity,
        "stiffening": match (study.stiffened, &body.preload) {
            (true, _) => "on",
            (false, Some(_)) => "off",
            (false, None) => "none",
        },
        "integrator": {"scheme": "gen-alpha", "step": parameters.integration.step,
                       "end": parameters.integration.end,
                       "spectral_radius": parameters.integration.spectral_radius},
        "outputs": study.output_names,
        "axes": parameters.axes.id(),
        "stability": study.stability.iter().map(|c| json!({
            "model": c.label,
            "highest_hz": c.highest_hz,
            "critical_step_s": c.critical_s,
            "above_step_s": c.above_step_s,
            "diverged_at_s": c.diverged_at,
        })).collect::<Vec<_>>(),
        "times": study.times,
        "runs": runs,
    })
}

/// Whether the runs carried dynamic stiffening, and what leaving it out means at this rate.
fn stiffening_words(
    body: &ImportedBody,
    parameters: &DrivenBodyParameters,
    study: &DrivenStudy,
) -> String {
    if parameters.rate == 0.0 {
        return String::new();
    }
    // The lowest frequency on the frame at rest any reduced run found, rad/s.
    let lowest = study
        .runs
        .iter()
        .filter_map(|r| r.hz_range.map(|(lo, _)| lo))
        .fold(f64::INFINITY, f64::min)
        * 2.0
        * std::f64::consts::PI;
    let share = (parameters.rate / lowest).powi(2);
    let share = if share.is_finite() {
        format!(
            " (the spin's share of the lowest stiffness, (Ω/ω₁)², is {share} at {} rad/s)",
            parameters.rate,
            share = flexmodes_core::report::readable(share, 2)
        )
    } else {
        String::new()
    };
    match (study.stiffened, &body.preload) {
        (true, Some(p)) => format!(
            "\nDynamic stiffening: on, from the body's [preload] (the stiffness its FE code wrote \
             spun at {} rad/s), its geometric stiffness scaled by (θ̇/Ω₀)²{share}.\n",
            sig(p.load.rate)
        ),
        (false, Some(_)) => format!(
            "\nDynamic stiffening: OFF (--stiffening off): the body's [preload] is not used, so \
             the models keep the centrifugal softening but not the stress stiffening{share}.\n"
        ),
        _ => format!(
            "\nDynamic stiffening: none: the body file gives no [preload], so the models keep the \
             centrifugal softening but not the stress stiffening{share}; a CalculiX run spun \
             at the rate gives it (docs/bodies.md).\n"
        ),
    }
}

/// One row per run: its size, frequency range, costs and errors against the full body (the
/// online time and both errors ranked, lower is better).
pub fn runs_table(study: &DrivenStudy) -> Table {
    let full_online = study
        .runs
        .iter()
        .find(|r| r.method.is_none())
        .map(|r| r.cost.online_s);
    let none = || Cell::text("–");
    let hz = |x: Option<f64>| x.map_or_else(none, |x| Cell::number(x, format!("{:.6}", sig(x))));
    let error = |x: Option<f64>| x.map_or_else(none, |e| Cell::number(e, crate::report::sig3(e)));
    let mut table = Table::new(&[
        "model",
        "coordinates",
        "residual vectors",
        "lowest Hz",
        "highest Hz",
        "offline s",
        "online s",
        "NR online / online",
        "Krylov iterations",
        "a-priori estimate",
        "history error",
        "reaction error",
    ])
    .rank_lower(&[6, 10, 11]);
    for r in &study.runs {
        let online = r.cost.online_s;
        table.push(vec![
            Cell::text(r.label()),
            Cell::number(r.coordinates as f64, r.coordinates.to_string()),
            match r.method {
                None => none(),
                Some(_) => Cell::number(r.residual_vectors as f64, r.residual_vectors.to_string()),
            },
            hz(r.hz_range.map(|h| h.0)),
            hz(r.hz_range.map(|h| h.1)),
            Cell::number(r.offline_s, format!("{:.3}", r.offline_s)),
            Cell::number(online, format!("{online:.4}")),
            full_online.map_or_else(none, |f| {
                let ratio = f / online.max(1e-9);
                Cell::number(ratio, format!("{ratio:.0}"))
            }),
            Cell::text(r.cost.iterations.to_string()),
            error(r.estimate_max()),
            error(r.history_error),
            error(r.reaction_error),
        ]);
    }
    table
}

/// What moves the drive, in words: spun up, shaken, gravity, or held still.
fn motion_words(parameters: &DrivenBodyParameters, length: &str) -> Vec<String> {
    let list = |v: [f64; 3]| v.map(|x| x.to_string()).join(", ");
    let mut motion = Vec::new();
    if parameters.rate != 0.0 {
        motion.push(format!(
            "spun up about ({}){} to {} rad/s over {} s",
            list(parameters.axis),
            parameters.axis_point.map_or(String::new(), |p| format!(
                " through ({}) {length}",
                list(p)
            )),
            parameters.rate,
            parameters.ramp
        ));
    }
    if let Some((d, a, f)) = parameters.shake {
        motion.push(format!("shaken along ({}) by {a} m at {f} Hz", list(d)));
    }
    if let Some(g) = parameters.gravity {
        motion.push(format!("gravity ({}) m/s²", list(g)));
    }
    if motion.is_empty() {
        motion.push("held still".into());
    }
    motion
}

/// Each run's outputs and reaction force at the last time.
fn final_values(study: &DrivenStudy, force: &str) -> String {
    let mut text = String::new();
    if let Some(last) = study.times.last() {
        for run in &study.runs {
            let finals: Vec<String> = study
                .output_names
                .iter()
                .zip(&run.outputs)
                .map(|(name, h)| {
                    let u = h.last().copied().unwrap_or([0.0; 3]);
                    format!(
                        "{name} ({})",
                        u.map(|x| flexmodes_core::report::readable(x, 7).to_string())
                            .join(", ")
                    )
                })
                .collect();
            let r = run.reaction.last().copied().unwrap_or([0.0; 6]);
            text += &format!(
                "\n{} at t = {last} s: {}; reaction force ({}) {force}",
                run.label(),
                finals.join("; "),
                r[..3]
                    .iter()
                    .map(|x| flexmodes_core::report::readable(x, 7).to_string())
                    .collect::<Vec<_>>()
                    .join(", ")
            );
        }
        text.push('\n');
    }
    text
}

/// One run's row of the JSON value.
fn run_json(r: &DrivenRun) -> serde_json::Value {
    json!({
        "model": r.label(),
        "method": r.method.map(|m| m.id()).unwrap_or("nr"),
        "modes": r.modes,
        "coordinates": r.coordinates,
        "lowest_hz": r.hz_range.map(|h| h.0),
        "highest_hz": r.hz_range.map(|h| h.1),
        "offline_s": r.offline_s,
        "online_s": r.cost.online_s,
        "steps": r.cost.steps,
        "scheme": if r.explicit_step.is_some() { "dp5" } else { "gen-alpha" },
        "explicit_step_s": r.explicit_step,
        "solves": r.cost.solves,
        "krylov_iterations": r.cost.iterations,
        "history_error": r.history_error,
        "reaction_error": r.reaction_error,
        "residual_vectors": r.residual_vectors,
        "a_priori_estimate": r.estimate_max(),
        "a_priori_estimate_by_load": r.estimate.iter()
            .map(|(name, e)| json!({"load": name, "share_outside": e}))
            .collect::<Vec<_>>(),
        "outputs": r.outputs,
        "reaction": r.reaction,
    })
}
