//! `flexmodes simulate`: a driven body's runs (models::driven_body_study) as a table, as
//! JSON and as a recording.

use serde_json::json;

pub use super::body_simulation_visuals::recording;
use super::{RunCache, SceneId};
use crate::{
    Error, Progress, Result,
    body_file::ImportedBody,
    models::{DrivenBodyParameters, DrivenRun, DrivenStudy, driven_body_study},
    record::RecordingContent,
    reduction::Method,
    report::{Cell, Table, sig},
};

/// A driven simulation asked of the `modes` scene (the explorer's `simulate`): the body's
/// interface driven as `flexmodes simulate` drives it, one model per method.
#[derive(Debug, Clone, PartialEq)]
pub struct BodySimulation {
    /// The drive, its motion and the integrator's steps.
    pub parameters: DrivenBodyParameters,
    /// Also integrate the full body: the reference of every history and reaction error.
    pub full_body: bool,
}

/// A drive as the explorer's panel states it: which node set, how it moves, for how long.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DriveRequest<'a> {
    /// The driven node set, tied rigidly to its master (`rbe2:SET`).
    pub drive: &'a str,
    /// Other node sets the reduced models keep as interfaces (tied rigidly, free in the
    /// simulation).
    pub kept: &'a [String],
    /// Steady spin rate about z through the drive's master, rad/s (a spin-up).
    pub rate: f64,
    /// Time to reach the rate, s.
    pub ramp: f64,
    /// A harmonic shake along ground x instead of a spin: amplitude (m) and frequency (Hz).
    pub shake: Option<(f64, f64)>,
    /// Simulated interval, s.
    pub end: f64,
    /// Also integrate the full body.
    pub full_body: bool,
}

/// Samples of the histories over a requested interval (as `simulate`'s default).
const REQUEST_SAMPLES: usize = 100;

impl BodySimulation {
    /// The simulation `request` states: generalized-α at `simulate`'s default step,
    /// a hundred samples of the histories. No drive, or a rate, ramp, amplitude,
    /// frequency or interval that is not a positive number, is refused by name.
    pub fn of_request(request: &DriveRequest<'_>) -> Result<Self> {
        let defaults = DrivenBodyParameters::default();
        let invalid = |reason: String| Error::InvalidOption {
            option: "simulate",
            scene: Some(SceneId::Modes.as_str()),
            reason,
        };
        let drive = request.drive.trim();
        if drive.is_empty() {
            return Err(invalid("choose the interface to drive".into()));
        }
        let (amplitude, frequency) = request.shake.unwrap_or((1.0, 1.0));
        let positive = [
            (
                "rate",
                if request.shake.is_some() {
                    1.0
                } else {
                    request.rate
                },
            ),
            ("ramp", request.ramp),
            ("amplitude", amplitude),
            ("frequency", frequency),
            ("end time", request.end),
        ];
        if let Some((name, value)) = positive.iter().find(|(_, v)| !(v.is_finite() && *v > 0.0)) {
            return Err(invalid(format!("the {name} must be positive, not {value}")));
        }
        let step = defaults.integration.step;
        let steps = (request.end / step).round().max(1.0) as usize;
        Ok(Self {
            parameters: DrivenBodyParameters {
                drive: format!("rbe2:{drive}"),
                boundary: request
                    .kept
                    .iter()
                    .filter(|set| set.trim() != drive)
                    .map(|set| format!("rbe2:{}", set.trim()))
                    .collect(),
                rate: if request.shake.is_some() {
                    0.0
                } else {
                    request.rate
                },
                ramp: request.ramp,
                shake: request.shake.map(|(a, f)| ([1.0, 0.0, 0.0], a, f)),
                integration: crate::dynamics::DrivenIntegration {
                    end: request.end,
                    output_every: (steps / REQUEST_SAMPLES).max(1),
                    ..defaults.integration
                },
                ..defaults
            },
            full_body: request.full_body,
        })
    }
}

/// Runs `simulation` of `body` with `methods` (one model per count of `modes` kept
/// fixed-interface modes each, Guyan one) and returns the study: what `flexmodes simulate`
/// prints and, through [`recording`], writes.
///
/// With a cache that keeps runs (the explorer's), the full body's run and each method's are
/// kept apart and joined: ticking a method on or off, or changing the kept modes, integrates
/// only the reduced models it adds, never the full body again (its tens of seconds, not the
/// reduced models' second, are the cost). Without one (the command line), one study runs.
/// The runs not yet kept go on up to `concurrent` threads, the full body's first: the reduced
/// models are done beside it.
pub fn simulated_study(
    body: &ImportedBody,
    simulation: &BodySimulation,
    (methods, modes): (&[Method], &[usize]),
    progress: &Progress,
    cache: &RunCache,
    concurrent: usize,
) -> Result<DrivenStudy> {
    let study_of = |parameters, methods: &[Method], full: bool, progress: &Progress| {
        driven_body_study(body, parameters, methods, modes, full, progress)
    };
    Ok(if cache.is_detached() {
        study_of(
            &simulation.parameters,
            methods,
            simulation.full_body,
            progress,
        )?
    } else {
        // The body by its file and its contents: a file edited and loaded again is another
        // body.
        let contents = fingerprint(&body.model);
        let key = |run: &str, parameters: &DrivenBodyParameters| {
            format!(
                "simulate/{:?}/{contents:016x}/{parameters:?}/{run}",
                body.location
            )
        };
        // The full body leaves the reduced models' kept interfaces free: its run does not
        // depend on them.
        let full = DrivenBodyParameters {
            boundary: Vec::new(),
            ..simulation.parameters.clone()
        };
        let runs: Vec<Option<Method>> = simulation
            .full_body
            .then_some(None)
            .into_iter()
            .chain(methods.iter().copied().map(Some))
            .collect();
        let parts =
            crate::work_pool::run_concurrently(&runs, concurrent, progress, |run, p| match run {
                None => cache.get_or_run(key("nr", &full), || study_of(&full, &[], true, p)),
                Some(m) => {
                    let parameters = &simulation.parameters;
                    let reduced = key(&format!("{}/{modes:?}", m.id()), parameters);
                    cache.get_or_run(reduced, || study_of(parameters, &[m], false, p))
                }
            })
            .into_iter()
            .collect::<Result<Vec<_>>>()?;
        DrivenStudy::joined(&parts.iter().map(|p| p.as_ref()).collect::<Vec<_>>())?
    })
}

/// [`simulated_study`]'s recording, with the kept modes `modes` for every method: the one
/// `flexmodes simulate --save` writes for the same choices.
pub fn simulated(
    body: &ImportedBody,
    simulation: &BodySimulation,
    (methods, modes): (&[Method], usize),
    progress: &Progress,
    cache: &RunCache,
    concurrent: usize,
) -> Result<RecordingContent> {
    let study = simulated_study(
        body,
        simulation,
        (methods, &[modes]),
        progress,
        cache,
        concurrent,
    )?;
    let (_, text) = summary(body, &simulation.parameters, &study);
    Ok(recording(&body.model, &study, &text))
}

/// A hash of what a driven body's runs depend on: its DOF map, node coordinates and every
/// stored entry of K and M (bit for bit).
fn fingerprint(model: &crate::fem::FeModel) -> u64 {
    use std::hash::{Hash, Hasher};
    let mut h = std::collections::hash_map::DefaultHasher::new();
    model.name.hash(&mut h);
    model.dof_count().hash(&mut h);
    for p in model.nodes.iter().flatten() {
        p.to_bits().hash(&mut h);
    }
    let mut values = |m: &crate::linalg::SparseSymmetric| {
        let a = m.as_faer();
        a.symbolic().col_ptr().hash(&mut h);
        a.symbolic().row_idx().hash(&mut h);
        for v in a.val() {
            v.to_bits().hash(&mut h);
        }
    };
    values(&model.k);
    match &model.m {
        crate::linalg::MassMatrix::Lumped(d) => d.iter().for_each(|v| v.to_bits().hash(&mut h)),
        crate::linalg::MassMatrix::Consistent(m) => values(m),
    }
    h.finish()
}

impl super::CacheWeight for DrivenStudy {
    fn bytes(&self) -> usize {
        self.heap_bytes()
    }
}

/// The JSON value and the text of a driven body's study.
pub fn summary(
    body: &ImportedBody,
    parameters: &DrivenBodyParameters,
    study: &DrivenStudy,
) -> (serde_json::Value, String) {
    let length = &body.units.length;
    let force = &body.units.force;
    let table = runs_table(study).markdown();
    let (drive, master, ring) = &study.drive;
    let steps = study.runs.first().map_or(0, |r| r.cost.steps);
    let motion = motion_words(parameters, length);
    let mut text = format!(
        "# simulate `{}` ({} DOF): `{drive}` ({ring} nodes, master at ({}) {length}) {}, \
         generalized-α ρ∞ = {}, {steps} steps of {} s\n\n{table}\n",
        body.model.name,
        study.dof,
        master.map(sig).map(|x| x.to_string()).join(", "),
        motion.join("; "),
        parameters.integration.spectral_radius,
        parameters.integration.step,
    );
    text += &format!(
        "\nHistory: the mean displacement of {} {} ({length}); history error = \
         largest difference over the largest full-body value; reaction error = largest \
         reaction-force difference over the largest elastic part of the full body's. Lowest \
         and highest Hz: the reduced model on the frame at rest, ring clamped. Online: the \
         integration alone (the outputs' reconstruction left out).\n",
        study.output_names.join(", "),
        match parameters.axes {
            crate::dynamics::AxisKind::Mean => {
                "seen from the body's mean axes (the motion in the drive's frame less its rigid \
                 part in the mass metric, §4.2 linearised)"
            }
            _ => "in the drive's turning frame",
        }
    );
    for c in &study.stability {
        text += &format!(
            "\nExplicit Dormand–Prince on {}: highest frequency {:.6} Hz, critical step \
             {:.3e} s; the run below it ({} DP5) {}; at {:.3e} s ({:.0}× critical) {}.\n",
            c.label,
            sig(c.highest_hz),
            c.critical_s,
            c.label,
            "is bounded (its row above)",
            c.above_step_s,
            c.above_step_s / c.critical_s,
            match c.diverged_at {
                Some(t) => format!("it diverged at t = {t:.4e} s, as predicted"),
                None => "it did NOT diverge: the prediction is not confirmed".into(),
            }
        );
    }
    if !parameters.boundary.is_empty() && study.runs.iter().any(|r| r.method.is_some()) {
        text += &format!(
            "\nThe reduced models keep {} as interfaces (an rbe2 set as a rigid ring) while the full \
             body leaves them free: part of their history error is that ring's stiffening, \
             not the reduction.\n",
            parameters.boundary.join(", ")
        );
    }
    text += &final_values(study, force);
    let runs: Vec<serde_json::Value> = study.runs.iter().map(run_json).collect();
    let value = json!({
        "body": body.model.name,
        "dof": study.dof,
        "units": {"length": length, "force": force},
        "drive": {"interface": drive, "master": master, "nodes": ring},
        "motion": {"axis": parameters.axis, "rate": parameters.rate, "ramp": parameters.ramp,
                   "axis_point": parameters.axis_point,
                   "shake": parameters.shake.map(|(d, a, f)| json!({
                       "direction": d, "amplitude_m": a, "frequency_hz": f}))},
        "gravity": parameters.gravity,
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
    });
    (value, text)
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
    let error = |x: Option<f64>| x.map_or_else(none, |e| Cell::number(e, format!("{e:.2e}")));
    let mut table = Table::new(&[
        "model",
        "coordinates",
        "lowest Hz",
        "highest Hz",
        "offline s",
        "online s",
        "NR online / online",
        "Krylov iterations",
        "history error",
        "reaction error",
    ])
    .rank_lower(&[5, 8, 9]);
    for r in &study.runs {
        let online = r.cost.online_s;
        table.push(vec![
            Cell::text(r.label()),
            Cell::number(r.coordinates as f64, r.coordinates.to_string()),
            hz(r.hz_range.map(|h| h.0)),
            hz(r.hz_range.map(|h| h.1)),
            Cell::number(r.offline_s, format!("{:.3}", r.offline_s)),
            Cell::number(online, format!("{online:.4}")),
            full_online.map_or_else(none, |f| {
                let ratio = f / online.max(1e-9);
                Cell::number(ratio, format!("{ratio:.0}"))
            }),
            Cell::text(r.cost.iterations.to_string()),
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
                    format!("{name} ({})", u.map(|x| format!("{x:.6e}")).join(", "))
                })
                .collect();
            let r = run.reaction.last().copied().unwrap_or([0.0; 6]);
            text += &format!(
                "\n{} at t = {last} s: {}; reaction force ({}) {force}",
                run.label(),
                finals.join("; "),
                r[..3]
                    .iter()
                    .map(|x| format!("{x:.6e}"))
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
        "outputs": r.outputs,
        "reaction": r.reaction,
    })
}
