//! The explorer's `simulate` choices for the `modes` scene's body: which interface is driven,
//! how, and for how long; persisted with the other controls.

use serde::{Deserialize, Serialize};

use crate::{
    Result,
    models::DrivenBodyParameters,
    reduction::Method,
    scenes::body_simulation::{BodySimulation, DriveRequest},
};

/// How the driven interface moves.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum DriveMotion {
    /// Spun up about the body's z axis through the drive's master, then held at the rate.
    SpinUp,
    /// Shaken harmonically along the ground's x axis, not turning.
    Shake,
}

/// A body driven through one of its interfaces (`flexmodes simulate --drive rbe2:SET`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SimulationControls {
    /// The driven interface: a node set of the body, tied rigidly to its master (RBE2).
    pub drive: String,
    /// Other node sets the reduced models keep as interfaces (each tied rigidly, free in the
    /// simulation): Guyan needs one, and they bound what the reduced models can do there.
    #[serde(default)]
    pub kept: Vec<String>,
    /// How the drive moves.
    pub motion: DriveMotion,
    /// Steady spin rate, rad/s (spin-up).
    pub rate: f64,
    /// Time to reach the rate, s (spin-up).
    pub ramp: f64,
    /// Shaking amplitude, m (shake).
    pub amplitude: f64,
    /// Shaking frequency, Hz (shake).
    pub frequency: f64,
    /// Simulated interval, s.
    pub end: f64,
    /// Also integrate the full body, the reference of every error.
    pub full_body: bool,
    /// Dynamic stiffening from the body file's `[preload]` (bodies without one have none).
    #[serde(default = "stiffening_default")]
    pub stiffening: bool,
    /// Inertia-load residual vectors in the reduced bases.
    #[serde(default = "residual_vectors_default")]
    pub residual_vectors: bool,
}

/// `simulate`'s default: residual vectors on.
fn residual_vectors_default() -> bool {
    DrivenBodyParameters::default().residual_vectors
}

/// `simulate`'s default: stiffened wherever the body file gives the preload.
fn stiffening_default() -> bool {
    DrivenBodyParameters::default().stiffening
}

/// The models a drive is first simulated with, as `flexmodes simulate` (beside the full body).
pub const DRIVEN_DEFAULT: [Method; 2] = [Method::CraigBampton, Method::ModeCondensation];

/// Steady rates the panel offers, rad/s.
pub const RATES: [f64; 4] = [25.0, 50.0, 100.0, 200.0];
/// Ramp times the panel offers, s.
pub const RAMPS: [f64; 4] = [0.1, 0.25, 0.5, 1.0];
/// Shaking frequencies the panel offers, Hz.
pub const FREQUENCIES: [f64; 4] = [10.0, 50.0, 200.0, 1000.0];
/// Simulated intervals the panel offers, s.
pub const ENDS: [f64; 4] = [0.1, 0.25, 0.5, 1.0];

impl SimulationControls {
    /// `flexmodes simulate`'s defaults with `drive` driven.
    pub fn for_drive(drive: &str) -> Self {
        let d = DrivenBodyParameters::default();
        Self {
            drive: drive.into(),
            kept: Vec::new(),
            motion: DriveMotion::SpinUp,
            rate: d.rate,
            ramp: d.ramp,
            amplitude: 1e-3,
            frequency: 50.0,
            end: d.integration.end,
            full_body: true,
            stiffening: d.stiffening,
            residual_vectors: d.residual_vectors,
        }
    }

    /// The scene's simulation: the drive tied rigidly (`rbe2:`), generalized-α at
    /// `simulate`'s default step, a hundred samples of the histories; values that do not
    /// hold are named.
    pub fn simulation(&self) -> Result<BodySimulation> {
        BodySimulation::of_request(
            &DriveRequest {
                drive: &self.drive,
                kept: &self.kept,
                rate: self.rate,
                ramp: self.ramp,
                shake: (self.motion == DriveMotion::Shake)
                    .then_some((self.amplitude, self.frequency)),
                end: self.end,
                full_body: self.full_body,
                stiffening: self.stiffening,
                residual_vectors: self.residual_vectors,
            },
            crate::scenes::SceneId::Modes.as_str(),
        )
    }
}
