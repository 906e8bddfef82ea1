//! The explicit scheme on a reduced driven body, where it works and where it fails: its
//! critical step predicted from the model's highest frequency on the frame at rest
//! ([`critical_step`]), a run at [`BELOW_CRITICAL`] of it sampled like the implicit runs (its
//! history compared with the full body's like theirs), and a run at [`ABOVE_CRITICAL`] of it
//! that must diverge.

use crate::{
    Error, Result,
    dynamics::{
        Combination, DrivenExplicit, DrivenFrameBody, DynamicsError, critical_step,
        integrate_driven_explicit,
    },
    linalg::{GeneralizedEigen, generalized_eigen},
    progress::Progress,
};

use super::{
    ABOVE_CRITICAL, BELOW_CRITICAL,
    driven_measure::{FieldMap, Measure},
};

/// Steps of the run above the critical step at most (it diverges within a few hundred).
const ABOVE_RUN_STEPS: usize = 2000;

/// The explicit scheme's check on one reduced model.
#[derive(Debug, Clone, PartialEq)]
pub struct ExplicitCheck {
    /// The model's label (e.g. `CB 10`).
    pub label: String,
    /// Its highest frequency on the frame at rest, Hz.
    pub highest_hz: f64,
    /// The predicted critical step, s.
    pub critical_s: f64,
    /// The step of the run above it, s.
    pub above_step_s: f64,
    /// When the run above it diverged, s (`None`: it did not, within its steps).
    pub diverged_at: Option<f64>,
}

/// What an explicit run recorded: states, outputs and reaction per sample, and its cost.
pub(super) struct ExplicitRun {
    pub(super) step: f64,
    pub(super) cost: crate::dynamics::DrivenCost,
    pub(super) states: Vec<Vec<f64>>,
    pub(super) outputs: Vec<Vec<[f64; 3]>>,
    pub(super) reaction: Vec<[f64; 6]>,
}

/// Runs `body` (with `map` to its field) explicitly below and above its critical step; the
/// run below outputs every `sample_s` seconds up to `end`, like the implicit runs. Both are
/// driven as `measure` drives the full body, and stop as diverged where the state exceeds the
/// full body's size.
pub(super) fn explicit_runs(
    body: &mut DrivenFrameBody,
    map: &FieldMap,
    measure: &Measure<'_>,
    (label, highest_hz): (String, f64),
    (sample_s, end): (f64, f64),
    progress: &Progress,
) -> Result<(ExplicitRun, ExplicitCheck)> {
    let (driving, bound) = (&measure.driving, measure.model.size());
    let critical = critical_step(2.0 * std::f64::consts::PI * highest_hz);
    // Below: a step that divides the sampling interval, at most BELOW_CRITICAL of critical.
    let per_sample = (sample_s / (BELOW_CRITICAL * critical)).ceil().max(1.0);
    let step = sample_s / per_sample;
    let (mut states, mut outputs, mut reaction) = (Vec::new(), Vec::new(), Vec::new());
    let cost = integrate_driven_explicit(
        body,
        driving,
        &DrivenExplicit {
            step,
            end,
            output_every: per_sample as usize,
            bound,
        },
        progress,
        |t, z, zd, zdd| {
            let (u, v, a) = (map.field(z), map.field(zd), map.field(zdd));
            states.push(z.to_vec());
            outputs.push(measure.output(&u));
            reaction.push(measure.reaction(t, &u, &v, &a));
            Ok(())
        },
    )?;
    let above_step = ABOVE_CRITICAL * critical;
    let above = integrate_driven_explicit(
        body,
        driving,
        &DrivenExplicit {
            step: above_step,
            end: end.min(ABOVE_RUN_STEPS as f64 * above_step),
            output_every: usize::MAX,
            bound,
        },
        progress,
        |_, _, _, _| Ok(()),
    );
    let diverged_at = match above {
        Ok(_) => None,
        Err(Error::Dynamics(DynamicsError::Diverged { time, .. })) => Some(time),
        Err(e) => return Err(e),
    };
    Ok((
        ExplicitRun {
            step,
            cost,
            states,
            outputs,
            reaction,
        },
        ExplicitCheck {
            label,
            highest_hz,
            critical_s: critical,
            above_step_s: above_step,
            diverged_at,
        },
    ))
}

/// The lowest and highest natural frequencies of a reduced body on its frame at rest, Hz,
/// checked by the dense generalised eigensolver.
pub(super) fn frame_frequencies(body: &DrivenFrameBody) -> Result<Option<(f64, f64)>> {
    let stiffness = Combination {
        k: 1.0,
        ..Default::default()
    };
    let mass = Combination {
        m: 1.0,
        ..Default::default()
    };
    let (kk, mm) = (body.dense_matrix(stiffness), body.dense_matrix(mass));
    let e: GeneralizedEigen =
        generalized_eigen(kk.as_ref(), mm.as_ref(), "reduced body on the driven frame")?;
    let hz = e.hz();
    Ok(match (hz.first(), hz.last()) {
        (Some(&lo), Some(&hi)) => Some((lo, hi)),
        _ => None,
    })
}
