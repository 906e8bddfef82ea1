//! What an integration is asked to do: which scheme, over which interval, with which steps
//! and tolerances.

/// The implicit scheme's step when none is given, s.
pub const DEFAULT_IMPLICIT_STEP: f64 = 1e-3;
/// The implicit scheme's spectral radius at infinite frequency when none is given.
pub const DEFAULT_SPECTRAL_RADIUS: f64 = 0.8;

/// Which time-integration scheme [`simulate`](super::simulate) runs; written in settings by
/// its id (generalized-α read back with [`DEFAULT_SPECTRAL_RADIUS`]).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(try_from = "String", into = "String")]
pub enum IntegrationScheme {
    /// Dormand–Prince 5(4): explicit, adaptive steps unless
    /// [`IntegratorParameters::fixed_step`] is set (then without error control).
    DormandPrince,
    /// Generalized-α (Chung–Hulbert): implicit, fixed steps of
    /// [`IntegratorParameters::fixed_step`] or [`DEFAULT_IMPLICIT_STEP`].
    GeneralizedAlpha {
        /// Spectral radius $\rho_\infty \in [0, 1]$ at infinite frequency (1: no numerical
        /// damping; 0: the highest frequencies annihilated in one step).
        spectral_radius: f64,
    },
}

impl IntegrationScheme {
    /// The ids `--integrator` accepts.
    pub const IDS: [&'static str; 2] = ["dp5", "gen-alpha"];

    /// `dp5` or `gen-alpha`.
    pub fn id(&self) -> &'static str {
        match self {
            Self::DormandPrince => "dp5",
            Self::GeneralizedAlpha { .. } => "gen-alpha",
        }
    }

    /// The scheme for an id of [`Self::IDS`] (generalized-α with [`DEFAULT_SPECTRAL_RADIUS`]).
    pub fn from_id(id: &str) -> Option<Self> {
        match id {
            "dp5" => Some(Self::DormandPrince),
            "gen-alpha" => Some(Self::GeneralizedAlpha {
                spectral_radius: DEFAULT_SPECTRAL_RADIUS,
            }),
            _ => None,
        }
    }

    /// Its name in tables and panels.
    pub fn name(&self) -> String {
        match self {
            Self::DormandPrince => "Dormand–Prince 5(4)".into(),
            Self::GeneralizedAlpha { spectral_radius } => {
                format!("generalized-α (ρ∞ = {spectral_radius})")
            }
        }
    }
}

/// Settings of [`simulate`](super::simulate).
#[derive(Debug, Clone, PartialEq)]
pub struct IntegratorParameters {
    /// The scheme.
    pub scheme: IntegrationScheme,
    /// End time, s.
    pub end_time: f64,
    /// Output interval, s (also the largest step).
    pub output_interval: f64,
    /// Relative error tolerance per step.
    pub rtol: f64,
    /// Absolute error tolerance per step.
    pub atol: f64,
    /// Smallest step before the integration counts as diverged, s.
    pub min_step: f64,
    /// Largest number of steps.
    pub max_steps: usize,
    /// A fixed step, s: no error control, every step accepted (how a critical step is
    /// verified). `None` for adaptive steps.
    pub fixed_step: Option<f64>,
    /// A state component beyond this magnitude (m, m/s, rad/s, modal units) counts as
    /// diverged.
    pub divergence_bound: f64,
}

impl Default for IntegratorParameters {
    fn default() -> Self {
        Self {
            scheme: IntegrationScheme::DormandPrince,
            end_time: 1.0,
            output_interval: 5e-3,
            rtol: 1e-6,
            atol: 1e-9,
            min_step: 1e-9,
            max_steps: 2_000_000,
            fixed_step: None,
            divergence_bound: 1e4,
        }
    }
}

impl IntegratorParameters {
    /// The step the run uses: the fixed one, the implicit default, or `None` (adaptive).
    pub fn step(&self) -> Option<f64> {
        match self.scheme {
            IntegrationScheme::DormandPrince => self.fixed_step,
            IntegrationScheme::GeneralizedAlpha { .. } => {
                Some(self.fixed_step.unwrap_or(DEFAULT_IMPLICIT_STEP))
            }
        }
    }

    /// One sentence for panels: scheme, steps and tolerances.
    pub fn describe(&self) -> String {
        match (self.scheme, self.step()) {
            (IntegrationScheme::DormandPrince, None) => format!(
                "the explicit Dormand-Prince 5(4) scheme with adaptive steps (rtol {:e}, atol \
                 {:e})",
                self.rtol, self.atol
            ),
            (IntegrationScheme::DormandPrince, Some(h)) => format!(
                "the explicit Dormand-Prince 5(4) scheme with fixed steps of {h} s and no error \
                 control"
            ),
            (scheme, h) => format!(
                "the implicit {} scheme with fixed steps of {} s (Newton on a \
                 finite-difference iteration matrix kept across steps)",
                scheme.name(),
                h.unwrap_or(DEFAULT_IMPLICIT_STEP)
            ),
        }
    }
}

impl std::fmt::Display for IntegrationScheme {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.id())
    }
}

impl TryFrom<String> for IntegrationScheme {
    type Error = crate::error::UnknownId;

    fn try_from(id: String) -> Result<Self, Self::Error> {
        id.parse()
    }
}

impl From<IntegrationScheme> for String {
    fn from(scheme: IntegrationScheme) -> Self {
        scheme.id().into()
    }
}

impl std::str::FromStr for IntegrationScheme {
    type Err = crate::error::UnknownId;

    /// `dp5`, or `gen-alpha` with the default spectral radius.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        IntegrationScheme::from_id(s.trim()).ok_or_else(|| {
            crate::error::UnknownId::new("integrator", s.trim(), &IntegrationScheme::IDS)
        })
    }
}
