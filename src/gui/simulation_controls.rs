//! The explorer's `simulate` choices for the `modes` scene's body: which interface is driven,
//! how, and for how long; persisted with the other controls.

use serde::{Deserialize, Serialize};

use crate::{
    Error, Result,
    models::DrivenBodyParameters,
    reduction::Method,
    scenes::{SceneId, body_simulation::BodySimulation},
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
/// Samples of the histories over the interval (as `simulate`'s default).
const SAMPLES: usize = 100;

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
        }
    }

    /// The scene's simulation: the drive tied rigidly (`rbe2:`), generalized-α at
    /// `simulate`'s default step, a hundred samples of the histories.
    pub fn simulation(&self) -> Result<BodySimulation> {
        let defaults = DrivenBodyParameters::default();
        let invalid = |reason: String| Error::InvalidOption {
            option: "simulate",
            scene: Some(SceneId::Modes.as_str()),
            reason,
        };
        if self.drive.trim().is_empty() {
            return Err(invalid("choose the interface to drive".into()));
        }
        let positive = [
            ("rate", self.rate),
            ("ramp", self.ramp),
            ("amplitude", self.amplitude),
            ("frequency", self.frequency),
            ("end time", self.end),
        ];
        if let Some((name, value)) = positive.iter().find(|(_, v)| !(v.is_finite() && *v > 0.0)) {
            return Err(invalid(format!("the {name} must be positive, not {value}")));
        }
        let step = defaults.integration.step;
        let steps = (self.end / step).round().max(1.0) as usize;
        let shake = self.motion == DriveMotion::Shake;
        Ok(BodySimulation {
            parameters: DrivenBodyParameters {
                drive: format!("rbe2:{}", self.drive.trim()),
                boundary: self
                    .kept
                    .iter()
                    .filter(|set| set.trim() != self.drive.trim())
                    .map(|set| format!("rbe2:{}", set.trim()))
                    .collect(),
                rate: if shake { 0.0 } else { self.rate },
                ramp: self.ramp,
                shake: shake.then_some(([1.0, 0.0, 0.0], self.amplitude, self.frequency)),
                integration: crate::dynamics::DrivenIntegration {
                    end: self.end,
                    output_every: (steps / SAMPLES).max(1),
                    ..defaults.integration
                },
                ..defaults
            },
            full_body: self.full_body,
        })
    }
}
