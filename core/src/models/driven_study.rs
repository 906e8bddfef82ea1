//! What a driven body's study holds: every model's run, sampled, and its errors against the
//! full body's (models::driven_body makes it).

use crate::{Result, dynamics::DrivenCost, error::DynamicsError, reduction::Method};

use super::ExplicitCheck;
use super::driven_measure::{FieldMap, history_error, reaction_error};

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
    /// The fixed step of an explicit (Dormand–Prince) run, s; `None`: generalized-α.
    pub explicit_step: Option<f64>,
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
    /// Inertia-load residual vectors in the basis (0 for NR and without them).
    pub residual_vectors: usize,
    /// The a-priori estimate: per load the drive puts on the body (its name), the share of
    /// its static response (the body held at its interfaces) that the basis misses in the
    /// energy norm (empty for NR).
    pub estimate: Vec<(String, f64)>,
}

impl DrivenRun {
    /// The largest share of the drive's loads the basis misses (`None` for NR).
    pub fn estimate_max(&self) -> Option<f64> {
        self.estimate.iter().map(|(_, e)| *e).reduce(|a, b| {
            if a.is_nan() || b.is_nan() {
                f64::NAN
            } else {
                a.max(b)
            }
        })
    }
}

impl DrivenRun {
    /// `NR`, e.g. `CB 10`, and `CB 10 DP5` for an explicit run.
    pub fn label(&self) -> String {
        let model = match self.method {
            None => "NR".into(),
            Some(Method::Guyan) => "GR".into(),
            Some(m) => format!("{} {}", m.id().to_uppercase(), self.modes),
        };
        match self.explicit_step {
            Some(_) => format!("{model} DP5"),
            None => model,
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
    /// Whether the runs carried the dynamic stiffening of the body's preloaded stiffness
    /// (false: stiffening off, or the body has no `[preload]`).
    pub stiffened: bool,
    /// The explicit scheme's critical step per reduced model, checked (with `explicit`).
    pub stability: Vec<ExplicitCheck>,
    /// The reaction force a rigid body would need at each sample time: what the reaction
    /// errors leave out of the full body's reaction (its elastic part is their scale).
    pub rigid_force: Vec<[f64; 3]>,
    /// The point of the spin axis the frame turned about, and where it came from
    /// (`--axis-point`, the preload's axis, the drive's master).
    pub axis_point: ([f64; 3], &'static str),
    /// Whether the reduced bases carried inertia-load residual vectors.
    pub residual_vectors: bool,
}

impl DrivenStudy {
    /// One study of the runs of `studies`, made of one body under one drive (and integrator)
    /// each: the full body's run first when one of them has it, and every reduced run's
    /// errors against it. Each run and its errors are independent of the others, so this is
    /// the study `driven_body_study` makes of all their methods at once. Studies that differ
    /// in their sample times, outputs, drive or its motion (the rigid reaction it needs) are
    /// an error, never zipped; so is none.
    pub fn joined(studies: &[&DrivenStudy]) -> Result<Self> {
        let differ = |what| Err(DynamicsError::StudiesDiffer { what }.into());
        let Some(first) = studies.first() else {
            return differ("number: there are none");
        };
        for s in studies {
            if s.times != first.times {
                return differ("sample times");
            }
            if s.output_names != first.output_names {
                return differ("outputs");
            }
            if s.drive != first.drive || s.dof != first.dof {
                return differ("drive");
            }
            if s.rigid_force != first.rigid_force {
                return differ("motion (the rigid reaction)");
            }
            if s.stiffened != first.stiffened {
                return differ("dynamic stiffening");
            }
        }
        let mut runs: Vec<DrivenRun> = studies
            .iter()
            .flat_map(|s| s.runs.iter().filter(|r| r.method.is_none()))
            .take(1)
            .cloned()
            .collect();
        let full = !runs.is_empty();
        runs.extend(
            studies
                .iter()
                .flat_map(|s| s.runs.iter().filter(|r| r.method.is_some()))
                .cloned(),
        );
        if full {
            compare_with_full(&mut runs, &first.rigid_force);
        }
        Ok(Self {
            runs,
            stability: studies
                .iter()
                .flat_map(|s| s.stability.iter().cloned())
                .collect(),
            times: first.times.clone(),
            output_names: first.output_names.clone(),
            drive: first.drive.clone(),
            dof: first.dof,
            rigid_force: first.rigid_force.clone(),
            stiffened: first.stiffened,
            axis_point: first.axis_point,
            residual_vectors: studies.iter().any(|s| s.residual_vectors),
        })
    }

    /// Bytes the study holds on the heap: its samples and each reduced run's basis.
    pub fn heap_bytes(&self) -> usize {
        let f = std::mem::size_of::<f64>();
        let run = |r: &DrivenRun| {
            let states: usize = r.states.iter().map(|x| x.len() * f).sum();
            let outputs: usize = r.outputs.iter().map(|o| o.len() * 3 * f).sum();
            let basis = match &r.field_map {
                FieldMap::Basis(psi) => psi.nrows() * psi.ncols() * f,
                FieldMap::Full(_) => 0,
            };
            states + outputs + r.reaction.len() * 6 * f + basis
        };
        self.times.len() * f + self.runs.iter().map(run).sum::<usize>()
    }
}

/// Every run's history and reaction error against the full body's (the first run).
pub(super) fn compare_with_full(runs: &mut [DrivenRun], rigid_force: &[[f64; 3]]) {
    let (reference, rest) = runs.split_first_mut().expect("the full body ran first");
    for run in rest {
        // An explicit run sampled otherwise (an end the samples do not divide) is not
        // compared.
        if run.reaction.len() != reference.reaction.len() {
            continue;
        }
        run.history_error = Some(history_error(&reference.outputs, &run.outputs));
        run.reaction_error = Some(reaction_error(
            &reference.reaction,
            &run.reaction,
            rigid_force,
        ));
    }
}
