//! Method ids, which modes to keep and which linear algebra; the request and its entry point
//! are [`ReductionRequest`](super::ReductionRequest) and [`reduce`](super::reduce).

use super::ReductionError;
use crate::{Error, Result, linalg::PairSelection};

/// The reduction methods and their stable ids (how they are written in files and settings).
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, serde::Serialize, serde::Deserialize,
)]
#[serde(try_from = "String", into = "String")]
pub enum Method {
    /// `nr`: no reduction, Ψ = I.
    NoReduction,
    /// `gr`: Guyan / static condensation (§6.2).
    Guyan,
    /// `mt`: modal truncation (§6.3, Eq. 6.17).
    ModalTruncation,
    /// `cb`: Craig–Bampton (§6.4, Eq. 6.19).
    CraigBampton,
    /// `mc`: mode condensation (§6.5, Eq. 6.30).
    ModeCondensation,
    /// `eit`: Eitelberg's method (§6.6, App. C).
    Eitelberg,
    /// `mr`: MacNeal–Rubin, free-interface plus residual modes (Spanos–Tsuha Eqs. 8–17).
    MacNealRubin,
    /// `bh`: Benfield–Hruda, loaded-interface modes (Spanos–Tsuha Eqs. 18–22).
    BenfieldHruda,
    /// `mm`: second-order Krylov moment matching (Witteveen Eq. 21).
    MomentMatching,
    /// `bt`: balanced truncation (Spanos–Tsuha Eqs. 35–42; Witteveen §3.3).
    BalancedTruncation,
}

impl Method {
    /// Every method, in display order.
    pub const ALL: [Method; 10] = [
        Method::NoReduction,
        Method::Guyan,
        Method::ModalTruncation,
        Method::CraigBampton,
        Method::ModeCondensation,
        Method::Eitelberg,
        Method::MacNealRubin,
        Method::BenfieldHruda,
        Method::MomentMatching,
        Method::BalancedTruncation,
    ];

    /// The stable id used in the CLI, reports and entity paths.
    pub fn id(self) -> &'static str {
        match self {
            Method::NoReduction => "nr",
            Method::Guyan => "gr",
            Method::ModalTruncation => "mt",
            Method::CraigBampton => "cb",
            Method::ModeCondensation => "mc",
            Method::Eitelberg => "eit",
            Method::MacNealRubin => "mr",
            Method::BenfieldHruda => "bh",
            Method::MomentMatching => "mm",
            Method::BalancedTruncation => "bt",
        }
    }

    /// Full name.
    pub fn name(self) -> &'static str {
        match self {
            Method::NoReduction => "no reduction",
            Method::Guyan => "Guyan reduction",
            Method::ModalTruncation => "modal truncation",
            Method::CraigBampton => "Craig-Bampton",
            Method::ModeCondensation => "mode condensation",
            Method::Eitelberg => "Eitelberg",
            Method::MacNealRubin => "MacNeal-Rubin",
            Method::BenfieldHruda => "Benfield-Hruda",
            Method::MomentMatching => "Krylov moment matching",
            Method::BalancedTruncation => "balanced truncation",
        }
    }

    /// Parses an id.
    pub fn from_id(id: &str) -> Option<Method> {
        Method::ALL.into_iter().find(|m| m.id() == id)
    }

    /// Whether the method keeps normal modes (and so honours `--modes`).
    pub fn keeps_normal_modes(self) -> bool {
        matches!(
            self,
            Method::ModalTruncation | Method::CraigBampton | Method::ModeCondensation
        )
    }
}

/// Which fixed-interface normal modes to keep.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ModeSelection {
    /// The `n` lowest.
    Count(usize),
    /// Every mode up to this frequency, Hz.
    UpToHz(f64),
}

impl ModeSelection {
    /// How many of the ascending frequencies `hz` to keep.
    pub fn count(&self, hz: &[f64]) -> Result<usize> {
        match *self {
            ModeSelection::Count(n) if n > hz.len() => {
                Err(Error::Reduction(ReductionError::TooManyModes {
                    requested: n,
                    available: hz.len(),
                }))
            }
            ModeSelection::Count(n) => Ok(n),
            ModeSelection::UpToHz(f) if f.is_nan() || f < 0.0 => {
                Err(Error::Reduction(ReductionError::InvalidCutoff { hz: f }))
            }
            ModeSelection::UpToHz(f) => Ok(hz.iter().take_while(|&&h| h <= f).count()),
        }
    }

    /// The pairs of a complete dense solve of `available` modes after `always` leading ones
    /// (a free body's rigid motions) that this selection keeps; checked as [`Self::count`]
    /// checks before anything is solved.
    pub fn pairs(&self, available: usize, always: usize) -> Result<PairSelection> {
        match *self {
            ModeSelection::Count(n) => {
                if n > available {
                    return Err(Error::Reduction(ReductionError::TooManyModes {
                        requested: n,
                        available,
                    }));
                }
                Ok(PairSelection::Lowest(always + n))
            }
            ModeSelection::UpToHz(hz) => {
                self.count(&[])?;
                Ok(PairSelection::UpToHz { hz, always })
            }
        }
    }
}

/// Which linear algebra a reduction runs on.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash)]
pub enum SolverPath {
    /// Dense for small interiors, sparse above
    /// [`DENSE_INTERIOR_LIMIT`](super::DENSE_INTERIOR_LIMIT) interior DOF.
    #[default]
    Auto,
    /// Dense factorisations and complete eigenproblems.
    Dense,
    /// Sparse Cholesky and the partial eigensolver.
    Sparse,
}

impl std::fmt::Display for Method {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.id())
    }
}

impl TryFrom<String> for Method {
    type Error = crate::error::UnknownId;

    fn try_from(id: String) -> Result<Self, Self::Error> {
        id.parse()
    }
}

impl From<Method> for String {
    fn from(method: Method) -> Self {
        method.id().into()
    }
}

impl std::str::FromStr for Method {
    type Err = crate::error::UnknownId;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Method::from_id(s.trim()).ok_or_else(|| {
            crate::error::UnknownId::new("method", s.trim(), &Method::ALL.map(Method::id))
        })
    }
}
