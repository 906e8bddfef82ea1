//! A user's body driven through an interface: the interface's master follows a prescribed
//! spin-up about an axis through it, its ring clamped in the turning frame (nodal-fixed axes
//! at the interface, Table 4-1), gravity on or off, every other interface free. The full body
//! (NR, sparse) and every reduced model that keeps the ring still (GR, MT, CB, MC on the
//! drive and the other interfaces) run the same motion with the same integrator; each
//! model's history (the mean displacement of chosen node sets in the frame, and the reaction
//! at the drive) is compared with the full body's.

use std::{sync::Arc, time::Instant};

use faer::Mat;
use nalgebra::Vector3;

use crate::{
    Result,
    analysis::{ZeroEnergyCount, count_zero_energy_modes},
    body_file::ImportedBody,
    dynamics::{
        AxisKind, DrivenCost, DrivenFrameBody, DrivenIntegration, Driving, FrameCoordinates,
        PinnedRing, integrate_driven, positions,
    },
    fem::{FeModel, acceleration_field},
    progress::Progress,
    reduction::{Basis, Method, ReductionError, RigidInterface},
};

use super::driven_setup::{
    apply_preload, drive_interface, driving_of, free_columns, mean_axes_of, output_names,
    output_nodes, pinned_rings, spin_axis_point,
};
use super::{
    BodyInterfaces, BodyReducer,
    driven_measure::{FieldMap, Measure, rigid_reaction, transpose},
    driven_stability::{ExplicitCheck, explicit_runs, frame_frequencies},
    driven_study::{DrivenRun, DrivenStudy, compare_with_full},
};

/// The methods a driven body can be reduced by: those whose boundary columns are unit motions
/// of the interfaces, so the driven ring can be held still.
pub const DRIVEN_METHODS: [Method; 4] = [
    Method::Guyan,
    Method::ModalTruncation,
    Method::CraigBampton,
    Method::ModeCondensation,
];

/// The set-up of a driven body.
#[derive(Debug, Clone, PartialEq)]
pub struct DrivenBodyParameters {
    /// The driven interface: `rbe2:SET` or an rbe2 interface the body file declares.
    pub drive: String,
    /// Other interfaces the reduced models keep (constraint modes of their masters), free in
    /// the simulation.
    pub boundary: Vec<String>,
    /// Node sets whose mean displacement is the history (empty: every node set but the
    /// drive's).
    pub outputs: Vec<String>,
    /// Node sets (rbe2) pinned to the frame: their masters' translations held, rotations
    /// free; the reduced models keep their masters' rotations.
    pub pinned: Vec<String>,
    /// The axis (body axes, normalised here), the steady rate (rad/s) and the ramp time (s).
    pub axis: [f64; 3],
    /// Steady rate Ω, rad/s.
    pub rate: f64,
    /// Ramp time, s.
    pub ramp: f64,
    /// A point of the spin axis (the body's length unit); `None`: the drive's master. Away
    /// from the master the drive orbits the axis.
    pub axis_point: Option<[f64; 3]>,
    /// A harmonic translation of the drive: direction (ground axes), amplitude (m) and
    /// frequency (Hz).
    pub shake: Option<([f64; 3], f64, f64)>,
    /// Gravity in ground axes, m/s² (converted to the body's length unit).
    pub gravity: Option<[f64; 3]>,
    /// The integrator's steps.
    pub integration: DrivenIntegration,
    /// Also run each reduced model with the explicit Dormand–Prince scheme below its critical
    /// step, and check that it diverges above it.
    pub explicit: bool,
    /// The axes the histories are seen from: the drive's frame (nodal-fixed at the
    /// interface) or the body's mean axes (the same motion, its rigid part in the mass metric
    /// taken out); principal axes are not offered.
    pub axes: AxisKind,
    /// Dynamic stiffening from the body's preloaded stiffness (`[preload]`), when it has
    /// one: on by default.
    pub stiffening: bool,
    /// The residual vectors of the frame's inertia loads in every reduced basis
    /// ([`crate::reduction::with_inertia_residual_vectors`]): on by default for a user's body.
    pub residual_vectors: bool,
}

impl Default for DrivenBodyParameters {
    fn default() -> Self {
        Self {
            drive: String::new(),
            boundary: Vec::new(),
            outputs: Vec::new(),
            pinned: Vec::new(),
            axis: [0.0, 0.0, 1.0],
            rate: 100.0,
            ramp: 0.5,
            axis_point: None,
            shake: None,
            gravity: None,
            integration: DrivenIntegration {
                step: 1e-3,
                end: 1.0,
                spectral_radius: 0.9,
                output_every: 10,
            },
            explicit: false,
            axes: AxisKind::NodalFixed,
            stiffening: true,
            residual_vectors: true,
        }
    }
}

/// Runs the full body (when `full`) and each method × kept-mode count on `body` under
/// `parameters`; the errors are against the full body's run.
pub fn driven_body_study(
    body: &ImportedBody,
    parameters: &DrivenBodyParameters,
    methods: &[Method],
    modes: &[usize],
    full: bool,
    progress: &Progress,
) -> Result<DrivenStudy> {
    body.require_coordinates()?;
    let model = &body.model;
    let (items, pinned_items) = interface_items(parameters);
    let interfaces = BodyInterfaces::of(body, &items, None)?;
    let drive = drive_interface(body, &parameters.drive, &interfaces)?;
    let driving = driving_of(body, parameters)?;
    // The frame turns about the axis point; the drive's ring is clamped in it wherever it is.
    let axis_point = spin_axis_point(
        body,
        &drive,
        driving.spin.axis,
        parameters.axis_point,
        parameters.stiffening,
    )?;
    let origin = axis_point.0;
    let (output_names, measure) =
        measure_of(body, parameters, &drive, &pinned_items, driving, origin)?;
    let ring = model.dofs_of_nodes(&drive.nodes)?;
    let pins = pinned_rings(model, &interfaces, &pinned_items)?;

    progress.phase("full body on the driven frame")?;
    let started = Instant::now();
    let axis = (driving.spin.axis, origin);
    let mut full_body = DrivenFrameBody::full(model, &ring, pins.clone(), origin, axis.0)?;
    let stiffened = apply_preload(body, &mut full_body, parameters.stiffening, axis, &ring)?;
    let full_offline = started.elapsed().as_secs_f64();
    let coords = full_body
        .coordinates()
        .cloned()
        .expect("the full body has coordinates");
    let full_map = FieldMap::Full(Arc::new(coords.clone()));

    // The eigen solve the reduced models need comes first: a body whose free-free modes
    // cannot be found fails here, not after minutes of integrating the full body.
    let reduces = !methods.is_empty() && !modes.is_empty();
    let zero_energy = reduces
        .then(|| zero_energy_modes(model, progress))
        .transpose()?;
    let mut collected = Collected::default();
    if full {
        progress.phase("NR: the full body, sparse")?;
        let integration = &parameters.integration;
        let (times, run) = full_run(
            &mut full_body,
            &full_map,
            &measure,
            integration,
            full_offline,
            progress,
        )?;
        collected.times = times;
        collected.runs.push(run);
    }

    if let Some((zero, zero_s)) = zero_energy {
        let mut reducer = BodyReducer::new(model, interfaces, &zero, zero_s, progress.clone())?
            .with_residual_vectors(parameters.residual_vectors);
        let drive_loads = drive_loads(model, origin, &measure.driving);
        let reduced = ReducedRuns {
            drive_loads: &drive_loads,
            full_body: &full_body,
            coords: &coords,
            drive: &drive,
            pins: &pins,
            measure: &measure,
            parameters,
            progress,
        };
        for &method in methods {
            let counts: &[usize] = if method == Method::Guyan { &[0] } else { modes };
            for &kept in counts {
                reduced.run(&mut reducer, method, kept, &mut collected)?;
            }
        }
    }
    let rigid_force = rigid_reaction(&measure, &collected.times);
    if full {
        compare_with_full(&mut collected.runs, &rigid_force);
    }
    Ok(DrivenStudy {
        times: collected.times,
        output_names,
        drive: (drive.name.clone(), drive.master, drive.nodes.len()),
        dof: model.dof_count(),
        runs: collected.runs,
        stability: collected.stability,
        rigid_force,
        stiffened,
        axis_point,
        residual_vectors: parameters.residual_vectors,
    })
}

/// The body's zero-energy modes (a free-free eigen solve) and the seconds they took.
fn zero_energy_modes(model: &FeModel, progress: &Progress) -> Result<(ZeroEnergyCount, f64)> {
    progress.phase("the body's zero-energy modes (free-free eigen solve)")?;
    let started = Instant::now();
    let zero = count_zero_energy_modes(model, 1)?;
    Ok((zero, started.elapsed().as_secs_f64()))
}

/// The histories' output sets (named, and as DOF) and how they are measured: in the frame
/// turning about `origin`, moments about the drive's master, from mean axes where asked.
fn measure_of<'a>(
    body: &'a ImportedBody,
    parameters: &DrivenBodyParameters,
    drive: &RigidInterface,
    pinned_items: &[String],
    driving: Driving,
    origin: [f64; 3],
) -> Result<(Vec<String>, Measure<'a>)> {
    let model = &body.model;
    let pinned_names: Vec<&str> = pinned_items
        .iter()
        .map(|p| p.split_once(':').map_or(p.as_str(), |(_, n)| n))
        .collect();
    let names = output_names(body, parameters, drive, &pinned_names);
    let mut outputs = Vec::new();
    for name in &names {
        outputs.push(model.dofs_of_nodes(&output_nodes(body, name)?)?);
    }
    let measure = Measure {
        mean_axes: mean_axes_of(model, parameters.axes, &outputs)?,
        model,
        s: positions(model, origin),
        arm: Vector3::from(drive.master) - Vector3::from(origin),
        axis: driving.spin.axis.into_inner(),
        outputs,
        driving,
    };
    Ok((names, measure))
}

/// The interfaces the study names, the drive first, then the other boundaries and the pinned
/// sets (`rbe2:` where no kind is given); and the pinned ones alone.
fn interface_items(parameters: &DrivenBodyParameters) -> (Vec<String>, Vec<String>) {
    let pinned: Vec<String> = parameters
        .pinned
        .iter()
        .map(|p| {
            if p.contains(':') {
                p.clone()
            } else {
                format!("rbe2:{p}")
            }
        })
        .collect();
    let mut items = vec![parameters.drive.clone()];
    items.extend(parameters.boundary.iter().cloned());
    items.extend(pinned.iter().cloned());
    (items, pinned)
}

/// The full body (NR) integrated and sampled: the sample times and its run, built in
/// `offline_s` seconds.
fn full_run(
    full_body: &mut DrivenFrameBody,
    map: &FieldMap,
    measure: &Measure,
    integration: &DrivenIntegration,
    offline_s: f64,
    progress: &Progress,
) -> Result<(Vec<f64>, DrivenRun)> {
    let sampled = sample_run(full_body, map, measure, integration, progress)?;
    let run = DrivenRun {
        method: None,
        modes: 0,
        coordinates: full_body.dim(),
        hz_range: None,
        offline_s,
        cost: sampled.cost,
        explicit_step: None,
        states: sampled.states,
        field_map: map.clone(),
        outputs: transpose(sampled.outputs, measure.outputs.len()),
        reaction: sampled.reaction,
        history_error: None,
        reaction_error: None,
        residual_vectors: 0,
        estimate: Vec::new(),
    };
    Ok((sampled.times, run))
}

/// What the runs gather as they go: the sample times (of the first run), every run, and the
/// explicit scheme's checks.
#[derive(Default)]
struct Collected {
    times: Vec<f64>,
    runs: Vec<DrivenRun>,
    stability: Vec<ExplicitCheck>,
}

/// One integration's samples: times (s), states, output histories and reactions.
struct Sampled {
    times: Vec<f64>,
    states: Vec<Vec<f64>>,
    outputs: Vec<Vec<[f64; 3]>>,
    reaction: Vec<[f64; 6]>,
    cost: DrivenCost,
}

/// Integrates `body` (full or reduced, its coordinates mapped to the full field by `map`)
/// and measures every sample.
fn sample_run(
    body: &mut DrivenFrameBody,
    map: &FieldMap,
    measure: &Measure,
    integration: &DrivenIntegration,
    progress: &Progress,
) -> Result<Sampled> {
    let (mut outputs, mut reaction) = (Vec::new(), Vec::new());
    let (mut times, mut states) = (Vec::new(), Vec::new());
    let cost = integrate_driven(
        body,
        &measure.driving,
        integration,
        progress,
        |t, x, xd, xdd| {
            let (u, v, a) = (map.field(x), map.field(xd), map.field(xdd));
            states.push(x.to_vec());
            times.push(t);
            outputs.push(measure.output(&u));
            reaction.push(measure.reaction(t, &u, &v, &a));
            Ok(())
        },
    )?;
    Ok(Sampled {
        times,
        states,
        outputs,
        reaction,
        cost,
    })
}

/// What every reduced run of one study shares.
struct ReducedRuns<'a> {
    drive_loads: &'a [(String, Vec<f64>)],
    full_body: &'a DrivenFrameBody,
    coords: &'a FrameCoordinates,
    drive: &'a RigidInterface,
    pins: &'a [PinnedRing],
    measure: &'a Measure<'a>,
    parameters: &'a DrivenBodyParameters,
    progress: &'a Progress,
}

impl ReducedRuns<'_> {
    /// The a-priori estimate of a basis: per drive load, the share of its static response the
    /// basis misses.
    fn estimate(&self, reducer: &mut BodyReducer, basis: &Basis) -> Result<Vec<(String, f64)>> {
        let loads: Vec<Vec<f64>> = self.drive_loads.iter().map(|(_, f)| f.clone()).collect();
        Ok(self
            .drive_loads
            .iter()
            .map(|(name, _)| name.clone())
            .zip(reducer.static_shares(basis, &loads)?)
            .collect())
    }

    /// The basis' columns but the drive's and the pins' held ones; none left is refused.
    fn kept_columns(&self, basis: &Basis, method: Method) -> Result<Vec<usize>> {
        let keep = free_columns(basis, &self.drive.name, self.pins);
        if keep.is_empty() {
            return Err(ReductionError::MethodNeedsContext {
                method: method.name(),
                needs: "a coordinate besides the drive: Guyan keeps only the interfaces' \
                        constraint modes, and with the drive the only interface the body \
                        would be rigid (keep another interface: `simulate --boundary \
                        rbe2:SET`, or \"also kept\" in the explorer)",
            }
            .into());
        }
        Ok(keep)
    }

    /// `method` with `kept` modes: reduced, its drive's and pins' held columns removed,
    /// integrated (and, when asked, integrated explicitly beside), appended to `collected`.
    fn run(
        &self,
        reducer: &mut BodyReducer,
        method: Method,
        kept: usize,
        collected: &mut Collected,
    ) -> Result<()> {
        let Collected {
            times,
            runs,
            stability,
        } = collected;
        if !DRIVEN_METHODS.contains(&method) {
            return Err(ReductionError::MethodNeedsContext {
                method: method.name(),
                needs: "a basis whose boundary columns are unit interface motions, so the \
                        driven ring can be held still on the frame (gr, mt, cb, mc)",
            }
            .into());
        }
        let progress = self.progress;
        progress.phase(&format!("{} {kept}", method.name()))?;
        let started = Instant::now();
        let reduced = reducer.reduce(method, kept)?;
        let estimate = self.estimate(reducer, &reduced.basis)?;
        let residual_vectors = reduced
            .residual_vectors
            .as_ref()
            .map_or(0, |r| r.kept.len());
        let keep = self.kept_columns(&reduced.basis, method)?;
        let psi_all = &reduced.basis.psi;
        let psi = Arc::new(Mat::from_fn(psi_all.nrows(), keep.len(), |i, j| {
            psi_all[(i, keep[j])]
        }));
        let map = FieldMap::Basis(psi.clone());
        let psi_free = self.coords.coordinates_of(psi.as_ref().as_ref())?;
        let mut reduced_body = DrivenFrameBody::reduced(self.full_body, psi_free.as_ref())?;
        let hz_range = frame_frequencies(&reduced_body)?;
        let offline_s = reduced.offline_s + started.elapsed().as_secs_f64();
        let integration = &self.parameters.integration;
        let sampled = sample_run(&mut reduced_body, &map, self.measure, integration, progress)?;
        if times.is_empty() {
            *times = sampled.times;
        }
        let modes = if method == Method::Guyan { 0 } else { kept };
        let outputs = self.measure.outputs.len();
        let run = DrivenRun {
            method: Some(method),
            modes,
            coordinates: keep.len(),
            hz_range,
            offline_s,
            cost: sampled.cost,
            explicit_step: None,
            states: sampled.states,
            field_map: map.clone(),
            outputs: transpose(sampled.outputs, outputs),
            reaction: sampled.reaction,
            history_error: None,
            reaction_error: None,
            residual_vectors,
            estimate: estimate.clone(),
        };
        let label = run.label();
        runs.push(run);
        if let (true, Some((_, highest))) = (self.parameters.explicit, hz_range) {
            progress.phase(&format!("{label} explicit"))?;
            let (explicit, check) = explicit_runs(
                &mut reduced_body,
                &map,
                self.measure,
                (label, highest),
                (
                    integration.step * integration.output_every.max(1) as f64,
                    integration.end,
                ),
                progress,
            )?;
            stability.push(check);
            runs.push(DrivenRun {
                method: Some(method),
                modes,
                coordinates: keep.len(),
                hz_range,
                offline_s,
                cost: explicit.cost,
                explicit_step: Some(explicit.step),
                states: explicit.states,
                field_map: map,
                outputs: transpose(explicit.outputs, outputs),
                reaction: explicit.reaction,
                history_error: None,
                reaction_error: None,
                residual_vectors,
                estimate,
            });
        }
        Ok(())
    }
}

/// The loads the drive puts on the undeformed body, $M a(x)$ with $a$ per unit coefficient:
/// when it spins, the spin's centrifugal load about the axis through `origin` ("rate²") and
/// its tangential load ("angular acceleration"); when gravity or shaking move the frame, a
/// unit linear acceleration along each axis.
fn drive_loads(model: &FeModel, origin: [f64; 3], driving: &Driving) -> Vec<(String, Vec<f64>)> {
    let e = driving.spin.axis.into_inner();
    let load = |field: &dyn Fn([f64; 3]) -> ([f64; 3], [f64; 3])| -> Vec<f64> {
        let a = acceleration_field(model, origin, 1.0, field);
        let y = model
            .m
            .mul(faer::MatRef::from_column_major_slice(&a, a.len(), 1));
        (0..a.len()).map(|i| y[(i, 0)]).collect()
    };
    let centrifugal = |s: [f64; 3]| {
        let r = Vector3::from(s);
        let a = e * e.dot(&r) - r;
        ([a.x, a.y, a.z], [0.0; 3])
    };
    let tangential = |s: [f64; 3]| {
        let a = e.cross(&Vector3::from(s));
        ([a.x, a.y, a.z], [e.x, e.y, e.z])
    };
    let mut loads = Vec::new();
    if driving.spin.rate != 0.0 {
        loads.push(("rate²".to_string(), load(&centrifugal)));
        loads.push(("angular acceleration".to_string(), load(&tangential)));
    }
    if driving.gravity != Vector3::zeros() || driving.shake.is_some() {
        for (k, name) in ["x", "y", "z"].iter().enumerate() {
            let linear = move |_: [f64; 3]| {
                let mut t = [0.0; 3];
                t[k] = 1.0;
                (t, [0.0; 3])
            };
            loads.push((format!("linear acceleration {name}"), load(&linear)));
        }
    }
    loads
}
