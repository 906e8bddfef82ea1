//! Which DOF set an error of a reduction names.

use std::fmt;

use super::Name;

/// Which DOF set a [`super::ReductionError::InvalidDofSet`] names.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub enum DofSetName {
    /// A set as the method calls it: `boundary`, `interface`, `r-set`, `restrained`,
    /// `input`, `moment-matching loads`, …
    Of(&'static str),
    /// An interface of the body file, by its kind (`rbe2`, `rbe3`) and name.
    Interface { kind: &'static str, name: Name },
    /// A part numbered from 1 (`interface 2` of a Benfield–Hruda model, `component 1` of a
    /// synthesis).
    Numbered { what: &'static str, number: usize },
    /// A driven body's drive or pinned ring, as the user gave it (`rbe2:hub`).
    Given(Name),
}

impl From<&'static str> for DofSetName {
    fn from(set: &'static str) -> Self {
        Self::Of(set)
    }
}

impl fmt::Display for DofSetName {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Of(set) => f.write_str(set),
            Self::Interface { kind, name } => write!(f, "{kind} interface `{name}`"),
            Self::Numbered { what, number } => write!(f, "{what} {number}"),
            Self::Given(name) => write!(f, "`{name}`"),
        }
    }
}
