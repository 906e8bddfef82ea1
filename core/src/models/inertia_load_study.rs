//! A part with a radial arm spun up: what Craig–Bampton's fixed-interface modes miss of its
//! own inertia loads, and what the loads' residual vectors restore (Dickens, Nakagawa &
//! Wittbrodt's modal truncation augmentation; Nastran's RESVEC). The body is CalculiX's
//! steel lever (`builtin:spun-lever`: 12 × 2 × 2 C3D8 bricks, K, M and the stiffness spun
//! at 1 000 rad/s written by CalculiX 2.20), clamped at its root and spun about z.
//!
//! The arm stretches quasi-statically under its centrifugal load $\Omega^2 M\,r$; that
//! shape is no low fixed-interface mode, and the clamped root has no constraint mode to
//! carry it. The a-priori estimate is the share of each unit inertia load's static response
//! $K_{ii}^{-1} f_i$ that lies outside the basis, in the energy norm.

use crate::{
    Result, body_file::ImportedBody, dynamics::DrivenIntegration, error::DynamicsError,
    progress::Progress, reduction::Method,
};

use super::{DrivenBodyParameters, DrivenRun, DrivenStudy, driven_body_study};

/// The builtin body the study spins.
pub const INERTIA_LOAD_BODY: &str = "builtin:spun-lever";

/// Fixed-interface modes kept, with and without the residual vectors.
pub const INERTIA_LOAD_MODES: [usize; 5] = [1, 2, 4, 8, 16];

/// The lever's runs: the full body (NR), and CB with each of [`INERTIA_LOAD_MODES`] fixed
/// interface modes, without and with the inertia-load residual vectors.
#[derive(Debug, Clone)]
pub struct InertiaLoadStudy {
    /// The body's name and DOF.
    pub body: (String, usize),
    /// Steady rate (rad/s) and ramp time (s).
    pub rate: (f64, f64),
    /// Every run: NR first, then CB k without residual vectors, then CB k with them.
    pub study: DrivenStudy,
}

impl InertiaLoadStudy {
    /// The reduced runs with (`true`) or without residual vectors, by kept modes.
    pub fn reduced(&self, with_vectors: bool) -> Vec<&DrivenRun> {
        self.study
            .runs
            .iter()
            .filter(|r| r.method.is_some() && (r.residual_vectors > 0) == with_vectors)
            .collect()
    }

    /// The full body's run.
    pub fn full(&self) -> Option<&DrivenRun> {
        self.study.runs.iter().find(|r| r.method.is_none())
    }
}

/// Spins the lever up to the rate CalculiX spun its `[preload]` at (1 000 rad/s) in 0.1 s, held for 0.1 s more (generalized-α,
/// 0.2 ms steps), with the preload's dynamic stiffening, NR and CB k with and without the
/// residual vectors.
pub fn inertia_load_study(progress: &Progress) -> Result<InertiaLoadStudy> {
    let body = ImportedBody::load(INERTIA_LOAD_BODY)?;
    let rate = body
        .preload
        .as_ref()
        .map(|p| p.load.rate)
        .ok_or(DynamicsError::Misuse {
            what: "the inertia-load study's body has no [preload] to take its rate from",
        })?;
    let base = DrivenBodyParameters {
        drive: "rbe2:root".into(),
        outputs: vec!["tip".into()],
        rate,
        ramp: 0.1,
        integration: DrivenIntegration {
            step: 2e-4,
            end: 0.2,
            spectral_radius: 0.9,
            output_every: 10,
        },
        ..Default::default()
    };
    let methods = [Method::CraigBampton];
    progress.phase("inertia loads: NR and CB without residual vectors")?;
    let without = driven_body_study(
        &body,
        &DrivenBodyParameters {
            residual_vectors: false,
            ..base.clone()
        },
        &methods,
        &INERTIA_LOAD_MODES,
        true,
        progress,
    )?;
    progress.phase("inertia loads: CB with residual vectors")?;
    let with = driven_body_study(&body, &base, &methods, &INERTIA_LOAD_MODES, false, progress)?;
    Ok(InertiaLoadStudy {
        body: (body.model.name.clone(), body.model.dof_count()),
        rate: (base.rate, base.ramp),
        study: DrivenStudy::joined(&[&without, &with])?,
    })
}
