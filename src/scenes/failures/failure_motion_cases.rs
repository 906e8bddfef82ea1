//! The failures scene's cases in motion: mean axes with a Guyan mass, an explicit step above
//! critical, modal truncation and boundary motion, a spin-up without dynamic stiffening.

use crate::dynamics::DynamicsError;
use crate::record::{REFERENCE, method_color};
use crate::scenes::SceneOptions;
use crate::scenes::failures::failure_cases::Failure;
use crate::{
    Result,
    error::CoreError,
    fem::FeModel,
    models::{
        ABOVE_CRITICAL, BELOW_CRITICAL, BELOW_RUN_S, KEPT_MODES, MOVED_NODE, SpinUpModels,
        SpinUpParameters, boundary_motion, explicit_step, guyan_mean_axes,
    },
    record::{Geometry, LogLogChart, LogLogSeries, Visual},
    reduction::Method,
    report::sig,
};
use serde_json::{Value, json};

/// The mass matrix of Guyan's masters as a nodal mass matrix under mean axes.
pub(super) fn guyan_mean_axes_failure(model: &FeModel) -> Result<Failure> {
    let g = guyan_mean_axes(model)?;
    Ok(Failure {
        json: json!({
            "masters": g.masters,
            "block_anisotropy": {"lumped": g.anisotropy_lumped, "guyan": sig(g.anisotropy_guyan)},
            "identity_defect": {"lumped": g.identity_full, "guyan": sig(g.identity_guyan)},
            "coupling_rel_error": sig(g.coupling_error),
        }),
        line: [
            "Mean axes with a Guyan-condensed mass matrix (slab, masters 16, 18, 28, 30, 5, 11)"
                .into(),
            format!(
                "the condensed M's 3×3 nodal blocks are {:.0} % anisotropic (lumped: \
                 {}); δ̇̃^T M δ̇ for two modes' velocities is {:.1} % of its \
                 scale (full body: {}); the deformation term δ̃^T M δ̇ of the \
                 angular mean-axis condition is off by {:.0} %",
                100.0 * g.anisotropy_guyan,
                flexmodes_core::report::readable(g.anisotropy_lumped, 1),
                100.0 * g.identity_guyan,
                flexmodes_core::report::readable(g.identity_full, 1),
                100.0 * g.coupling_error
            ),
            "Eqs. 3.26 and 4.17 need M's nodal blocks to be multiples of I (lumped or \
             consistent) so that M commutes with rotations; a condensed M couples directions, \
             so mean axes imposed with it drift from the body's mean axes (measured here on \
             the terms, not by a simulation)"
                .into(),
        ],
        visuals: Vec::new(),
    })
}

/// slab-sim1 with Craig–Bampton: fixed Dormand–Prince steps below and above the critical
/// step; the critical steps of NR, GR, MT and CB beside it.
pub(super) fn explicit_step_failure(model: &FeModel, opts: &SceneOptions) -> Result<Failure> {
    let study = explicit_step(model, &opts.progress)?;
    let critical = study.critical;
    let below_ok = study.below.is_ok();
    let (above_diverged, above_text) = match &study.above {
        Some(e @ CoreError::Dynamics(DynamicsError::Diverged { .. })) => (true, e.to_string()),
        Some(e) => (false, e.to_string()),
        None => (false, "no divergence".into()),
    };
    let below_zeta = *study.below.as_ref().unwrap_or(&f64::NAN);
    let mut histories = Vec::new();
    if let Some(points) = study.below_history {
        histories.push((
            format!("{BELOW_CRITICAL}× critical"),
            method_color(Method::CraigBampton),
            points,
        ));
    }
    if let Some(points) = study.above_history {
        histories.push((
            format!("{ABOVE_CRITICAL}× critical"),
            [230, 90, 60, 255],
            points,
        ));
    }
    let chart = LogLogChart {
        path: "charts/explicit_step".into(),
        x_unit: "time, s".into(),
        y_unit: "deflection, m".into(),
        series: histories
            .into_iter()
            .enumerate()
            .map(|(k, (label, color, points))| LogLogSeries {
                id: format!("run{}", k + 1),
                label,
                color,
                points,
                line: true,
            })
            .collect(),
        x_linear: true,
    };
    let predicted_json: serde_json::Map<String, Value> = study
        .predicted
        .iter()
        .map(|p| {
            (
                p.method.id().to_string(),
                json!({
                    "coordinates": p.coordinates,
                    "highest_hz": sig(p.highest_hz),
                    "critical_dt_s": sig(p.critical_s),
                }),
            )
        })
        .collect();
    let nr = study.predicted[0];
    Ok(Failure {
        json: json!({
            "scene": "slab-sim1",
            "method": "cb",
            "modes": KEPT_MODES,
            "critical_dt_s": sig(critical),
            "run_below_ok": below_ok,
            "run_above_diverged": above_diverged,
            "above_message": above_text,
            "below_max_zeta_m": sig(below_zeta),
            "predicted": predicted_json,
        }),
        line: [
            "Explicit step above critical (slab-sim1, CB 6 modes, DP5 fixed step)".into(),
            format!(
                "critical step {critical} s; at {BELOW_CRITICAL}× it runs {BELOW_RUN_S} s \
                 ({}); at {ABOVE_CRITICAL}×: {above_text}. NR's bound is {} s \
                 ({:.0} Hz), {:.0}× smaller",
                if below_ok { "bounded" } else { "FAILED" },
                flexmodes_core::report::readable(nr.critical_s, 2),
                nr.highest_hz,
                critical / nr.critical_s,
                critical = flexmodes_core::report::readable(critical, 3)
            ),
            format!(
                "Dormand–Prince 5(4) is stable on the imaginary axis (undamped modes) only for \
                 ω·h ≤ {:.3}, so the highest retained frequency bounds the step; reduction \
                 lowers it (the full model keeps the stiff modes; at 3× the growth is 1.44× per \
                 step)",
                crate::dynamics::imaginary_stability_limit()
            ),
        ],
        visuals: chart.visuals(),
    })
}

/// Modal truncation and Craig–Bampton following a boundary displacement of the slab.
pub(super) fn boundary_motion_failure(model: &FeModel) -> Result<Failure> {
    let study = boundary_motion(model)?;
    // Drawn at one common scale: the exact response's largest displacement at 15 % of the
    // slab's size.
    let largest = study
        .exact
        .chunks(3)
        .map(|d| (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt())
        .fold(0.0f64, f64::max);
    let scale = 0.15 * model.size() / largest;
    let geometry = Geometry::of(model);
    let mut visuals = Vec::new();
    for (k, (id, name, u, color)) in [
        ("exact", "exact (full model)", &study.exact, REFERENCE),
        (
            "mt",
            "modal truncation",
            &study.mt,
            method_color(Method::ModalTruncation),
        ),
        (
            "cb",
            "Craig–Bampton",
            &study.cb,
            method_color(Method::CraigBampton),
        ),
    ]
    .into_iter()
    .enumerate()
    {
        let path = format!("static/{id}");
        visuals.push(Visual::Offset {
            path: path.clone(),
            translation: [0.0, -3.0 * k as f64, 0.0],
        });
        visuals.push(Visual::Mode {
            path,
            geometry: geometry.clone(),
            shape: u
                .chunks(3)
                .map(|d| [d[0] * scale, d[1] * scale, d[2] * scale])
                .collect(),
            label: format!("{name}: node {MOVED_NODE} moved up"),
            color,
        });
    }
    let (mt_error, cb_error, ratio) = (study.mt_error, study.cb_error, study.mt_energy_ratio);
    Ok(Failure {
        json: json!({
            "moved": format!("node {MOVED_NODE} z"),
            "rel_error": {"mt": sig(mt_error), "cb": cb_error},
            "mt_energy_ratio": sig(ratio),
        }),
        line: [
            "Modal truncation and boundary motion (slab held at 16, 18, 28, 30)".into(),
            format!(
                "static response to a displacement of node {MOVED_NODE} (z): modal \
                 truncation's best response is {:.0} % off (strain energy {ratio:.1}× \
                 the exact), Craig–Bampton's {cb_error}",
                100.0 * mt_error,
                cb_error = flexmodes_core::report::readable(cb_error, 1)
            ),
            "MT's boundary columns move no interior node (Eq. 6.17), so boundary motion reaches \
             the body only through the kept fixed-interface modes; CB's constraint modes are \
             the exact static response (Eq. 6.3)"
                .into(),
        ],
        visuals,
    })
}

/// Kane's beam spun up to 10 rad/s by the linear floating-frame model without dynamic
/// stiffening (NR, the full FE beam): it diverges once the hub's rate has passed the first
/// bending frequency; the same model with stiffening does not (the `spin-up` scene).
pub(super) fn spin_up_failure(opts: &SceneOptions) -> Result<Failure> {
    /// The steady rate of Kane et al.'s faster case, rad/s.
    const RATE: f64 = 10.0;
    let parameters = SpinUpParameters {
        rates: vec![RATE],
        ..Default::default()
    };
    let models = SpinUpModels::new(&parameters)?;
    let run = models.run(RATE, 0, false, &opts.progress)?;
    let w1 = models.first_frequency;
    let length = parameters.beam.length;
    let (json, what) = match run.divergence {
        Some(d) => (
            json!({
                "diverged_at_s": sig(d.time),
                "hub_rate_rad_s": sig(d.rate),
                "first_frequency_rad_s": sig(w1),
                "passed_first_frequency_at_s": d.rate_passed_first_frequency.map(sig),
            }),
            format!(
                "NR without stiffening: the tip's deflection passed the beam's length \
                 ({length} m) at t = {:.2} s, the hub at {:.2} rad/s; the hub passed the first \
                 bending frequency ω₁ = {w1:.3} rad/s at t = {}",
                d.time,
                d.rate,
                d.rate_passed_first_frequency
                    .map_or("–".into(), |t| format!("{t:.2} s")),
            ),
        ),
        None => (
            json!({"diverged_at_s": null, "peak_m": sig(run.peak())}),
            format!(
                "NR without stiffening did not diverge (peak {:.3} m): expected it to",
                run.peak()
            ),
        ),
    };
    Ok(Failure {
        json,
        line: [
            format!("Spin-up without dynamic stiffening (Kane et al.'s beam, ω_s = {RATE} rad/s)"),
            what,
            "linear elastic coordinates keep the centrifugal softening −Ω²M but not the \
             centrifugal tension's geometric stiffness: the in-plane bending stiffness \
             K − Ω²M turns indefinite at Ω = ω₁ (Lin §1, refs. [16], [18]); with the \
             geometric stiffness of the frame's loads the model follows the nonlinear \
             reference (`spin-up` scene)"
                .into(),
        ],
        visuals: Vec::new(),
    })
}
