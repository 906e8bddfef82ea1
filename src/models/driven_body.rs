//! A user's body driven through an interface: the interface's master follows a prescribed
//! spin-up about an axis through it, its ring clamped in the turning frame (nodal-fixed axes
//! at the interface, Table 4-1), gravity on or off, every other interface free. The full body
//! (NR, sparse) and every reduced model that keeps the ring still (GR, MT, CB, MC on the
//! drive and the other interfaces) run the same motion with the same integrator; each
//! model's history (the mean displacement of chosen node sets in the frame, and the reaction
//! at the drive) is compared with the full body's.

use std::{sync::Arc, time::Instant};

use faer::Mat;
use nalgebra::{Unit, Vector3};

use crate::{
    Error, Result,
    analysis::count_zero_energy_modes,
    body_file::{ImportedBody, InterfaceKind},
    dynamics::{
        DrivenCost, DrivenFrameBody, DrivenIntegration, Driving, SpinUp, free_rows,
        integrate_driven, positions,
    },
    fem::FeModel,
    linalg::{GeneralizedEigen, MassMatrix, generalized_eigen},
    progress::Progress,
    reduction::{ColumnKind, Method, ReductionError},
};

use super::{BodyInterfaces, BodyReducer};

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
    /// The axis (body axes, normalised here), the steady rate (rad/s) and the ramp time (s).
    pub axis: [f64; 3],
    /// Steady rate Ω, rad/s.
    pub rate: f64,
    /// Ramp time, s.
    pub ramp: f64,
    /// Gravity in ground axes, m/s² (converted to the body's length unit).
    pub gravity: Option<[f64; 3]>,
    /// The integrator's steps.
    pub integration: DrivenIntegration,
}

impl Default for DrivenBodyParameters {
    fn default() -> Self {
        Self {
            drive: String::new(),
            boundary: Vec::new(),
            outputs: Vec::new(),
            axis: [0.0, 0.0, 1.0],
            rate: 100.0,
            ramp: 0.5,
            gravity: None,
            integration: DrivenIntegration {
                step: 1e-3,
                end: 1.0,
                spectral_radius: 0.9,
                output_every: 10,
            },
        }
    }
}

/// How a run's coordinates give the full displacement field.
#[derive(Debug, Clone)]
pub enum FieldMap {
    /// The full body's free DOF (the clamped ring at zero).
    Free {
        /// DOF of the body.
        dofs: usize,
        /// The free DOF, ascending.
        free: Arc<Vec<usize>>,
    },
    /// A reduced body's basis Ψ (every DOF's row).
    Basis(Arc<Mat<f64>>),
}

impl FieldMap {
    /// The nodal displacements (node-major, every DOF) of coordinates `x`.
    pub fn field(&self, x: &[f64]) -> Vec<f64> {
        match self {
            FieldMap::Free { dofs, free } => {
                assert_eq!(x.len(), free.len(), "one coordinate per free DOF");
                let mut y = vec![0.0; *dofs];
                for (&d, &v) in free.iter().zip(x) {
                    y[d] = v;
                }
                y
            }
            FieldMap::Basis(psi) => {
                assert_eq!(x.len(), psi.ncols(), "one coordinate per column of Ψ");
                let mut y = vec![0.0; psi.nrows()];
                for (c, &xc) in x.iter().enumerate() {
                    if xc != 0.0 {
                        let col = psi.col(c);
                        y.iter_mut()
                            .enumerate()
                            .for_each(|(i, y)| *y += col[i] * xc);
                    }
                }
                y
            }
        }
    }
}

/// One model's run.
#[derive(Debug, Clone)]
pub struct DrivenRun {
    /// `None` for the full body (NR).
    pub method: Option<Method>,
    /// Kept modes asked for (0 for NR).
    pub modes: usize,
    /// Coordinates integrated.
    pub coordinates: usize,
    /// The model's highest and lowest natural frequencies on the frame at rest (ring
    /// clamped), Hz (reduced models only).
    pub hz_range: Option<(f64, f64)>,
    /// Building the model: reduction and projection (NR: the operators and the symbolic
    /// analysis), s.
    pub offline_s: f64,
    /// The integration.
    pub cost: DrivenCost,
    /// Per sample: the run's coordinates (free DOF or modal coordinates).
    pub states: Vec<Vec<f64>>,
    /// From coordinates to the full displacement field.
    pub field_map: FieldMap,
    /// Per output set, per sample: the mean displacement in frame axes (length unit).
    pub outputs: Vec<Vec<[f64; 3]>>,
    /// Per sample: the reaction at the drive, force (force unit) and moment about the master
    /// (force × length unit) in frame axes.
    pub reaction: Vec<[f64; 6]>,
    /// Against the full body: the largest output difference over the largest full output.
    pub history_error: Option<f64>,
    /// Against the full body: the largest reaction force difference over the largest
    /// elastic part of the full reaction force (its change from the rigid body's).
    pub reaction_error: Option<f64>,
}

impl DrivenRun {
    /// `NR` or e.g. `CB 10`.
    pub fn label(&self) -> String {
        match self.method {
            None => "NR".into(),
            Some(Method::Guyan) => "GR".into(),
            Some(m) => format!("{} {}", m.id().to_uppercase(), self.modes),
        }
    }
}

/// Every run of one driven body.
#[derive(Debug, Clone)]
pub struct DrivenStudy {
    /// Sample times, s.
    pub times: Vec<f64>,
    /// Output node sets.
    pub output_names: Vec<String>,
    /// The drive's name, master point and ring size.
    pub drive: (String, [f64; 3], usize),
    /// The body's DOF.
    pub dof: usize,
    /// The runs, the full body first when it ran.
    pub runs: Vec<DrivenRun>,
}

/// Metres per length unit of the body files' units.
pub fn metres_per(unit: &str) -> Result<f64> {
    Ok(match unit {
        "m" => 1.0,
        "cm" => 1e-2,
        "mm" => 1e-3,
        "in" => 0.0254,
        "ft" => 0.3048,
        other => {
            return Err(Error::InvalidOption {
                scene: "simulate".into(),
                reason: format!(
                    "the body's length unit `{other}` is not one gravity can be converted to \
                     (m, cm, mm, in, ft)"
                ),
            });
        }
    })
}

/// What each sample is measured with: the output sets' DOF and the full field's pieces.
struct Measure<'a> {
    model: &'a FeModel,
    s: Vec<f64>,
    axis: Vector3<f64>,
    outputs: Vec<Vec<usize>>,
    driving: Driving,
}

impl Measure<'_> {
    fn output(&self, u_full: &[f64]) -> Vec<[f64; 3]> {
        self.outputs
            .iter()
            .map(|dofs| {
                let mut mean = [0.0; 3];
                for triple in dofs.chunks_exact(3) {
                    for a in 0..3 {
                        mean[a] += u_full[triple[a]] / (dofs.len() / 3) as f64;
                    }
                }
                mean
            })
            .collect()
    }

    /// The reaction at the drive: the rate of the body's momentum less gravity, force and
    /// moment about the frame's origin, from the nodal accelerations in frame axes
    /// $a = \ddot\theta\,e\times b + \dot\theta^2 e\times(e\times b) + 2\dot\theta\,e\times
    /// \dot u + \ddot u$, $b = s + u$.
    fn reaction(&self, t: f64, u: &[f64], v: &[f64], a: &[f64]) -> [f64; 6] {
        let (rate, acceleration, g_body) = self.driving.at(t);
        let n = u.len();
        let mut acc = vec![0.0; n];
        for j in 0..n / 3 {
            let b = Vector3::new(
                self.s[3 * j] + u[3 * j],
                self.s[3 * j + 1] + u[3 * j + 1],
                self.s[3 * j + 2] + u[3 * j + 2],
            );
            let ud = Vector3::new(v[3 * j], v[3 * j + 1], v[3 * j + 2]);
            let e = self.axis;
            let x = e.cross(&b) * acceleration
                + e.cross(&e.cross(&b)) * (rate * rate)
                + e.cross(&ud) * (2.0 * rate)
                + Vector3::new(a[3 * j], a[3 * j + 1], a[3 * j + 2])
                - g_body;
            acc[3 * j..3 * j + 3].copy_from_slice(x.as_slice());
        }
        let w = mass_mul(&self.model.m, &acc);
        let mut out = [0.0; 6];
        for j in 0..n / 3 {
            let wj = Vector3::new(w[3 * j], w[3 * j + 1], w[3 * j + 2]);
            let b = Vector3::new(
                self.s[3 * j] + u[3 * j],
                self.s[3 * j + 1] + u[3 * j + 1],
                self.s[3 * j + 2] + u[3 * j + 2],
            );
            let m = b.cross(&wj);
            for q in 0..3 {
                out[q] += wj[q];
                out[3 + q] += m[q];
            }
        }
        out
    }
}

fn mass_mul(m: &MassMatrix, x: &[f64]) -> Vec<f64> {
    let y = m.mul(faer::MatRef::from_column_major_slice(x, x.len(), 1));
    (0..x.len()).map(|i| y[(i, 0)]).collect()
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
    let mut items = vec![parameters.drive.clone()];
    items.extend(parameters.boundary.iter().cloned());
    let interfaces = BodyInterfaces::of(body, &items, None)?;
    // The drive is the first rigid interface the items name.
    let drive_set = body.boundary_with_interfaces(std::slice::from_ref(&parameters.drive))?;
    let drive = match drive_set.1.first() {
        Some(set) if set.kind == InterfaceKind::Rbe2 && drive_set.1.len() == 1 => interfaces
            .rigid
            .iter()
            .find(|i| i.name == set.name)
            .cloned()
            .expect("named above"),
        _ => {
            return Err(ReductionError::InvalidDofSet {
                set: parameters.drive.clone(),
                reason: "the drive must be one rigid interface: rbe2:SET or an rbe2 interface \
                         of the body file"
                    .into(),
            }
            .into());
        }
    };
    let axis = Unit::try_new(Vector3::from(parameters.axis), 1e-12).ok_or_else(|| {
        Error::InvalidOption {
            scene: "simulate".into(),
            reason: "the spin axis is zero".into(),
        }
    })?;
    if !(parameters.ramp > 0.0 && parameters.integration.step > 0.0) {
        return Err(Error::InvalidOption {
            scene: "simulate".into(),
            reason: "the ramp time and the step must be positive".into(),
        });
    }
    let gravity = match parameters.gravity {
        Some(g) => Vector3::from(g) / metres_per(&body.units.length)?,
        None => Vector3::zeros(),
    };
    let driving = Driving {
        spin: SpinUp {
            axis,
            rate: parameters.rate,
            ramp: parameters.ramp,
        },
        gravity,
    };
    let output_names: Vec<String> = if parameters.outputs.is_empty() {
        body.node_sets
            .keys()
            .filter(|k| **k != drive.name)
            .cloned()
            .collect()
    } else {
        parameters.outputs.clone()
    };
    let mut outputs = Vec::new();
    for name in &output_names {
        let nodes = body
            .node_sets
            .get(name)
            .ok_or_else(|| Error::InvalidOption {
                scene: "simulate".into(),
                reason: format!(
                    "no node set `{name}` to output (the body has: {})",
                    body.node_sets
                        .keys()
                        .cloned()
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
            })?;
        outputs.push(model.dofs_of_nodes(nodes)?);
    }
    let measure = Measure {
        model,
        s: positions(model, drive.master),
        axis: axis.into_inner(),
        outputs,
        driving,
    };
    let ring = model.dofs_of_nodes(&drive.nodes)?;

    progress.phase("full body on the driven frame")?;
    let started = Instant::now();
    let mut full_body = DrivenFrameBody::full(model, &ring, drive.master, axis)?;
    let full_offline = started.elapsed().as_secs_f64();
    let full_map = FieldMap::Free {
        dofs: model.dof_count(),
        free: Arc::new(full_body.free_dofs().to_vec()),
    };

    let mut times = Vec::new();
    let mut runs = Vec::new();
    if full {
        progress.phase("NR: the full body, sparse")?;
        let (mut outs, mut reaction) = (Vec::new(), Vec::new());
        let (mut t_samples, mut states) = (Vec::new(), Vec::new());
        let cost = integrate_driven(
            &mut full_body,
            &driving,
            &parameters.integration,
            progress,
            |t, x, v, a| {
                let (u, v, a) = (full_map.field(x), full_map.field(v), full_map.field(a));
                states.push(x.to_vec());
                t_samples.push(t);
                outs.push(measure.output(&u));
                reaction.push(measure.reaction(t, &u, &v, &a));
                Ok(())
            },
        )?;
        times = t_samples;
        runs.push(DrivenRun {
            method: None,
            modes: 0,
            coordinates: full_body.dim(),
            hz_range: None,
            offline_s: full_offline,
            cost,
            states,
            field_map: full_map.clone(),
            outputs: transpose(outs, measure.outputs.len()),
            reaction,
            history_error: None,
            reaction_error: None,
        });
    }

    let needs_reducer = !methods.is_empty() && !modes.is_empty();
    if needs_reducer {
        progress.phase("the body's zero-energy modes")?;
        let started = Instant::now();
        let zero = count_zero_energy_modes(model, 1)?;
        let zero_s = started.elapsed().as_secs_f64();
        let mut reducer = BodyReducer::new(model, interfaces, &zero, zero_s, progress.clone())?;
        for &method in methods {
            if !DRIVEN_METHODS.contains(&method) {
                return Err(ReductionError::MethodNeedsContext {
                    method: method.name().into(),
                    needs: "a basis whose boundary columns are unit interface motions, so the \
                            driven ring can be held still on the frame (gr, mt, cb, mc)"
                        .into(),
                }
                .into());
            }
            let counts: &[usize] = if method == Method::Guyan { &[0] } else { modes };
            for &kept in counts {
                progress.phase(&format!("{} {kept}", method.name()))?;
                let started = Instant::now();
                let reduced = reducer.reduce(method, kept)?;
                let keep: Vec<usize> = reduced
                    .basis
                    .columns
                    .iter()
                    .enumerate()
                    .filter(|(_, c)| {
                        !matches!(&c.kind, ColumnKind::RigidInterface { interface, .. }
                            if *interface == drive.name)
                    })
                    .map(|(j, _)| j)
                    .collect();
                if keep.is_empty() {
                    return Err(ReductionError::MethodNeedsContext {
                        method: method.name().into(),
                        needs: "a coordinate besides the drive: Guyan keeps only the \
                                interfaces' constraint modes, and with the drive the only \
                                interface the body would be rigid (add --boundary)"
                            .into(),
                    }
                    .into());
                }
                let psi_all = &reduced.basis.psi;
                let psi = Arc::new(Mat::from_fn(psi_all.nrows(), keep.len(), |i, j| {
                    psi_all[(i, keep[j])]
                }));
                let map = FieldMap::Basis(psi.clone());
                let psi_free = free_rows(&full_body, psi.as_ref().as_ref())?;
                let mut reduced_body = DrivenFrameBody::reduced(&full_body, psi_free.as_ref())?;
                let hz_range = frame_frequencies(&reduced_body)?;
                let offline_s = reduced.offline_s + started.elapsed().as_secs_f64();
                let (mut outs, mut reaction) = (Vec::new(), Vec::new());
                let (mut t_samples, mut states) = (Vec::new(), Vec::new());
                let cost = integrate_driven(
                    &mut reduced_body,
                    &driving,
                    &parameters.integration,
                    progress,
                    |t, z, zd, zdd| {
                        let (u, v, a) = (map.field(z), map.field(zd), map.field(zdd));
                        states.push(z.to_vec());
                        t_samples.push(t);
                        outs.push(measure.output(&u));
                        reaction.push(measure.reaction(t, &u, &v, &a));
                        Ok(())
                    },
                )?;
                if times.is_empty() {
                    times = t_samples;
                }
                runs.push(DrivenRun {
                    method: Some(method),
                    modes: if method == Method::Guyan { 0 } else { kept },
                    coordinates: keep.len(),
                    hz_range,
                    offline_s,
                    cost,
                    states,
                    field_map: map,
                    outputs: transpose(outs, measure.outputs.len()),
                    reaction,
                    history_error: None,
                    reaction_error: None,
                });
            }
        }
    }
    if full {
        let (reference, rest) = runs.split_first_mut().expect("the full body ran first");
        let rigid_force = rigid_reaction(&measure, &times);
        for run in rest {
            run.history_error = Some(history_error(&reference.outputs, &run.outputs));
            run.reaction_error = Some(reaction_error(
                &reference.reaction,
                &run.reaction,
                &rigid_force,
            ));
        }
    }
    Ok(DrivenStudy {
        times,
        output_names,
        drive: (drive.name.clone(), drive.master, drive.nodes.len()),
        dof: model.dof_count(),
        runs,
    })
}

/// Per output, per sample.
fn transpose(samples: Vec<Vec<[f64; 3]>>, outputs: usize) -> Vec<Vec<[f64; 3]>> {
    (0..outputs)
        .map(|o| samples.iter().map(|s| s[o]).collect())
        .collect()
}

fn norm3(x: [f64; 3]) -> f64 {
    (x[0] * x[0] + x[1] * x[1] + x[2] * x[2]).sqrt()
}

fn diff3(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// $\max_{o,t} |y_o(t) - y^{ref}_o(t)| / \max_{o,t} |y^{ref}_o(t)|$; the histories must be
/// sampled alike.
pub fn history_error(reference: &[Vec<[f64; 3]>], run: &[Vec<[f64; 3]>]) -> f64 {
    assert_eq!(reference.len(), run.len(), "outputs of the two runs");
    let mut largest = 0.0f64;
    let mut worst = 0.0f64;
    for (r, y) in reference.iter().zip(run) {
        assert_eq!(r.len(), y.len(), "samples of the two runs");
        for (&a, &b) in r.iter().zip(y) {
            largest = largest.max(norm3(a));
            worst = worst.max(norm3(diff3(a, b)));
        }
    }
    worst / largest.max(f64::MIN_POSITIVE)
}

/// The reaction force of the undeformed body on the frame at each sample.
fn rigid_reaction(measure: &Measure<'_>, times: &[f64]) -> Vec<[f64; 3]> {
    let zero = vec![0.0; measure.s.len()];
    times
        .iter()
        .map(|&t| {
            let r = measure.reaction(t, &zero, &zero, &zero);
            [r[0], r[1], r[2]]
        })
        .collect()
}

fn reaction_error(reference: &[[f64; 6]], run: &[[f64; 6]], rigid: &[[f64; 3]]) -> f64 {
    assert_eq!(reference.len(), run.len(), "samples of the two runs");
    assert_eq!(
        reference.len(),
        rigid.len(),
        "samples of the rigid reaction"
    );
    let force = |r: &[f64; 6]| [r[0], r[1], r[2]];
    let mut largest = 0.0f64;
    let mut worst = 0.0f64;
    for ((a, b), g) in reference.iter().zip(run).zip(rigid) {
        largest = largest.max(norm3(diff3(force(a), *g)));
        worst = worst.max(norm3(diff3(force(a), force(b))));
    }
    worst / largest.max(f64::MIN_POSITIVE)
}

/// The lowest and highest natural frequencies of a reduced body on its frame at rest, Hz,
/// checked by the dense generalised eigensolver.
fn frame_frequencies(body: &DrivenFrameBody) -> Result<Option<(f64, f64)>> {
    let k = body.dim();
    let columns = |c| -> Vec<Vec<f64>> {
        (0..k)
            .map(|j| {
                let mut e = vec![0.0; k];
                e[j] = 1.0;
                body.mul(c, &e)
            })
            .collect()
    };
    let stiffness = crate::dynamics::Combination {
        k: 1.0,
        ..Default::default()
    };
    let mass = crate::dynamics::Combination {
        m: 1.0,
        ..Default::default()
    };
    let (kc, mc) = (columns(stiffness), columns(mass));
    let kk = Mat::from_fn(k, k, |i, j| kc[j][i]);
    let mm = Mat::from_fn(k, k, |i, j| mc[j][i]);
    let e: GeneralizedEigen =
        generalized_eigen(kk.as_ref(), mm.as_ref(), "reduced body on the driven frame")?;
    let hz = e.hz();
    Ok(match (hz.first(), hz.last()) {
        (Some(&lo), Some(&hi)) => Some((lo, hi)),
        _ => None,
    })
}
