//! Options a scene is run with and what it returns.

use crate::dynamics::AxisKind;
use crate::{
    Error, Progress, Result,
    dynamics::{IntegrationScheme, IntegratorParameters},
    reduction::Method,
};

/// What a scene produces is what the recorder logs: numbers, text panel, visuals, layout.
pub use crate::record::RecordingContent as SceneOutput;

use crate::scenes::{RunCache, SceneInfo};

/// Scene options from the command line (or the GUI). `None` means the scene's default.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SceneOptions {
    /// `--method`: the methods to compute and show.
    pub methods: Option<Vec<Method>>,
    /// `--modes`: kept normal modes.
    pub modes: Option<usize>,
    /// `--boundary`: boundary/master nodes, 1-based.
    pub boundary: Option<Vec<usize>>,
    /// `--boundary rbe2:SET`: node sets of the boundary tied rigidly to a master node each
    /// (a body file's scene only).
    pub rigid_interfaces: Vec<crate::reduction::RigidInterface>,
    /// `--boundary rbe3:SET`: node sets averaged into a master node each, not in `boundary`
    /// (a body file's scene only).
    pub averaging_interfaces: Vec<crate::reduction::AveragingInterface>,
    /// `--interface-modes N`: the interface's constraint modes reduced to N characteristic
    /// constraint modes (a body file's scene only).
    pub interface_modes: Option<usize>,
    /// `--band HZ`: compare each model's interface response with the full body's up to this
    /// frequency (a body file's scene only).
    pub band_hz: Option<f64>,
    /// `--axes`: axis type id.
    pub axes: Option<AxisKind>,
    /// `--end-time`: simulated interval of the dynamic scenes, s.
    pub end_time: Option<f64>,
    /// `--integrator` (with `--rho-inf`): the time-integration scheme of the simulations
    /// (`None`: Dormand–Prince 5(4)).
    pub integrator: Option<IntegrationScheme>,
    /// `--dt`: a fixed step of the simulations, s (the explicit scheme then runs without error
    /// control; the implicit one defaults to
    /// [`DEFAULT_IMPLICIT_STEP`](crate::dynamics::DEFAULT_IMPLICIT_STEP)).
    pub dt: Option<f64>,
    /// `--refine NX,NY,NZ`: bricks of the slab mesh (App. B: 4, 2, 1).
    pub refine: Option<[usize; 3]>,
    /// `--stiffening on|off`: the dynamic (geometric) stiffening of the slab simulations'
    /// floating frame (`None`: off, the thesis' model).
    pub stiffening: Option<bool>,
    /// `--deformation-scale`: factor on the drawn elastic deflections of the simulations
    /// (`None`: automatic).
    pub deformation_scale: Option<f64>,
    /// `--body`: a body from a body file (the `modes` scene).
    pub body: Option<crate::body_file::BodyHandle>,
    /// The body driven through one of its interfaces instead of its modes compared (the
    /// `modes` scene; the explorer's `simulate`).
    pub simulation: Option<crate::scenes::body::body_simulation::BodySimulation>,
    /// Where the time integrations report how far they got; cancelling it stops the scene.
    pub progress: Progress,
    /// Time integrations kept from earlier requests (the desktop explorer's).
    pub cache: RunCache,
    /// How many of a scene's time integrations may run at once, one thread each (0 and 1:
    /// one after the other, as the command line and the bench run them). The explorer sets
    /// the machine's cores, so a switch that integrates several methods anew waits for the
    /// slowest share, not the sum.
    pub concurrent_integrations: usize,
}

impl SceneOptions {
    /// The methods to run: the requested ones, each checked against `available`, in the order
    /// of `available`; or `default`.
    pub fn methods_or(
        &self,
        scene: &'static str,
        available: &[Method],
        default: &[Method],
    ) -> Result<Vec<Method>> {
        match &self.methods {
            None => Ok(default.to_vec()),
            Some(req) => {
                for m in req {
                    if !available.contains(m) {
                        return Err(Error::UnknownMethod {
                            id: m.id(),
                            scene,
                            available: available.iter().map(|m| m.id()).collect(),
                        });
                    }
                }
                Ok(available
                    .iter()
                    .copied()
                    .filter(|m| req.contains(m))
                    .collect())
            }
        }
    }

    /// `--boundary`, or the scene's default (its `SceneControls`).
    pub fn boundary_or_default(&self, info: &SceneInfo) -> Vec<usize> {
        self.boundary
            .clone()
            .unwrap_or_else(|| info.controls.boundary.to_vec())
    }

    /// Boundary nodes (1-based) typed as text, separated by commas or spaces (the explorer's
    /// boundary field); a token that is not a node number is named.
    pub fn boundary_from_text(scene: &'static str, text: &str) -> Result<Vec<usize>> {
        text.split([',', ' '])
            .filter(|t| !t.trim().is_empty())
            .map(|t| {
                t.trim().parse::<usize>().map_err(|_| Error::InvalidOption {
                    option: "--boundary",
                    scene: Some(scene),
                    reason: format!("boundary `{text}`: `{t}` is not a node number"),
                })
            })
            .collect()
    }

    /// Refuses an empty choice of methods for a scene that offers some (a scene without
    /// method choices, the failures scene, runs with its own settings).
    pub fn require_a_method(info: &SceneInfo, methods: &[Method]) -> Result<()> {
        if methods.is_empty() && !info.controls.methods.is_empty() {
            return Err(Error::InvalidOption {
                option: "--method",
                scene: Some(info.name),
                reason: "select at least one method".into(),
            });
        }
        Ok(())
    }

    /// `--modes`, or the scene's default (0 when it keeps none).
    pub fn modes_or_default(&self, info: &SceneInfo) -> usize {
        self.modes.or(info.controls.modes).unwrap_or(0)
    }

    /// `--end-time` checked as in [`Self::end_time_or`], or the scene's default.
    pub fn end_time_or_default(&self, info: &SceneInfo) -> Result<f64> {
        let default = info.controls.end_time.ok_or_else(|| Error::InvalidOption {
            option: "--end-time",
            scene: Some(info.name),
            reason: "--end-time applies to simulations only".into(),
        })?;
        self.end_time_or(info.name, default)
    }

    /// The simulated interval: `--end-time` checked (0 < t ≤ 60 s), or `default`.
    pub fn end_time_or(&self, scene: &'static str, default: f64) -> Result<f64> {
        match self.end_time {
            None => Ok(default),
            Some(t) if t > 0.0 && t <= 60.0 => Ok(t),
            Some(t) => Err(Error::InvalidOption {
                option: "--end-time",
                scene: Some(scene),
                reason: format!("end time {t} s must lie in (0, 60] s"),
            }),
        }
    }

    /// The integrator settings of a simulation scene: `--end-time`, `--integrator` and `--dt`
    /// checked (0 < dt ≤ 10 ms), or the scene's defaults.
    pub fn integrator_parameters(&self, info: &SceneInfo) -> Result<IntegratorParameters> {
        let end_time = self.end_time_or_default(info)?;
        let defaults = IntegratorParameters::default();
        if let Some(dt) = self.dt
            && !(dt > 0.0 && dt <= 0.01)
        {
            return Err(Error::InvalidOption {
                option: "--dt",
                scene: Some(info.name),
                reason: format!("step {dt} s must lie in (0, 0.01] s"),
            });
        }
        if let Some(IntegrationScheme::GeneralizedAlpha { spectral_radius }) = self.integrator
            && !(0.0..=1.0).contains(&spectral_radius)
        {
            return Err(Error::InvalidOption {
                option: "--rho-inf",
                scene: Some(info.name),
                reason: format!("spectral radius ρ∞ = {spectral_radius} must lie in [0, 1]"),
            });
        }
        Ok(IntegratorParameters {
            scheme: self.integrator.unwrap_or(defaults.scheme),
            end_time,
            fixed_step: self.dt,
            ..defaults
        })
    }

    /// `--deformation-scale` checked (a finite factor ≥ 0; 0 draws no deflection), or `auto`.
    pub fn deformation_scale_or(
        &self,
        scene: &'static str,
        auto: impl FnOnce() -> f64,
    ) -> Result<f64> {
        match self.deformation_scale {
            None => Ok(auto()),
            Some(f) if f.is_finite() && f >= 0.0 => Ok(f),
            Some(f) => Err(Error::InvalidOption {
                option: "--deformation-scale",
                scene: Some(scene),
                reason: format!("deformation scale {f} must be a finite number ≥ 0"),
            }),
        }
    }
}
