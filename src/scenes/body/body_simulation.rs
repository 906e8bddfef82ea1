//! `flexmodes simulate` and the explorer's driven body: the simulation asked, and its runs
//! (models::driven_body_study), cached apart and joined; their table and JSON are in
//! `body_simulation_report`, their recording in `body_simulation_visuals`.

use crate::scenes::RunCache;
pub use crate::scenes::body::body_simulation_report::{runs_table, summary};
pub use crate::scenes::body::body_simulation_visuals::recording;
use crate::{
    Error, Progress, Result,
    body_file::ImportedBody,
    models::{DrivenBodyParameters, DrivenStudy, driven_body_study},
    record::RecordingContent,
    reduction::Method,
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
    /// Dynamic stiffening from the body file's `[preload]`.
    pub stiffening: bool,
    /// Inertia-load residual vectors in the reduced bases.
    pub residual_vectors: bool,
}

/// Samples of the histories over a requested interval (as `simulate`'s default).
const REQUEST_SAMPLES: usize = 100;

impl BodySimulation {
    /// The simulation `request` states: generalized-α at `simulate`'s default step,
    /// a hundred samples of the histories. No drive, or a rate, ramp, amplitude,
    /// frequency or interval that is not a positive number, is refused by name.
    pub fn of_request(request: &DriveRequest<'_>, scene: &'static str) -> Result<Self> {
        let defaults = DrivenBodyParameters::default();
        let invalid = |reason: String| Error::InvalidOption {
            option: "simulate",
            scene: Some(scene),
            reason,
        };
        let drive = request.drive.trim();
        if drive.is_empty() {
            return Err(invalid("choose the interface to drive".into()));
        }
        // The values the motion uses: a spin's rate, or a shake's amplitude and frequency.
        let mut positive = vec![("ramp", request.ramp), ("end time", request.end)];
        match request.shake {
            Some((amplitude, frequency)) => {
                positive.extend([("amplitude", amplitude), ("frequency", frequency)])
            }
            None => positive.push(("rate", request.rate)),
        }
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
                stiffening: request.stiffening,
                residual_vectors: request.residual_vectors,
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
            .collect::<Result<Vec<_>, _>>()?;
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
    Ok(recording(&body.model, &study, &text, &body.units.length))
}

/// A hash of what a driven body's runs depend on: its DOF map, node coordinates and every
/// stored entry of K and M (bit for bit).
fn fingerprint(model: &crate::fem::FeModel) -> u64 {
    use std::hash::{Hash, Hasher};
    let mut h = std::collections::hash_map::DefaultHasher::new();
    model.name.hash(&mut h);
    model.dof_count().hash(&mut h);
    model.dofs.node_dofs().hash(&mut h);
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

impl crate::scenes::CacheWeight for DrivenStudy {
    fn bytes(&self) -> usize {
        self.heap_bytes()
    }
}
