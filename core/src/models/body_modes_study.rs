//! The `modes` scene's model: a body's full free-free modes, its constraint and fixed-interface
//! modes on the interface, every asked method's reduced model measured against the full
//! body (frequency errors, MAC, principal angles, rigid modes), the interface-reduction sweep
//! of Craig–Bampton, the modal influence across the interfaces and, over a band, the interface
//! response (§6.2–6.5 on a body of one's own).

use std::time::Instant;

use faer::{Mat, MatRef};

use super::{
    BodyInterfaces, BodyReducer, INTERFACE_MODE_SWEEP, InterfaceReductionPoint, InterfaceResponse,
    ReducedBody, interface_reduction_sweep, modes_up_to, refuse_mechanism,
};
use crate::{
    Error, Progress, Result,
    analysis::{FrequencyResponse, ZeroEnergyCount, pair_modes},
    fem::FeModel,
    linalg::{GeneralizedEigen, LinalgError, principal_angles},
    reduction::{
        Basis, ColumnKind, Method, ModalInfluence, ModeSelection, Partition, ReductionError,
    },
};

/// Elastic frequencies compared per model (the six lowest).
pub const BODY_MODES_COMPARED: usize = 6;

/// What the study computes.
#[derive(Debug, Clone, PartialEq)]
pub struct BodyModesParameters {
    /// The interfaces (boundary nodes, rigid and averaging interfaces, interface reduction).
    pub interfaces: BodyInterfaces,
    /// The methods, in the order their rows are listed.
    pub methods: Vec<Method>,
    /// Kept normal modes.
    pub kept: usize,
    /// Top of the band of the full body's modes and of the interface response, Hz (None:
    /// [`Self::full_modes`] modes, no response).
    pub band_hz: Option<f64>,
    /// Elastic free-free modes solved for without a band.
    pub full_modes: usize,
    /// Constraint mode shapes solved for drawing.
    pub drawn_constraint_modes: usize,
}

/// One method's reduced model, measured against the full body.
#[derive(Debug, Clone)]
pub struct MethodMeasure {
    /// Reduced coordinates.
    pub size: usize,
    /// Elastic frequencies, Hz (checked pairs) and their residuals.
    pub hz: Vec<f64>,
    pub residuals: Vec<f64>,
    /// Zero-energy modes of the reduced model.
    pub zero_modes: usize,
    /// Relative errors of the elastic frequencies against the full body's, paired by order.
    pub rel_errors: Vec<f64>,
    /// The largest of the first [`BODY_MODES_COMPARED`] (NaN: fewer elastic modes than that).
    pub worst_error: f64,
    /// The largest principal angle between Ψ and the full body's zero-energy and lowest
    /// elastic modes, rad.
    pub max_angle: f64,
    /// MAC of each compared full mode against its best-paired expanded reduced mode.
    pub macs: Vec<f64>,
    /// Their smallest (NaN: no elastic mode to pair).
    pub min_mac: f64,
    /// The highest frequency the model gives a rigid-body motion, Hz.
    pub rigid_hz_max: f64,
    /// Offline wall time, s.
    pub offline_s: f64,
    /// The model's interface response over the band.
    pub response: Option<FrequencyResponse>,
}

/// The modes of the body held at its interface.
#[derive(Debug, Clone)]
pub struct HeldModes {
    /// Constraint mode shapes (DOF × drawn modes) and their labels.
    pub constraint_shapes: (Mat<f64>, Vec<String>),
    /// The kept fixed-interface modes (checked pairs).
    pub fixed_interface: GeneralizedEigen,
    /// The interior partition they live on.
    pub partition: Partition,
}

/// What [`body_modes_study`] computed.
pub struct BodyModesStudy {
    /// The full body's lowest modes (zero-energy ones first) and their wall time, s.
    pub full: ZeroEnergyCount,
    pub full_s: f64,
    /// The full body's elastic modes alone.
    pub elastic: GeneralizedEigen,
    /// The constraint and fixed-interface modes, when a boundary holds the body.
    pub held: Option<HeldModes>,
    /// Per method, in order: its measures, or why it was not computed.
    pub methods: Vec<(Method, std::result::Result<MethodMeasure, String>)>,
    /// What a method took in place of what a single body lacks, by method.
    pub notes: Vec<(Method, String)>,
    /// The interface reduction sweep of Craig–Bampton (when CB ran and has more constraint
    /// modes than the sweep's first count).
    pub sweep: Option<Vec<InterfaceReductionPoint>>,
    /// The full body's interface response over the band.
    pub response: Option<InterfaceResponse>,
    /// The lowest elastic free-free frequencies and their modal influence across the
    /// interfaces (Gregory's coefficients), for `influence_count` modes.
    pub influence: (Vec<f64>, ModalInfluence),
    /// Modes the influence ranks.
    pub influence_count: usize,
}

/// MAC of the full body's first elastic modes against a reduced model's expanded ones (the
/// lowest 2 × compared of them, paired by best MAC), and the smallest of them (NaN with none);
/// `eig` are the reduced model's modes, `skip` of them zero-energy, `hz` its elastic ones.
fn paired_macs(
    elastic: &GeneralizedEigen,
    full_hz: &[f64],
    basis: &Basis,
    eig: &GeneralizedEigen,
    skip: usize,
    hz: &[f64],
) -> (Vec<f64>, f64) {
    let candidates = hz.len().min(2 * BODY_MODES_COMPARED);
    let expanded = basis.psi.as_ref() * eig.vectors.subcols(skip, candidates);
    let compared_full: Vec<usize> = (0..full_hz.len().min(BODY_MODES_COMPARED)).collect();
    let macs: Vec<f64> = pair_modes(
        elastic.vectors.as_ref(),
        full_hz,
        &compared_full,
        expanded.as_ref(),
        &hz[..candidates],
    )
    .iter()
    .map(|pair| pair.mac)
    .collect();
    let min_mac = if candidates == 0 {
        f64::NAN
    } else {
        macs.iter().copied().fold(1.0, f64::min)
    };
    (macs, min_mac)
}

/// The constraint and fixed-interface modes, when a boundary holds the body (rbe3 interfaces
/// alone hold nothing).
fn held_modes(reducer: &mut BodyReducer<'_>, p: &BodyModesParameters) -> Result<Option<HeldModes>> {
    Ok(if p.interfaces.boundary.is_empty() {
        None
    } else {
        let problem = reducer.problem()?;
        Some(HeldModes {
            constraint_shapes: problem.constraint_shapes(p.drawn_constraint_modes)?,
            fixed_interface: problem.kept_modes(ModeSelection::Count(p.kept))?,
            partition: problem.partition.clone(),
        })
    })
}

/// How many characteristic constraint modes the interface needs (Castanier–Tan–Pierre): the
/// sweep over CB's constraint modes, when it has more than the sweep's first count.
fn interface_sweep(
    model: &FeModel,
    cb_basis: Option<&Basis>,
    full: &ZeroEnergyCount,
    progress: &Progress,
) -> Result<Option<Vec<InterfaceReductionPoint>>> {
    Ok(match cb_basis {
        Some(cb)
            if cb.columns_of(|k| *k == ColumnKind::Constraint).len() > INTERFACE_MODE_SWEEP[0] =>
        {
            progress.phase("interface reduction sweep")?;
            Some(interface_reduction_sweep(
                model,
                cb,
                full,
                BODY_MODES_COMPARED,
            )?)
        }
        _ => None,
    })
}

/// One reduced model measured against the full body: its frequencies' relative errors (the
/// worst over the compared modes), the largest principal angle of its basis to the full body's
/// `target` modes, its MACs against the `elastic` modes, and its interface response.
fn measure(
    model: &FeModel,
    built: &ReducedBody,
    (elastic, full_hz, target): (&GeneralizedEigen, &[f64], MatRef<'_, f64>),
    response: Option<&InterfaceResponse>,
) -> Result<MethodMeasure> {
    let (basis, eig, skip) = (&built.basis, &built.modes, built.zero_modes);
    let hz = built.elastic_hz();
    let rel_errors = built.relative_errors(full_hz);
    // A model with fewer elastic modes than compared has no error over them: said, not
    // ranked (a rigid interface under Guyan is a rigid body).
    let worst_error = if rel_errors.len() >= BODY_MODES_COMPARED.min(full_hz.len()) {
        rel_errors
            .iter()
            .take(BODY_MODES_COMPARED)
            .fold(0.0f64, |a, e| a.max(e.abs()))
    } else {
        f64::NAN
    };
    let max_angle = principal_angles(basis.psi.as_ref(), target)?
        .into_iter()
        .fold(0.0f64, f64::max);
    let (macs, min_mac) = paired_macs(elastic, full_hz, basis, eig, skip, &hz);
    let model_response = match response {
        Some(r) => Some(r.of_model(model, basis)?),
        None => None,
    };
    Ok(MethodMeasure {
        size: basis.size(),
        residuals: built.elastic_residuals(),
        zero_modes: skip,
        rigid_hz_max: built.rigid_hz_max(),
        offline_s: built.offline_s,
        hz,
        rel_errors,
        worst_error,
        max_angle,
        macs,
        min_mac,
        response: model_response,
    })
}

/// Solves and measures everything the `modes` scene shows. `influence_count` modes are ranked
/// by their influence (damping ratio `zeta`).
pub fn body_modes_study(
    model: &FeModel,
    p: &BodyModesParameters,
    (influence_count, zeta): (usize, f64),
    progress: &Progress,
) -> Result<BodyModesStudy> {
    progress.phase("full body's lowest modes")?;
    let started = Instant::now();
    let full = modes_up_to(model, p.band_hz, p.full_modes, progress)?;
    let full_s = started.elapsed().as_secs_f64();
    refuse_mechanism(model, &full)?;
    let full_hz = full.elastic_hz();
    let elastic = GeneralizedEigen {
        values: full.modes.values[full.zero_modes..].to_vec(),
        vectors: full
            .modes
            .vectors
            .subcols(full.zero_modes, full_hz.len())
            .to_owned(),
        residuals: full.modes.residuals[full.zero_modes..].to_vec(),
        zero_energy: 0,
        sturm: None,
    };
    let mut reducer =
        BodyReducer::new(model, p.interfaces.clone(), &full, full_s, progress.clone())?;
    // The full body's interface response over the band, and each model's below.
    let response = match p.band_hz {
        Some(top) => Some(InterfaceResponse::of_full_body(
            model,
            reducer.loads()?,
            top,
            &full_hz,
            progress,
        )?),
        None => None,
    };
    let held = held_modes(&mut reducer, p)?;
    // The full body's rigid and lowest elastic modes each basis should contain.
    let compared =
        (full.zero_modes + full_hz.len().min(BODY_MODES_COMPARED)).min(full.modes.vectors.ncols());
    let target = full.modes.vectors.subcols(0, compared);
    let mut methods = Vec::new();
    let mut notes = Vec::new();
    let mut cb_basis: Option<Basis> = None;
    for &m in &p.methods {
        let built = match reducer.reduce(m, p.kept) {
            Ok(r) => r,
            Err(
                e @ (Error::Reduction(ReductionError::MethodNeedsContext { .. })
                | Error::Linalg(LinalgError::EigenCheckFailed { .. })),
            ) => {
                // A method that cannot apply to this body, or whose reduced pairs fail their
                // check: said in its row, not computed, never printed as if right.
                methods.push((m, Err(e.to_string())));
                continue;
            }
            Err(e) => return Err(e),
        };
        if let Some(note) = &built.note {
            notes.push((m, note.clone()));
        }
        if m == Method::CraigBampton {
            cb_basis = Some(if p.interfaces.interface_modes.is_some() {
                reducer.reduce_keeping_constraint_modes(m, p.kept)?.basis
            } else {
                built.basis.clone()
            });
        }
        let measure = measure(
            model,
            &built,
            (&elastic, &full_hz, target),
            response.as_ref(),
        )?;
        methods.push((m, Ok(measure)));
    }
    let sweep = interface_sweep(model, cb_basis.as_ref(), &full, progress)?;
    progress.phase("modal influence across the interfaces")?;
    let influence = reducer.interface_influence(influence_count, zeta)?;
    Ok(BodyModesStudy {
        full,
        full_s,
        elastic,
        held,
        methods,
        notes,
        sweep,
        response,
        influence,
        influence_count,
    })
}
